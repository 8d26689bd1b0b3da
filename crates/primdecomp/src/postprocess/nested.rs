//! Post-processing (§3.4 "Removing Redundant Primitives"): drop primitives whose
//! subsumed points all lie inside another primitive, and optionally thin boxes (the
//! Bistro figure's rule) — never losing coverage. A primitive that hosts a removed
//! one is pinned (never removed itself), so two identical primitives cannot delete
//! each other and no face is left uncovered by a chain of removals. Coverage is checked
//! face by face: every face of a removed primitive lies in one kept primitive (the
//! enclosure guarantee), not merely each of its corners in some primitive.

use crate::input::mesh::Mesh;
use crate::math::V3;
use crate::primitive::Primitive;
use crate::progress::Ask;
use rayon::prelude::*;

/// Containment slack, relative to the input diagonal: far below any test tolerance.
const TOL_REL: f64 = 1e-9;

/// What to remove.
#[derive(Clone, Copy, Debug)]
pub struct Cleanup {
    /// The input's AABB diagonal (scales the containment slack).
    pub diagonal: f64,
    pub remove_nested: bool,
    /// Boxes whose smallest half-extent is below this (absolute) are removed when
    /// every one of their faces lies in some other kept primitive.
    pub thin_box_half: Option<f64>,
}

/// Which primitives to keep; `verts[i]` are the distinct vertices and `members[i]` the
/// faces of primitive `i` (the project's tests and benchmarks; a run asks as it goes,
/// [`keep_mask_checked`]).
#[cfg(any(test, feature = "test-internals"))]
pub fn keep_mask(
    mesh: &Mesh,
    prims: &[Primitive],
    verts: &[Vec<u32>],
    members: &[Vec<u32>],
    cleanup: Cleanup,
) -> Vec<bool> {
    let mask = keep_mask_checked(mesh, prims, verts, members, cleanup, &|| true);
    mask.expect("a mask never told to stop")
}

/// Which primitives to keep (as `keep_mask`), asking `go_on` before each
/// primitive's hosts are found and each thin box is tested (a level's primitives hold every face of the input: one
/// step over all of them is seconds long at tens of millions of faces); `None`
/// once it said stop.
pub(crate) fn keep_mask_checked(
    mesh: &Mesh,
    prims: &[Primitive],
    verts: &[Vec<u32>],
    members: &[Vec<u32>],
    cleanup: Cleanup,
    go_on: Ask,
) -> Option<Vec<bool>> {
    let n = prims.len();
    let mut keep = vec![true; n];
    if n < 2 {
        return Some(keep);
    }
    let tol = TOL_REL * cleanup.diagonal.max(f64::MIN_POSITIVE);
    let boxes: Vec<(V3, V3)> = prims.iter().map(|p| inflate(p.aabb(), tol)).collect();
    let mut pinned = vec![false; n];
    let order = smallest_first(prims);
    if cleanup.remove_nested {
        let hosts = all_hosts(mesh, prims, &boxes, verts, tol, go_on)?;
        for &i in &order {
            if pinned[i] {
                continue;
            }
            if let Some(&h) = hosts[i].iter().find(|&&h| keep[h]) {
                keep[i] = false;
                pinned[h] = true;
            }
        }
    }
    if let Some(t) = cleanup.thin_box_half {
        for &i in &order {
            if !go_on() {
                return None;
            }
            if keep[i] && !pinned[i] && is_thin_box(&prims[i], t) {
                remove_if_covered(
                    mesh,
                    prims,
                    &boxes,
                    &members[i],
                    i,
                    tol,
                    &mut keep,
                    &mut pinned,
                );
            }
        }
    }
    Some(keep)
}

/// The primitives' indices by volume, smallest first (ties by index).
fn smallest_first(prims: &[Primitive]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..prims.len()).collect();
    order.sort_by(|&i, &j| {
        prims[i]
            .volume()
            .total_cmp(&prims[j].volume())
            .then(i.cmp(&j))
    });
    order
}

/// Each primitive's hosts ([`hosts_of`]), asking `go_on` before each; `None` once it
/// said stop. Hosts are independent of what gets removed, so all are found in
/// parallel.
fn all_hosts(
    mesh: &Mesh,
    prims: &[Primitive],
    boxes: &[(V3, V3)],
    verts: &[Vec<u32>],
    tol: f64,
    go_on: Ask,
) -> Option<Vec<Vec<usize>>> {
    (0..prims.len())
        .into_par_iter()
        .map(|i| go_on().then(|| hosts_of(mesh, prims, boxes, &verts[i], i, tol)))
        .collect()
}

fn is_thin_box(p: &Primitive, t: f64) -> bool {
    matches!(p, Primitive::Box(b) if b.half.iter().cloned().fold(f64::INFINITY, f64::min) < t)
}

/// Removes `i` when each of its faces lies in one other kept primitive; pins those.
/// (Corner by corner would not do: a face whose corners lie in two different
/// primitives need not lie in either, and the fuzzer found one.)
#[allow(clippy::too_many_arguments)]
fn remove_if_covered(
    mesh: &Mesh,
    prims: &[Primitive],
    boxes: &[(V3, V3)],
    faces: &[u32],
    i: usize,
    tol: f64,
    keep: &mut [bool],
    pinned: &mut [bool],
) {
    let mut used = Vec::new();
    for &f in faces {
        let corners = mesh.face(f as usize);
        let host = (0..prims.len()).find(|&j| {
            j != i
                && keep[j]
                && corners
                    .iter()
                    .all(|&v| holds(prims, boxes, j, mesh.pos(v), tol))
        });
        match host {
            Some(j) => used.push(j),
            None => return,
        }
    }
    keep[i] = false;
    used.into_iter().for_each(|j| pinned[j] = true);
}

/// Every other primitive holding all of `verts`, in index order.
fn hosts_of(
    mesh: &Mesh,
    prims: &[Primitive],
    boxes: &[(V3, V3)],
    verts: &[u32],
    i: usize,
    tol: f64,
) -> Vec<usize> {
    let own = crate::math::aabb_of(verts.iter().map(|&v| mesh.pos(v)));
    (0..prims.len())
        .filter(|&j| {
            j != i
                && in_box(boxes[j], own.0)
                && in_box(boxes[j], own.1)
                && verts.iter().all(|&v| prims[j].contains(mesh.pos(v), tol))
        })
        .collect()
}

/// Whether primitive `j` contains `p` (its inflated AABB rejects most misses cheaply).
fn holds(prims: &[Primitive], boxes: &[(V3, V3)], j: usize, p: V3, tol: f64) -> bool {
    in_box(boxes[j], p) && prims[j].contains(p, tol)
}

fn inflate((lo, hi): (V3, V3), t: f64) -> (V3, V3) {
    (lo.map(|x| x - t), hi.map(|x| x + t))
}

fn in_box((lo, hi): (V3, V3), p: V3) -> bool {
    (0..3).all(|k| p[k] >= lo[k] && p[k] <= hi[k])
}
