//! A bounding-volume hierarchy over items with axis-aligned boxes (triangles,
//! primitives, hulls), with exact nearest-item and containing-item queries, and the
//! exact point-to-triangle distance: the merge tree's node errors (`cut`) and
//! `primdecomp-eval`'s distance metrics both stand on it.
//!
//! Built by median splits on the longest axis of the item centroids (ties broken by
//! item index, so the tree is the same on every run); queried depth-first, nearer
//! child first, pruning nodes whose box is farther than the best distance so far (a
//! node exactly as far is visited, so the nearest item of least id is found whatever
//! the visiting order or the starting guess).

use crate::vec3::{add, cross, dot, norm, norm2, scale, sub, V3};
use rayon::prelude::*;
use std::sync::atomic::AtomicBool;

mod build;
pub use build::CHECK_AT;
#[cfg(test)]
use build::PARALLEL;
use build::{centre, leaf_box, Build, Centre, Coarse, Item, Sizes, Tied};

/// Items per leaf, at most, of [`Bvh::build`]'s hierarchies.
pub const LEAF: usize = 4;

#[derive(Clone, Copy, Debug, Default)]
struct Node<B> {
    b: B,
    /// Leaf: first item in `items`; inner: index of the left child (right = left + 1).
    first: u32,
    /// Leaf: item count; inner: 0.
    count: u32,
}

/// How a hierarchy stores its nodes' boxes: [`Exact`] or [`Compact`].
pub trait Bounds: Copy + Default + std::fmt::Debug + Send + Sync {
    /// Whether a stored box is its items' box itself (else it only holds it).
    const EXACT: bool;
    /// The stored form of the box `lo..hi`.
    fn of(lo: V3, hi: V3) -> Self;
    /// The stored box (holding the one it was made of).
    fn get(&self) -> (V3, V3);
}

/// A node's box as its items' (f64): 56 bytes a node.
#[derive(Clone, Copy, Debug, Default)]
pub struct Exact {
    lo: V3,
    hi: V3,
}

impl Bounds for Exact {
    const EXACT: bool = true;
    #[inline]
    fn of(lo: V3, hi: V3) -> Self {
        Exact { lo, hi }
    }
    #[inline]
    fn get(&self) -> (V3, V3) {
        (self.lo, self.hi)
    }
}

/// A node's box rounded outwards to f32: 32 bytes a node, a box that holds its
/// items'. A query pruned by it visits every node the exact box would and perhaps
/// more, so nearest items and first hits are the same; [`Bvh::slots_meeting`] tests
/// a leaf again on its items' own boxes.
#[derive(Clone, Copy, Debug, Default)]
pub struct Compact {
    lo: [f32; 3],
    hi: [f32; 3],
}

impl Bounds for Compact {
    const EXACT: bool = false;
    #[inline]
    fn of(lo: V3, hi: V3) -> Self {
        Compact {
            lo: lo.map(f32_below),
            hi: hi.map(|x| -f32_below(-x)),
        }
    }
    #[inline]
    fn get(&self) -> (V3, V3) {
        (self.lo.map(f64::from), self.hi.map(f64::from))
    }
}

/// The largest f32 at most `x` (−inf below f32's range, NaN as it is).
fn f32_below(x: f64) -> f32 {
    let f = x as f32;
    match f64::from(f) > x {
        true => f.next_down(),
        false => f,
    }
}

/// The hierarchy; item ids are indices into the caller's item list. Its nodes'
/// boxes are [`Exact`] unless built by [`Bvh::build_compact`].
#[derive(Clone, Debug, Default)]
pub struct Bvh<B = Exact> {
    nodes: Vec<Node<B>>,
    items: Vec<u32>,
}

/// Squared distance from `p` to the box `lo..hi` (0 inside).
#[inline]
pub fn box_dist2(p: V3, lo: V3, hi: V3) -> f64 {
    let mut d = 0.0;
    for k in 0..3 {
        let e = (lo[k] - p[k]).max(p[k] - hi[k]).max(0.0);
        d += e * e;
    }
    d
}

