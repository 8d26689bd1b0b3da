//! Priority queues of candidate merges with lazy deletion (§3.3): stale entries stay in
//! the queue and are skipped when popped (a cluster changed after they were priced).
//! Ties are broken by cluster ids, so the merge order is fully deterministic.
//!
//! [`RadixHeap`] drives the merges: a radix heap (buckets indexed by the highest bit in
//! which a cost differs from the last extracted one) in front of a small binary heap
//! that holds the current minimum cost group and the few candidates pushed below it.
//! Merge costs are nearly monotone (few pushes land below the last popped cost;
//! docs/decisions/perf-merge-queue-radix-heap.md), so most pushes are an O(1) append to a
//! bucket, and a pop touches a short heap instead of a multi-million-entry one.
//! [`StdHeap`] (`std::collections::BinaryHeap`) is kept as the reference: both pop
//! the same sequence (tested), and `benches/stages.rs` compares them on real runs.

use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// A candidate merge of clusters `a < b`, priced at merge clock `t`: fresh while neither
/// cluster has changed since (`Clusters::changed`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Candidate {
    pub cost: f64,
    /// Volume of the merged primitive (kept so that applying the merge needs no refit).
    pub volume: f64,
    pub a: u32,
    pub b: u32,
    /// The merge clock (`Clusters::clock`) when the pair was priced.
    pub t: u32,
    /// The merged points are coplanar: the merge makes a plate (`driver::free`).
    pub flat: bool,
}

impl Eq for Candidate {}

impl Ord for Candidate {
    /// Reversed so that `BinaryHeap` pops the cheapest, then the lowest ids, then the
    /// newest pricing of the same pair (a fresh entry before its stale copies).
    fn cmp(&self, o: &Self) -> Ordering {
        o.cost
            .total_cmp(&self.cost)
            .then(o.a.cmp(&self.a))
            .then(o.b.cmp(&self.b))
            .then(self.t.cmp(&o.t))
    }
}

impl PartialOrd for Candidate {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}

/// A min-queue of candidates, cheapest first, then by `(a, b)`, then newest `t` first.
pub trait Queue: Default {
    /// Builds the queue from an initial batch.
    #[cfg(test)]
    fn from_vec(v: Vec<Candidate>) -> Self;
    fn push(&mut self, c: Candidate);
    fn pop(&mut self) -> Option<Candidate>;
    fn len(&self) -> usize;
    /// Drops every candidate for which `keep` is false (stale ones), in O(len).
    fn retain(&mut self, keep: impl Fn(&Candidate) -> bool);
    fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// The reference queue: `std::collections::BinaryHeap`.
#[derive(Debug, Default)]
#[cfg(any(test, feature = "test-internals"))]
pub struct StdHeap {
    heap: BinaryHeap<Candidate>,
}

#[cfg(any(test, feature = "test-internals"))]
impl Queue for StdHeap {
    #[cfg(test)]
    fn from_vec(v: Vec<Candidate>) -> Self {
        StdHeap {
            heap: BinaryHeap::from(v),
        }
    }
    fn push(&mut self, c: Candidate) {
        self.heap.push(c);
    }
    fn pop(&mut self) -> Option<Candidate> {
        self.heap.pop()
    }
    fn len(&self) -> usize {
        self.heap.len()
    }
    fn retain(&mut self, keep: impl Fn(&Candidate) -> bool) {
        self.heap.retain(keep);
    }
}

/// Order-preserving map of a cost to an integer key (the order of `f64::total_cmp`).
#[inline]
fn cost_key(cost: f64) -> u64 {
    let bits = cost.to_bits();
    if bits >> 63 == 1 {
        !bits
    } else {
        bits | 1 << 63
    }
}

/// Largest allocation (in candidates, 128 KiB) an emptied bucket keeps for reuse.
const KEEP_CAPACITY: usize = 4096;

/// Radix heap over cost keys with a binary-heap front (see the module doc).
///
/// Invariant: every candidate in `front` has key ≤ `last`; every candidate in
/// `buckets[i]` (i ≥ 1) has key > `last` and its highest bit differing from `last`
/// is bit `i − 1`.
#[derive(Debug)]
pub struct RadixHeap {
    last: u64,
    front: BinaryHeap<Candidate>,
    buckets: Vec<Vec<Candidate>>,
    len: usize,
}

impl Default for RadixHeap {
    fn default() -> Self {
        RadixHeap {
            last: 0,
            front: BinaryHeap::new(),
            buckets: vec![Vec::new(); 65],
            len: 0,
        }
    }
}

impl RadixHeap {
    #[inline]
    fn bucket(&self, key: u64) -> usize {
        64 - (key ^ self.last).leading_zeros() as usize
    }

    /// Moves the lowest non-empty bucket's minimum-key group to the front and spreads
    /// the rest of that bucket over lower buckets.
    fn refill(&mut self) {
        let Some(i) = (1..self.buckets.len()).find(|&i| !self.buckets[i].is_empty()) else {
            return;
        };
        let items = std::mem::take(&mut self.buckets[i]);
        self.last = items
            .iter()
            .map(|c| cost_key(c.cost))
            .min()
            .expect("non-empty");
        for &c in &items {
            let key = cost_key(c.cost);
            if key == self.last {
                self.front.push(c);
            } else {
                let b = self.bucket(key);
                self.buckets[b].push(c);
            }
        }
        // Give the emptied bucket its allocation back for the next round, unless it
        // is large: its items now sit in lower buckets, and a kept allocation stays
        // resident however rarely the bucket fills again (hundreds of MiB at the peak on
        // the largest inputs: docs/decisions/perf-merge-queue-radix-heap.md).
        let mut items = items;
        items.clear();
        if self.buckets[i].is_empty() && items.capacity() <= KEEP_CAPACITY {
            self.buckets[i] = items;
        }
    }
}

impl Queue for RadixHeap {
    #[cfg(test)]
    fn from_vec(v: Vec<Candidate>) -> Self {
        let mut h = RadixHeap::default();
        let mut counts = [0usize; 65];
        v.iter()
            .for_each(|c| counts[h.bucket(cost_key(c.cost))] += 1);
        for (b, &n) in h.buckets.iter_mut().zip(&counts) {
            b.reserve_exact(n);
        }
        v.into_iter().for_each(|c| h.push(c));
        h
    }

