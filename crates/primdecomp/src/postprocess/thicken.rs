//! Plates thickened inward to a minimum thickness (`Plates::min_thickness`,
//! docs/decisions/0033-plates-thickened-inward.md; not in the paper, whose §3.2 fits
//! make a flat cluster's primitive as thin as the floor allows).
//!
//! A closed part's faces become plates 2 × `min_extent` thick (0.001 of the diagonal),
//! which a fast body skips between two discrete physics steps. Here each box or prism
//! thinner than the minimum whose faces all face one way along its thin axis keeps its
//! outer side where it is and reaches inward, as far as the minimum allows and no
//! further than [`DEPTH_SHARE`] of the input's depth behind it: rays cast inward from a
//! grid on its inner side must leave the input through the far side's back faces (no
//! miss, no face seen from outside), and the input's interior (the voxel grid of
//! `--solid`, `input::solid`) must hold the middle of the added slab at most of them.
//! So the outer surface stays (the enclosure guarantee holds, as the primitive only
//! grows), holes in a plate's plane stay open (its footprint is unchanged), and a
//! single sheet or an open cavity behind a plate is not filled. Plates facing each
//! other across a part each fill a little over half of it, so the part becomes solid
//! and the inner sides bury each other.

use rayon::prelude::*;

use crate::input::mesh::{outward_normal, Mesh};
use crate::input::solid::{self, Solid};
use crate::input::triangles::Triangles;
use crate::math::{dot, madd, V3};
use crate::merge::cost::InputView;
use crate::merge::Snapshot;
use crate::primitive::Primitive;

/// Share of the input's depth behind a plate (from its outer side along its inward
/// normal to where the rays leave the input) it may fill: over half, so plates
/// facing each other overlap and bury each other's inner sides, and short of the far
/// side by the rest, so sampling between rays cannot poke through it.
pub const DEPTH_SHARE: f64 = 0.6;
/// How closely a plate's faces must agree on their outward side: the area-weighted
/// mean cosine of their outward normals with its thin axis.
const ONE_SIDE: f64 = 0.5;
/// Rays per side of a plate's grid (`GRID` × `GRID` rays, rims included).
const GRID: usize = 5;
/// Rims are sampled this far inside (share of the half-extent), off the side faces'
/// planes.
const INSET: f64 = 1e-3;
/// Shifts of the grid along the footprint's two sides (shares of the half-extents).
const SKEW: [f64; 2] = [0.0123, 0.0371];

/// The input as rays see it: its triangles (shared with the run, `input::triangles`)
/// and its interior on the `--solid` voxel grid.
pub(crate) struct Interior<'a> {
    tris: &'a Triangles<'a>,
    solid: Solid,
}

