//! The subcommands, one module each (`decompose` with its helpers in a folder), and
//! what more than one of them needs: the worker-thread count.

pub mod decompose;
pub mod demo_scene;
pub mod eval;
pub mod export;
pub mod sim;
pub mod view;

use anyhow::anyhow;

/// Starts `threads` worker threads (at least 1) for rayon; `None` keeps its default
/// (all cores).
pub fn set_threads(threads: Option<usize>) -> anyhow::Result<()> {
    if let Some(t) = threads {
        rayon::ThreadPoolBuilder::new()
            .num_threads(t.max(1))
            .build_global()
            .map_err(|e| anyhow!("cannot start {t} threads: {e}"))?;
    }
    Ok(())
}