    #[inline]
    fn push(&mut self, c: Candidate) {
        let key = cost_key(c.cost);
        self.len += 1;
        if key <= self.last {
            self.front.push(c);
        } else {
            let b = self.bucket(key);
            self.buckets[b].push(c);
        }
    }

    fn pop(&mut self) -> Option<Candidate> {
        if self.front.is_empty() {
            self.refill();
        }
        let c = self.front.pop()?;
        self.len -= 1;
        Some(c)
    }

    fn len(&self) -> usize {
        self.len
    }

    fn retain(&mut self, keep: impl Fn(&Candidate) -> bool) {
        self.front.retain(&keep);
        // A large equal-cost group (zero-cost merges of coplanar faces) once grew the
        // front to 2^21 entries (64 MiB) on the 3.5M-face dragon; like the buckets',
        // its allocation is trimmed here rather than kept resident for the whole run.
        let n = self.front.len();
        self.front.shrink_to(n + n / 4);
        let mut len = n;
        for b in &mut self.buckets {
            b.retain(&keep);
            b.shrink_to(b.len() + b.len() / 4);
            len += b.len();
        }
        self.len = len;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn c(cost: f64, a: u32, b: u32) -> Candidate {
        Candidate {
            cost,
            volume: 0.0,
            a,
            b,
            t: 0,
            flat: false,
        }
    }

    #[test]
    fn pops_cheapest_then_lowest_ids() {
        let batch = vec![c(2.0, 0, 1), c(1.0, 5, 6), c(1.0, 2, 9), c(-1.0, 7, 8)];
        let mut h = RadixHeap::from_vec(batch);
        let order: Vec<(u32, u32)> = std::iter::from_fn(|| h.pop()).map(|c| (c.a, c.b)).collect();
        assert_eq!(order, vec![(7, 8), (2, 9), (5, 6), (0, 1)]);
    }

    #[test]
    fn cost_key_follows_total_order() {
        let xs = [
            f64::NEG_INFINITY,
            -1e300,
            -2.0,
            -1.0,
            -f64::MIN_POSITIVE,
            -0.0,
            0.0,
            f64::MIN_POSITIVE,
            1.0,
            3.0,
            1e300,
            f64::INFINITY,
        ];
        for w in xs.windows(2) {
            assert!(cost_key(w[0]) < cost_key(w[1]), "{} vs {}", w[0], w[1]);
        }
    }

    /// Buckets far larger than `KEEP_CAPACITY` (whose allocations refills free rather
    /// than keep) pop the same sequence as `BinaryHeap`, with many tied costs and
    /// pushes below the last pop in between; the proptest below never fills a bucket
    /// that far.
    #[test]
    fn large_buckets_pop_like_binary_heap() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        let n = 50 * KEEP_CAPACITY + 17;
        let mut make = || {
            let cost = rng.gen_range(0..1000) as f64 - 50.0;
            c(cost, rng.gen_range(0..4000), rng.gen_range(0..4000))
        };
        let batch: Vec<Candidate> = (0..n).map(|_| make()).collect();
        let (mut r, mut s) = (RadixHeap::default(), StdHeap::from_vec(batch.clone()));
        batch.into_iter().for_each(|x| r.push(x));
        for i in 0..n {
            assert_eq!(r.pop(), s.pop(), "pop {i}");
            if i % 3 == 0 {
                let x = make();
                r.push(x);
                s.push(x);
            }
        }
        while let Some(x) = s.pop() {
            assert_eq!(r.pop(), Some(x));
        }
        assert!(r.pop().is_none());
    }

    proptest! {
        /// Any interleaving of pushes and pops, with costs drawn from a small set
        /// (many ties) including negative ones and ones below the last pop, gives the
        /// same pop sequence from the radix heap as from `BinaryHeap`.
        #[test]
        fn same_sequence_as_binary_heap(
            init in prop::collection::vec((-4i32..8, 0u32..20, 0u32..20), 0..40),
            ops in prop::collection::vec(prop::option::of((-4i32..8, 0u32..20, 0u32..20)), 0..200),
        ) {
            let make = |&(k, a, b): &(i32, u32, u32)| c(k as f64 * 0.5, a.min(b), a.max(b));
            let batch: Vec<Candidate> = init.iter().map(make).collect();
            let mut r = RadixHeap::from_vec(batch.clone());
            let mut s = StdHeap::from_vec(batch);
            for op in &ops {
                match op {
                    Some(t) => {
                        r.push(make(t));
                        s.push(make(t));
                    }
                    None => prop_assert_eq!(r.pop(), s.pop()),
                }
                if op.is_some_and(|(k, _, _)| k == 7) {
                    // An occasional purge of one id keeps both queues equal.
                    r.retain(|c| c.a != 3);
                    s.retain(|c| c.a != 3);
                }
                prop_assert_eq!(r.len(), s.len());
            }
            while let Some(x) = s.pop() {
                prop_assert_eq!(r.pop(), Some(x));
            }
            prop_assert!(r.pop().is_none());
        }
    }
}
