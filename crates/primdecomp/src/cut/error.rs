//! A node's error: the one-way distance from its primitive's surface to the input's
//! surface, the quantity `primdecomp eval` reports as Hausdorff (there over the union
//! of the output; here over one primitive, so an upper bound of its share). Bounded,
//! not sampled (docs/decisions/0040): the primitive's conservative tessellation
//! (`output::tessellate`) is cut into triangles and refined best-first, the triangle
//! of largest bound cut in two across its longest edge. The distance to the input is
//! 1-Lipschitz, so over a triangle it is at most its centroid's distance plus the
//! centroid's farthest vertex; and the distance to one triangle is convex, so over a
//! triangle it is at most the largest of its vertices' distances to the input
//! triangle nearest its centroid (tight where a face lies flush on the input). A
//! round primitive's cell, once its search has run long, is also bounded by its
//! shadow (`cut::cell_shadow`, docs/decisions/0047): tight over a few input facets.
//! Centroids and vertices measured give lower bounds; a round primitive's own surface
//! lies within a known gap of its tessellation, which is added. Measured to the
//! nearest input triangle anywhere in the mesh (`input::triangles`): the whole mesh, as
//! eval measures, not only the node's faces, so a primitive lying on another part's
//! surface is not charged for it, and one hierarchy serves every node.
//!
//! Under `--solid` (`Triangles::with_solid`, docs/decisions/0056) the distance is to
//! the input's solid, what merges are priced against: a solid part's faces that lie
//! inside the input (where two parts meet) stand at 0, not at their distance to the
//! surface. That distance is 1-Lipschitz too and never above the surface's, so every
//! bound above still bounds it; besides, a point proven inside (`Triangles::inside`)
//! measures 0, and so does the ball around it that meets no face: a cell whose
//! centroid is proven inside is bounded by how far it reaches beyond that ball.

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use rayon::prelude::*;

use super::cell_shadow;
use crate::input::triangles::Triangles;
use crate::math::bvh::point_segment_dist2;
use crate::math::{add, madd, norm, scale, sub, V3};
use crate::output::tessellate;
use crate::primitive::Primitive;

/// Segments around circles of the tessellation (its polygons stand at most
/// 1/cos(π/24) − 1 ≈ 0.9% of a radius outside a round primitive, its balls' about
/// 1.7%),
const DETAIL: usize = 24;
/// doubled (at most twice) until that is at most this fraction of the diagonal.
const GAP: f64 = 1e-3;
/// The bound is refined until it is within this fraction of the largest distance
/// measured,
const RELATIVE: f64 = 0.02;
/// or within this fraction of the mesh's diagonal,
const ABSOLUTE: f64 = 2e-4;
/// or this many triangles have been split (then the bound, looser, stands).
const MAX_SPLITS: usize = 16384;
/// A search splits this many cells before it tries their shadows (`cut::cell_shadow`).
const SHADOW_AFTER: usize = 512;
/// Shadows stop being tried in a search where fewer than one in this many gave a
/// bound (after the first [`SHADOW_TRIAL`]).
const SHADOW_RATE: u32 = 8;
/// A cell's [`Cell::shade`] when its shadow has nothing to add.
const SHADED: u8 = u8::MAX;
/// Where a cell's shadow gave nothing, its halves wait this many splits.
const RETRY: u8 = 2;
/// Shadows are tried this many times in a search before [`SHADOW_RATE`] may stop them.
const SHADOW_TRIAL: u32 = 64;
/// Under `--solid`, a cell whose centroid is inside is tested against at most this
/// many input triangles near it for lying wholly inside (`Triangles::apart`),
const APART_MOST: usize = 32;
/// shrunk towards its centroid by this share: a face may touch it (a solid box's
/// face meets the surface along its edges), and the cell stands within this share of
/// its size of the shrunk cell.
const SHRINK: f64 = 1e-4;
/// A level's search settles its primitives together in at most this many rounds
/// ([`worst_error`]); then the bounds found stand.
const ROUNDS: usize = 64;

/// An upper bound of the error of `prim` (0 for an empty surface), within
/// [`RELATIVE`] of it or [`ABSOLUTE`] of the diagonal.
#[cfg(test)]
pub(crate) fn error_of(prim: &Primitive, surface: &Triangles) -> f64 {
    error_until(prim, surface, StopAt::exact(0.0))
}

