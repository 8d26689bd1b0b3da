//! Building a [`Bvh`](super::Bvh): median splits of the item centroids on their
//! longest axis, ties broken by the exact centre and then the item index, the two
//! halves of a large node built in parallel, a stop asked for between (and inside)
//! the large selections.

use super::{Bounds, Node};
use crate::vec3::{add, scale, V3};
use std::cmp::Ordering;
#[cfg(panic = "unwind")]
use std::panic::AssertUnwindSafe;
use std::sync::atomic::{AtomicBool, Ordering::Relaxed};

/// Nodes of at least this many items build their two halves in parallel.
pub(super) const PARALLEL: usize = 4096;

/// How many nodes the hierarchy over a count of items has: a median split halves
/// it, so the count fixes the shape. Looked up below [`PARALLEL`] items.
pub(super) struct Sizes {
    pub(super) table: Vec<usize>,
    /// Items per leaf, at most.
    pub(super) leaf: usize,
}

impl Sizes {
    pub(super) fn new(items: usize, leaf: usize) -> Sizes {
        let mut table = vec![1; items.min(PARALLEL) + 1];
        for c in leaf + 1..table.len() {
            table[c] = 1 + table[c / 2] + table[c - c / 2];
        }
        Sizes { table, leaf }
    }

    pub(super) fn nodes(&self, count: usize) -> usize {
        match self.table.get(count) {
            Some(&n) => n,
            None => 1 + self.nodes(count / 2) + self.nodes(count - count / 2),
        }
    }
}

/// Nodes of at least this many items ask whether to go on before they split.
pub const CHECK_AT: usize = 1 << 16;

/// What building a subtree reads.
pub(super) struct Build<'a> {
    pub(super) bbox: &'a (dyn Fn(u32) -> (V3, V3) + Sync),
    pub(super) sizes: Sizes,
    pub(super) go_on: &'a (dyn Fn(f64) -> bool + Sync),
    /// `go_on` said stop: the nodes left are not built.
    pub(super) stopped: AtomicBool,
}

/// An item being placed: its box's centroid as the build keeps it and its id,
/// packed (16 bytes with an f32 centroid, the build's largest table; 28 with an f64
/// one).
#[derive(Clone, Copy)]
#[repr(C, packed(4))]
pub(super) struct Item<C> {
    pub(super) c: C,
    pub(super) id: u32,
}

/// The centre of the box `(lo, hi)`, as every build computes it.
#[inline]
pub(super) fn centre((lo, hi): (V3, V3)) -> V3 {
    scale(add(lo, hi), 0.5)
}

/// A centroid as a build keeps it: in f64 (the reference, in tests), rounded to
/// f32 with what the rounding ties decided on the exact centre ([`Tied`]), or
/// rounded to f32 alone ([`Coarse`], [`Bvh::build_coarse`]).
pub(super) trait Centre: Copy + Send + Sync {
    /// Whether an order or extreme the kept centres leave tied (or NaN) is decided
    /// on the exact centres, computed again from the item's box.
    const TIES_EXACT: bool;
    fn keep(c: V3) -> Self;
    fn at(&self, k: usize) -> f64;
}

#[cfg(test)]
impl Centre for V3 {
    const TIES_EXACT: bool = false;
    #[inline]
    fn keep(c: V3) -> Self {
        c
    }
    #[inline]
    fn at(&self, k: usize) -> f64 {
        self[k]
    }
}

/// A centroid rounded to f32 for a build whose tree is that of the exact centres:
/// rounding to nearest keeps order (`a < b` gives `round(a) <= round(b)`, signs
/// kept), so two items whose rounded centres differ on an axis are in the exact
/// centres' order, and an axis's least (greatest) exact centre is among the items
/// whose rounded one is least (greatest). What the rounded ones tie is decided on
/// the exact centres: every comparison, so every selection and extent, and so the
/// tree and its order, is the exact build's, at 16 bytes an item instead of 28.
#[derive(Clone, Copy)]
pub(super) struct Tied([f32; 3]);

