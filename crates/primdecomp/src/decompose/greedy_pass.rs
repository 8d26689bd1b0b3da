//! The greedy variant of a pass (§3.3, Alg. 1 as the paper has it): merging cheapest
//! first stops at each count asked, and the clusters alive there, post-processed
//! (§3.4), are its level.

use super::stages::{self, fitter_of, merge_stage, Graph, Seeds};
use crate::error::Result;
use crate::input::mesh::Mesh;
use crate::merge::stage::{merge_order, AtTargets, FirstPhase};
use crate::output::result::Decomposition;
use crate::params::Params;
use crate::postprocess;
use crate::progress::clock::Clock;
use crate::progress::{Latch, Stage};

/// The levels of `params.goal`'s counts, each the clusters alive when the merge loop
/// reached it, post-processed.
pub(crate) fn run(
    mesh: &Mesh,
    params: &Params,
    mut graph: Graph,
    mut clock: Clock,
) -> Result<Decomposition> {
    // The loop stops at each count asked, the largest first.
    let targets = merge_order(&params.goal.targets());
    // Where the merge loop starts: spatial parts (down to their share of the largest
    // count's groups, docs/decisions/0042), whole components, or the faces themselves.
    let first = FirstPhase::choose(mesh, params, &graph.pairs, targets[0], targets[0]);
    // One operator per face (§3.1), the faces' surface and the input's interior.
    let (seeds, around) = Seeds::build(&mut clock, mesh, params, &mut graph, &first)?;
    let fitter = fitter_of(mesh, &graph, params, &around);
    // One primitive per face seeds the volumes (Alg. 1, line 2).
    let volumes = stages::seed(&mut clock, &fitter, seeds.quadrics(), &first)?;
    let (input, mut stats) = seeds.merge_input(volumes, &around, params);
    // Greedy merging down through every target in one pass (Alg. 1's loop), keeping
    // the clusters at each.
    let at = (&targets[..], AtTargets);
    let (merged, (), signs) = merge_stage(&mut clock, &fitter, (input, first), at, &mut stats)?;
    // Output fits read the faces' outer sides, found by the merge stage after parts.
    let around = around.with_signs(signs);
    let fitter = fitter_of(mesh, &graph, params, &around);
    // The input's triangles, once, for thickened plates (--min-thickness), and its
    // interior for plates thickened inward.
    let tris = stages::triangles(&mut clock, mesh, params.plates.min_thickness > 0.0)?;
    let reads = stages::interior(&mut clock, mesh, params, tris.as_ref())?;
    // Plates joined, duplicates absorbed, nested primitives removed, back to world
    // coordinates (§3.4).
    let levels = clock.stage(Stage::Postprocess, "postprocess", |go_on, _| {
        let latch = Latch::new(go_on, 0.0);
        postprocess::levels(&fitter, merged.snapshots, params, &reads, &|| {
            latch.goes_on()
        })
    })?;
    Ok(stages::decomposition(mesh, &graph, levels, clock, stats))
}