impl Bvh {
    /// Builds over `boxes[i] = (lo, hi)`, the two halves of large nodes in parallel
    /// (the same hierarchy on any thread count).
    pub fn build(boxes: &[(V3, V3)]) -> Bvh {
        Bvh::build_by(boxes.len(), LEAF, &|i| boxes[i as usize])
    }

    /// [`Bvh::build`] over `count` items whose boxes `bbox` gives, up to `leaf` items
    /// per leaf, with no table of boxes: each item's box is asked for twice (its
    /// centre, then its leaf's box). For large inputs queried a few times, where a
    /// table of boxes and small leaves would cost more memory than the queries save.
    pub fn build_by(count: usize, leaf: usize, bbox: &(dyn Fn(u32) -> (V3, V3) + Sync)) -> Bvh {
        Bvh::build_with::<Tied>(count, leaf, bbox, &|_| true).unwrap_or_default()
    }

    /// [`Bvh::build_by`] that asks `go_on` whether to go on before splitting each
    /// node of [`CHECK_AT`] items or more (a few milliseconds of work apart), and
    /// within such a node's median selection, and stops (`None`) when it says no: a
    /// large input's build answers a cancel. The same hierarchy either way.
    pub fn build_by_checked(
        count: usize,
        leaf: usize,
        bbox: &(dyn Fn(u32) -> (V3, V3) + Sync),
        go_on: &(dyn Fn(f64) -> bool + Sync),
    ) -> Option<Bvh> {
        Bvh::build_with::<Tied>(count, leaf, bbox, go_on)
    }

    /// The build over the exact (f64) centres kept in its table (28 bytes an item):
    /// the reference [`Tied`]'s builds are tested against.
    #[cfg(test)]
    pub(crate) fn build_f64(
        count: usize,
        leaf: usize,
        bbox: &(dyn Fn(u32) -> (V3, V3) + Sync),
    ) -> Bvh {
        Bvh::build_with::<V3>(count, leaf, bbox, &|_| true).unwrap_or_default()
    }
}

impl Bvh<Compact> {
    /// [`Bvh::build_by`] with the items' centres rounded to f32 for the splits and
    /// nothing decided on the exact ones, and the nodes' boxes [`Compact`]: a tree as
    /// good for queries whose answers do not depend on its shape (whether any item
    /// meets a ray), not the same tree, at 16 bytes an item while it is built and 32
    /// a node. It asks `go_on` whether to go on as [`Bvh::build_by_checked`] does.
    pub fn build_coarse(
        count: usize,
        leaf: usize,
        bbox: &(dyn Fn(u32) -> (V3, V3) + Sync),
        go_on: &(dyn Fn(f64) -> bool + Sync),
    ) -> Option<Bvh<Compact>> {
        Bvh::build_with::<Coarse>(count, leaf, bbox, go_on)
    }

    /// [`Bvh::build_by_checked`] (the same tree, items in the same order) with the
    /// nodes' boxes stored [`Compact`]: 32 bytes a node instead of 56, for a large
    /// hierarchy kept through a run.
    pub fn build_compact(
        count: usize,
        leaf: usize,
        bbox: &(dyn Fn(u32) -> (V3, V3) + Sync),
        go_on: &(dyn Fn(f64) -> bool + Sync),
    ) -> Option<Bvh<Compact>> {
        Bvh::build_with::<Tied>(count, leaf, bbox, go_on)
    }
}

