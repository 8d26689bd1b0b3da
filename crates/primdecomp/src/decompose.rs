//! The library's entry points: check the settings, then one bottom-up pass
//! ([`pass`]) or, to fill each target's budget, several (`crate::postprocess::fill`).

mod cut_pass;
mod greedy_pass;
pub(crate) mod objects;
pub(crate) mod stages;
pub(crate) mod tiles;

use crate::error::{Error, Result};
use crate::input::mesh::Mesh;
use crate::output::result::Decomposition;
use crate::params::{short_of, Goal, Params};
use crate::postprocess::fill;
use crate::progress::clock::Clock;
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
/// [`Progress`] for a progress that cancels).
///
/// ```
/// use primdecomp::{decompose_with, Mesh, Params, Stage};
/// use std::sync::Mutex;
///
/// let corners = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
/// let tetrahedron = Mesh::from_triangles(&corners, &[[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])?;
/// let seen = Mutex::new(Vec::new());
/// let result = decompose_with(&tetrahedron, &Params::default(), &|stage: Stage, _done: f64| {
///     seen.lock().unwrap().push(stage)
/// })?;
/// assert_eq!(result.levels.len(), 1);
/// assert!(seen.into_inner().unwrap().contains(&Stage::Merge));
/// # Ok::<(), primdecomp::Error>(())
/// ```
pub fn decompose_with(
    mesh: &Mesh,
    params: &Params,
    progress: &dyn Progress,
) -> Result<Decomposition> {
    params.validate()?;
    if let Goal::Fill { .. } = params.goal {
        // Nested primitives removed leave room: merge less to fill it.
        return fill::fill(mesh, params, progress, &pass);
    }
    let mut dec = pass(mesh, params, progress)?;
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
    let cut = pass(mesh, &recut, progress)?;
    for (&i, level) in short.iter().zip(cut.levels) {
        dec.levels[i] = level;
    }
    let recut_stages = cut.timings.into_iter();
    dec.timings
        .extend(recut_stages.map(|(s, t)| (format!("recut {s}"), t)));
    Ok(dec)
}

/// One pass through the goal's targets (a fill's further passes are the caller's:
/// `postprocess::fill`): the merge graph, then the variant the goal asks for, the
/// greedy ([`greedy_pass`]) or the cut of the merge tree ([`cut_pass`]).
pub(crate) fn pass(mesh: &Mesh, params: &Params, progress: &dyn Progress) -> Result<Decomposition> {
    // Far-flung vertices would overflow volumes to inf and NaN
    // (docs/decisions/hostile-input-limits.md).
    stages::check_input(mesh)?;
    let mut clock = Clock::new(progress);
    // Welded vertices and the faces sharing an edge: the merge graph (§3.4, §3.3).
    let graph = stages::Graph::build(&mut clock, mesh, params)?;
    // Counts on several separate parts are cuts of the merge tree: the greedy level
    // drops the parts nested in one part's primitive (docs/decisions/0054).
    let several = || graph.several_parts(mesh, &|| !progress.cancelled());
    if params.goal.count_cut() && several().ok_or(Error::Cancelled)? {
        let cut = Params {
            goal: params.goal.as_cut(),
            ..params.clone()
        };
        return cut_pass::run(mesh, &cut, graph, clock);
    }
    match params.uses_cut() {
        true => cut_pass::run(mesh, params, graph, clock),
        false => greedy_pass::run(mesh, params, graph, clock),
    }
}