impl Centre for Tied {
    const TIES_EXACT: bool = true;
    #[inline]
    fn keep(c: V3) -> Self {
        Tied(c.map(|x| x as f32))
    }
    #[inline]
    fn at(&self, k: usize) -> f64 {
        f64::from(self.0[k])
    }
}

/// A centroid rounded to f32, nothing decided on the exact one ([`Bvh::build_coarse`]).
#[derive(Clone, Copy)]
pub(super) struct Coarse([f32; 3]);

impl Centre for Coarse {
    const TIES_EXACT: bool = false;
    #[inline]
    fn keep(c: V3) -> Self {
        Coarse(c.map(|x| x as f32))
    }
    #[inline]
    fn at(&self, k: usize) -> f64 {
        f64::from(self.0[k])
    }
}

impl Build<'_> {
    /// Builds the subtree over `span` (the item list's entries from `first` on) into
    /// `node`, its descendants into `below` (whose first node has index `at`): a
    /// node's children side by side, then the left child's descendants, then the
    /// right's. Split at the median of the item centroids on their longest axis; a
    /// node's box is its items' (a leaf) or its children's.
    pub(super) fn subtree<C: Centre, B: Bounds>(
        &self,
        node: &mut Node<B>,
        below: &mut [Node<B>],
        at: usize,
        span: &mut [Item<C>],
        first: usize,
    ) {
        let count = span.len();
        if count <= self.sizes.leaf {
            let (lo, hi) = union(span.iter().map(|it| (self.bbox)(it.id)));
            node.b = B::of(lo, hi);
            (node.first, node.count) = (first as u32, count as u32);
            return;
        }
        if count >= CHECK_AT && (self.stopped.load(Relaxed) || !(self.go_on)(0.0)) {
            self.stopped.store(true, Relaxed);
            return;
        }
        let (clo, chi) = self.centre_range(span);
        let axis = (0..3)
            .max_by(|&a, &b| (chi[a] - clo[a]).total_cmp(&(chi[b] - clo[b])))
            .unwrap_or(0);
        let mid = count / 2;
        let by_axis = |a: &Item<C>, b: &Item<C>| {
            let (ca, cb) = ({ a.c }.at(axis), { b.c }.at(axis));
            let order = ca.total_cmp(&cb);
            let tied = order == Ordering::Equal || ca.is_nan() || cb.is_nan();
            let order = match C::TIES_EXACT && tied {
                true => self.centre(a.id)[axis].total_cmp(&self.centre(b.id)[axis]),
                false => order,
            };
            order.then({ a.id }.cmp(&{ b.id }))
        };
        if !self.select(span, mid, by_axis) {
            self.stopped.store(true, Relaxed);
            return;
        }
        (node.first, node.count) = (at as u32, 0);
        let (kids, rest) = below.split_at_mut(2);
        let (left, right) = kids.split_at_mut(1);
        let left_below = self.sizes.nodes(mid) - 1;
        let (below_l, below_r) = rest.split_at_mut(left_below);
        let (span_l, span_r) = span.split_at_mut(mid);
        let at_r = at + 2 + left_below;
        let (l, r) = (&mut left[0], &mut right[0]);
        let mut build_l = || self.subtree(l, below_l, at + 2, span_l, first);
        let mut build_r = || self.subtree(r, below_r, at_r, span_r, first + mid);
        match count >= PARALLEL {
            true => rayon::join(build_l, build_r),
            false => (build_l(), build_r()),
        };
        let (lo, hi) = union([left[0].b.get(), right[0].b.get()].into_iter());
        node.b = B::of(lo, hi);
    }
}

