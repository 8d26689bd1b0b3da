//! A cell's shadow: a bound of the error over one triangle of a primitive's
//! tessellation (`cut::error`'s cells) from the input triangles that the lines through
//! the cell, along its normal, meet. The error bound of docs/decisions/0040 (part of
//! the node error of the cut, beyond the paper) bounds a cell by its centroid's
//! distance plus its size, or by its corners' distances to one input triangle; over a
//! curved input made of many small facets neither is tight until the cells are far
//! smaller than the facets, and a round primitive runs out of splits
//! (docs/decisions/0047). Here the cell is cut into the pieces that lie over each
//! input triangle: over a piece the distance along the line to that triangle's plane
//! is affine, so its largest is at the piece's corners, and it bounds the distance to
//! the input (the line meets the triangle there). Only for cells over a few triangles.

use crate::input::triangles::Triangles;
use crate::math::bvh::tri_box;
use crate::math::polygon::{clip_by, signed_area};
use crate::math::{add, cross, dot, norm, normalize, scale, sub, V3};

/// Cells over more input triangles than this are left to the other bounds.
const MOST: usize = 32;
/// Pieces over no input triangle bounded by their centroid's distance plus their
/// size; more than this and the shadow gives no bound.
const LEFT: usize = 8;
/// Input triangles steeper than this (the cosine of their normal with the cell's)
/// are skipped: they cover little of the cell, and a point just outside one in the
/// plane stands far from it along the line.
const STEEP: f64 = 1e-3;

/// Reusable space for [`bound`].
#[derive(Default)]
pub(crate) struct Scratch {
    stack: Vec<u32>,
    slots: Vec<u32>,
    near: Vec<(f64, u32)>,
    pieces: Pieces,
    next: Pieces,
    piece: Vec<[f64; 2]>,
    clipped: Vec<[f64; 2]>,
}

/// Convex polygons in the cell's plane, stored end to end.
#[derive(Default)]
struct Pieces {
    points: Vec<[f64; 2]>,
    ends: Vec<usize>,
}

impl Pieces {
    fn clear(&mut self) {
        self.points.clear();
        self.ends.clear();
    }

    fn push(&mut self, poly: &[[f64; 2]]) {
        if signed_area(poly) > 0.0 {
            self.points.extend_from_slice(poly);
            self.ends.push(self.points.len());
        }
    }

    /// Drops the polygons pushed after `count` of them.
    fn truncate(&mut self, count: usize) {
        self.ends.truncate(count);
        self.points.truncate(self.ends.last().copied().unwrap_or(0));
    }

    fn get(&self, i: usize) -> &[[f64; 2]] {
        let start = if i == 0 { 0 } else { self.ends[i - 1] };
        &self.points[start..self.ends[i]]
    }
}

/// An upper bound of the distance from every point of `cell` to the input, if the
/// lines through it along its normal meet few enough input triangles within `below`
/// of it (a bound it is to beat) and it comes out below `below`; otherwise `None`.
pub(crate) fn bound(
    cell: &[V3; 3],
    below: f64,
    surface: &Triangles,
    s: &mut Scratch,
) -> Option<f64> {
    let plane = Plane::of(cell)?;
    // The cell swept along its normal by `below` each way.
    let (lo, hi) = tri_box(cell);
    let reach = plane.n.map(|c| (c * below).abs());
    let (lo, hi) = (sub(lo, reach), add(hi, reach));
    if !surface.meeting((lo, hi), MOST, &mut s.stack, &mut s.slots) {
        return None;
    }
    // Grown by this in the plane, the triangles that share an edge overlap instead of
    // leaving a sliver between them to rounding.
    let grow = 1e-9 * surface.diagonal;
    s.pieces.clear();
    s.pieces.push(&plane.corners);
    let mut worst = 0.0f64;
    for &k in &s.slots {
        let Some(over) = Over::of(&plane, &surface.corners(k), grow) else {
            continue;
        };
        s.next.clear();
        for i in 0..s.pieces.ends.len() {
            let piece = s.pieces.get(i);
            let mark = s.next.ends.len();
            s.piece.clear();
            s.piece.extend_from_slice(piece);
            // The piece's parts outside each edge (and inside the ones before) go on;
            // what is inside all three is over the triangle.
            for e in over.edges {
                clip_by(&s.piece, half([-e[0], -e[1], -e[2]]), &mut s.clipped);
                s.next.push(&s.clipped);
                clip_by(&s.piece, half(e), &mut s.clipped);
                std::mem::swap(&mut s.piece, &mut s.clipped);
            }
            if signed_area(&s.piece) <= 0.0 {
                // Not over the triangle: the piece goes on whole.
                s.next.truncate(mark);
                s.next.push(piece);
                continue;
            }
            let far = s.piece.iter().map(|&q| over.along(q).abs());
            worst = worst.max(far.fold(0.0, f64::max) + over.slack);
        }
        std::mem::swap(&mut s.pieces, &mut s.next);
        if worst >= below {
            return None;
        }
    }
    left_over(&plane, worst, below, surface, s)
}