/// Whether `prim` is certainly within `bound` of the input, found with no more
/// refinement than that answer needs.
pub(crate) fn is_within(prim: &Primitive, surface: &Triangles, bound: f64) -> bool {
    let ask = StopAt {
        level: bound,
        above: bound,
        coarse: true,
    };
    error_until(prim, surface, ask) <= bound
}

/// How far to refine [`error_until`]'s bound.
#[derive(Clone, Copy, Debug)]
pub(crate) struct StopAt {
    /// A bound near `level` is refined until it is on one side of it (or the
    /// refinement runs out): at most `level` only if the error is, and over it only
    /// if the error is over it or the error is within [`RELATIVE`] of `level` and
    /// bounds could not tell.
    pub level: f64,
    /// Once a point is found over `above`, its distance is returned (a lower bound).
    pub above: f64,
    /// Once the bound is at most `level`, it is returned (some upper bound at most
    /// `level`, not refined further).
    pub coarse: bool,
}

impl StopAt {
    /// Refined to [`RELATIVE`] (and settled against `level`), no early exit.
    #[cfg(test)]
    pub(crate) fn exact(level: f64) -> StopAt {
        StopAt {
            level,
            above: f64::INFINITY,
            coarse: false,
        }
    }
}

/// An upper bound of the error of `prim`, refined best-first as `ask` says. Results
/// at most `ask.level` mean the error is; results over `ask.above` mean it is over.
pub(crate) fn error_until(prim: &Primitive, surface: &Triangles, ask: StopAt) -> f64 {
    error_until_checked(prim, surface, ask, &|| true)
}

/// [`error_until`] asking `go_on` every [`SPLITS_PER_CHECK`] splits; once it says
/// stop, the bound as it stands (a number for a run that keeps nothing).
pub(crate) fn error_until_checked(
    prim: &Primitive,
    surface: &Triangles,
    ask: StopAt,
    go_on: &(dyn Fn() -> bool + Sync),
) -> f64 {
    let mut search = Refinement {
        go_on,
        ..Refinement::new(surface)
    };
    let start = Start::of(prim, surface, ask.above, &mut search.scratch);
    search.take(start);
    search.run(ask, MAX_SPLITS)
}

/// The largest error of `prims` (0 for none): an upper bound within [`RELATIVE`] (or
/// [`ABSOLUTE`] of the diagonal) of the farthest point measured on any of them, and
/// at most `level` only if every primitive is within it. `known[i]` is an upper bound
/// of `prims[i]`'s error proved before (infinite where none was): a primitive is
/// refined only while that is over the round's threshold. Settled in rounds, each
/// primitive's search on its own thread: a round refines every unsettled primitive
/// until its bound is within the round's threshold (from the farthest point measured
/// before it) or a point beyond that is found; then the threshold is raised from that
/// point and the unsettled go on. Only the threshold is shared, so the answer does
/// not depend on the threads, and only primitives near the largest are refined far.
pub(crate) fn worst_error(
    prims: &[Primitive],
    known: &[f64],
    surface: &Triangles,
    level: f64,
) -> f64 {
    let mut searches: Vec<(Refinement, Option<f64>)> = prims
        .par_iter()
        .map(|p| {
            let mut search = Refinement::new(surface);
            let start = Start::of(p, surface, f64::INFINITY, &mut search.scratch);
            search.take(start);
            (search, None)
        })
        .collect();
    let mut low = searches.iter().map(|(s, _)| s.low).fold(0.0, f64::max);
    for _ in 0..ROUNDS {
        let t = threshold(low, level, ABSOLUTE * surface.diagonal);
        let ask = StopAt {
            level: t,
            above: t,
            coarse: true,
        };
        searches
            .par_iter_mut()
            .zip(known)
            .filter(|((_, settled), _)| settled.is_none())
            .for_each(|((search, settled), &known)| {
                // A bound proved before, within the threshold, settles it as it is.
                let bound = match known <= t {
                    true => known.max(search.low),
                    false => search.run(ask, MAX_SPLITS),
                };
                // Over `t` only by a point found beyond it, unless the splits ran out.
                if search.low <= t {
                    *settled = Some(bound);
                    search.heap = BinaryHeap::new();
                }
            });
        let raised = searches.iter().map(|(s, _)| s.low).fold(low, f64::max);
        if raised == low {
            break;
        }
        low = raised;
    }
    searches
        .iter()
        .map(|(s, settled)| settled.unwrap_or_else(|| s.bound()))
        .fold(low, f64::max)
}

