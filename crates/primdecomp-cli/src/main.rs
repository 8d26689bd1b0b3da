//! The `primdecomp` command: a thin shell over the library (see `cli.rs`).

/// mimalloc only with `--features mimalloc`: measured no faster than the system
/// allocator here, and it held ~60 MB more at peak (ARCHITECTURE.md, "Performance").
#[cfg(feature = "mimalloc")]
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

mod batch;
mod cli;
mod exit;
mod export_cmd;
mod paths;

fn main() {
    std::process::exit(cli::main());
}
