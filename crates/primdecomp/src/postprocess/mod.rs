//! Post-processing (§3.4 "Removing Redundant Primitives"), after the merge loop: each
//! target's snapshot has near-duplicate primitives absorbed (with solid pricing,
//! [`absorb`]), coplanar plates joined ([`plates`]), plates thickened inward
//! ([`thicken`], opt-in), nested primitives removed
//! ([`nested`]) and is moved back to world coordinates.

pub(crate) mod absorb;
pub(crate) mod fill;
pub(crate) mod nested;
pub(crate) mod plates;
pub(crate) mod thicken;

use crate::input::triangles::Triangles;
use crate::merge::{Evaluator, Snapshot};
use crate::output::result::Level;
use crate::params::Params;
use nested::{keep_mask, Cleanup};

/// What post-processing reads of the input besides the evaluator, made once per run
/// (a cut may post-process its levels several times, `cut::recut`): its triangles, built
/// by the run when a step needs them, and with a minimum thickness the input as rays
/// see it (its interior on a voxel grid), for plates thickened inward
/// (docs/decisions/0033).
pub(crate) struct Input<'a> {
    tris: Option<&'a Triangles<'a>>,
    thick: Option<thicken::Input<'a>>,
}

impl<'a> Input<'a> {
    pub(crate) fn new(ev: &Evaluator, params: &Params, tris: Option<&'a Triangles>) -> Self {
        let thick = tris
            .filter(|_| params.plates.min_thickness > 0.0)
            .map(|t| thicken::Input::build(ev, t));
        Input { tris, thick }
    }
}

/// One level per target of `params.goal` (in the order given) from the merge
/// loop's snapshots.
pub(crate) fn levels(
    ev: &Evaluator,
    mut snaps: Vec<Snapshot>,
    params: &Params,
    input: &Input,
) -> Vec<Level> {
    let diag = ev.mesh.diagonal();
    let (tris, thick) = (input.tris, &input.thick);
    for snap in &mut snaps {
        let mut q = std::mem::take(&mut snap.q);
        // Solid pricing: near-duplicate primitives become one (docs/decisions/0023).
        if ev.solid.is_some() {
            absorb::absorb(ev, snap, &mut q);
        }
        // Plates in one plane the merge left apart become one where that adds no
        // area (docs/decisions/0028).
        if ev.join_plates {
            plates::join(ev, snap, &mut q, tris);
        }
        // Plates reach inward to the minimum thickness where the input is closed.
        if let Some(input) = thick {
            thicken::thicken(ev, input, snap, params.plates.min_thickness * diag);
        }
    }
    // A cut's snapshots are one per target, in order (targets may repeat with
    // different tolerances); the greedy pass's are found by their count.
    let targets = params.goal.targets();
    if params.uses_cut() && snaps.len() == targets.len() {
        return snaps.iter().map(|s| finish(ev, s, params, diag)).collect();
    }
    targets
        .iter()
        .map(|&n| {
            let snap = snaps
                .iter()
                .find(|s| s.target == n)
                .expect("a snapshot per target");
            finish(ev, snap, params, diag)
        })
        .collect()
}

/// Removes nested primitives from one snapshot and moves it to world coordinates.
fn finish(ev: &Evaluator, snap: &Snapshot, params: &Params, diag: f64) -> Level {
    let cleanup = Cleanup {
        diagonal: diag,
        remove_nested: params.plates.remove_nested,
        thin_box_half: params.plates.remove_thin_boxes.map(|t| t * diag),
    };
    let keep = keep_mask(ev.mesh, &snap.prims, &snap.verts, &snap.members, cleanup);
    let mut level = Level {
        target: snap.target,
        merged_to: snap.target,
        shortfall: snap.shortfall,
        ..Default::default()
    };
    for (i, p) in snap.prims.iter().enumerate() {
        if keep[i] {
            level.primitives.push(p.to_world(ev.mesh.offset));
            level.faces.push(snap.faces[i]);
        }
    }
    level
}
