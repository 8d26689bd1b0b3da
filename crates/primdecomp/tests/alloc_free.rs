//! The fit kernels allocate nothing per candidate: once a `Workspace` has
//! grown to the largest point set it has seen, pricing merges — gathering points,
//! the eigen-solve, every kind's fit, the sorts and profile hulls — makes no heap
//! allocation. A counting global allocator proves it; it counts this thread only, so
//! the test harness's other threads cannot disturb the count.

use primdecomp::internals::Workspace;
use primdecomp_testkit::demo::{grow, with_demo};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

struct Counting;

thread_local! {
    static ALLOCS: Cell<u64> = const { Cell::new(0) };
}

// SAFETY: every call forwards to `System` with the caller's own arguments; the
// counter is a thread-local `Cell` with a const initialiser, which never allocates.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, l: Layout) -> *mut u8 {
        ALLOCS.with(|c| c.set(c.get() + 1));
        // SAFETY: same contract as our caller's.
        unsafe { System.alloc(l) }
    }
    unsafe fn dealloc(&self, p: *mut u8, l: Layout) {
        // SAFETY: same contract as our caller's.
        unsafe { System.dealloc(p, l) }
    }
    unsafe fn realloc(&self, p: *mut u8, l: Layout, n: usize) -> *mut u8 {
        ALLOCS.with(|c| c.set(c.get() + 1));
        // SAFETY: same contract as our caller's.
        unsafe { System.realloc(p, l, n) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

fn allocations() -> u64 {
    ALLOCS.with(|c| c.get())
}

#[test]
fn pricing_merges_allocates_nothing_once_warm() {
    with_demo(|fitter, mut cl, pairs| {
        grow(fitter, &mut cl, &pairs, 1500);
        let live: Vec<(u32, u32)> = pairs
            .iter()
            .map(|&(a, b)| (cl.find(a), cl.find(b)))
            .filter(|(a, b)| a != b)
            .collect();
        assert!(cl.live + 500 < cl.len(), "{} live of {}", cl.live, cl.len());
        let pairs = live;
        let mut ws = Workspace::default();
        // Warm-up: the workspace grows to the largest candidate.
        let priced = pairs
            .iter()
            .filter(|&&(a, b)| fitter.candidate(&cl, a, b, &mut ws).is_some())
            .count();
        assert!(priced > 1000, "only {priced} pairs priced");
        let before = allocations();
        let mut cost = 0.0;
        for &(a, b) in &pairs {
            if let Some((c, _)) = fitter.candidate(&cl, a, b, &mut ws) {
                cost += c.cost;
            }
        }
        let after = allocations();
        assert!(cost.is_finite());
        assert_eq!(
            after - before,
            0,
            "{} allocations in {priced} candidates",
            after - before
        );
    });
}

/// The counter works: a fresh workspace does allocate on its first candidate.
#[test]
fn counter_sees_a_cold_workspace_allocate() {
    with_demo(|fitter, cl, pairs| {
        let before = allocations();
        let mut ws = Workspace::default();
        let (a, b) = pairs[0];
        let _ = fitter.candidate(&cl, a, b, &mut ws);
        assert!(allocations() > before);
    });
}
