//! Coplanar plates joined after the merge loop (`Plates::join_coplanar`,
//! docs/decisions/0028-coplanar-plates-joined.md; not in the paper, whose §3.4 removes only
//! primitives nested in
//! another).
//!
//! Free merges (docs/decisions/0025-free-merges-into-plates.md) join adjacent clusters into a
//! plate of no more area, but
//! only along the greedy order and only across shared edges. A flat polygon cut into
//! long sliver triangles then keeps several plates that overlap: kenney_wall_high's
//! top, 15 triangles in one plane, stayed four plates at N = 93, 90, 85, 80, 70 and
//! 60, two of them (not adjacent: a third cluster's sliver runs between) covering the
//! same 0.63 × 0.7 area, so a ball rolling there touched both. Here two plates in
//! one plane whose bounding boxes touch are replaced by the output fit of both
//! clusters' faces when that fit is itself a plate of no more k·V than the two (as a
//! free merge is priced) that covers almost nothing neither of them did (a plate
//! across an L of two plates would cover the L's corner, which may be a hole): one
//! shape where there were two, enclosing the faces of both.

use rayon::prelude::*;

use crate::cut::error::is_within;
use crate::input::triangles::Triangles;
use crate::math::polygon::{clip, signed_area};
use crate::math::{add, cross, dot, madd, normalize, scale, Sym3, V3};
use crate::merge::{Fitter, Snapshot, Workspace};
use crate::primitive::frame::convex_hull_2d;
use crate::primitive::Primitive;
use crate::progress::Ask;

/// Plates whose thin axes differ by more than this (cosine) are not in one plane.
const PARALLEL_COS: f64 = 1.0 - 1e-9;
/// A prism whose extrusion axis is further off a plane's normal than this (cosine) has
/// no footprint in that plane (a union's fit is that close to its parts' plane).
const CAST_COS: f64 = 1.0 - 1e-6;
/// Planes further apart than this share of the output floor are not one plane.
const OFFSET_SHARE: f64 = 0.5;
/// How much more area than the two parts cover together (their union, not their sum)
/// the joined plate may cover, as a share of its own area: a plate across two sliver
/// plates' seam covers a sliver of neither, one across an L of two plates the L's
/// empty corner (which may be a hole in the mesh).
const SPILL: f64 = 0.01;

/// One pair that may be joined: its key (here the union's k·V less the two parts',
/// ≤ 0), the two indices (i < j) and the union's fit.
pub(super) type Candidate = (f64, usize, usize, Primitive);

/// A primitive's plate: its thin axis made to point along its largest component's
/// positive side, its mid-plane's offset along that axis (halfway between its support
/// both ways), and its bounding box.
#[derive(Clone, Copy)]
struct Plate {
    axis: V3,
    offset: f64,
    aabb: (V3, V3),
}

/// Joins pairs of coplanar plates of `snap` into one plate of no more k·V, in rounds
/// until none is left ([`in_rounds`]); `q` holds each primitive's operator and is
/// compacted with the snapshot. A cut's snapshot keeps its bound: a joined plate
/// standing farther from `surface` (the input) than `bound` is refused
/// (docs/decisions/0038).
pub fn join(
    fitter: &Fitter,
    snap: &mut Snapshot,
    q: &mut Vec<Sym3>,
    surface: Option<&Triangles>,
    bound: Option<f64>,
    go_on: Ask,
) {
    let keeps = |p: &Primitive| match (bound, surface) {
        (Some(bound), Some(s)) => is_within(p, s, bound),
        _ => true,
    };
    in_rounds(snap, q, |snap, q, alive, dirty| {
        coplanar_pairs(fitter, snap, q, (alive, dirty), &keeps, go_on)
    });
}

