//! The children of the splits the worst-first loop comes to next, fitted together on
//! every thread (beyond the paper: scheduling only, as [`Cutter::ahead`],
//! docs/decisions/0043). Where the tree's top is a chain, `ahead` stops at once, and
//! each split then fitted its own two children, one large and one small, while the
//! second thread soon ran out of work. Here a split whose children are not fitted yet
//! also fits those of the next nodes of the queue, the largest first. A fit does not
//! depend on when or on which thread it is made (errors are kept by answer,
//! [`super::error_memo`]), so the cut is the same on any thread count; a node fitted
//! here that the loop never splits is work lost, at most a batch where the count
//! runs out.

use super::past_worst::Queued;
use super::{Cutter, Entry, Explored, Scratch};
use rayon::prelude::*;
use std::cmp::Reverse;
use std::collections::{BinaryHeap, HashMap};

/// Nodes of the queue looked at for a batch, per thread: the dragon's tolerance run
/// fits the same batches with 4, 8 or 16 (its queue's next nodes are mostly fitted).
const NEXT_PER_THREAD: usize = 4;

impl Cutter<'_> {
    /// Fits into `ready` the children of `e`'s node and of the nodes over `enough`
    /// among the next of `heap` ([`NEXT_PER_THREAD`] a thread), where `e`'s are not
    /// fitted yet and more than one thread runs (and the tests have not turned
    /// fitting ahead off); errors up to `above`, `known`'s fits
    /// kept, as [`Cutter::divide`] fits them.
    pub(super) fn fit_next(
        &self,
        (e, heap): (&Entry, &mut BinaryHeap<Queued>),
        (ex, ready): (&Explored, &mut HashMap<u32, Entry>),
        (enough, above, known): (f64, f64, &HashMap<u32, Entry>),
    ) {
        let threads = rayon::current_num_threads();
        if threads < 2 || super::off(&super::AHEAD_OFF) || !self.unfitted(ex, ready, e.node) {
            return;
        }
        let mut next = vec![e.node];
        let mut looked = Vec::new();
        while looked.len() + 1 < threads * NEXT_PER_THREAD {
            let Some(q) = heap.pop() else { break };
            if q.e.error > enough && self.unfitted(ex, ready, q.e.node) {
                next.push(q.e.node);
            }
            looked.push(q);
        }
        heap.extend(looked);
        let mut kids: Vec<u32> = (next.iter())
            .flat_map(|&n| self.tree.nodes[n as usize].children)
            .collect();
        // The largest first, so that the small ones fill in around it.
        kids.sort_by_key(|&c| Reverse(self.tree.faces(c).len()));
        let fitted: Vec<Entry> = (kids.par_iter())
            .with_max_len(1)
            .map_init(Scratch::default, |s, &c| self.entry(c, s, above, known))
            .collect();
        ready.extend(fitted.into_iter().map(|e| (e.node, e)));
    }

    /// Whether `n` is a node of the tree (not a group) whose children are neither in
    /// `ready` nor fitted.
    fn unfitted(&self, ex: &Explored, ready: &HashMap<u32, Entry>, n: u32) -> bool {
        let Some(node) = self.tree.nodes.get(n as usize) else {
            return false;
        };
        let have = |c: &u32| ready.contains_key(c) || ex.fitted.contains_key(c);
        !node.is_leaf() && !node.children.iter().all(have)
    }
}
