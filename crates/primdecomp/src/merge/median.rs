//! The median split of the spatial parts ([`super::partition`]) in steps of bounded
//! work: a selection over millions of faces is one long loop, which would keep a
//! cancel waiting for seconds (docs/results/throughput.md, "Cancellation").
//!
//! Which faces end up below the split depends only on the order (every key is
//! distinct), not on how they are found: [`select`] puts the same set first as
//! `select_nth_unstable_by` does, so the parts are the same.

use crate::progress::Checkpoint;
use std::cmp::Ordering;

/// Items scanned between two checks of `go_on` (a few milliseconds on one core).
pub(crate) const BLOCK: usize = 1 << 20;

/// Ranges this short are finished by `select_nth_unstable_by` without a check.
const SHORT: usize = 1 << 16;

/// Rounds of sampled pivots before the rest is finished unchecked (a pivot from
/// a sample nearly halves the range each round; 48 rounds leave 2^-48 of it).
const ROUNDS: usize = 48;

/// Puts the `m` items of `ids` that come first by `cmp` (a total order) in
/// `ids[..m]`, in some order, asking `go_on` every [`BLOCK`] steps of a scan; false
/// when it said stop (`ids` is then a permutation of what it was).
pub(crate) fn select(
    ids: &mut [u32],
    m: usize,
    cmp: &(impl Fn(u32, u32) -> Ordering + Sync),
    go_on: Checkpoint,
) -> bool {
    // Everything before `lo` comes before everything from `lo` on; everything from
    // `hi` on after everything before `hi`; lo ≤ m ≤ hi.
    let (mut lo, mut hi) = (0, ids.len());
    for _ in 0..ROUNDS {
        if hi - lo <= SHORT || m == lo || m == hi {
            break;
        }
        let pivot = sampled_median(&ids[lo..hi], cmp);
        let Some(p) = partition(&mut ids[lo..hi], pivot, cmp, go_on) else {
            return false;
        };
        match lo + p {
            // The pivot is the least: it alone goes first.
            p if p == lo => {
                let at = lo + (ids[lo..hi].iter().position(|&i| i == pivot)).expect("in range");
                ids.swap(lo, at);
                lo += 1;
            }
            p if m <= p => hi = p,
            p => lo = p,
        }
    }
    if lo < m && m < hi {
        ids[lo..hi].select_nth_unstable_by(m - lo, |&a, &b| cmp(a, b));
    }
    true
}

/// The median of 255 items spread evenly over `ids` (deterministic).
fn sampled_median(ids: &[u32], cmp: &impl Fn(u32, u32) -> Ordering) -> u32 {
    let step = (ids.len() / 255).max(1);
    let mut sample: Vec<u32> = ids.iter().step_by(step).copied().collect();
    let mid = sample.len() / 2;
    *sample.select_nth_unstable_by(mid, |&a, &b| cmp(a, b)).1
}

/// Moves the items before `pivot` to the front (two cursors closing in, one item
/// a step), asking `go_on` every [`BLOCK`] steps; how many came first, or `None`
/// when `go_on` said stop.
fn partition(
    ids: &mut [u32],
    pivot: u32,
    cmp: &impl Fn(u32, u32) -> Ordering,
    go_on: Checkpoint,
) -> Option<usize> {
    let before = |i: u32| cmp(i, pivot) == Ordering::Less;
    let (mut i, mut j) = (0, ids.len());
    let mut steps = 0usize;
    while i < j {
        if before(ids[i]) {
            i += 1;
        } else if !before(ids[j - 1]) {
            j -= 1;
        } else {
            ids.swap(i, j - 1);
            (i, j) = (i + 1, j - 1);
        }
        steps += 1;
        if steps % BLOCK == 0 && !go_on(0.0) {
            return None;
        }
    }
    Some(i)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The same set first as `select_nth_unstable_by`, for ranges long enough to
    /// take the sampled rounds, with many equal coordinates (ties by id), and a
    /// stop when told.
    #[test]
    fn selects_the_set_std_selects_and_stops_when_told() {
        let n = 300_000u32;
        let coord: Vec<f64> = (0..n).map(|i| f64::from((i * 7919) % 1013) * 0.5).collect();
        let cmp = |a: u32, b: u32| {
            coord[a as usize]
                .total_cmp(&coord[b as usize])
                .then(a.cmp(&b))
        };
        for m in [0, 1, 70_000, 150_000, 299_999, 300_000] {
            let mut ours: Vec<u32> = (0..n).rev().collect();
            assert!(select(&mut ours, m as usize, &cmp, &|_| true));
            let mut std: Vec<u32> = (0..n).rev().collect();
            if m > 0 && m < n {
                std.select_nth_unstable_by(m as usize, |&a, &b| cmp(a, b));
            }
            let (mut a, mut b) = (ours[..m as usize].to_vec(), std[..m as usize].to_vec());
            a.sort_unstable();
            b.sort_unstable();
            assert_eq!(a, b, "m = {m}");
        }
        let mut big: Vec<u32> = (0..3 * BLOCK as u32).rev().collect();
        let key = |a: u32, b: u32| (a % 1000).cmp(&(b % 1000)).then(a.cmp(&b));
        let asked = std::sync::atomic::AtomicUsize::new(0);
        let stop = |_: f64| asked.fetch_add(1, std::sync::atomic::Ordering::Relaxed) < 1;
        assert!(!select(&mut big, BLOCK, &key, &stop));
    }
}
