//! The `primdecomp` command: a thin shell over the library (see `cli.rs`, and
//! `commands/` for each subcommand).

/// mimalloc only with `--features mimalloc`: it was no faster than the system
/// allocator and held more memory at peak (docs/decisions/perf-allocator-and-build.md).
#[cfg(feature = "mimalloc")]
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

mod args;
mod batch;
mod cli;
mod commands;
mod exit;
mod manifest;
mod outputs;
mod paths;

/// A fresh, empty directory for one unit test (`tag` names it; the pid keeps runs
/// apart).
#[cfg(test)]
fn scratch_dir(tag: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("primdecomp-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn main() {
    // Rust ignores SIGPIPE, so printing into a closed pipe (`primdecomp … | head`)
    // would panic; with the default action the process ends quietly, as other tools.
    #[cfg(unix)]
    // SAFETY: set once at start-up, before any thread exists.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    std::process::exit(cli::main());
}
