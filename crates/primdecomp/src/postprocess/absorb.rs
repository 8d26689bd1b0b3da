//! Near-duplicate output primitives absorbed into one, with solid pricing
//! (`Plates::solid`, docs/decisions/0023-merges-priced-by-the-air-they-add.md; not in the paper,
//! whose §3.4 removes
//! only primitives nested in another).
//!
//! Filled parts can leave two solid primitives that overlap almost entirely: the top
//! slab of kenney_wall_high at 64 was two boxes over 97% of its length, each leaving
//! out one bevelled end, and every ball resting on it touched both. Their merge adds
//! almost no air, but the merge loop had stopped at its target before it. Here, two
//! primitives whose bounding boxes mostly overlap are replaced by the output fit of
//! both clusters' points when that fit exceeds the larger of the two by at most
//! [`ABSORB`] of the smaller: one shape where there were two, enclosing the faces of
//! both.

use rayon::prelude::*;

use super::plates::{in_rounds, Candidate};
use crate::cut::error::is_within;
use crate::input::triangles::Triangles;
use crate::math::{Sym3, V3};
use crate::merge::{Fitter, Snapshot, Workspace};
use crate::primitive::Primitive;

/// How much larger than the larger of two primitives their union's fit may be, as a
/// share of the smaller one's volume: a near duplicate adds almost nothing, while a
/// large box swallowing a small part beside it (a wheel under a truck's body) grows by
/// more than the part.
pub const ABSORB: f64 = 0.05;
/// The share of the smaller bounding box the two must overlap to be tried.
const OVERLAP: f64 = 0.5;
/// Containment slack for the nested test, relative to the input diagonal (as
/// `postprocess`'s, so that a pair skipped here is one it removes).
const NESTED_TOL_REL: f64 = 1e-9;

/// Replaces near-duplicate pairs of `snap`'s primitives by their union's fit, in rounds
/// until none is left, the least growth first (`plates::in_rounds`); `q` holds each
/// primitive's operator and is compacted with the snapshot. A cut's snapshot keeps its
/// bound, as joined plates do (docs/decisions/0038): a union standing farther from
/// `surface` than `bound` is refused (docs/decisions/0056).
pub fn absorb(
    fitter: &Fitter,
    snap: &mut Snapshot,
    q: &mut Vec<Sym3>,
    (surface, bound): (Option<&Triangles>, Option<f64>),
) {
    let keeps = |p: &Primitive| match (bound, surface) {
        (Some(bound), Some(s)) => is_within(p, s, bound),
        _ => true,
    };
    in_rounds(snap, q, |snap, q, alive, dirty| {
        let found = near_duplicates(fitter, snap, q, alive, dirty);
        found.into_par_iter().filter(|c| keeps(&c.3)).collect()
    });
}

/// Every live pair (i < j) with a dirty member whose bounding boxes overlap by
/// [`OVERLAP`] of the smaller, neither of which already holds the other's points (the
/// nested removal of §3.4 drops those), and whose union's fit grows the larger by at
/// most [`ABSORB`] of the smaller, with that growth and fit.
fn near_duplicates(
    fitter: &Fitter,
    snap: &Snapshot,
    q: &[Sym3],
    alive: &[bool],
    dirty: &[bool],
) -> Vec<Candidate> {
    let n = snap.prims.len();
    let boxes: Vec<(V3, V3)> = snap.prims.iter().map(|p| p.aabb()).collect();
    let live = |i: usize, j: usize| alive[i] && alive[j] && (dirty[i] || dirty[j]);
    let pairs: Vec<(usize, usize)> = (0..n)
        .flat_map(|i| (i + 1..n).map(move |j| (i, j)))
        .filter(|&(i, j)| live(i, j) && overlaps(boxes[i], boxes[j]))
        .collect();
    let tol = NESTED_TOL_REL * fitter.input.mesh.diagonal().max(f64::MIN_POSITIVE);
    let holds = |i: usize, j: usize| {
        let p = &snap.prims[i];
        snap.verts[j]
            .iter()
            .all(|&v| p.contains(fitter.input.mesh.pos(v), tol))
    };
    pairs
        .par_iter()
        .filter(|&&(i, j)| !holds(i, j) && !holds(j, i))
        .map_init(Workspace::default, |ws, &(i, j)| {
            let (vi, vj) = (snap.prims[i].volume(), snap.prims[j].volume());
            let faces = snap.members[i].iter().chain(&snap.members[j]).copied();
            let fit = fitter.fit_output(faces, &q[i].add(&q[j]), ws);
            let growth = (fit.prim.volume() - vi.max(vj)) / vi.min(vj);
            (growth <= ABSORB).then_some((growth, i, j, fit.prim))
        })
        .flatten()
        .collect()
}

/// Whether the two boxes' intersection holds at least [`OVERLAP`] of the smaller's
/// volume (boxes of zero volume never do).
fn overlaps(a: (V3, V3), b: (V3, V3)) -> bool {
    let vol = |lo: V3, hi: V3| (0..3).map(|k| (hi[k] - lo[k]).max(0.0)).product::<f64>();
    let lo = [0, 1, 2].map(|k| a.0[k].max(b.0[k]));
    let hi = [0, 1, 2].map(|k| a.1[k].min(b.1[k]));
    let small = vol(a.0, a.1).min(vol(b.0, b.1));
    small > 0.0 && vol(lo, hi) >= OVERLAP * small
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn overlap_is_measured_against_the_smaller_box() {
        let unit = ([0.0; 3], [1.0; 3]);
        assert!(overlaps(unit, ([0.5, 0.0, 0.0], [1.5, 1.0, 1.0])));
        assert!(!overlaps(unit, ([0.6, 0.0, 0.0], [1.6, 1.0, 1.0])));
        // A small box inside a large one overlaps all of itself.
        assert!(overlaps(([0.2; 3], [0.3; 3]), ([0.0; 3], [5.0; 3])));
        // Flat boxes have no volume and are never tried.
        assert!(!overlaps(unit, ([0.0; 3], [1.0, 1.0, 0.0])));
    }
}