impl<B: Bounds> Bvh<B> {
    /// The build, each item's centre kept as `C` keeps it; `None` when `go_on` said
    /// stop.
    fn build_with<C: Centre>(
        count: usize,
        leaf: usize,
        bbox: &(dyn Fn(u32) -> (V3, V3) + Sync),
        go_on: &(dyn Fn(f64) -> bool + Sync),
    ) -> Option<Bvh<B>> {
        if count == 0 {
            return Some(Bvh::default());
        }
        let leaf = leaf.max(1);
        let sizes = Sizes::new(count, leaf);
        let empty = Node::<B>::default();
        // Written a block at a time, asking between (two nodes for every few items:
        // at 56M items, a gigabyte and more).
        let total = sizes.nodes(count);
        let mut nodes = Vec::with_capacity(total);
        for n0 in (0..total).step_by(CHECK_AT << 4) {
            if n0 > 0 && !go_on(0.0) {
                return None;
            }
            nodes.resize((n0 + (CHECK_AT << 4)).min(total), empty);
        }
        let (root, below) = nodes.split_first_mut().expect("one node or more");
        // The splits move each item's centroid with its id, so that they read
        // memory in order; the boxes are read again for the leaves.
        // A block of items at a time, asking `go_on` between blocks (a build of
        // fewer items than one block asks only at its nodes).
        let mut span: Vec<Item<C>> = Vec::with_capacity(count);
        for i0 in (0..count).step_by(CHECK_AT << 4) {
            if i0 > 0 && !go_on(0.0) {
                return None;
            }
            let items = (i0 as u32..(i0 + (CHECK_AT << 4)).min(count) as u32).into_par_iter();
            span.par_extend(items.map(|i| Item {
                c: C::keep(centre(bbox(i))),
                id: i,
            }));
        }
        let build = Build {
            bbox,
            sizes,
            go_on,
            stopped: AtomicBool::new(false),
        };
        build.subtree(root, below, 1, &mut span, 0);
        if build.stopped.into_inner() {
            return None;
        }
        // The ids written over the table's own memory (an in-place collect: the
        // item's alignment is the id's) and the rest returned, so the ids add
        // nothing to the build's peak.
        let mut items: Vec<u32> = span.into_iter().map(|it| it.id).collect();
        items.shrink_to_fit();
        Some(Bvh { nodes, items })
    }

    /// The smallest `dist2(item)` over all items, with that item (or `u32::MAX` when
    /// empty). `dist2` must be at least the squared distance from `p` to the item's box.
    pub fn nearest(&self, p: V3, dist2: impl FnMut(u32) -> f64) -> (f64, u32) {
        self.nearest_with(p, &mut Vec::with_capacity(64), dist2)
    }

    /// [`Bvh::nearest`] with a reusable `stack` (scratch; its contents are replaced),
    /// for callers that query in a loop.
    pub fn nearest_with(
        &self,
        p: V3,
        stack: &mut Vec<(f64, u32)>,
        dist2: impl FnMut(u32) -> f64,
    ) -> (f64, u32) {
        self.nearest_until(p, f64::NEG_INFINITY, stack, dist2)
    }

    /// [`Bvh::nearest_with`] that stops at the first item with `dist2` at most `enough`:
    /// the exact nearest when it is farther than `enough`, otherwise some item within
    /// it. For a running maximum of distances, where a point no farther than the
    /// maximum so far cannot change it.
    pub fn nearest_until(
        &self,
        p: V3,
        enough: f64,
        stack: &mut Vec<(f64, u32)>,
        mut dist2: impl FnMut(u32) -> f64,
    ) -> (f64, u32) {
        let items = &self.items;
        let (d, slot) = self.nearest_slot(p, enough, u32::MAX, stack, |k| dist2(items[k as usize]));
        (d, items.get(slot as usize).copied().unwrap_or(u32::MAX))
    }

    /// The items in the hierarchy's order: a leaf's items side by side. A caller
    /// that stores its items in this order reads them in order ([`Bvh::nearest_slot`]).
    pub fn order(&self) -> &[u32] {
        &self.items
    }

    /// [`Bvh::nearest_until`] with items named by their slot, their position in
    /// [`Bvh::order`] (`dist2` gets a slot and the answer is one), searched from the
    /// slot `start` (a guess: the nearer it is, the less is visited; `u32::MAX` for
    /// none). The nearest item of least id, whatever the guess.
    pub fn nearest_slot(
        &self,
        p: V3,
        enough: f64,
        start: u32,
        stack: &mut Vec<(f64, u32)>,
        mut dist2: impl FnMut(u32) -> f64,
    ) -> (f64, u32) {
        let mut best = (f64::INFINITY, u32::MAX);
        let mut best_id = u32::MAX;
        if self.nodes.is_empty() {
            return best;
        }
        if let Some(&id) = self.items.get(start as usize) {
            (best, best_id) = ((dist2(start), start), id);
        }
        stack.clear();
        stack.push((0.0, 0));
        while let Some((d, n)) = stack.pop() {
            if d > best.0 {
                continue;
            }
            let node = self.nodes[n as usize];
            if node.count > 0 {
                for k in node.first..node.first + node.count {
                    let (di, i) = (dist2(k), self.items[k as usize]);
                    if di < best.0 || (di == best.0 && i < best_id) {
                        (best, best_id) = ((di, k), i);
                    }
                }
                if best.0 <= enough {
                    return best;
                }
                continue;
            }
            let (l, r) = (node.first, node.first + 1);
            let dl = self.node_dist2(l, p);
            let dr = self.node_dist2(r, p);
            // Push the farther child first so the nearer one is visited next.
            if dl <= dr {
                stack.extend([(dr, r), (dl, l)]);
            } else {
                stack.extend([(dl, l), (dr, r)]);
            }
        }
        best
    }

