//! Priority queue of candidate merges with lazy deletion (§3.3): stale entries stay in
//! the queue and are skipped when popped (their cluster versions no longer match).
//! Ties are broken by cluster ids, so the merge order is fully deterministic.

use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// A candidate merge of clusters `a < b`, valid while both versions are unchanged.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Candidate {
    pub cost: f64,
    pub a: u32,
    pub b: u32,
    pub ver_a: u32,
    pub ver_b: u32,
}

impl Eq for Candidate {}

impl Ord for Candidate {
    /// Reversed so that `BinaryHeap` pops the cheapest, then the lowest ids.
    fn cmp(&self, o: &Self) -> Ordering {
        o.cost
            .total_cmp(&self.cost)
            .then(o.a.cmp(&self.a))
            .then(o.b.cmp(&self.b))
            .then(o.ver_a.cmp(&self.ver_a))
            .then(o.ver_b.cmp(&self.ver_b))
    }
}

impl PartialOrd for Candidate {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}

/// Min-queue of candidates.
#[derive(Debug, Default)]
pub struct CandidateHeap {
    heap: BinaryHeap<Candidate>,
}

impl CandidateHeap {
    /// Builds the queue from an initial batch in O(n).
    pub fn from_vec(v: Vec<Candidate>) -> Self {
        CandidateHeap {
            heap: BinaryHeap::from(v),
        }
    }
    pub fn push(&mut self, c: Candidate) {
        self.heap.push(c);
    }
    pub fn pop(&mut self) -> Option<Candidate> {
        self.heap.pop()
    }
    pub fn len(&self) -> usize {
        self.heap.len()
    }
    pub fn is_empty(&self) -> bool {
        self.heap.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pops_cheapest_then_lowest_ids() {
        let c = |cost, a, b| Candidate {
            cost,
            a,
            b,
            ver_a: 0,
            ver_b: 0,
        };
        let mut h = CandidateHeap::from_vec(vec![
            c(2.0, 0, 1),
            c(1.0, 5, 6),
            c(1.0, 2, 9),
            c(-1.0, 7, 8),
        ]);
        let order: Vec<(u32, u32)> = std::iter::from_fn(|| h.pop()).map(|c| (c.a, c.b)).collect();
        assert_eq!(order, vec![(7, 8), (2, 9), (5, 6), (0, 1)]);
    }
}
