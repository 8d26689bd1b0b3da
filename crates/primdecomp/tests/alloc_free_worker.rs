//! Re-pricing shared with the worker thread (`merge::worker`) allocates nothing per
//! batch or candidate once warm: neither the main thread (the job snapshot,
//! the result slots) nor the worker (its workspace, its result list). The allocator
//! here counts every thread, so this file holds this one test only: the harness's main
//! thread just waits for it.

use primdecomp::internals::{with_pricer, Clusters, Fitter};
use primdecomp_testkit::demo::{grow, with_demo};
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicU64, Ordering::Relaxed};

struct Counting;

static ALLOCS: AtomicU64 = AtomicU64::new(0);

// SAFETY: every call forwards to `System` with the caller's own arguments; the
// counter is a static atomic, which never allocates.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, l: Layout) -> *mut u8 {
        ALLOCS.fetch_add(1, Relaxed);
        // SAFETY: same contract as our caller's.
        unsafe { System.alloc(l) }
    }
    unsafe fn dealloc(&self, p: *mut u8, l: Layout) {
        // SAFETY: same contract as our caller's.
        unsafe { System.dealloc(p, l) }
    }
    unsafe fn realloc(&self, p: *mut u8, l: Layout, n: usize) -> *mut u8 {
        ALLOCS.fetch_add(1, Relaxed);
        // SAFETY: same contract as our caller's.
        unsafe { System.realloc(p, l, n) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Rounds over the same batches: a warm round allocates nothing. The worker's share
/// depends on timing (a round may hand it a bigger cluster than it has seen, which
/// grows its buffers once), so the test passes on the first round that allocated
/// nothing while the worker priced neighbours, and fails if no round of many does.
#[test]
fn shared_repricing_allocates_nothing_once_warm() {
    with_demo(|fitter, mut cl, pairs| {
        grow(fitter, &mut cl, &pairs, 1500);
        priced_cleanly(fitter, cl)
    });
}

/// Runs up to 50 rounds over every live cluster's batch, on a two-thread pool (so the
/// pricer has its worker); passes once a round allocated nothing while the worker
/// priced neighbours.
fn priced_cleanly(fitter: &Fitter, mut cl: Clusters) {
    let roots = cl.roots();
    let batches: Vec<(u32, Vec<u32>)> = roots
        .iter()
        .map(|&r| (r, cl.resolved_neighbors(r)))
        .filter(|(_, n)| n.len() >= 2)
        .collect();
    assert!(batches.len() > 500, "only {} batches", batches.len());
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .expect("pool");
    let clean = pool.install(|| {
        with_pricer(fitter, |pricer| {
            let mut cost = 0.0;
            for _ in 0..50 {
                let (allocs, worker) = (ALLOCS.load(Relaxed), pricer.stats.by_worker);
                for (r, ns) in &batches {
                    pricer.price(&cl, *r, ns, || {}, |c| cost += c.cost);
                }
                if ALLOCS.load(Relaxed) == allocs && pricer.stats.by_worker > worker {
                    return Some(pricer.stats);
                }
            }
            assert!(cost.is_finite());
            None
        })
    });
    assert!(
        clean.is_some(),
        "every round allocated (or the worker never priced a neighbour)"
    );
}