impl<'a> Interior<'a> {
    /// The interior of `mesh` beside its triangles `tris`.
    pub fn build(mesh: &Mesh, tris: &'a Triangles) -> Interior<'a> {
        Interior {
            tris,
            solid: Solid::build(mesh, solid::CELLS, solid::VOTES),
        }
    }
}

/// Thickens the plates of `snap` inward to `thickness` (absolute) where the input
/// allows it (module docs); other primitives are unchanged.
pub fn thicken(view: &InputView, input: &Interior, snap: &mut Snapshot, thickness: f64) {
    let grown: Vec<Primitive> = (0..snap.prims.len())
        .into_par_iter()
        .map_init(Vec::new, |stack, i| {
            let p = &snap.prims[i];
            grow(view, input, p, &snap.members[i], thickness, stack).unwrap_or(*p)
        })
        .collect();
    snap.prims = grown;
}

/// A plate's thin side: its outward unit normal `n` and its current thickness.
struct Slab {
    n: V3,
    thick: f64,
}

/// `p` grown inward to at most `thickness`, or `None` when it is not a thin box or
/// prism with one-sided faces or the input behind it does not allow it.
fn grow(
    view: &InputView,
    input: &Interior,
    p: &Primitive,
    members: &[u32],
    thickness: f64,
    stack: &mut Vec<u32>,
) -> Option<Primitive> {
    let (axis, thick) = match p {
        Primitive::Box(b) => {
            let k = (0..3).min_by(|&x, &y| b.half[x].total_cmp(&b.half[y]))?;
            (b.axes[k], 2.0 * b.half[k])
        }
        Primitive::Prism(q) => (q.axes[0], 2.0 * q.hx),
        _ => return None,
    };
    if thick.partial_cmp(&thickness) != Some(std::cmp::Ordering::Less) {
        return None;
    }
    let side = outward_side(view, members, axis)?;
    let slab = Slab {
        n: axis.map(|c| c * side),
        thick,
    };
    let samples = inner_grid(p, &slab);
    let target = allowed(
        input,
        &slab,
        &samples,
        thickness,
        view.mesh.diagonal(),
        stack,
    )?;
    // Round-off in the new centre must not pull the outer side in off its faces.
    let pad = 1e-12 * view.mesh.diagonal();
    (target > thick * (1.0 + 1e-9)).then(|| widened(p, &slab, target, pad))
}

/// +1 or −1: the side of `axis` the faces of `members` face (area-weighted mean
/// cosine of their outward normals at least [`ONE_SIDE`] either way), else `None`.
fn outward_side(view: &InputView, members: &[u32], axis: V3) -> Option<f64> {
    let (mut sum, mut area) = (0.0, 0.0);
    for &f in members {
        if let Some((n, len)) = outward_normal(view.mesh, view.face_sign, f) {
            sum += len * dot(n, axis);
            area += len;
        }
    }
    let c = sum / area;
    if c >= ONE_SIDE {
        Some(1.0)
    } else if c <= -ONE_SIDE {
        Some(-1.0)
    } else {
        None
    }
}

/// A `GRID` × `GRID` grid of points on the inner side of plate `p` (rims inset by
/// [`INSET`]), shifted off the footprint's diagonals by [`SKEW`]: rays through a
/// symmetric part's centre would run along the far side's triangle edges.
fn inner_grid(p: &Primitive, slab: &Slab) -> Vec<V3> {
    let at = |i: usize, skew: f64| {
        let x = 2.0 * i as f64 / (GRID - 1) as f64 - 1.0 + skew;
        x.clamp(INSET - 1.0, 1.0 - INSET)
    };
    let mut out = Vec::with_capacity(GRID * GRID);
    for i in 0..GRID {
        for j in 0..GRID {
            let (a, b) = (at(i, SKEW[0]), at(j, SKEW[1]));
            let x = match p {
                Primitive::Box(o) => {
                    let k = (0..3).min_by(|&x, &y| o.half[x].total_cmp(&o.half[y]));
                    let k = k.unwrap_or(0);
                    let (u, v) = ((k + 1) % 3, (k + 2) % 3);
                    let c = madd(o.center, o.axes[u], a * o.half[u]);
                    madd(c, o.axes[v], b * o.half[v])
                }
                Primitive::Prism(q) => {
                    // The trapezoid's half-width at height y runs from hz_bottom to
                    // hz_top, its middle from −shift to shift.
                    let w = q.hz_bottom + 0.5 * (a + 1.0) * (q.hz_top - q.hz_bottom);
                    let c = madd(q.center, q.axes[1], a * q.hy);
                    madd(c, q.axes[2], a * q.shift + b * w)
                }
                _ => continue,
            };
            out.push(madd(x, slab.n, -0.5 * slab.thick));
        }
    }
    out
}

/// The thickness the input lets the plate reach (at most `thickness`): every ray
/// inward from `samples` must meet a face of the input, the least depth (from the
/// outer side to that face, whichever way it faces: a part overlapping this one
/// stops the plate too) times [`DEPTH_SHARE`] caps it, and at least half the added
/// slab's middles must lie in the input's interior; `None` otherwise.
fn allowed(
    input: &Interior,
    slab: &Slab,
    samples: &[V3],
    thickness: f64,
    diag: f64,
    stack: &mut Vec<u32>,
) -> Option<f64> {
    let d = slab.n.map(|c| -c);
    let tmin = 1e-9 * diag;
    let mut depth = f64::INFINITY;
    for &o in samples {
        // Nothing behind the plate (`?`): a sheet open on that side.
        let t = input.tris.ray_first(o, d, (tmin, 4.0 * diag), stack)?;
        depth = depth.min(slab.thick + t);
    }
    let target = thickness.min(DEPTH_SHARE * depth);
    let mid = 0.5 * (target + slab.thick) - slab.thick;
    let inside = samples
        .iter()
        .filter(|&&o| input.solid.contains(madd(o, d, mid.max(0.0))))
        .count();
    (2 * inside >= samples.len()).then_some(target)
}

/// `p` with its thin side `target` thick, the outer side where it was (`pad` out).
fn widened(p: &Primitive, slab: &Slab, target: f64, pad: f64) -> Primitive {
    let shift = slab.n.map(|c| c * 0.5 * (slab.thick - target));
    let half = 0.5 * target + pad;
    match *p {
        Primitive::Box(mut o) => {
            let k = (0..3).min_by(|&x, &y| o.half[x].total_cmp(&o.half[y]));
            o.half[k.unwrap_or(0)] = half;
            o.center = madd(o.center, shift, 1.0);
            Primitive::Box(o)
        }
        Primitive::Prism(mut q) => {
            q.hx = half;
            q.center = madd(q.center, shift, 1.0);
            Primitive::Prism(q)
        }
        other => other,
    }
}
