//! Shared test helpers.
#![allow(dead_code)]
pub mod check;
pub mod contain;
pub mod demo;
pub mod shapes;

/// Runs `f` on a rayon pool of `threads` threads.
pub fn on_threads<R: Send>(threads: usize, f: impl FnOnce() -> R + Send) -> R {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("thread pool")
        .install(f)
}