    fn node_dist2(&self, n: u32, p: V3) -> f64 {
        let (lo, hi) = self.nodes[n as usize].b.get();
        box_dist2(p, lo, hi)
    }

    /// Whether `test(item)` holds for some item whose box, grown by `grow`, holds `p`.
    pub fn any_at(&self, p: V3, grow: f64, mut test: impl FnMut(u32) -> bool) -> bool {
        if self.nodes.is_empty() {
            return false;
        }
        let g2 = grow.max(0.0) * grow.max(0.0);
        let mut stack: Vec<u32> = Vec::with_capacity(64);
        stack.push(0);
        while let Some(n) = stack.pop() {
            let node = self.nodes[n as usize];
            let (lo, hi) = node.b.get();
            if box_dist2(p, lo, hi) > g2 {
                continue;
            }
            if node.count == 0 {
                stack.extend([node.first, node.first + 1]);
                continue;
            }
            let span = node.first as usize..(node.first + node.count) as usize;
            if self.items[span].iter().any(|&i| test(i)) {
                return true;
            }
        }
        false
    }

    /// The slots ([`Bvh::order`]) of the items of every leaf whose box meets the box
    /// `lo..hi` (so every item whose own box meets it, and perhaps some more), into
    /// `out` in slot order; or `false` (and `out` partly filled) once there are more
    /// than `most`. `slot_box` gives the box of the item in a slot, as the build was
    /// given it: a [`Compact`] leaf is tested again on its items' boxes, so the
    /// slots are those of an [`Exact`] hierarchy. `stack` is scratch.
    pub fn slots_meeting(
        &self,
        (lo, hi): (V3, V3),
        most: usize,
        slot_box: impl Fn(u32) -> (V3, V3),
        stack: &mut Vec<u32>,
        out: &mut Vec<u32>,
    ) -> bool {
        out.clear();
        stack.clear();
        if !self.nodes.is_empty() {
            stack.push(0);
        }
        let meets = |(a, b): (V3, V3)| (0..3).all(|k| a[k] <= hi[k] && lo[k] <= b[k]);
        while let Some(n) = stack.pop() {
            let node = self.nodes[n as usize];
            if !meets(node.b.get()) {
                continue;
            }
            if !B::EXACT && node.count > 0 && !meets(leaf_box(node.first, node.count, &slot_box)) {
                continue;
            }
            if node.count == 0 {
                // Right first, so the left is visited next: slots come out in order.
                stack.extend([node.first + 1, node.first]);
                continue;
            }
            out.extend(node.first..node.first + node.count);
            if out.len() > most {
                return false;
            }
        }
        true
    }

    /// The least `hit(item)` (a distance along the ray `o + t·d`, `None` for a miss)
    /// over the items whose box the ray meets for some `t` in `[0, tmax]`, capped at
    /// `tmax`, with that item (`u32::MAX` when none is nearer). `stack` is scratch.
    pub fn ray_first(
        &self,
        o: V3,
        d: V3,
        tmax: f64,
        stack: &mut Vec<u32>,
        mut hit: impl FnMut(u32) -> Option<f64>,
    ) -> (f64, u32) {
        let items = &self.items;
        let (t, slot) = self.ray_slot_first(o, d, tmax, stack, |k| hit(items[k as usize]));
        (t, items.get(slot as usize).copied().unwrap_or(u32::MAX))
    }

