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

use crate::input::mesh::Mesh;
use crate::input::triangles::Triangles;
use crate::merge::cost::InputView;
use crate::merge::{Fitter, Snapshot};
use crate::output::result::Level;
use crate::params::Params;
use crate::progress::Ask;
use nested::{keep_mask_checked, Cleanup};

/// What post-processing reads of the input besides the fitter, made once per run
/// (a cut may post-process its levels several times, `cut::recut`): its triangles, built
/// by the run when a step needs them, and with a minimum thickness the input as rays
/// see it (its interior on a voxel grid), for plates thickened inward
/// (docs/decisions/0033).
pub(crate) struct Prepared<'a> {
    tris: Option<&'a Triangles<'a>>,
    thick: Option<thicken::Interior<'a>>,
}

impl<'a> Prepared<'a> {
    pub(crate) fn new(mesh: &Mesh, params: &Params, tris: Option<&'a Triangles>) -> Self {
        let thick = tris
            .filter(|_| params.plates.min_thickness > 0.0)
            .map(|t| thicken::Interior::build(mesh, t));
        Prepared { tris, thick }
    }
}

/// One level per target of `params.goal` (in the order given) from the greedy merge
/// loop's snapshots (one per distinct target), each post-processed once ([`level`]:
/// once `go_on` said stop, levels not to be kept).
pub(crate) fn levels(
    fitter: &Fitter,
    snaps: Vec<Snapshot>,
    params: &Params,
    input: &Prepared,
    go_on: Ask,
) -> Vec<Level> {
    let done: Vec<Level> = (snaps.into_iter())
        .map(|snap| level(fitter, snap, None, params, input, go_on))
        .collect();
    (params.goal.targets().iter())
        .map(|&n| {
            let level = done.iter().find(|l| l.target == n);
            level.expect("a snapshot per target").clone()
        })
        .collect()
}

/// One snapshot post-processed into its level; `bound`: a cut's, the farthest its
/// primitives may stand from the input, which joined plates keep to. `go_on` is
/// asked between the steps, before each pair of plates fitted together and each
/// primitive tested for hosts: once it said stop, the steps left are skipped and
/// the level returned is not one to keep.
pub(crate) fn level(
    fitter: &Fitter,
    mut snap: Snapshot,
    bound: Option<f64>,
    params: &Params,
    input: &Prepared,
    go_on: Ask,
) -> Level {
    let diag = fitter.input.mesh.diagonal();
    let (tris, thick) = (input.tris, &input.thick);
    let mut q = std::mem::take(&mut snap.q);
    // Solid pricing: near-duplicate primitives become one (docs/decisions/0023).
    if fitter.input.solid.is_some() && go_on() {
        absorb::absorb(fitter, &mut snap, &mut q, (tris, bound));
    }
    // Plates in one plane the merge left apart become one where that adds no
    // area (docs/decisions/0028).
    if params.plates.join_coplanar && go_on() {
        plates::join(fitter, &mut snap, &mut q, tris, bound, go_on);
    }
    // Plates reach inward to the minimum thickness where the input is closed.
    if let Some(input) = thick.as_ref().filter(|_| go_on()) {
        thicken::thicken(
            &fitter.input,
            input,
            &mut snap,
            params.plates.min_thickness * diag,
        );
    }
    finish(&fitter.input, &snap, params, diag, go_on)
}

/// Removes nested primitives from one snapshot and moves it to world coordinates
/// (all kept once `go_on` said stop).
fn finish(view: &InputView, snap: &Snapshot, params: &Params, diag: f64, go_on: Ask) -> Level {
    let cleanup = Cleanup {
        diagonal: diag,
        remove_nested: params.plates.remove_nested,
        thin_box_half: params.plates.remove_thin_boxes.map(|t| t * diag),
    };
    let (prims, verts, members) = (&snap.prims, &snap.verts, &snap.members);
    let keep = keep_mask_checked(view.mesh, prims, verts, members, cleanup, go_on)
        .unwrap_or_else(|| vec![true; prims.len()]);
    let mut level = Level {
        target: snap.target,
        merged_to: snap.target,
        ..Default::default()
    };
    for (i, p) in snap.prims.iter().enumerate() {
        if keep[i] {
            level.primitives.push(p.to_world(view.mesh.offset));
            level.faces.push(snap.faces[i]);
        }
    }
    level
}