/// [`bound`] with the pieces over no triangle: each by its centroid's distance to
/// the input plus its size (the distance is 1-Lipschitz).
fn left_over(
    plane: &Plane,
    mut worst: f64,
    below: f64,
    surface: &Triangles,
    s: &mut Scratch,
) -> Option<f64> {
    if s.pieces.ends.len() > LEFT {
        return None;
    }
    for i in 0..s.pieces.ends.len() {
        let piece = s.pieces.get(i);
        let sum = piece
            .iter()
            .fold([0.0; 2], |a, q| [a[0] + q[0], a[1] + q[1]]);
        let c = [sum[0] / piece.len() as f64, sum[1] / piece.len() as f64];
        let size = piece
            .iter()
            .map(|q| (q[0] - c[0]).hypot(q[1] - c[1]))
            .fold(0.0, f64::max);
        let (d, _) = surface.nearest_from(plane.at(c), u32::MAX, &mut s.near);
        worst = worst.max(d + size);
        if worst >= below {
            return None;
        }
    }
    Some(worst)
}

/// The cell's plane: an origin (its first corner), a frame, its normal, and its
/// corners in that frame (counter-clockwise about the normal).
struct Plane {
    o: V3,
    u: V3,
    w: V3,
    n: V3,
    corners: [[f64; 2]; 3],
}

impl Plane {
    fn of(t: &[V3; 3]) -> Option<Plane> {
        let (e1, e2) = (sub(t[1], t[0]), sub(t[2], t[0]));
        let n = normalize(cross(e1, e2))?;
        let u = normalize(e1)?;
        let w = cross(n, u);
        let corners = [[0.0, 0.0], [norm(e1), 0.0], [dot(e2, u), dot(e2, w)]];
        Some(Plane {
            o: t[0],
            u,
            w,
            n,
            corners,
        })
    }

    /// A point of space in the plane's frame (its part along the normal dropped).
    fn frame(&self, p: V3) -> [f64; 2] {
        let d = sub(p, self.o);
        [dot(d, self.u), dot(d, self.w)]
    }

    /// The point of the plane at `q`.
    fn at(&self, q: [f64; 2]) -> V3 {
        let a = add(self.o, scale(self.u, q[0]));
        add(a, scale(self.w, q[1]))
    }
}

/// An input triangle as the cell's plane sees it: its edges as half-planes
/// `a·x + b·y + c ≥ 0` (grown), and the distance along the normal from a point of
/// the cell's plane to the triangle's plane, affine in the point.
struct Over {
    edges: [[f64; 3]; 3],
    along: [f64; 3],
    /// How far from the triangle a line through a point within the growth of its
    /// shadow may meet its plane.
    slack: f64,
}

impl Over {
    fn of(plane: &Plane, t: &[V3; 3], grow: f64) -> Option<Over> {
        let m = cross(sub(t[1], t[0]), sub(t[2], t[0]));
        let mn = dot(m, plane.n);
        let cos = mn.abs() / norm(m);
        // NaN for a degenerate triangle: skipped too.
        if cos.is_nan() || cos <= STEEP {
            return None;
        }
        let mut q = t.map(|p| plane.frame(p));
        if cross2(q[0], q[1], q[2]) < 0.0 {
            q.swap(1, 2);
        }
        let edges = std::array::from_fn(|i| {
            let (a, b) = (q[i], q[(i + 1) % 3]);
            let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
            let len = dx.hypot(dy);
            // Left of a → b is inside: −dy·(x − ax) + dx·(y − ay) ≥ −grow·len.
            [-dy, dx, dy * a[0] - dx * a[1] + grow * len]
        });
        // The line o + x·u + y·w + s·n meets m·(p − t0) = 0 at
        // s = (m·(t0 − o) − x·m·u − y·m·w) / m·n.
        let along = [
            -dot(m, plane.u) / mn,
            -dot(m, plane.w) / mn,
            dot(m, sub(t[0], plane.o)) / mn,
        ];
        Some(Over {
            edges,
            along,
            slack: grow / cos,
        })
    }

    fn along(&self, q: [f64; 2]) -> f64 {
        self.along[0] * q[0] + self.along[1] * q[1] + self.along[2]
    }
}

/// The half-plane `h[0]·x + h[1]·y + h[2] ≥ 0` as a side function for [`clip_by`].
fn half(h: [f64; 3]) -> impl Fn([f64; 2]) -> f64 {
    move |q| h[0] * q[0] + h[1] * q[1] + h[2]
}

