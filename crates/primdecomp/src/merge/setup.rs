//! The merge's settings made absolute for one input ([`pricing`]) and each face's
//! seed volume (Alg. 1, line 2).

use super::cost::Pricing;
use super::{Fitter, Workspace};
use crate::math::{Sym3, V3};
use crate::params::{Params, Reprice};
use crate::primitive::fit::{FitConfig, FrameSearch};
use crate::progress::Checkpoint;
use rayon::prelude::*;

/// Smallest half-extent or radius of any primitive, whatever the mesh and settings.
/// Every fit divides by half-extents, and volumes are their cubes: with a zero diagonal
/// (a mesh collapsed to one point) or a product `min_extent × diagonal` that
/// underflows (a mesh 6e-22 across with a minimum extent of 7e-304 made it 0, and the
/// frustum fit divided 0 by 0), lengths must still be positive, and their cubes (and the
/// reciprocals of their squares, in the tests' oracle) normal numbers. Together with
/// `mesh::MAX_EXTENT` this keeps every length the engine fits within [1e-90, 1e60].
/// Only meshes under ~1e-87 across are affected: their primitives are at least 2e-90
/// across.
pub(crate) const MIN_HALF: f64 = 1e-90;

/// Merge costs are compared on a grid of this fraction of the diagonal cubed (2^-40).
pub(crate) const COST_GRID: f64 = 1.0 / (1u64 << 40) as f64;

/// The settings made absolute for an input whose used vertices span `bounds`
/// (re-centred, from [`Mesh::aabb`]): the minimum extent, the excess cap, the cost
/// grid and the hull tolerance scale with its diagonal.
pub fn pricing(params: &Params, bounds: (V3, V3)) -> Pricing {
    let (lo, hi) = bounds;
    let diag = crate::math::norm(crate::math::sub(hi, lo));
    let min_half = (params.fit.min_extent * diag).max(MIN_HALF);
    let aabb_volume: f64 = (0..3)
        .map(|k| (hi[k] - lo[k]).max(2.0 * min_half))
        .product();
    Pricing {
        fit: FitConfig {
            weights: params.fit.weights,
            enabled: params.fit.kinds,
            min_half,
            frames: FrameSearch::Degenerate,
        },
        flat_scale: (params.plates.open_holes * diag / min_half).max(1.0),
        max_excess: params
            .fit
            .max_excess_volume
            .map_or(f64::INFINITY, |m| m * aabb_volume),
        defer_degree: match params.reprice {
            Reprice::Deferred { min_degree } => min_degree,
            Reprice::Exact => u32::MAX,
        },
        // Never 0 (at least 2^-40 × MIN_HALF³ ≈ 1e-282): a zero grid priced every merge
        // 0/0 = NaN, which the merge loop drops like a merge over the excess cap.
        cost_unit: COST_GRID * diag.max(min_half).powi(3),
        hull_eps: 1e-12 * diag.max(min_half),
        rim_weight: params.plates.rim_weight,
        free_merges: params.plates.join_coplanar,
        flush_plates: params.plates.flush_plates,
    }
}

/// A [`Fitter`] on `mesh` welded by `weld` alone (no surface, no
/// interior), its settings made absolute by [`pricing`] (the tests' and benchmarks').
#[cfg(any(test, feature = "test-internals"))]
pub fn fitter<'a>(
    mesh: &'a crate::input::mesh::Mesh,
    weld: &'a crate::input::dedup::Weld,
    params: &Params,
    bounds: (V3, V3),
) -> Fitter<'a> {
    Fitter {
        input: super::cost::InputView::new(mesh, weld),
        pricing: pricing(params, bounds),
    }
}

/// Faces per block of seed fits between progress reports and cancellation checks.
pub(crate) const SEED_BLOCK: usize = 1 << 16;

/// Volume of each face's own primitive, in parallel, a block at a time (stops early,
/// with the rest left 0, when `go_on` says so; the caller then returns cancelled).
pub(crate) fn seed_volumes(fitter: &Fitter, q: &[Sym3], go_on: Checkpoint) -> Vec<f64> {
    let mut out = vec![0.0; q.len()];
    for (b, block) in out.chunks_mut(SEED_BLOCK).enumerate() {
        let start = b * SEED_BLOCK;
        block
            .par_iter_mut()
            .enumerate()
            .with_min_len(1024)
            .for_each_init(Workspace::default, |ws, (i, v)| {
                let f = start + i;
                *v = fitter.seed_volume(f as u32, &q[f], ws);
            });
        if !go_on((start + block.len()) as f64 / q.len().max(1) as f64) {
            break;
        }
    }
    out
}