/// The largest bound [`worst_error`] may answer with when the farthest point
/// measured is `low`: within [`RELATIVE`] of it (or `slack`), and at most `level`
/// while `low` is.
fn threshold(low: f64, level: f64, slack: f64) -> f64 {
    let close = low + slack.max(RELATIVE * low);
    match low <= level {
        true => close.min(level),
        false => close,
    }
}

/// A best-first search for the largest distance over a set of triangles: the cells
/// by bound, the largest distance measured, the splits made.
struct Refinement<'a> {
    surface: &'a Triangles<'a>,
    heap: BinaryHeap<Cell>,
    low: f64,
    splits: usize,
    shadows: Shadows,
    scratch: Scratch,
    /// Asked every [`SPLITS_PER_CHECK`] splits whether to go on: a search over a
    /// large primitive near millions of faces runs for seconds.
    go_on: &'a (dyn Fn() -> bool + Sync),
}

/// Splits of a search between two asks of its `go_on`.
const SPLITS_PER_CHECK: usize = 64;

/// How often a search's shadows were tried, and how often they gave a bound.
#[derive(Default)]
struct Shadows {
    tried: u32,
    helped: u32,
}

impl Shadows {
    /// Whether to try another after `splits` splits: once the search has run long,
    /// and while one in [`SHADOW_RATE`] gives a bound.
    fn worth(&self, splits: usize) -> bool {
        splits >= SHADOW_AFTER
            && (self.tried < SHADOW_TRIAL || self.helped * SHADOW_RATE >= self.tried)
    }

    fn count(&mut self, helped: bool) {
        self.tried += 1;
        self.helped += u32::from(helped);
    }
}

/// Reusable space for a search's measures.
#[derive(Default)]
struct Scratch {
    stack: Vec<(f64, u32)>,
    shadow: cell_shadow::Scratch,
    /// For `Triangles::apart`.
    boxes: (Vec<u32>, Vec<u32>),
}

impl Scratch {
    fn boxes(&mut self) -> (&mut Vec<u32>, &mut Vec<u32>) {
        (&mut self.boxes.0, &mut self.boxes.1)
    }
}

/// A primitive's cells and the largest distance measured on them.
struct Start {
    cells: Vec<Cell>,
    low: f64,
}

impl Start {
    /// `prim`'s tessellation's vertices measured and its triangles as cells; no
    /// cells once a vertex is found over `above` (the search then answers at once).
    fn of(prim: &Primitive, surface: &Triangles, above: f64, scratch: &mut Scratch) -> Start {
        let (tess, gap) = tessellation(prim, surface.diagonal);
        let mut low = 0.0f64;
        for &p in &tess.vertices {
            // Over `low - gap` it is exact, and may prove `p` inside the solid (at 0).
            let d = surface.distance_beyond(p, low - gap, &mut scratch.stack);
            let d = match d > low - gap && surface.inside(p, d, &mut scratch.stack) {
                true => 0.0,
                false => d,
            };
            low = low.max(d + gap);
            if low > above {
                return Start {
                    cells: Vec::new(),
                    low,
                };
            }
        }
        // Each cell's search starts from the last one's nearest triangle: the
        // tessellation's triangles follow each other around the primitive.
        let mut near = u32::MAX;
        let cells = triangles(&tess)
            .into_iter()
            .map(|t| {
                let first = (f64::INFINITY, gap, near, 0);
                let (cell, d) = Cell::measure(t, first, surface, scratch);
                (low, near) = (low.max(d), cell.near);
                cell
            })
            .collect();
        Start { cells, low }
    }
}

impl<'a> Refinement<'a> {
    fn new(surface: &'a Triangles) -> Self {
        Refinement {
            surface,
            heap: BinaryHeap::new(),
            low: 0.0,
            splits: 0,
            shadows: Shadows::default(),
            scratch: Scratch::default(),
            go_on: &|| true,
        }
    }

    /// The bound as it stands: the largest cell's, or the farthest point measured.
    fn bound(&self) -> f64 {
        self.heap.peek().map_or(self.low, |c| c.bound.max(self.low))
    }

    /// Adds a primitive's cells to the search.
    fn take(&mut self, s: Start) {
        self.low = self.low.max(s.low);
        self.heap.extend(s.cells);
    }

