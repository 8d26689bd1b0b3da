//! One bottom-up pass (the paper's Algorithm 1), read top to bottom: weld, adjacency,
//! quadrics, the surface around each face, seed primitives, the merge loop through
//! every target, post-processing. Each stage is one call; [`Clock`] times it, reports
//! it to the caller's [`Progress`] and stops the run when it is cancelled.

use crate::cut::{limits, recut, tree};
use crate::error::{Error, Result};
use crate::input::mesh::Mesh;
use crate::input::solid::{self, Solid};
use crate::input::triangles::Triangles;
use crate::input::{adjacency, dedup};
use crate::math::V3;
use crate::merge::components;
use crate::merge::setup::{evaluator, seed_volumes};
use crate::merge::stage::{merge, merge_order, FirstPhase, MergeInput, Surface};
use crate::merge::Evaluator;
use crate::output::result::{Decomposition, InputInfo, Stats};
use crate::params::Params;
use crate::postprocess;
use crate::progress::clock::Clock;
use crate::progress::{Progress, Stage};
use crate::seed::quadric;

/// One pass through the goal's targets (a fill's further passes are the caller's: `postprocess::fill`).
pub(crate) fn run(mesh: &Mesh, params: &Params, progress: &dyn Progress) -> Result<Decomposition> {
    // Far-flung vertices would overflow volumes to inf and NaN
    // (docs/decisions/hostile-input-limits.md).
    check_input(mesh)?;
    let mut clock = Clock::new(progress);
    let bounds = mesh.aabb();
    // Weld overlapping vertices so seams between parts become adjacency (§3.4).
    let (welded, distinct) = clock
        .stage(Stage::Dedup, "dedup", |go_on, _| {
            dedup::weld_checked(mesh, params.fit.dedup, go_on)
        })?
        .ok_or(Error::Cancelled)?;
    // Faces sharing an edge form the merge graph (§3.3).
    let pairs = clock
        .stage(Stage::Adjacency, "adjacency", |go_on, _| {
            adjacency::face_pairs_checked(&mesh.face_offsets, &welded, go_on)
        })?
        .ok_or(Error::Cancelled)?;
    // Counts on several separate parts are cuts of the merge tree: the greedy level
    // drops the parts nested in one part's primitive (docs/decisions/0054).
    let point = |f: usize| {
        let corners = &welded[mesh.face_offsets[f] as usize..mesh.face_offsets[f + 1] as usize];
        corners.iter().all(|&v| v == corners[0])
    };
    let several = params.goal.count_cut() && components::several(mesh.face_count(), &pairs, point);
    let cut_params;
    let params = match several {
        true => {
            cut_params = Params {
                goal: params.goal.as_cut(),
                ..params.clone()
            };
            &cut_params
        }
        false => params,
    };
    let counts = params.goal.targets();
    // Spatial parts merge down to their share of the largest requested count's groups,
    // the greedy's own; a cut's leaves come from the global loop after them (0042).
    let largest = counts.iter().copied().max().unwrap_or(1);
    let mut targets = if params.uses_cut() {
        // The tree's leaves (a snapshot of a few times the largest target, needed only
        // after spatial parts: below) up to its roots (docs/decisions/0032, 0034).
        let leaves = largest.saturating_mul(crate::cut::LEAVES_PER_TARGET);
        merge_order(&[leaves.min(mesh.face_count()).max(largest), 1])
    } else {
        merge_order(&counts)
    };
    // Where the merge loop starts: spatial parts, components, or the faces themselves.
    let first = FirstPhase::choose(mesh, params, &pairs, targets[0], largest);
    // Spatial parts compute their faces' operators and seed volumes themselves, and
    // read the pairs from the surface's neighbour lists: none is held for every face.
    let per_part = matches!(first, FirstPhase::Parts { .. });
    // One operator per face (§3.1).
    let q = clock.stage(Stage::Quadrics, "quadrics", |go_on, _| {
        let mut q = Vec::new();
        if !per_part {
            quadric::face_quadrics_checked(mesh, params.fit.tangent_eps, &mut q, go_on);
        }
        q
    })?;
    // Each face's neighbours (the clusters' adjacency too) and outer side: output
    // fits keep off rims and lie flush.
    let adjacency_edges = pairs.len();
    let mut pairs = Some(pairs);
    let surface = clock
        .step_checked(Stage::Seed, "surface", |go_on| {
            let lists = adjacency::neighbour_lists(mesh.face_count(), pairs.as_ref()?);
            if per_part {
                pairs = None;
            }
            Surface::build(mesh, &welded, lists, params, go_on)
        })?
        .ok_or(Error::Cancelled)?;
    let pairs = pairs.unwrap_or_default();
    // The input's interior, where merges are priced by the air they add (--solid).
    let solid = clock.step(Stage::Seed, "solid", || {
        params
            .plates
            .solid
            .then(|| Solid::build(mesh, solid::CELLS, solid::VOTES))
    })?;
    let ev = Evaluator {
        face_sign: &surface.signs,
        face_adj: surface.adjacency(),
        solid: solid.as_ref(),
        ..evaluator(mesh, &welded, params, bounds)
    };
    // One primitive per face seeds the volumes (Alg. 1, line 2).
    let volumes = clock.stage(Stage::Seed, "seed", |go_on, _| match per_part {
        true => Vec::new(),
        false => seed_volumes(&ev, &q, go_on),
    })?;
    // Without spatial parts every merge is logged and the tree's leaves are the faces:
    // the leaf snapshot would be fitted for nothing.
    if params.uses_cut() && !per_part {
        targets = vec![1];
    }
    let mut stats = Stats {
        welded_vertices: distinct,
        adjacency_edges,
        partitions: first.parts(),
        ..Stats::default()
    };
    // The merge tree's leaves keep their own operators (a cut of the tree), when its
    // leaves are faces (after spatial parts they are the first snapshot's clusters).
    let face_q = if params.uses_cut() && !matches!(first, FirstPhase::Parts { .. }) {
        q.clone()
    } else {
        Vec::new()
    };
    // Greedy merging down through every target in one pass (Alg. 1's loop).
    let input = MergeInput {
        q,
        volumes,
        pairs,
        lists: (surface.offsets.clone(), surface.adj.clone()),
        tree: params.uses_cut(),
        hulls_over: tree::tree_hulls_over(mesh, params, largest),
        tangent_eps: params.fit.tangent_eps,
    };
    let mut merged = clock.stage(Stage::Merge, "merge", |go_on, laps| {
        merge(&ev, input, first, &targets, &mut stats, go_on, laps)
    })?;
    // The input's triangles, once, for the cut's distances and thickened plates.
    let cut = params.uses_cut() && !merged.stopped;
    let tris = clock.step_checked(Stage::Postprocess, "triangles", |go_on| {
        (cut || params.plates.min_thickness > 0.0).then(|| Triangles::new_checked(mesh, go_on))
    })?;
    let tris = match tris {
        Some(None) => return Err(Error::Cancelled),
        Some(Some(tris)) => Some(tris),
        None => None,
    };
    // The input's interior, once, for plates thickened inward (--min-thickness).
    let post = clock.step(Stage::Postprocess, "interior", || {
        postprocess::Input::new(&ev, params, tris.as_ref())
    })?;
    let requests = limits::requests(params, mesh);
    // The cut of the merge tree at each target where the error is (docs/decisions/0032), its
    // counts and bytes spent on what post-processing keeps.
    if let (true, Some(tris)) = (cut, &tris) {
        merged.snapshots = clock
            .stage(Stage::Postprocess, "cut", |go_on, _| {
                let tree = tree::merge_tree(&ev, &mut merged, &face_q);
                let post = |snaps| postprocess::levels(&ev, snaps, params, &post);
                recut::snapshots(&ev, &tree, &requests, tris, &post, go_on)
            })?
            .ok_or(Error::Cancelled)?;
    }
    // The bounds the cut proved, for the distances of what post-processing keeps.
    let known: Vec<Vec<(crate::primitive::Primitive, f64)>> = merged
        .snapshots
        .iter_mut()
        .map(|s| std::mem::take(&mut s.known))
        .collect();
    // Plates joined, duplicates absorbed, nested primitives removed, back to world
    // coordinates (§3.4).
    let mut levels = clock.stage(Stage::Postprocess, "postprocess", |_, _| {
        postprocess::levels(&ev, merged.snapshots, params, &post)
    })?;
    // What each cut's caller asked and how far its primitives stand from the input.
    if let (true, Some(tris)) = (cut, &tris) {
        clock.stage(Stage::Postprocess, "distance", |_, _| {
            limits::record_limits(&mut levels, &requests, &known, mesh, tris)
        })?;
    }
    Ok(Decomposition {
        input: input_info(mesh, bounds),
        levels,
        timings: clock.timings,
        stats,
    })
}

/// Refuses an input the engine cannot decompose: no faces, or vertices so far apart
/// that volumes would overflow.
fn check_input(mesh: &Mesh) -> Result<()> {
    if mesh.face_count() == 0 {
        return Err(Error::EmptyMesh {
            path: "<mesh>".into(),
        });
    }
    mesh.check_extent("<mesh>".as_ref())
}

pub(crate) fn input_info(mesh: &Mesh, (lo, hi): (V3, V3)) -> InputInfo {
    InputInfo {
        path: None,
        faces: mesh.face_count(),
        vertices: mesh.vertex_count(),
        aabb_min: crate::math::add(lo, mesh.offset),
        aabb_max: crate::math::add(hi, mesh.offset),
        up: None,
        up_from: None,
    }
}