    /// [`Bvh::ray_first`] with items named by their slot ([`Bvh::order`]), as
    /// [`Bvh::nearest_slot`] names them.
    pub fn ray_slot_first(
        &self,
        o: V3,
        d: V3,
        tmax: f64,
        stack: &mut Vec<u32>,
        mut hit: impl FnMut(u32) -> Option<f64>,
    ) -> (f64, u32) {
        let mut best = (tmax, u32::MAX);
        let mut best_id = u32::MAX;
        if self.nodes.is_empty() {
            return best;
        }
        let inv = d.map(|c| 1.0 / c);
        stack.clear();
        stack.push(0);
        while let Some(n) = stack.pop() {
            let node = self.nodes[n as usize];
            let (lo, hi) = node.b.get();
            if !ray_meets_box(o, inv, best.0, lo, hi) {
                continue;
            }
            if node.count == 0 {
                stack.extend([node.first, node.first + 1]);
                continue;
            }
            for k in node.first..node.first + node.count {
                let i = self.items[k as usize];
                match hit(k) {
                    Some(t) if t < best.0 || (t == best.0 && i < best_id) => {
                        (best, best_id) = ((t, k), i);
                    }
                    _ => {}
                }
            }
        }
        best
    }
}

impl<B: Bounds> Bvh<B> {
    /// Whether `hit(item)` holds for some item whose box the ray `o + t·d` meets for
    /// some `t` in `[0, tmax]`; stops at the first. `stack` is scratch.
    pub fn ray_any(
        &self,
        o: V3,
        d: V3,
        tmax: f64,
        stack: &mut Vec<u32>,
        mut hit: impl FnMut(u32) -> bool,
    ) -> bool {
        if self.nodes.is_empty() {
            return false;
        }
        let inv = d.map(|c| 1.0 / c);
        stack.clear();
        stack.push(0);
        while let Some(n) = stack.pop() {
            let node = self.nodes[n as usize];
            let (lo, hi) = node.b.get();
            if !ray_meets_box(o, inv, tmax, lo, hi) {
                continue;
            }
            if node.count == 0 {
                stack.extend([node.first, node.first + 1]);
                continue;
            }
            let span = node.first as usize..(node.first + node.count) as usize;
            if self.items[span].iter().any(|&i| hit(i)) {
                return true;
            }
        }
        false
    }
}

/// Whether the ray `o + t·d` (`inv` = 1/d componentwise) meets the box `lo..hi` for
/// some `t` in `[0, tmax]` (slab test; a zero component of `d` gives ±inf in `inv`).
fn ray_meets_box(o: V3, inv: V3, tmax: f64, lo: V3, hi: V3) -> bool {
    let (mut t0, mut t1) = (0.0_f64, tmax);
    for k in 0..3 {
        let (a, b) = ((lo[k] - o[k]) * inv[k], (hi[k] - o[k]) * inv[k]);
        let (a, b) = if a <= b { (a, b) } else { (b, a) };
        // NaN (0 · inf: the ray in the slab's plane) keeps the bound as it is.
        t0 = if a > t0 { a } else { t0 };
        t1 = if b < t1 { b } else { t1 };
    }
    t0 <= t1
}

/// Where the ray `o + t·d` meets triangle `t` (Möller–Trumbore), if at some `t > tmin`.
pub fn ray_tri(o: V3, d: V3, t: &[V3; 3], tmin: f64) -> Option<f64> {
    let (e1, e2) = (sub(t[1], t[0]), sub(t[2], t[0]));
    let p = cross(d, e2);
    let det = dot(e1, p);
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    let s = sub(o, t[0]);
    let u = dot(s, p) / det;
    let q = cross(s, e1);
    let v = dot(d, q) / det;
    let at = dot(e2, q) / det;
    (u >= 0.0 && v >= 0.0 && u + v <= 1.0 && at > tmin).then_some(at)
}

/// Box of a triangle.
pub fn tri_box(t: &[V3; 3]) -> (V3, V3) {
    let mut lo = t[0];
    let mut hi = t[0];
    for v in &t[1..] {
        for k in 0..3 {
            lo[k] = lo[k].min(v[k]);
            hi[k] = hi[k].max(v[k]);
        }
    }
    (lo, hi)
}

