//! Choosing each request's cut from the explored tree: the fewest nodes within a
//! tolerance, or the least worst error the count and bytes allow, filled up to the
//! count (docs/decisions/0032, 0034).

use super::{Cutter, Explored, Request, SLACK};
use crate::output::result::Shortfall;
use std::collections::{BTreeSet, HashMap};

/// What the cut of a node's subtree costs under one error bound: its nodes and bytes,
/// its worst error, the least worst error any cut of the subtree reaches, and whether
/// the node itself is kept (else its parts' cuts).
#[derive(Clone, Copy, Default)]
pub(super) struct Cost {
    count: usize,
    bytes: usize,
    worst: f64,
    best: f64,
    own: bool,
}

impl Cutter<'_> {
    /// With a tolerance, the cut of fewest nodes within it, if the caps allow it.
    pub(super) fn within(&self, ex: &Explored, r: &Request) -> Option<Vec<u32>> {
        let cut = self.cheapest(ex, r.tolerance?, r.bytes.is_some());
        fits(r, totals(ex, &cut)).then_some(cut)
    }

    /// The cut for `r`: with a tolerance the fewest nodes within it if the caps allow,
    /// else the least error bound the caps allow (searched over the nodes' errors),
    /// then filled — splits in the order they were made, while both children stay
    /// within the bound and the caps allow — so that the count is used.
    pub(super) fn choose(&self, ex: &Explored, r: &Request) -> Vec<u32> {
        if let Some(cut) = self.within(ex, r) {
            return cut;
        }
        let mut bounds: Vec<f64> = ex.ids.iter().map(|n| ex.fitted[n].error).collect();
        bounds.push(0.0);
        bounds.sort_unstable_by(f64::total_cmp);
        bounds.dedup();
        let ok = |i: usize| {
            fits(
                r,
                totals(ex, &self.cheapest(ex, bounds[i], r.bytes.is_some())),
            )
        };
        // The least bound whose cheapest cut fits (feasibility only grows with it).
        let (mut lo, mut hi) = (0, bounds.len().saturating_sub(1));
        while lo < hi {
            let mid = (lo + hi) / 2;
            match ok(mid) {
                true => hi = mid,
                false => lo = mid + 1,
            }
        }
        let table = self.costs(ex, bounds[lo], r.bytes.is_some());
        let cut = collect(ex, &table, &ex.roots);
        if !fits(r, totals(ex, &cut)) {
            // Nothing fits the caps (more roots than the count): the roots.
            return ex.roots.clone();
        }
        let filled = self.fill(ex, cut.clone(), &table, bounds[lo], r);
        // A count alone still short by more than a few is filled within SLACK times its
        // least worst error: where one feature no split brings nearer sets that error,
        // a bound a hair lower must not keep one primitive of the eight asked for
        // (docs/decisions/0054).
        let count_alone = r.tolerance.is_none() && r.bytes.is_none();
        if !count_alone || !crate::params::short_of(filled.len(), r.count, usize::MAX) {
            return filled;
        }
        let bound = SLACK * bounds[lo].max(worst(ex, &cut));
        let loose = self.costs(ex, bound, false);
        self.fill(ex, cut, &loose, bound, r)
    }

    /// The cut of fewest nodes (of least bytes with `by_bytes`) whose every node's
    /// error is at most `bound`, or where no cut of its subtree is, the least reached
    /// ([`Cutter::costs`]).
    pub(super) fn cheapest(&self, ex: &Explored, bound: f64, by_bytes: bool) -> Vec<u32> {
        let table = self.costs(ex, bound, by_bytes);
        collect(ex, &table, &ex.roots)
    }

    /// For every explored node, the cheapest cut of its subtree whose every node's
    /// error is at most the node's bound: `bound`, or the least worst error any cut of
    /// the explored subtree reaches if that is more (a leaf, or a split that does not
    /// help, is kept rather than made worse). One pass over the ids in increasing
    /// order sees children first.
    pub(super) fn costs(&self, ex: &Explored, bound: f64, by_bytes: bool) -> HashMap<u32, Cost> {
        let mut cost: HashMap<u32, Cost> = HashMap::with_capacity(ex.ids.len());
        let key = |c: &Cost| match by_bytes {
            true => (c.bytes, c.count),
            false => (c.count, c.bytes),
        };
        for &n in &ex.ids {
            let e = &ex.fitted[&n];
            let kids = ex.parts.get(&n).map(|parts| {
                parts.iter().fold(Cost::default(), |k, c| {
                    let c = cost[c];
                    Cost {
                        count: k.count + c.count,
                        bytes: k.bytes + c.bytes,
                        worst: k.worst.max(c.worst),
                        best: k.best.max(c.best),
                        own: false,
                    }
                })
            });
            let best = kids.map_or(e.error, |k| k.best.min(e.error));
            let limit = bound.max(best);
            let own = Cost {
                count: 1,
                bytes: e.bytes(),
                worst: e.error,
                best,
                own: true,
            };
            let chosen = match kids {
                Some(k) if k.worst <= limit && (e.error > limit || key(&k) < key(&own)) => k,
                _ => own,
            };
            cost.insert(n, Cost { best, ..chosen });
        }
        cost
    }

    /// `cut` with the splits of the sequence applied, in order, wherever the node is
    /// in the cut, the cheapest cut of its parts by `table` (`bound`'s costs)
    /// stays within `bound` (or the least the node's subtree reaches) and the caps
    /// still hold: the node is replaced by that cut.
    pub(super) fn fill(
        &self,
        ex: &Explored,
        cut: Vec<u32>,
        table: &HashMap<u32, Cost>,
        bound: f64,
        r: &Request,
    ) -> Vec<u32> {
        let (mut count, mut bytes) = totals(ex, &cut);
        let mut set: BTreeSet<u32> = cut.into_iter().collect();
        for &n in &ex.splits {
            if count >= r.count {
                break;
            }
            if !set.contains(&n) {
                continue;
            }
            let parts = &ex.parts[&n];
            let worst = parts.iter().map(|c| table[c].worst).fold(0.0, f64::max);
            if worst > bound.max(table[&n].best) {
                continue;
            }
            let sub = collect(ex, table, parts);
            let (c, b) = totals(ex, &sub);
            let more = bytes + b - ex.fitted[&n].bytes();
            if count + c - 1 > r.count || r.bytes.is_some_and(|cap| more > cap) {
                continue;
            }
            set.remove(&n);
            set.extend(sub);
            count += c - 1;
            bytes = more;
        }
        set.into_iter().collect()
    }

    /// Why `cut` stands over `r`'s tolerance, if it does: the count, where the count
    /// stopped the splits or a cut of the nodes reached is within it with more nodes;
    /// the bytes, where that cut needs more; else the faces ([`Shortfall`]).
    pub(super) fn shortfall(&self, ex: &Explored, r: &Request, cut: &[u32]) -> Option<Shortfall> {
        let t = r.tolerance?;
        if worst(ex, cut) <= t {
            return None;
        }
        let nearest = self.cheapest(ex, t, r.bytes.is_some());
        let (count, _) = totals(ex, &nearest);
        Some(match worst(ex, &nearest) <= t {
            true if count > r.count => Shortfall::Count,
            true => Shortfall::Bytes,
            false if ex.capped => Shortfall::Count,
            false => Shortfall::Faces,
        })
    }
}

/// The cheapest cuts of `from`'s subtrees by `table` ([`Cutter::costs`]), joined.
pub(super) fn collect(ex: &Explored, table: &HashMap<u32, Cost>, from: &[u32]) -> Vec<u32> {
    let mut cut = Vec::new();
    let mut stack: Vec<u32> = from.to_vec();
    while let Some(n) = stack.pop() {
        let c = table[&n];
        if c.own {
            cut.push(n);
        } else {
            stack.extend(&ex.parts[&n]);
        }
    }
    cut
}

/// Whether a cut of `c` = (nodes, bytes) meets `r`'s caps.
pub(crate) fn fits(r: &Request, c: (usize, usize)) -> bool {
    c.0 <= r.count && r.bytes.is_none_or(|b| c.1 <= b)
}

/// The largest error of the nodes of `cut`.
pub(super) fn worst(ex: &Explored, cut: &[u32]) -> f64 {
    cut.iter().map(|n| ex.fitted[n].error).fold(0.0, f64::max)
}

/// The node count and bytes of `cut`.
pub(super) fn totals(ex: &Explored, cut: &[u32]) -> (usize, usize) {
    (cut.len(), cut.iter().map(|n| ex.fitted[n].bytes()).sum())
}