/// Replaces pairs of `snap`'s primitives by their union's fit in rounds until none is
/// left: `find` gives the acceptable pairs (key, i < j, union's fit) among the live
/// ones with a dirty member. The least keys go first (then the lowest indices) and a
/// primitive joins at most one pair per round, so the result is the same for any
/// thread count; a pair found earlier whose members are unchanged is kept without
/// pricing it again (its fit depends on the pair alone). `q` (each primitive's
/// operator) is joined and compacted with the snapshot. Shared with `absorb`.
pub(super) fn in_rounds(
    snap: &mut Snapshot,
    q: &mut Vec<Sym3>,
    find: impl Fn(&Snapshot, &[Sym3], &[bool], &[bool]) -> Vec<Candidate>,
) {
    let n = snap.prims.len();
    let mut alive = vec![true; n];
    let mut dirty = vec![true; n];
    let mut found: Vec<Candidate> = Vec::new();
    loop {
        found.retain(|c| alive[c.1] && alive[c.2] && !dirty[c.1] && !dirty[c.2]);
        found.extend(find(snap, q, &alive, &dirty));
        found.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)).then(a.2.cmp(&b.2)));
        dirty.fill(false);
        let mut used = vec![false; n];
        for &(_, i, j, prim) in &found {
            if used[i] || used[j] {
                continue;
            }
            (used[i], used[j], dirty[i], alive[j]) = (true, true, true, false);
            snap.prims[i] = prim;
            snap.faces[i] += snap.faces[j];
            snap.verts[i] = union(&snap.verts[i], &snap.verts[j]);
            let members = std::mem::take(&mut snap.members[j]);
            snap.members[i].extend(members);
            q[i] = q[i].add(&q[j]);
        }
        if !dirty.contains(&true) {
            break;
        }
    }
    compact(snap, q, &alive);
}

/// Keeps the entries of `snap` and `q` whose `alive` is set, in order.
fn compact(snap: &mut Snapshot, q: &mut Vec<Sym3>, alive: &[bool]) {
    let idx: Vec<usize> = (0..alive.len()).filter(|&k| alive[k]).collect();
    snap.prims = idx.iter().map(|&k| snap.prims[k]).collect();
    snap.faces = idx.iter().map(|&k| snap.faces[k]).collect();
    snap.verts = idx
        .iter()
        .map(|&k| std::mem::take(&mut snap.verts[k]))
        .collect();
    snap.members = idx
        .iter()
        .map(|&k| std::mem::take(&mut snap.members[k]))
        .collect();
    *q = idx.iter().map(|&k| q[k]).collect();
}

/// The plate of `p` at the output floor `floor`, if it is one.
fn plate(p: &Primitive, floor: f64) -> Option<Plate> {
    let mut axis = p.plate_axis(floor)?;
    let k = (0..3).max_by(|&a, &b| axis[a].abs().total_cmp(&axis[b].abs()))?;
    if axis[k] < 0.0 {
        axis = axis.map(|c| -c);
    }
    let back = axis.map(|c| -c);
    Some(Plate {
        axis,
        offset: 0.5 * (p.support(axis) - p.support(back)),
        aabb: p.aabb(),
    })
}

/// Every live pair (i < j) with a dirty member of plates in one plane whose bounding
/// boxes touch (within the floor), whose union's output fit is a plate of no more k·V
/// than the two that covers at most [`SPILL`] more than they do, with that difference
/// and fit.
fn coplanar_pairs(
    fitter: &Fitter,
    snap: &Snapshot,
    q: &[Sym3],
    (alive, dirty): (&[bool], &[bool]),
    keeps: &(dyn Fn(&Primitive) -> bool + Sync),
    go_on: Ask,
) -> Vec<Candidate> {
    let floor = fitter.pricing.fit.min_half;
    let plates: Vec<(usize, Plate)> = (0..snap.prims.len())
        .filter(|&i| alive[i])
        .filter_map(|i| plate(&snap.prims[i], floor).map(|p| (i, p)))
        .collect();
    let pairs = touching_pairs(&plates, dirty, floor);
    let kv = |p: &Primitive| fitter.pricing.fit.weights[p.kind() as usize] * p.volume();
    let scratch = || (Workspace::default(), Vec::new(), Vec::new());
    pairs
        .par_iter()
        .map_init(scratch, |(ws, pts, hull), &(i, j)| {
            if !go_on() {
                return None;
            }
            let (a, b) = (&snap.prims[i], &snap.prims[j]);
            let (both, frame) = covered_together(a, b, floor)?;
            let most = both / (1.0 - SPILL);
            // The union's plate holds both clusters' points, so its footprint holds
            // their hull: a pair whose hull already covers more is refused unfitted.
            let flat = |v: &u32| project(fitter.input.mesh.pos(*v), frame);
            pts.clear();
            pts.extend(snap.verts[i].iter().chain(&snap.verts[j]).map(flat));
            if hull_area(pts, hull) > most * (1.0 + 1e-9) {
                return None;
            }
            let faces = snap.members[i].iter().chain(&snap.members[j]).copied();
            let fit = fitter.fit_output_checked(faces, &q[i].add(&q[j]), ws, go_on)?;
            let gain = kv(&fit.prim) - (kv(a) + kv(b));
            let joined = gain <= 0.0
                && fit.prim.plate_axis(floor).is_some()
                && footprint(&fit.prim, frame).is_some_and(|f| area(&f) <= most)
                && keeps(&fit.prim);
            joined.then_some((gain, i, j, fit.prim))
        })
        .flatten()
        .collect()
}

