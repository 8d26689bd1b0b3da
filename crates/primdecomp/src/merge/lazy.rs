//! Deferred ("lazy greedy") re-pricing, `Params::reprice`: after a deferred merge the
//! merged cluster's pairs are not re-priced; their old queue entries (priced for the
//! clusters before the merge) stay in the queue as keys, and each is re-priced for the
//! clusters as they are when it is popped, then pushed back with its fresh cost
//! (Minoux's accelerated greedy; our costs need not rise as clusters grow, so the
//! merge order is no longer exactly greedy, see
//! docs/decisions/0015-deferred-repricing-of-high-degree-clusters.md).
//!
//! Every entry carries the merge clock it was priced at; each cluster records when it
//! last changed (`Clusters::changed`) and when all its pairs were last priced
//! (`Clusters::repriced`, equal unless its last merge was deferred). A pair reached
//! through several faces of a grown cluster has several stale entries; the first one
//! popped is re-priced, and [`Lazy`] remembers that, so the others are dropped.

use super::cluster::Clusters;
use super::heap::Candidate;
use rustc_hash::FxHashMap;

/// What a popped queue entry stands for.
pub(super) enum Pop {
    /// Priced for both clusters as they are: merge them.
    Fresh,
    /// A merge inside one cluster, or a pair with a fresher entry: skip it.
    Drop,
    /// A stale key of live roots `a < b` that nobody re-priced since: re-price it.
    Reprice(u32, u32),
}

/// Pairs re-priced when popped, and the clock they were re-priced at.
#[derive(Debug, Default)]
pub(super) struct Lazy {
    priced: FxHashMap<(u32, u32), u32>,
}

impl Lazy {
    /// Classifies a popped entry; a [`Pop::Reprice`] is recorded as priced now.
    pub fn classify(&mut self, cl: &mut Clusters, c: &Candidate) -> Pop {
        if valid(cl, c) {
            return Pop::Fresh;
        }
        let (a, b) = (cl.find(c.a), cl.find(c.b));
        let (a, b) = (a.min(b), a.max(b));
        if a == b || self.has_fresh(cl, a, b) {
            return Pop::Drop;
        }
        self.priced.insert((a, b), cl.clock);
        Pop::Reprice(a, b)
    }

    /// Whether a purge keeps `c`: fresh, or the key of a pair nobody re-priced since.
    pub fn keep(&self, cl: &Clusters, c: &Candidate) -> bool {
        if valid(cl, c) {
            return true;
        }
        let (a, b) = (cl.root(c.a), cl.root(c.b));
        a != b && !self.has_fresh(cl, a.min(b), a.max(b))
    }

    /// Forgets re-pricings that a later change made stale (with a queue purge).
    pub fn prune(&mut self, cl: &Clusters) {
        self.priced.retain(|&(a, b), &mut t| {
            cl.is_root(a) && cl.is_root(b) && t >= latest_change(cl, a, b)
        });
    }

    /// Live roots `a < b` have an entry priced after both last changed.
    fn has_fresh(&self, cl: &Clusters, a: u32, b: u32) -> bool {
        let changed = latest_change(cl, a, b);
        let (ra, rb) = (cl.repriced(a), cl.repriced(b));
        // One of them re-priced all its pairs (at once) since the later change…
        ra.max(rb) >= changed
            // … or this pair was re-priced when popped since then.
            || self.priced.get(&(a, b)).is_some_and(|&t| t >= changed)
    }
}

fn latest_change(cl: &Clusters, a: u32, b: u32) -> u32 {
    cl.changed(a).max(cl.changed(b))
}

/// Both clusters are live and unchanged since the pair was priced.
pub(super) fn valid(cl: &Clusters, c: &Candidate) -> bool {
    cl.is_root(c.a) && cl.is_root(c.b) && cl.changed(c.a) <= c.t && cl.changed(c.b) <= c.t
}
