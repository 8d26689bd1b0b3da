//! Where the cut cannot split nearer: a node over a tolerance that is a leaf, or
//! that no cut of its explored subtree brings nearer, gets the least-error fit of
//! every kind in every frame instead of the least k·V (§3.2's fit chooses by volume,
//! blind to how far a corner stands off a triangle; a deviation for the cut only:
//! docs/decisions/0041).

use super::error::{error_until_checked, StopAt};
use super::{Cutter, Entry, Explored, Scratch};
use rayon::prelude::*;
use std::collections::HashMap;

impl Cutter<'_> {
    /// Refits the nodes of `cuts` kept over their tolerance that splitting does not
    /// bring nearer ([`Cutter::kept_over`]) as their nearest fits and chooses the
    /// cuts again, until every such node is its nearest fit.
    pub(super) fn nearest_where_kept(&self, ex: &mut Explored, cuts: &mut Vec<Vec<u32>>) {
        loop {
            let over = self.kept_over(ex, cuts);
            if over.is_empty() {
                return;
            }
            self.refit_nearest(ex, &over);
            *cuts = self.requests.iter().map(|r| self.choose(ex, r)).collect();
        }
    }

    /// `nodes` refitted as their nearest fits ([`Cutter::closest`]), in parallel.
    pub(super) fn refit_nearest(&self, ex: &mut Explored, nodes: &[u32]) {
        let nearer: Vec<Entry> = nodes
            .par_iter()
            .map_init(Scratch::default, |s, n| self.closest(ex, &ex.fitted[n], s))
            .collect();
        for e in nearer {
            ex.fitted.insert(e.node, e);
        }
    }

    /// Node `e` refitted as the least-error candidate of every kind in every frame
    /// ([`Fitter::output_candidates`]), or kept if none is nearer: where the cut
    /// cannot split, the fit's k·V (a volume, blind to how far a corner stands off a
    /// triangle) no longer chooses (docs/decisions/0041). The candidates enclose the
    /// nodes it carries too.
    fn closest(&self, ex: &Explored, e: &Entry, s: &mut Scratch) -> Entry {
        if !self.goes_on() {
            return e.clone();
        }
        let q = self.q_of(ex, e.node);
        let faces = self.faces_of(ex, e.node);
        let ask = || self.goes_on();
        if !(self.fitter).output_candidates(faces, &q, &mut s.ws, &mut s.candidates, &ask) {
            // Told to stop: nothing the cutter makes since is kept.
            return e.clone();
        }
        let mut best = Entry {
            closest: true,
            ..self.remeasured(e, f64::INFINITY)
        };
        for p in &s.candidates {
            if best.error <= self.enough {
                break;
            }
            let ask = StopAt {
                level: self.enough,
                above: best.error,
                coarse: true,
            };
            let error = error_until_checked(p, self.surface, ask, &|| self.goes_on());
            if error < best.error {
                best = Entry {
                    error,
                    prim: *p,
                    ..best
                };
            }
        }
        best
    }

    /// The nodes of `cuts` over their request's tolerance that splitting does not
    /// bring nearer (no cut of their explored subtree is), not yet refitted nearest
    /// ([`Cutter::closest`]), in increasing order. Nodes kept only because a cap
    /// stopped the splits are left as they are: their subtrees reach nearer.
    fn kept_over(&self, ex: &Explored, cuts: &[Vec<u32>]) -> Vec<u32> {
        let floor = self.floors(ex);
        let mut over = Vec::new();
        for (r, cut) in self.requests.iter().zip(cuts) {
            let Some(t) = r.tolerance else { continue };
            over.extend(cut.iter().copied().filter(|n| {
                let e = &ex.fitted[n];
                e.error > t && !e.closest && floor[n]
            }));
        }
        over.sort_unstable();
        over.dedup();
        over
    }

    /// For each explored node, whether it is as near as its subtree gets: a split
    /// node whose error is at most the least worst error of its explored subtree's
    /// cuts below it (the cuts of its parts).
    fn floors(&self, ex: &Explored) -> HashMap<u32, bool> {
        let mut best: HashMap<u32, f64> = HashMap::with_capacity(ex.ids.len());
        let mut floor = HashMap::with_capacity(ex.ids.len());
        for &n in &ex.ids {
            let error = ex.fitted[&n].error;
            let below =
                (ex.parts.get(&n)).map(|parts| parts.iter().map(|c| best[c]).fold(0.0, f64::max));
            floor.insert(n, below.is_some_and(|b| error <= b));
            best.insert(n, below.map_or(error, |b| b.min(error)));
        }
        floor
    }
}