/// The pairs (i < j, sorted) of `plates` (each with its primitive's index) with a
/// `dirty` member, in one plane and whose bounding boxes touch within `floor`.
fn touching_pairs(plates: &[(usize, Plate)], dirty: &[bool], floor: f64) -> Vec<(usize, usize)> {
    // Sweep along the axis the boxes overlap least on: a pair's boxes overlap there first.
    let k = sweep_axis(plates.iter().map(|p| p.1.aabb));
    let mut order: Vec<usize> = (0..plates.len()).collect();
    order.sort_by(|&a, &b| plates[a].1.aabb.0[k].total_cmp(&plates[b].1.aabb.0[k]));
    let mut pairs = Vec::new();
    for (s, &a) in order.iter().enumerate() {
        let (i, pa) = plates[a];
        for &b in &order[s + 1..] {
            let (j, pb) = plates[b];
            if pb.aabb.0[k] > pa.aabb.1[k] + floor {
                break;
            }
            if (dirty[i] || dirty[j]) && one_plane(&pa, &pb, floor) {
                pairs.push((i.min(j), i.max(j)));
            }
        }
    }
    pairs.sort_unstable();
    pairs
}

/// The axis along which boxes cover the least of their common span, summed: sweeping
/// along it visits the fewest pairs (plates as long as the input along x, side by
/// side in y, all overlap along x).
fn sweep_axis(boxes: impl Iterator<Item = (V3, V3)>) -> usize {
    let (mut lo, mut hi, mut sum) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3], [0.0; 3]);
    for (a, b) in boxes {
        for k in 0..3 {
            lo[k] = lo[k].min(a[k]);
            hi[k] = hi[k].max(b[k]);
            sum[k] += b[k] - a[k];
        }
    }
    let share = |k: usize| sum[k] / (hi[k] - lo[k]).max(f64::MIN_POSITIVE);
    (0..3)
        .min_by(|&a, &b| share(a).total_cmp(&share(b)))
        .unwrap_or(0)
}

/// Whether two plates lie in one plane and their bounding boxes touch.
fn one_plane(a: &Plate, b: &Plate, floor: f64) -> bool {
    let touch =
        (0..3).all(|k| a.aabb.0[k] <= b.aabb.1[k] + floor && b.aabb.0[k] <= a.aabb.1[k] + floor);
    touch
        && dot(a.axis, b.axis) >= PARALLEL_COS
        && (a.offset - b.offset).abs() <= OFFSET_SHARE * floor
}

/// The area plates `a` and `b` (in one plane) cover together, their union's and not
/// their sum, and the frame of their plane it was measured in; `None` when a
/// footprint is not a polygon. A plate joining them may cover at most [`SPILL`] of its
/// own area more than that.
fn covered_together(a: &Primitive, b: &Primitive, floor: f64) -> Option<(f64, (V3, V3))> {
    let frame = plane_frame(a.plate_axis(floor)?)?;
    let (fa, fb) = (footprint(a, frame)?, footprint(b, frame)?);
    Some((area(&fa) + area(&fb) - area(&clip(&fa, &fb)), frame))
}

/// Two unit vectors spanning the plane ⟂ `n` (with `n` right-handed).
fn plane_frame(n: V3) -> Option<(V3, V3)> {
    let k = (0..3).min_by(|&a, &b| n[a].abs().total_cmp(&n[b].abs()))?;
    let mut e = [0.0; 3];
    e[k] = 1.0;
    let u = normalize(cross(n, e))?;
    Some((u, cross(n, u)))
}

