//! The cut variant of a pass (docs/decisions/0032, a deviation from §3.3): merging
//! goes on to one cluster, every merge logged as the merge tree, and each level is
//! the cut of that tree its tolerance, byte budget or count asks for, post-processed
//! (§3.4) with its distance to the input recorded.

use super::stages::{self, fitter_of, merge_stage, Around, Graph, Seeds};
use crate::cut::tree::{self, MergeTree};
use crate::cut::{limits, recut, LevelCut, LEAVES_PER_TARGET};
use crate::error::{Error, Result};
use crate::input::mesh::Mesh;
use crate::input::triangles::Triangles;
use crate::merge::stage::{merge_order, FirstPhase, ForTree};
use crate::merge::Fitter;
use crate::output::result::{Decomposition, Level, Stats};
use crate::params::Params;
use crate::postprocess::{self, Prepared};
use crate::progress::clock::Clock;
use crate::progress::{Ask, Latch, Stage};

/// The levels of `params.goal`, each a cut of the merge tree, post-processed.
pub(crate) fn run(
    mesh: &Mesh,
    params: &Params,
    mut graph: Graph,
    mut clock: Clock,
) -> Result<Decomposition> {
    let largest = params.goal.targets().into_iter().max().unwrap_or(1);
    let (first, targets) = loop_plan(mesh, params, &graph, largest);
    // One operator per face (§3.1), the faces' surface and the input's interior.
    let (seeds, around) = Seeds::build(&mut clock, mesh, params, &mut graph, &first)?;
    let fitter = fitter_of(mesh, &graph, params, &around);
    let plan = (first, &targets[..], largest);
    let (tree, stats, signs) = grow_tree(&mut clock, &fitter, params, (seeds, &around), plan)?;
    // The cut's fits read the faces' outer sides, found by the merge stage after parts.
    let around = around.with_signs(signs);
    let fitter = fitter_of(mesh, &graph, params, &around);
    // What the merge stage freed goes back to the system before the largest
    // structure of the pass is built.
    crate::input::memory::release_freed();
    // The input's triangles, once, for the cut's distances and thickened plates, and
    // its interior for plates thickened inward (--min-thickness). Under --solid the
    // cut's distances are to the input's solid (docs/decisions/0056).
    let tris = stages::triangles(&mut clock, mesh, true)?.ok_or(Error::Cancelled)?;
    let tris = tris.with_solid(fitter.input.solid);
    let reads = stages::interior(&mut clock, mesh, params, Some(&tris))?;
    let levels = cut_levels(&mut clock, &fitter, &tree, params, (&tris, &reads))?;
    Ok(stages::decomposition(mesh, &graph, levels, clock, stats))
}

/// Where the merge loop starts and the counts it snapshots at on its way to the
/// roots. The tree's leaves are a snapshot of a few times the largest target, needed
/// only after spatial parts (docs/decisions/0032, 0034): spatial parts merge down to
/// their share of the largest count's groups, the greedy's own, and the leaves come
/// from the global loop after them (docs/decisions/0042), the large ones taken apart
/// down to their faces by the parts' logged merges (docs/decisions/0057). From
/// components or the faces, every merge is logged and the leaves are the faces: no
/// snapshot but the root.
fn loop_plan(
    mesh: &Mesh,
    params: &Params,
    graph: &Graph,
    largest: usize,
) -> (FirstPhase, Vec<usize>) {
    let leaves = largest.saturating_mul(LEAVES_PER_TARGET);
    let targets = merge_order(&[leaves.min(mesh.face_count()).max(largest), 1]);
    let first = FirstPhase::choose(mesh, params, &graph.pairs, targets[0], largest);
    match first {
        FirstPhase::Parts { .. } => (first, targets),
        _ => (first, vec![1]),
    }
}

