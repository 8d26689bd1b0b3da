//! The count past the least worst error (the cut's target: it should lose little or
//! nothing on Chamfer, the mean distance; beyond the paper, whose greedy pass takes a
//! level of the merge order; docs/decisions/0051). The worst-first splits spend a
//! count on the nodes that set the worst error, and the cut of the count is then the
//! only cut of the nodes reached with that many nodes: nothing is left for the mean.
//! So a cut of counts alone is explored a second time: a node over
//! [`LOOSE_FACTOR`] times the least worst error the count allows is split first, worst
//! first, and the rest of the count goes where the greedy pass would have put it, to
//! the latest merges first (the pass merges the cheapest pairs first, §3.3, so its
//! last merges added the most volume).

use super::{worst, Cutter, Entry, Explored};
use std::cmp::Ordering;
use std::collections::HashMap;

/// A cut of a count stands at most this many times the least worst error the count
/// allows; within it the count goes to the latest merges.
pub(crate) const LOOSE_FACTOR: f64 = 1.25;

/// The order [`Cutter::explore`] splits in: the worst node first, or, with a bound,
/// the worst of the nodes over it first and then the latest merge.
#[derive(Clone, Copy)]
pub(super) enum Order {
    Worst,
    Loose(f64),
}

/// A node waiting to be split, with its place in the order.
pub(super) struct Queued {
    key: (bool, f64, u32),
    pub e: Entry,
}

impl Order {
    /// `e` with its key; `tree` is the tree's node count (ids at or past it are
    /// groups of spatial parts, [`super::carried_parts`], merged before any logged merge
    /// and so split first).
    pub(super) fn queued(self, e: Entry, tree: u32) -> Queued {
        let key = match self {
            Order::Loose(bound) if e.error <= bound => {
                let late = if e.node < tree {
                    e.node as f64
                } else {
                    f64::INFINITY
                };
                (false, late, e.node)
            }
            // Worst error first; ties to the lower node id (as [`Entry`]'s order).
            _ => (true, e.error, u32::MAX - e.node),
        };
        Queued { key, e }
    }
}

impl PartialEq for Queued {
    fn eq(&self, o: &Self) -> bool {
        self.cmp(o) == Ordering::Equal
    }
}
impl Eq for Queued {}
impl PartialOrd for Queued {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Queued {
    fn cmp(&self, o: &Self) -> Ordering {
        let (a, b) = (self.key, o.key);
        (a.0.cmp(&b.0))
            .then(a.1.total_cmp(&b.1))
            .then(a.2.cmp(&b.2))
    }
}

impl Cutter<'_> {
    /// With one request of a count alone (no tolerance, no bytes): the tree
    /// explored again in [`Order::Loose`] under [`LOOSE_FACTOR`] times the error of its cut
    /// of `ex` (the one of `cuts`), the fits of `known` and `ex` kept, and the cut
    /// where the loose splits stopped (where that stands within the bound and the
    /// count; else the one chosen from the nodes reached) — if it stands within the
    /// bound and holds as many nodes as the first.
    pub(super) fn loosened(
        &self,
        (ex, cuts): (&Explored, &[Vec<u32>]),
        enough: f64,
        mut known: HashMap<u32, Entry>,
    ) -> Option<(Explored, Vec<u32>)> {
        let ([r], [cut]) = (self.requests.as_slice(), cuts) else {
            return None;
        };
        // A byte target's cut is chosen by bytes: on 22 meshes the loose cut was
        // kept on 15 of 44 byte levels for no measured gain (0051).
        if r.tolerance.is_some() || r.bytes.is_some() {
            return None;
        }
        let bound = LOOSE_FACTOR * worst(ex, cut);
        // Groups are numbered anew by each exploration.
        let tree = self.tree.nodes.len() as u32;
        known.extend(
            (ex.fitted.iter())
                .filter(|(n, _)| **n < tree)
                .map(|(n, e)| (*n, e.clone())),
        );
        let loose = self.explore(r.count, enough, f64::INFINITY, &known, Order::Loose(bound));
        // The cut is where the loose splits stopped, within the bound: choosing would
        // keep a node whose parts stand farther than it does, and leave the count
        // unspent.
        let ends: Vec<u32> = (loose.ids.iter().copied())
            .filter(|&n| !loose.is_split(n))
            .collect();
        let again = match worst(&loose, &ends) <= bound && ends.len() <= r.count {
            true => ends,
            false => self.choose(&loose, r),
        };
        let near = worst(&loose, &again) <= bound && again.len() >= cut.len();
        near.then_some((loose, again))
    }
}
