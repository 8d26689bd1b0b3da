//! The library's entry points: check the settings, then one bottom-up pass
//! ([`pass`]) or, to fill each target's budget, several (`crate::postprocess::fill`).

pub(crate) mod objects;
pub(crate) mod pass;
pub(crate) mod tiles;

use crate::error::Result;
use crate::input::mesh::Mesh;
use crate::output::result::Decomposition;
use crate::params::{short_of, Goal, Params};
use crate::postprocess::fill;
use crate::progress::{Progress, Silent};

/// Decomposes `mesh` into primitives, one [`crate::Level`] per target in
/// `params.goal` (§3), one per count, tolerance or byte budget ([`crate::Goal`]):
/// every face lies inside at least one primitive of every level. Deterministic: the
/// same mesh and settings give the same primitives whatever the number of threads
/// (rayon's global pool; run it inside your own pool to choose).
///
/// ```
/// use primdecomp::{decompose, demo_scene, Goal, Params};
///
/// let result = decompose(&demo_scene(), &Params { goal: Goal::counts([30]), ..Params::default() })?;
/// assert!(result.levels[0].primitives.len() <= 30);
/// # Ok::<(), primdecomp::Error>(())
/// ```
///
/// # Errors
/// [`crate::Error::InvalidParams`] for settings out of range, before any work;
/// [`crate::Error::EmptyMesh`] for a mesh without faces; [`crate::Error::Extent`] and
/// [`crate::Error::Position`] for vertices too far apart or from the origin.
pub fn decompose(mesh: &Mesh, params: &Params) -> Result<Decomposition> {
    decompose_with(mesh, params, &Silent)
}

/// [`decompose`], reporting each stage's progress to `progress` and stopping with
/// [`crate::Error::Cancelled`] soon after `progress.cancelled()` turns true (see
/// [`Progress`] for an example).
pub fn decompose_with(
    mesh: &Mesh,
    params: &Params,
    progress: &dyn Progress,
) -> Result<Decomposition> {
    params.validate()?;
    if let Goal::Fill { .. } = params.goal {
        // Nested primitives removed leave room: merge less to fill it.
        return fill::fill(mesh, params, progress, &pass::run);
    }
    let mut dec = pass::run(mesh, params, progress)?;
    // A greedy level post-processing left short of its count is cut from the merge
    // tree instead, as on several parts (docs/decisions/0054); the other levels stay
    // the greedy's, so each level is what its own run gives.
    let faces = mesh.face_count();
    let short: Vec<usize> = (0..dec.levels.len())
        .filter(|&i| {
            let l = &dec.levels[i];
            params.goal.count_cut()
                && l.distance.is_none()
                && short_of(l.primitives.len(), l.target, faces)
        })
        .collect();
    if short.is_empty() {
        return Ok(dec);
    }
    let targets = params.goal.targets();
    let recut = Params {
        goal: Goal::cut_counts(short.iter().map(|&i| targets[i]).collect()),
        ..params.clone()
    };
    let cut = pass::run(mesh, &recut, progress)?;
    for (&i, level) in short.iter().zip(cut.levels) {
        dec.levels[i] = level;
    }
    let recut_stages = cut.timings.stages.into_iter();
    dec.timings
        .stages
        .extend(recut_stages.map(|(s, t)| (format!("recut {s}"), t)));
    Ok(dec)
}
