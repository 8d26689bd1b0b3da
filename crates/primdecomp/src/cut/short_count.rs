//! A count the cut cannot fill: where the worst node's explored subtree splits no
//! nearer (a chain of merges that peels one small part at a time), the worst-first
//! exploration spends the count on that subtree, and the chosen cut, which only
//! splits a node while its children stay within the cut's worst error, comes back
//! with fewer nodes than asked. The rest of the count is then spent on the cut's
//! other nodes, worst first, and the cut is chosen again (the cut's target: a target is left
//! unfilled only where nothing is left worth splitting; beyond the paper, whose
//! greedy pass takes a level of the merge order; docs/decisions/0048).

use super::{Cutter, Entry, Explored, Scratch};
use std::collections::{BinaryHeap, HashMap};

impl Cutter<'_> {
    /// Splits, for each request of a count alone whose cut is short of it, as many
    /// of the cut's nodes (and their children) as it is short, worst first, never a
    /// node already split or within `enough`. Whether any was split.
    pub(super) fn spend(&self, ex: &mut Explored, cuts: &[Vec<u32>]) -> bool {
        let mut spent = false;
        let (mut sa, mut sb) = (Scratch::default(), Scratch::default());
        for (r, cut) in self.requests.iter().zip(cuts) {
            if r.tolerance.is_some() || r.bytes.is_some() {
                continue;
            }
            let mut short = r.count.saturating_sub(cut.len());
            let open = |n: &u32| !ex.is_split(*n);
            let mut heap: BinaryHeap<Entry> = cut
                .iter()
                .filter(|n| open(n))
                .map(|n| ex.fitted[n].clone())
                .collect();
            // Splits whose parts are carried add no node ([`super::carried_parts`]).
            let mut most = short.saturating_mul(super::SPLITS_PER_COUNT);
            while short > 0 && most > 0 {
                most -= 1;
                let Some(e) = heap.pop() else { break };
                if e.error <= self.enough {
                    break;
                }
                let none = HashMap::new();
                let split = (&mut sa, &mut sb);
                let at = (f64::INFINITY, &none);
                let Some(parts) = self.divide(ex, &e, &none, split, at) else {
                    continue;
                };
                short = short.saturating_sub(parts.len() - 1);
                heap.extend(parts);
                spent = true;
            }
        }
        if spent {
            ex.ids = ex.post_order();
        }
        spent
    }
}
