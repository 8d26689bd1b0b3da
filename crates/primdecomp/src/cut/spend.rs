//! A count the cut cannot fill: where the worst node's explored subtree splits no
//! nearer (a chain of merges that peels one small part at a time), the worst-first
//! exploration spends the count on that subtree, and the chosen cut, which only
//! splits a node while its children stay within the cut's worst error, comes back
//! with fewer nodes than asked. The rest of the count is then spent on the cut's
//! other nodes, worst first, and the cut is chosen again (issue 26: a target is left
//! unfilled only where nothing is left worth splitting; beyond the paper, whose
//! greedy pass takes a level of the merge order; docs/decisions/0048).

use super::{Cutter, Entry, Explored, Scratch};
use std::collections::BinaryHeap;

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
            let open = |n: &u32| !ex.is_split(self.tree, *n);
            let mut heap: BinaryHeap<Entry> = cut
                .iter()
                .filter(|n| open(n))
                .map(|n| ex.fitted[n].clone())
                .collect();
            while short > 0 {
                let Some(e) = heap.pop() else { break };
                if e.error <= self.enough {
                    break;
                }
                let node = self.tree.nodes[e.node as usize];
                if node.is_leaf() {
                    continue;
                }
                let [a, b] = node.children;
                let known = &ex.fitted;
                let (ea, eb): (Entry, Entry) = rayon::join(
                    || self.entry(a, &mut sa, f64::INFINITY, known),
                    || self.entry(b, &mut sb, f64::INFINITY, known),
                );
                ex.fitted.insert(a, ea.clone());
                ex.fitted.insert(b, eb.clone());
                heap.extend([ea, eb]);
                ex.splits.push(e.node);
                (short, spent) = (short - 1, true);
            }
        }
        if spent {
            ex.ids = ex.fitted.keys().copied().collect();
            ex.ids.sort_unstable();
        }
        spent
    }
}