/// Squared distance from `p` to the closest point of triangle `t` (Ericson,
/// Real-Time Collision Detection §5.1.5: Voronoi regions of vertices, edges, face).
pub fn point_tri_dist2(p: V3, t: &[V3; 3]) -> f64 {
    let [a, b, c] = *t;
    let (ab, ac, ap) = (sub(b, a), sub(c, a), sub(p, a));
    let (d1, d2) = (dot(ab, ap), dot(ac, ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return norm2(ap);
    }
    let bp = sub(p, b);
    let (d3, d4) = (dot(ab, bp), dot(ac, bp));
    if d3 >= 0.0 && d4 <= d3 {
        return norm2(bp);
    }
    // An edge's region is taken only if the edge has length (d1 - d3 is its squared
    // length, and so below): where two corners coincide its parameter would be 0/0,
    // and a NaN distance passes every comparison. Such a triangle is its segment
    // (the degenerate case at the end).
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 && d1 - d3 > 0.0 {
        let v = d1 / (d1 - d3);
        return norm2(sub(ap, scale(ab, v)));
    }
    let cp = sub(p, c);
    let (d5, d6) = (dot(ab, cp), dot(ac, cp));
    if d6 >= 0.0 && d5 <= d6 {
        return norm2(cp);
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 && d2 - d6 > 0.0 {
        let w = d2 / (d2 - d6);
        return norm2(sub(ap, scale(ac, w)));
    }
    let va = d3 * d6 - d5 * d4;
    let bc = (d4 - d3) + (d5 - d6);
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 && bc > 0.0 {
        let w = (d4 - d3) / bc;
        return norm2(sub(bp, scale(sub(c, b), w)));
    }
    let denom = va + vb + vc;
    if denom <= 0.0 || !denom.is_finite() {
        // Degenerate triangle: the nearest of its three edges.
        return [(a, b), (b, c), (c, a)]
            .iter()
            .map(|&(s, e)| point_segment_dist2(p, s, e))
            .fold(f64::INFINITY, f64::min);
    }
    let (v, w) = (vb / denom, vc / denom);
    norm2(sub(ap, add(scale(ab, v), scale(ac, w))))
}

/// Whether triangles `a` and `b` are certainly apart: some axis of the separating-axis
/// test (either normal, the cross product of an edge of each, or an edge's normal in
/// its triangle's plane, for triangles in one plane) leaves a gap of more than
/// `margin` between their projections (measured along the unit axis). False for
/// triangles that meet, and perhaps for some a little more than `margin` apart (an
/// axis too short to normalise is skipped): a proof of a gap, never of contact.
pub fn tris_apart(a: &[V3; 3], b: &[V3; 3], margin: f64) -> bool {
    let edges = |t: &[V3; 3]| [sub(t[1], t[0]), sub(t[2], t[1]), sub(t[0], t[2])];
    let (ea, eb) = (edges(a), edges(b));
    let (na, nb) = (cross(ea[0], ea[1]), cross(eb[0], eb[1]));
    let gap = |axis: V3| {
        let len = norm(axis);
        if !(len > 1e-300 && len.is_finite()) {
            return false;
        }
        let span = |t: &[V3; 3]| {
            let d = t.map(|v| dot(v, axis));
            (d[0].min(d[1]).min(d[2]), d[0].max(d[1]).max(d[2]))
        };
        let ((lo_a, hi_a), (lo_b, hi_b)) = (span(a), span(b));
        lo_b - hi_a > margin * len || lo_a - hi_b > margin * len
    };
    gap(na)
        || gap(nb)
        || ea.iter().any(|&u| eb.iter().any(|&v| gap(cross(u, v))))
        || ea.iter().any(|&u| gap(cross(na, u)))
        || eb.iter().any(|&v| gap(cross(nb, v)))
}

/// Squared distance from `p` to the segment `a`–`b`.
pub fn point_segment_dist2(p: V3, a: V3, b: V3) -> f64 {
    let ab = sub(b, a);
    let l2 = norm2(ab);
    let ap = sub(p, a);
    let t = if l2 > 0.0 {
        (dot(ap, ab) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    norm2(sub(ap, scale(ab, t)))
}

#[cfg(test)]
mod tests;