/// The merge tree: seeding, then merging down to the roots with every merge logged
/// (Alg. 1's loop); the run's counters, and the faces' outer sides where the merge
/// stage found them (`Around::with_signs`).
fn grow_tree(
    clock: &mut Clock,
    fitter: &Fitter,
    params: &Params,
    (seeds, around): (Seeds, &Around),
    (first, targets, largest): (FirstPhase, &[usize], usize),
) -> Result<(MergeTree, Stats, Option<Vec<i8>>)> {
    let mesh = fitter.input.mesh;
    // One primitive per face seeds the volumes (Alg. 1, line 2).
    let volumes = stages::seed(clock, fitter, seeds.quadrics(), &first)?;
    let keep = ForTree {
        hulls_over: tree::tree_hulls_over(mesh, params, largest),
    };
    // After spatial parts, the leaves larger than a primitive's mean at the largest
    // count are taken apart.
    let split = tree::Split {
        over: mesh.face_count() / largest.max(1),
        tangent_eps: params.fit.tangent_eps,
    };
    let (input, mut stats) = seeds.merge_input(volumes, around, params);
    let (merged, log, signs) =
        merge_stage(clock, fitter, (input, first), (targets, keep), &mut stats)?;
    if merged.stopped {
        return Err(Error::Cancelled);
    }
    // The merge tree, before the triangles are built: the loop's snapshots and its
    // log are dead once it is.
    let tree = clock.step(Stage::Postprocess, "tree", || {
        tree::merge_tree(fitter, &merged, log, split)
    })?;
    Ok((tree, stats, signs))
}

/// The levels: the cut of the merge tree at each target where the error is (0032),
/// its counts and bytes spent on what post-processing keeps (0044), post-processed,
/// back to world coordinates, each with what it asked and how far its primitives
/// stand from the input.
fn cut_levels(
    clock: &mut Clock,
    fitter: &Fitter,
    tree: &MergeTree,
    params: &Params,
    (tris, reads): (&Triangles, &Prepared),
) -> Result<Vec<Level>> {
    let mesh = fitter.input.mesh;
    let requests = limits::requests(params, mesh);
    let (mut cuts, done) = clock
        .stage(Stage::Postprocess, "cut", |go_on, _| {
            let latch = Latch::new(go_on, 0.0);
            let postprocess = |cuts: &mut [LevelCut]| {
                postprocess_cuts(fitter, params, reads, cuts, &|| latch.goes_on())
            };
            recut::snapshots(fitter, tree, &requests, tris, &postprocess, go_on)
        })?
        .ok_or(Error::Cancelled)?;
    // The kept cuts post-processed: the levels the cut's search made of them, or,
    // where each was cut once, made now. (The cut was post-processing's stage,
    // reported done: its fraction stays 1.)
    let mut levels = clock.stage(Stage::Postprocess, "postprocess", |go_on, _| {
        let latch = Latch::new(go_on, 1.0);
        done.unwrap_or_else(|| {
            postprocess_cuts(fitter, params, reads, &mut cuts, &|| latch.goes_on())
        })
    })?;
    clock.stage(Stage::Postprocess, "distance", |_, _| {
        limits::record_limits(&mut levels, &requests, &cuts, mesh, tris)
    })?;
    Ok(levels)
}

/// Post-processing (§3.4), the step each cut is measured after: plates joined within
/// the cut's bound, duplicates absorbed, nested primitives removed. Asks `go_on`
/// within each level (a level not to keep once it said stop). Each round's freed
/// scratch goes back to the system before and after it: what glibc keeps of the
/// cut's rounds otherwise adds to the pass's peak. Each cut's faces' lists are moved
/// into post-processing, not copied.
fn postprocess_cuts(
    fitter: &Fitter,
    params: &Params,
    reads: &Prepared,
    cuts: &mut [LevelCut],
    go_on: Ask,
) -> Vec<Level> {
    crate::input::memory::release_freed();
    let levels = (cuts.iter_mut())
        .map(|c| Level {
            shortfall: c.shortfall,
            ..postprocess::level(
                fitter,
                c.take_for_postprocess(),
                Some(c.bound),
                params,
                reads,
                go_on,
            )
        })
        .collect();
    crate::input::memory::release_freed();
    levels
}