    /// Splits the worst cell until `ask` is answered or `max_splits` are made; the
    /// bound then (or the distance found over `ask.above`).
    fn run(&mut self, ask: StopAt, max_splits: usize) -> f64 {
        let slack = ABSOLUTE * self.surface.diagonal;
        while let Some(top) = self.heap.peek() {
            let (low, bound) = (self.low, top.bound.max(self.low));
            if low > ask.above {
                return low;
            }
            if ask.coarse && bound <= ask.level {
                return bound;
            }
            // Close enough, unless the bound is still undecided about `level`.
            let undecided = low <= ask.level && ask.level < bound;
            let close = bound <= low + slack.max(RELATIVE * low);
            if (close && !undecided) || self.splits == max_splits {
                return bound;
            }
            if self.splits % SPLITS_PER_CHECK == SPLITS_PER_CHECK - 1 && !(self.go_on)() {
                return bound;
            }
            let mut cell = self.heap.pop().expect("peeked");
            let Some(next) = self.shade(&mut cell) else {
                self.heap.push(cell);
                continue;
            };
            self.splits += 1;
            for t in halves(&cell.tri) {
                let from = (cell.bound, cell.gap, cell.near, next);
                let (cell, d) = Cell::measure(t, from, self.surface, &mut self.scratch);
                self.low = self.low.max(d);
                self.heap.push(cell);
            }
        }
        self.low
    }
}

impl Refinement<'_> {
    /// Before the worst cell is split, the bound of its shadow: tight over a few
    /// input facets, where its halves' would not be for long. Tried only on a round
    /// primitive's cells, once a search has run long (most end sooner without it,
    /// and flat faces lie flush sooner), while it helps often. `None` where it
    /// bounded `cell` anew; else the [`Cell::shade`] its halves get (where it gave
    /// nothing, they wait for the grandchildren).
    fn shade(&mut self, cell: &mut Cell) -> Option<u8> {
        match cell.shade {
            SHADED => Some(0),
            0 if cell.gap > 0.0 && self.shadows.worth(self.splits) => {
                let shade = &mut self.scratch.shadow;
                let below = cell.bound - cell.gap;
                let tried = cell_shadow::bound(&cell.tri, below, self.surface, shade);
                self.shadows.count(tried.is_some());
                match tried {
                    Some(b) => {
                        (cell.bound, cell.shade) = (b + cell.gap, SHADED);
                        None
                    }
                    None => Some(RETRY),
                }
            }
            wait => Some(wait.saturating_sub(1)),
        }
    }
}

/// A triangle of the tessellation with an upper bound of the distance over it.
struct Cell {
    bound: f64,
    tri: [V3; 3],
    /// Added to its distances: how far the primitive's own surface may lie inside
    /// its tessellation ([`rounding`]).
    gap: f64,
    /// The input triangle nearest its centroid (where its halves' searches start).
    near: u32,
    /// Splits to wait before its shadow is tried ([`SHADED`]: its bound is its
    /// shadow's, or its centroid's distance, exact).
    shade: u8,
}

impl Cell {
    /// `t` with its bound (at most its parent's, `parent`) and its centroid's
    /// distance to the input, each plus `gap`; the nearest triangle searched from
    /// `start` (a triangle near a point close by, or none), the same whatever it is.
    /// Under `--solid` (`Triangles::with_solid`) a centroid proven inside is at 0, and
    /// so is the ball around it of radius its distance to the surface (it meets no
    /// face), and so is the whole cell where, shrunk by [`SHRINK`] towards it, it meets
    /// no input triangle (`Triangles::apart`): the cell's bound is then that share of
    /// its size, else how far its farthest vertex reaches beyond the ball; plus `gap`.
    fn measure(
        t: [V3; 3],
        (parent, gap, start, shade): (f64, f64, u32, u8),
        surface: &Triangles,
        scratch: &mut Scratch,
    ) -> (Cell, f64) {
        let c = scale(add(add(t[0], t[1]), t[2]), 1.0 / 3.0);
        let (d, nearest) = surface.nearest_from(c, start, &mut scratch.stack);
        let reach = t.iter().map(|&v| norm(sub(v, c))).fold(0.0, f64::max);
        let flush = t
            .iter()
            .map(|&v| surface.distance_to(v, nearest))
            .fold(0.0, f64::max);
        // Proven inside, the ball of radius `d` around `c` is: a point of the cell
        // stands no farther outside than its distance to `c` less `d`. Where the cell
        // shrunk towards `c` meets no face, that is all on the side of `c`, and the
        // rest (a face may touch the cell's border) within the shrink of it.
        let (at_c, over) = match surface.inside(c, d, &mut scratch.stack) {
            true if reach <= d => (0.0, 0.0),
            true if surface.apart(&shrunk(&t, c), APART_MOST, scratch.boxes()) => {
                (0.0, SHRINK * reach)
            }
            true => (0.0, (reach - d).min(flush)),
            false => (d, (d + reach).min(flush)),
        };
        let bound = (over + gap).min(parent);
        let cell = Cell {
            bound,
            tri: t,
            gap,
            near: nearest,
            shade: if bound <= at_c + gap { SHADED } else { shade },
        };
        (cell, at_c + gap)
    }
}