/// `x` in the plane frame `(u, v)`.
fn project(x: V3, (u, v): (V3, V3)) -> [f64; 2] {
    [dot(x, u), dot(x, v)]
}

/// The footprint of a box or prism in the plane frame `frame`: its shadow along the
/// plane's normal, as corners counter-clockwise. A box is cast along its axis nearest
/// the normal (a plate's thin axis; a union only a floor wide across too may be thinnest
/// along another), a prism only along its extrusion axis; `None` for a prism turned
/// off the normal and for other kinds (a disc).
fn footprint(p: &Primitive, frame: (V3, V3)) -> Option<Vec<[f64; 2]>> {
    let n = cross(frame.0, frame.1);
    let corners = match p {
        Primitive::Box(b) => {
            let t = (0..3)
                .max_by(|&x, &y| dot(b.axes[x], n).abs().total_cmp(&dot(b.axes[y], n).abs()))?;
            let (i, j) = ((t + 1) % 3, (t + 2) % 3);
            let s = |w: f64, ax: usize| scale(b.axes[ax], w * b.half[ax]);
            [(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)]
                .map(|(x, y)| add(add(b.center, s(x, i)), s(y, j)))
        }
        Primitive::Prism(q) if dot(q.axes[0], n).abs() >= CAST_COS => {
            let at = |y: f64, z: f64| madd(madd(q.center, q.axes[1], y), q.axes[2], z);
            let (t, b) = (q.shift, -q.shift);
            [
                at(q.hy, t + q.hz_top),
                at(q.hy, t - q.hz_top),
                at(-q.hy, b - q.hz_bottom),
                at(-q.hy, b + q.hz_bottom),
            ]
        }
        _ => return None,
    };
    let mut poly: Vec<[f64; 2]> = corners.iter().map(|&x| project(x, frame)).collect();
    if signed_area(&poly) < 0.0 {
        poly.reverse();
    }
    Some(poly)
}

/// The area of the convex hull of `pts` (reordered), built in `hull`.
fn hull_area(pts: &mut [[f64; 2]], hull: &mut Vec<[f64; 2]>) -> f64 {
    convex_hull_2d(pts, hull);
    if hull.len() < 3 {
        return 0.0;
    }
    area(hull)
}

fn area(p: &[[f64; 2]]) -> f64 {
    signed_area(p).abs()
}

