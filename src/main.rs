//! The `primdecomp` command: a thin shell over the library (see `cli.rs`).

/// mimalloc unless built with `--features system-alloc` (kept to measure the
/// difference: ARCHITECTURE.md, "Allocator").
#[cfg(not(feature = "system-alloc"))]
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

mod cli;

fn main() {
    std::process::exit(cli::main());
}
