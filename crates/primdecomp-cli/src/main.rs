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
    fixed_mmap_threshold();
    std::process::exit(cli::main());
}

/// glibc's allocator with fixed thresholds: blocks of 8 MiB and more are mapped on
/// their own, so freeing one gives it back. Left to itself glibc raises that threshold
/// to the largest mapped block freed (up to 32 MiB) and keeps blocks under it in its
/// heaps once freed: a one-thread run of 14M faces peaked at 101 bytes a face, 97.8
/// with these (docs/decisions/perf-allocator-and-build.md). Not for mimalloc, nor
/// other libcs.
fn fixed_mmap_threshold() {
    #[cfg(all(target_os = "linux", target_env = "gnu", not(feature = "mimalloc")))]
    {
        // 8 MiB: 1 MiB gave a lower peak, but 0.42 s of system time on the dragon
        // against 0.09 (8 MiB: 0.12).
        const MMAP_THRESHOLD: libc::c_int = 8 << 20;
        // Free memory kept at the heap's top before it is given back: fixing the mmap
        // threshold also stops glibc raising this one (from 128 KiB), and a heap that
        // shrinks and grows on every large free spends system time on it.
        const TRIM_THRESHOLD: libc::c_int = 32 << 20;
        // SAFETY: set once at start-up, before any thread exists or allocates.
        unsafe {
            libc::mallopt(libc::M_MMAP_THRESHOLD, MMAP_THRESHOLD);
            libc::mallopt(libc::M_TRIM_THRESHOLD, TRIM_THRESHOLD);
        }
    }
}