/// The sorted union of two sorted, distinct lists.
fn union(a: &[u32], b: &[u32]) -> Vec<u32> {
    let mut v: Vec<u32> = a.iter().chain(b).copied().collect();
    v.sort_unstable();
    v.dedup();
    v
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::primitive::{Obb, Prism};

    const FLOOR: f64 = 0.01;
    const I3: [V3; 3] = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

    /// Whether plate `u` covers no more than [`SPILL`] of its area beyond what `a` and
    /// `b` cover together (the join's footprint rule).
    fn covers_no_more(a: &Primitive, b: &Primitive, u: &Primitive, floor: f64) -> bool {
        let (both, frame) = covered_together(a, b, floor).unwrap();
        area(&footprint(u, frame).unwrap()) <= both / (1.0 - SPILL)
    }

    /// A plate in z = 0 over [x0, x1] × [y0, y1].
    fn plate(x0: f64, x1: f64, y0: f64, y1: f64) -> Primitive {
        Primitive::Box(Obb {
            center: [0.5 * (x0 + x1), 0.5 * (y0 + y1), 0.0],
            axes: I3,
            half: [0.5 * (x1 - x0), 0.5 * (y1 - y0), FLOOR],
        })
    }

    #[test]
    fn clipped_areas_are_exact() {
        let sq =
            |x0: f64, y0: f64, s: f64| vec![[x0, y0], [x0 + s, y0], [x0 + s, y0 + s], [x0, y0 + s]];
        assert_eq!(area(&clip(&sq(0.0, 0.0, 2.0), &sq(1.0, 1.0, 2.0))), 1.0);
        assert_eq!(area(&clip(&sq(0.0, 0.0, 1.0), &sq(2.0, 2.0, 1.0))), 0.0);
        // A square turned 45° inside the unit square's double: its own area.
        let diamond = vec![[1.0, 0.0], [2.0, 1.0], [1.0, 2.0], [0.0, 1.0]];
        assert!((area(&clip(&diamond, &sq(0.0, 0.0, 2.0))) - 2.0).abs() < 1e-12);
        assert!((area(&clip(&sq(0.0, 0.0, 2.0), &diamond)) - 2.0).abs() < 1e-12);
    }

    /// Two plates that overlap in an L: the box around both covers the L's empty
    /// corner (0, 1)–(1, 2), a quarter of its area, though it has no more area than
    /// the two together (4 = 2 + 2). Two plates side by side: their box covers nothing
    /// more.
    #[test]
    fn a_join_covers_no_corner_neither_part_covered() {
        let (a, b) = (plate(0.0, 2.0, 0.0, 1.0), plate(1.0, 2.0, 0.0, 2.0));
        assert!(!covers_no_more(&a, &b, &plate(0.0, 2.0, 0.0, 2.0), FLOOR));
        let (a, b) = (plate(0.0, 1.0, 0.0, 1.0), plate(0.5, 2.0, 0.0, 1.0));
        assert!(covers_no_more(&a, &b, &plate(0.0, 2.0, 0.0, 1.0), FLOOR));
    }

    /// A prism's footprint is its trapezoid: a triangle's prism (top width 0) and the
    /// other half of a rectangle make the rectangle, spilling nothing.
    #[test]
    fn prism_footprints_are_trapezoids() {
        // Extruded along z; y from −0.5 to 0.5; half-width along x 0 at the top, 1
        // at the bottom: the triangle (−1, −0.5), (1, −0.5), (0, 0.5).
        let tri = Primitive::Prism(Prism {
            center: [0.0, 0.0, 0.0],
            axes: [[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]],
            hx: FLOOR,
            hy: 0.5,
            hz_top: 0.0,
            hz_bottom: 1.0,
            shift: 0.0,
        });
        let n = tri.plate_axis(FLOOR).unwrap();
        assert!((area(&footprint(&tri, plane_frame(n).unwrap()).unwrap()) - 1.0).abs() < 1e-12);
        let rect = plate(-1.0, 1.0, -0.5, 0.5);
        assert!(covers_no_more(&tri, &rect, &rect, FLOOR));
        assert!(!covers_no_more(&tri, &tri, &rect, FLOOR));
    }

    /// Strips as long as the scene along x, side by side in y: the sweep runs along y.
    #[test]
    fn sweeps_run_across_long_strips() {
        let strips = (0..10).map(|i| {
            let y = i as f64;
            ([0.0, y, 0.0], [100.0, y + 0.5, 0.01])
        });
        assert_eq!(sweep_axis(strips), 1);
    }

    /// The hull bound that refuses pairs unfitted: a square's corners and inner points,
    /// collinear points (no area), and points given in any order.
    #[test]
    fn hull_areas_are_exact() {
        let mut sq = vec![
            [0.0, 0.0],
            [0.5, 0.5],
            [2.0, 0.0],
            [2.0, 2.0],
            [0.0, 2.0],
            [1.0, 0.0],
        ];
        assert_eq!(hull_area(&mut sq, &mut vec![]), 4.0);
        let mut line = vec![[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]];
        assert_eq!(hull_area(&mut line, &mut vec![]), 0.0);
        let mut tri = vec![[3.0, 0.0], [0.0, 0.0], [0.0, 4.0], [1.0, 1.0]];
        assert_eq!(hull_area(&mut tri, &mut vec![]), 6.0);
    }

    #[test]
    fn unions_of_vertex_lists_are_sorted_and_distinct() {
        assert_eq!(union(&[1, 3, 5], &[2, 3, 6]), vec![1, 2, 3, 5, 6]);
    }

    #[test]
    fn plates_in_other_planes_are_not_one_plane() {
        let p = |z: f64| Plate {
            axis: [0.0, 0.0, 1.0],
            offset: z,
            aabb: ([0.0, 0.0, z - FLOOR], [1.0, 1.0, z + FLOOR]),
        };
        assert!(one_plane(&p(0.0), &p(0.4 * FLOOR), FLOOR));
        assert!(!one_plane(&p(0.0), &p(FLOOR), FLOOR));
        let far = Plate {
            aabb: ([1.5, 0.0, -FLOOR], [2.0, 1.0, FLOOR]),
            ..p(0.0)
        };
        assert!(!one_plane(&p(0.0), &far, FLOOR));
    }
}