impl Build<'_> {
    /// Item `id`'s exact centre.
    #[inline]
    pub(super) fn centre(&self, id: u32) -> V3 {
        centre((self.bbox)(id))
    }

    /// The least and greatest centre of `span`'s items on each axis, as the exact
    /// centres give them (the same folds over the same values in the same order:
    /// where the kept centres are rounded, over the items whose rounded centre is
    /// the least or greatest, the others standing strictly beyond).
    pub(super) fn centre_range<C: Centre>(&self, span: &[Item<C>]) -> (V3, V3) {
        let (mut clo, mut chi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for it in span.iter() {
            for k in 0..3 {
                let c = { it.c }.at(k);
                (clo[k], chi[k]) = (clo[k].min(c), chi[k].max(c));
            }
        }
        if !C::TIES_EXACT {
            return (clo, chi);
        }
        let (rlo, rhi) = (clo, chi);
        let (mut clo, mut chi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for it in span.iter() {
            let c = { it.c };
            let (low, high): ([bool; 3], [bool; 3]) = (
                std::array::from_fn(|k| c.at(k) == rlo[k]),
                std::array::from_fn(|k| c.at(k) == rhi[k]),
            );
            if !(low.contains(&true) || high.contains(&true)) {
                continue;
            }
            let e = self.centre(it.id);
            for k in 0..3 {
                if low[k] {
                    clo[k] = clo[k].min(e[k]);
                }
                if high[k] {
                    chi[k] = chi[k].max(e[k]);
                }
            }
        }
        (clo, chi)
    }
}

/// The box holding `boxes` (empty: lo +inf, hi −inf).
pub(super) fn union(boxes: impl Iterator<Item = (V3, V3)>) -> (V3, V3) {
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for (blo, bhi) in boxes {
        for k in 0..3 {
            (lo[k], hi[k]) = (lo[k].min(blo[k]), hi[k].max(bhi[k]));
        }
    }
    (lo, hi)
}

/// The box of a leaf's items, `count` slots from `first`, as the build made it.
pub(super) fn leaf_box(first: u32, count: u32, slot_box: &impl Fn(u32) -> (V3, V3)) -> (V3, V3) {
    union((first..first + count).map(slot_box))
}

/// Comparisons of a node's median selection between two asks of `go_on` (tens of
/// milliseconds of work).
#[cfg(panic = "unwind")]
pub(super) const COMPARES_PER_CHECK: u64 = 1 << 22;

/// A stop asked for inside a selection's comparison, unwound to [`Build::select`].
#[cfg(panic = "unwind")]
pub(super) struct Stopped;

impl Build<'_> {
    /// `span.select_nth_unstable_by(mid, cmp)`: the same call, so the same order of
    /// the items (which decides the order inside the leaves). A node of [`CHECK_AT`]
    /// items or more asks `go_on` every [`COMPARES_PER_CHECK`] comparisons (the
    /// root's selection over every item is otherwise seconds long at 56M items);
    /// where it says stop the selection is left by unwinding (`resume_unwind`: no
    /// panic hook runs, nothing is printed), `span` stays a permutation of its
    /// items and the result is false. A build without unwinding (`panic = "abort"`)
    /// asks only before each split.
    pub(super) fn select<T>(
        &self,
        span: &mut [T],
        mid: usize,
        cmp: impl Fn(&T, &T) -> Ordering,
    ) -> bool {
        #[cfg(panic = "unwind")]
        if span.len() >= CHECK_AT {
            let mut compares = 0u64;
            let checked = |a: &T, b: &T| {
                compares += 1;
                if compares % COMPARES_PER_CHECK == 0 && !(self.go_on)(0.0) {
                    std::panic::resume_unwind(Box::new(Stopped));
                }
                cmp(a, b)
            };
            let run = AssertUnwindSafe(|| {
                span.select_nth_unstable_by(mid, checked);
            });
            return match std::panic::catch_unwind(run) {
                Ok(()) => true,
                Err(stop) if stop.is::<Stopped>() => false,
                Err(other) => std::panic::resume_unwind(other),
            };
        }
        span.select_nth_unstable_by(mid, cmp);
        true
    }
}
