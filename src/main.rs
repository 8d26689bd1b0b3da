//! The `primdecomp` command: a thin shell over the library (see `cli.rs`).

use mimalloc::MiMalloc;

#[global_allocator]
static GLOBAL: MiMalloc = MiMalloc;

mod cli;

fn main() {
    std::process::exit(cli::main());
}