fn cross2(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// A flat square of 2·n² triangles in z = 0, side n, centred on the origin.
    fn grid(n: u32) -> crate::input::mesh::Mesh {
        let (points, faces) = primdecomp_testkit::shapes::flat_grid(n);
        crate::input::mesh::Mesh::from_polygons(&points, &faces).expect("a grid")
    }

    /// A cell held level at height h over a grid of a few triangles is h from it at
    /// every point, tilted at most as far as its highest corner: the shadow says h, and
    /// the corner's distance along the cell's normal (up to its growth).
    #[test]
    fn a_cell_over_a_few_facets_is_as_far_as_its_highest_corner() {
        let mesh = grid(4);
        let surface = Triangles::new(&mesh);
        let mut s = Scratch::default();
        let level = [[-0.3, -0.3, 0.05], [0.3, -0.2, 0.05], [0.0, 0.3, 0.05]];
        let b = bound(&level, 1.0, &surface, &mut s).expect("over the grid");
        assert!((b - 0.05).abs() < 1e-8, "{b}");
        let tilted = [[-0.3, -0.3, 0.02], [0.3, -0.2, 0.05], [0.0, 0.3, 0.08]];
        // Along its normal, as far as the corner's height over the normal's cosine.
        let n = normalize(cross(sub(tilted[1], tilted[0]), sub(tilted[2], tilted[0])));
        let along = 0.08 / n.expect("a cell")[2].abs();
        let b = bound(&tilted, 1.0, &surface, &mut s).expect("over the grid");
        assert!(b >= 0.08 && (b - along).abs() < 1e-8, "{b} {along}");
        // Asked to beat a bound it cannot, it gives none.
        assert!(bound(&tilted, 0.07, &surface, &mut s).is_none());
    }

    /// Independent of the bound's reasoning: for cells of every size and tilt about
    /// the demo scene, a bound given is at least the distance of every point drawn
    /// at random on the cell (the exact distance to the nearest triangle).
    #[test]
    fn no_point_of_a_cell_is_beyond_its_shadow() {
        let mesh = crate::input::demo::demo_scene();
        let surface = Triangles::new(&mesh);
        let d = mesh.diagonal();
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let (mut s, mut stack, mut given) = (Scratch::default(), Vec::new(), 0);
        for i in 0..3000 {
            let size = [0.002, 0.01, 0.05][i % 3] * d;
            let c: V3 = std::array::from_fn(|_| rng.gen_range(-0.4..0.4) * d);
            let cell: [V3; 3] = std::array::from_fn(|_| {
                add(c, std::array::from_fn(|_| rng.gen_range(-size..size)))
            });
            let Some(b) = bound(&cell, 0.2 * d, &surface, &mut s) else {
                continue;
            };
            given += 1;
            for _ in 0..32 {
                let p = crate::cut::error::tests::point_on(&cell, &mut rng);
                let dp = surface.nearest_from(p, u32::MAX, &mut stack).0;
                assert!(dp <= b + 1e-9 * d, "{cell:?}: {dp} > {b}");
            }
        }
        // The test means something only if many cells got a bound.
        assert!(given > 300, "{given}");
    }

    /// A cell over a hole in the input (lines through its middle meet nothing) is
    /// bounded by its left-over piece's centroid distance and size: at least the
    /// distance of the hole's centre.
    #[test]
    fn a_cell_over_a_hole_is_charged_for_it() {
        let (points, faces) = primdecomp_testkit::shapes::flat_grid(4);
        // Every face but the unit quad from the centre out along +x and +y.
        let kept: Vec<Vec<u32>> = faces
            .iter()
            .filter(|f| {
                f.iter().any(|&v| {
                    points[v as usize][0] < 2.0
                        || points[v as usize][1] < 2.0
                        || points[v as usize][0] > 3.0
                        || points[v as usize][1] > 3.0
                })
            })
            .cloned()
            .collect();
        assert_eq!(kept.len() + 1, faces.len());
        let mesh = crate::input::mesh::Mesh::from_polygons(&points, &kept).expect("a grid");
        let surface = Triangles::new(&mesh);
        let cell = [[-0.4, -0.4, 0.01], [1.5, 0.2, 0.01], [0.2, 1.5, 0.01]];
        let mut s = Scratch::default();
        let b = bound(&cell, 10.0, &surface, &mut s).expect("one piece left over");
        let hole = [0.5, 0.5, 0.01];
        let mut stack = Vec::new();
        let dh = surface.nearest_from(hole, u32::MAX, &mut stack).0;
        assert!(b >= dh && dh > 0.4, "{b} {dh}");
    }
}