impl PartialEq for Cell {
    fn eq(&self, o: &Self) -> bool {
        self.cmp(o) == Ordering::Equal
    }
}
impl Eq for Cell {}
impl PartialOrd for Cell {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Cell {
    /// The largest bound first (ties in insertion order's heap order: deterministic).
    fn cmp(&self, o: &Self) -> Ordering {
        self.bound.total_cmp(&o.bound)
    }
}

/// `t` shrunk towards `c` by [`SHRINK`].
fn shrunk(t: &[V3; 3], c: V3) -> [V3; 3] {
    t.map(|v| madd(c, sub(v, c), 1.0 - SHRINK))
}

/// `prim`'s tessellation fine enough that its [`rounding`] is at most [`GAP`] of the
/// diagonal (or as fine as [`DETAIL`] × 4), and that rounding.
fn tessellation(prim: &Primitive, diagonal: f64) -> (crate::output::Tess, f64) {
    let mut k = DETAIL;
    loop {
        let tess = tessellate(prim, k);
        let gap = rounding(prim, &tess, k);
        if gap <= GAP * diagonal || k >= 4 * DETAIL {
            return (tess, gap);
        }
        k *= 2;
    }
}

/// How far a point of a round primitive's surface may be from its tessellation,
/// which circumscribes it (0 for boxes and prisms, which it is): the surface `eval`
/// samples is the primitive's own, and the distance is 1-Lipschitz, so adding this
/// bounds that surface's distance too. Each point of a ball or capsule lies on the
/// ray from its core out through the tessellation, which lies within its farthest
/// vertex; a cylinder's or frustum's side within 1/cos(π/k) of its radius.
fn rounding(prim: &Primitive, tess: &crate::output::Tess, k: usize) -> f64 {
    let circ = 1.0 / (std::f64::consts::PI / k as f64).cos();
    let beyond = |p0: V3, p1: V3, r: f64| {
        let far = tess
            .vertices
            .iter()
            .map(|&v| point_segment_dist2(v, p0, p1));
        far.fold(0.0, f64::max).sqrt() - r
    };
    match *prim {
        Primitive::Box(_) | Primitive::Prism(_) => 0.0,
        Primitive::Sphere(s) => beyond(s.center, s.center, s.radius),
        Primitive::Capsule(c) => beyond(c.p0, c.p1, c.radius),
        Primitive::Cylinder(c) => c.radius * (circ - 1.0),
        Primitive::Frustum(f) => f.r0.max(f.r1) * (circ - 1.0),
    }
    .max(0.0)
}

/// The tessellation's faces as triangles: quads and triangles fanned from their first
/// vertex, larger polygons (round caps) from their centre, so that no triangle is a
/// sliver across the cap.
pub(super) fn triangles(tess: &crate::output::Tess) -> Vec<[V3; 3]> {
    let mut tris = Vec::new();
    for f in &tess.faces {
        let v = |i: usize| tess.vertices[f[i] as usize];
        if f.len() <= 4 {
            tris.extend((2..f.len()).map(|k| [v(0), v(k - 1), v(k)]));
            continue;
        }
        let sum = (0..f.len()).fold([0.0; 3], |s, i| add(s, v(i)));
        let centre = scale(sum, 1.0 / f.len() as f64);
        tris.extend((0..f.len()).map(|i| [centre, v(i), v((i + 1) % f.len())]));
    }
    tris
}

/// `t` cut in two across its longest edge, at its midpoint: slivers (a cylinder's
/// side facets, fan triangles) become well-shaped as they are cut, instead of
/// staying slivers four times as many.
pub(super) fn halves(t: &[V3; 3]) -> [[V3; 3]; 2] {
    let len = |i: usize| norm(sub(t[(i + 1) % 3], t[i]));
    let i = (0..3).fold(0, |b, i| if len(i) > len(b) { i } else { b });
    let (a, b, c) = (t[i], t[(i + 1) % 3], t[(i + 2) % 3]);
    let m = scale(add(a, b), 0.5);
    [[a, m, c], [m, b, c]]
}

#[cfg(test)]
pub(crate) mod tests;
