//! What each level of a cut asked and how far its primitives stand from the input,
//! recorded on the post-processed levels.

use super::error::worst_error;
use super::{LevelCut, Request};
use crate::input::mesh::Mesh;
use crate::input::triangles::Triangles;
use crate::output::result::Level;
use crate::params::Params;
use crate::primitive::Primitive;
use std::collections::HashMap;

/// Records on each level what its request asked (tolerance, bytes) and the estimated
/// farthest its primitives stand from the input ([`worst_error`], in the input's
/// frame; to its solid where `surface` measures to it), `cuts[i].known` holding the primitives level `i`'s cut made with their bounds
/// (those post-processing left as they were need no search past them).
pub(crate) fn record_limits(
    levels: &mut [Level],
    requests: &[Request],
    cuts: &[LevelCut],
    mesh: &Mesh,
    surface: &Triangles,
) {
    let back = mesh.offset.map(|x| -x);
    for ((level, r), cut) in levels.iter_mut().zip(requests).zip(cuts) {
        level.tolerance = r.tolerance;
        level.max_bytes = r.bytes;
        let made = made_by_cut(&cut.known, mesh.offset);
        let (prims, bounds): (Vec<Primitive>, Vec<f64>) = level
            .primitives
            .iter()
            .map(|p| {
                made.get(&key(p))
                    .and_then(|v| v.iter().find(|m| m.world == *p))
                    .map_or((p.translated(back), f64::INFINITY), |m| (m.cut, m.bound))
            })
            .unzip();
        let worst = worst_error(&prims, &bounds, surface, r.tolerance.unwrap_or(0.0));
        level.distance = Some(worst);
        level.distance_to_solid = surface.to_solid();
        if r.tolerance.is_some_and(|t| worst <= t) {
            level.shortfall = None;
        }
    }
}

/// A primitive the cut made, as it made it and in world coordinates, with the upper
/// bound of its error it proved.
struct Made {
    cut: Primitive,
    world: Primitive,
    bound: f64,
}

/// The cut's primitives with a proved bound, by their world primitive's [`key`].
/// Only those whose move to world coordinates is a translation: a round one is
/// padded there, so the bound proved before would not be the world primitive's.
fn made_by_cut(
    known: &[(Primitive, f64)],
    offset: crate::math::V3,
) -> HashMap<[u64; 6], Vec<Made>> {
    let mut made: HashMap<[u64; 6], Vec<Made>> = HashMap::new();
    for &(cut, bound) in known {
        let world = cut.to_world(offset);
        if world == cut.translated(offset) {
            let m = Made { cut, world, bound };
            made.entry(key(&world)).or_default().push(m);
        }
    }
    made
}

/// A primitive's bounding box's bits: equal primitives have equal keys.
pub(super) fn key(p: &Primitive) -> [u64; 6] {
    let (lo, hi) = p.aabb();
    [lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]].map(f64::to_bits)
}

/// Each target's request of the cut, its tolerance in the mesh's units.
pub(crate) fn requests(params: &Params, mesh: &Mesh) -> Vec<Request> {
    let diagonal = mesh.diagonal();
    let counts = params.goal.targets();
    (0..counts.len())
        .map(|i| {
            let (tolerance, bytes) = params.goal.level_limits(i);
            Request {
                count: counts[i],
                bytes,
                tolerance: tolerance.map(|t| t.in_units(diagonal)),
            }
        })
        .collect()
}
