//! The driver (Alg. 1): reads top to bottom like the paper's recipe — weld, adjacency,
//! quadrics, seed primitives, merge loop through every target, post-process.

use crate::error::{Error, Result};
use crate::math::V3;
use crate::merge::rim::FaceAdjacency;
use crate::merge::{components, partition, Clusters, Evaluator, Workspace};
use crate::mesh::solid::{self, Solid};
use crate::mesh::{adjacency, dedup, Mesh};
use crate::params::{Params, Reprice};
use crate::postprocess::{keep_mask, Cleanup};
use crate::primitive::fit::{FitConfig, FrameSearch};
use crate::primitive::Primitive;
use crate::quadric;
use rayon::prelude::*;
use serde::Serialize;
use std::time::Instant;

/// What the input was.
#[derive(Clone, Debug, Default, Serialize)]
pub struct InputInfo {
    pub path: Option<String>,
    pub faces: usize,
    pub vertices: usize,
    pub aabb_min: V3,
    pub aabb_max: V3,
}

/// Result for one target count.
#[derive(Clone, Debug, Default)]
pub struct Level {
    /// The requested target N.
    pub target: usize,
    /// The target the merge loop stopped at: N, or with `Params::fill` the larger
    /// count whose post-processed result fills the budget of N best (budget.rs).
    pub merged_to: usize,
    /// Primitives in world coordinates, in a deterministic order.
    pub primitives: Vec<Primitive>,
    /// For each primitive, how many input faces it subsumes.
    pub faces: Vec<u32>,
}

impl Level {
    /// Primitive counts indexed by `Kind as usize`.
    pub fn counts(&self) -> [usize; 6] {
        let mut c = [0; 6];
        for p in &self.primitives {
            c[p.kind() as usize] += 1;
        }
        c
    }
    /// Bytes by the paper's Table 2.
    pub fn bytes(&self) -> usize {
        self.primitives.iter().map(|p| p.kind().bytes()).sum()
    }
}

/// Wall-clock seconds of each stage, in order.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Timings {
    pub stages: Vec<(String, f64)>,
}

impl Timings {
    pub fn push(&mut self, stage: &str, since: std::time::Instant) {
        self.stages
            .push((stage.to_string(), since.elapsed().as_secs_f64()));
    }
    pub fn total(&self) -> f64 {
        self.stages.iter().map(|s| s.1).sum()
    }
}

/// Everything a run produces.
#[derive(Clone, Debug, Default)]
pub struct Decomposition {
    pub input: InputInfo,
    /// One entry per target, in the order the targets were given.
    pub levels: Vec<Level>,
    pub timings: Timings,
    /// Faces after loading, vertices after deduplication, adjacency edges.
    pub welded_vertices: usize,
    pub adjacency_edges: usize,
    /// Merges done across components (edges added when adjacency ran out).
    pub bridge_edges: usize,
    /// Merges done and candidate merges priced by the merge loop.
    pub merges: usize,
    pub fits: crate::merge::FitCounts,
    /// Merges whose points were reduced while the batch before them was priced.
    pub merges_ahead: usize,
    /// Merges that components' loops did past the last target (they run each component
    /// whole, then the output is replayed from their first merges; merge/components.rs).
    pub merges_past: usize,
    /// Spatial parts merged in parallel before the global loop (1 = none).
    pub partitions: usize,
}

/// Decomposes `mesh` into primitives, one [`Level`] per target in `params.targets`.
pub fn decompose(mesh: &Mesh, params: &Params) -> Result<Decomposition> {
    decompose_with_progress(mesh, params, &|_| {})
}

/// [`decompose`], reporting the merge loop's progress as a fraction in [0, 1].
pub fn decompose_with_progress(
    mesh: &Mesh,
    params: &Params,
    progress: &(dyn Fn(f64) + Sync),
) -> Result<Decomposition> {
    params.validate()?;
    if params.fill {
        // Nested primitives removed leave room: merge less to fill it (budget.rs).
        return crate::budget::fill(mesh, params, progress);
    }
    decompose_once(mesh, params, progress)
}

/// One bottom-up pass through `params.targets` (ignores `params.fill`).
pub(crate) fn decompose_once(
    mesh: &Mesh,
    params: &Params,
    progress: &(dyn Fn(f64) + Sync),
) -> Result<Decomposition> {
    if mesh.face_count() == 0 {
        return Err(Error::EmptyMesh {
            path: "<mesh>".into(),
        });
    }
    // Far-flung vertices would overflow volumes to inf and NaN (issue 6).
    mesh.check_extent("<mesh>".as_ref())?;
    // One pass over the used vertices gives every size-relative setting its scale.
    let bounds = mesh.aabb();
    let diag = crate::math::norm(crate::math::sub(bounds.1, bounds.0));
    let mut dec = Decomposition {
        input: input_info(mesh, bounds),
        ..Default::default()
    };
    // Weld overlapping vertices so seams between parts become adjacency (§3.4).
    let now = Instant::now();
    let (welded, distinct) = dedup::weld(mesh, params.dedup);
    dec.welded_vertices = distinct;
    dec.timings.push("dedup", now);
    // Faces sharing an edge form the merge graph (§3.3).
    let now = Instant::now();
    let pairs = adjacency::face_pairs(&mesh.face_offsets, &welded);
    dec.adjacency_edges = pairs.len();
    dec.timings.push("adjacency", now);
    // One operator per face (§3.1).
    let now = Instant::now();
    let mut q = Vec::new();
    quadric::face_quadrics(mesh, params.tangent_eps, &mut q);
    dec.timings.push("quadrics", now);
    // One primitive per face seeds the volumes (Alg. 1, line 2).
    let now = Instant::now();
    // Face neighbour lists and outward sides agreeing across shared edges, for the
    // outward and rim reaches of the output fits and flush plates (deviations 22, 24, 26).
    let reaches = params.rim_weight > 0.0 || params.outward_weight > 0.0 || params.flush_plates;
    let (adj_offsets, adj) = if reaches {
        adjacency::neighbour_lists(mesh.face_count(), &pairs)
    } else {
        (Vec::new(), Vec::new())
    };
    let signs = if reaches {
        crate::mesh::orient::face_signs_of_lists(mesh, &welded, &adj_offsets, &adj)
    } else {
        Vec::new()
    };
    // The interior, where merges are priced by the air they add (deviation 23).
    let solid = params
        .solid
        .then(|| Solid::build(mesh, solid::CELLS, solid::VOTES));
    let ev = Evaluator {
        face_sign: &signs,
        solid: solid.as_ref(),
        face_adj: FaceAdjacency {
            offsets: &adj_offsets,
            adj: &adj,
        },
        ..evaluator(mesh, &welded, params, bounds)
    };
    let volumes = seed_volumes(&ev, &q);
    let mut targets = params.targets.clone();
    targets.sort_unstable_by(|a, b| b.cmp(a));
    targets.dedup();
    // Progress is the fraction of the merges to the last target (over both phases).
    let last = *targets.last().expect("validated: one target or more");
    let total = mesh.face_count().saturating_sub(last).max(1) as f64;
    dec.partitions = parts(mesh, params, targets[0]);
    let input = MergeInput { q, volumes, pairs };
    let merged_so_far = |m: usize| progress((m as f64 / total).min(1.0));
    // Where the global loop starts, and the targets reached without it.
    let (clusters, early) = if dec.partitions > 1 {
        dec.timings.push("seed", now);
        let clusters = partitioned(&ev, input, &targets, &mut dec, &merged_so_far);
        (Some(clusters), Vec::new())
    } else if let Some(comps) = component_phase(mesh, params, &input.pairs) {
        dec.timings.push("seed", now);
        by_components(&ev, input, comps, &targets, &mut dec, &merged_so_far)
    } else {
        // The clusters take the adjacency over; the pairs go at the end of this block.
        let MergeInput { q, volumes, pairs } = input;
        let clusters = Clusters::new(q, volumes, &pairs);
        dec.timings.push("seed", now);
        (Some(clusters), Vec::new())
    };

    // Greedy merging down through every target in one pass (Alg. 1 loop).
    let now = Instant::now();
    let merged = match clusters {
        None => crate::merge::MergeOutput {
            snapshots: early,
            ..Default::default()
        },
        Some(clusters) => {
            let (done, rest) = (dec.merges as f64, clusters.live.saturating_sub(last) as f64);
            let phase2 = |f: f64| progress((done + f * rest) / total);
            let mut m = crate::merge::run(&ev, clusters, &targets[early.len()..], &phase2);
            m.snapshots.splice(0..0, early);
            m
        }
    };
    dec.bridge_edges = merged.bridge_edges;
    dec.merges += merged.merges;
    dec.fits += merged.fits;
    dec.merges_ahead += merged.ahead;
    dec.timings.push("merge", now);
    // Remove nested primitives (§3.4), then return to world coordinates.
    let now = Instant::now();
    dec.levels = params
        .targets
        .iter()
        .map(|&n| {
            let snap = merged
                .snapshots
                .iter()
                .find(|s| s.target == n)
                .expect("snapshot per target");
            finish_level(mesh, snap, params, diag)
        })
        .collect();
    dec.timings.push("postprocess", now);
    Ok(dec)
}

/// What the merge loop consumes: the faces' operators and seed volumes, and the
/// adjacent pairs (its clusters take the adjacency over).
struct MergeInput {
    q: Vec<crate::math::Sym3>,
    volumes: Vec<f64>,
    pairs: Vec<(u32, u32)>,
}

/// Phase 1 of `Params::partitions`: the parts merged in parallel (merge/partition.rs),
/// then one cluster per group for the global loop.
fn partitioned(
    ev: &Evaluator,
    input: MergeInput,
    targets: &[usize],
    dec: &mut Decomposition,
    merged: &(dyn Fn(usize) + Sync),
) -> Clusters {
    let now = Instant::now();
    let MergeInput { q, volumes, pairs } = input;
    let k = dec.partitions;
    let p1 = partition::merge_parts(ev, &q, &volumes, &pairs, targets[0], k, merged);
    (dec.merges, dec.fits) = (p1.merges, p1.fits);
    dec.timings.push("partitions", now);
    // Phase 2 starts from one cluster per group (serial, linear in the faces).
    let now = Instant::now();
    let clusters = partition::clusters(p1, q, volumes, &pairs);
    dec.timings.push("regroup", now);
    clusters
}

/// Every component merged whole, groups of them in parallel: the same clusters the
/// global loop reaches before it links components (merge/components.rs). Returns the
/// snapshots at targets of at least one cluster per component, replayed from the
/// components' own merges, and the global loop's start if a target lies below.
fn by_components(
    ev: &Evaluator,
    input: MergeInput,
    comps: Vec<Vec<u32>>,
    targets: &[usize],
    dec: &mut Decomposition,
    merged: &(dyn Fn(usize) + Sync),
) -> (Option<Clusters>, Vec<crate::merge::Snapshot>) {
    let now = Instant::now();
    let MergeInput { q, volumes, pairs } = input;
    let count = comps.len();
    let p1 = components::merge_components(ev, &q, &volumes, &pairs, comps, targets[0], merged);
    (dec.merges, dec.fits) = (p1.merges, p1.fits);
    let (early, replayed) = components::snapshots(ev, &p1, &q, &volumes, &pairs, targets, count);
    let whole = early.len() == targets.len();
    if whole {
        (dec.merges, dec.merges_past) = (replayed, p1.merges - replayed);
    }
    // The global loop goes on only to targets below the component count.
    let clusters = (!whole).then(|| partition::clusters(p1, q, volumes, &pairs));
    dec.timings.push("components", now);
    (clusters, early)
}

/// How many parts the run starts with: `Params::partitions` for this input, or 1
/// when there are no more faces than phase 1 would leave (it would merge nothing).
fn parts(mesh: &Mesh, params: &Params, largest_target: usize) -> usize {
    let faces = mesh.face_count();
    if faces > partition::phase1_size(largest_target) {
        params.partitions.parts(faces)
    } else {
        1
    }
}

/// The input's connected components when the run can merge them separately first
/// ([`components::applies`]), else `None`.
fn component_phase(mesh: &Mesh, params: &Params, pairs: &[(u32, u32)]) -> Option<Vec<Vec<u32>>> {
    let faces = mesh.face_count();
    let capped = params.max_excess_volume.is_some();
    if faces < components::MIN_FACES || capped {
        return None;
    }
    let comps = components::components(faces, pairs);
    let largest = comps.iter().map(Vec::len).max().unwrap_or(0);
    components::applies(faces, comps.len(), largest, capped).then_some(comps)
}

fn input_info(mesh: &Mesh, (lo, hi): (V3, V3)) -> InputInfo {
    InputInfo {
        path: None,
        faces: mesh.face_count(),
        vertices: mesh.vertex_count(),
        aabb_min: crate::math::add(lo, mesh.offset),
        aabb_max: crate::math::add(hi, mesh.offset),
    }
}

/// Smallest half-extent or radius of any primitive, whatever the mesh and settings.
/// Every fit divides by half-extents, and volumes are their cubes: with a zero diagonal
/// (a mesh collapsed to one point) or a product `min_extent_rel × diagonal` that
/// underflows (a mesh 6e-22 across with a minimum extent of 7e-304 made it 0, and the
/// frustum fit divided 0 by 0), lengths must still be positive, and their cubes (and the
/// reciprocals of their squares, in the tests' oracle) normal numbers. Together with
/// `mesh::MAX_EXTENT` this keeps every length the engine fits within [1e-90, 1e60].
/// Only meshes under ~1e-87 across are affected: their primitives are at least 2e-90
/// across.
pub const MIN_HALF: f64 = 1e-90;

/// Merge costs are compared on a grid of this fraction of the diagonal cubed (2^-40).
const COST_GRID: f64 = 1.0 / (1u64 << 40) as f64;

/// Fit settings with the minimum extent and excess cap made absolute for this input,
/// whose used vertices span `bounds` (re-centred, from [`Mesh::aabb`]).
pub fn evaluator<'a>(
    mesh: &'a Mesh,
    welded: &'a [u32],
    params: &Params,
    bounds: (V3, V3),
) -> Evaluator<'a> {
    let (lo, hi) = bounds;
    let diag = crate::math::norm(crate::math::sub(hi, lo));
    let min_half = (params.min_extent_rel * diag).max(MIN_HALF);
    // Merges may be priced with a thicker floor than the output's (Params docs).
    let price_half = (params.merge_min_extent_rel.unwrap_or(0.0) * diag).max(min_half);
    let aabb_volume: f64 = (0..3)
        .map(|k| (hi[k] - lo[k]).max(2.0 * min_half))
        .product();
    Evaluator {
        mesh,
        welded,
        cfg: FitConfig {
            weights: params.weights,
            enabled: params.kinds,
            min_half: price_half,
            frames: FrameSearch::Degenerate,
        },
        output_min_half: min_half,
        flat_scale: (params.flat_merge_extent_rel * diag / price_half).max(1.0),
        max_excess: params
            .max_excess_volume
            .map_or(f64::INFINITY, |m| m * aabb_volume),
        // A pair over the cap has no queue entry to stand for it until re-priced, so
        // a cap keeps every merge exact.
        defer_degree: match (params.reprice, params.max_excess_volume) {
            (Reprice::Deferred { min_degree }, None) => min_degree,
            _ => u32::MAX,
        },
        // Never 0 (at least 2^-40 × MIN_HALF³ ≈ 1e-282): a zero grid priced every merge
        // 0/0 = NaN, which the merge loop drops like a merge over the excess cap.
        cost_unit: COST_GRID * diag.max(min_half).powi(3),
        hull_eps: 1e-12 * diag.max(min_half),
        reduction: params.reduction,
        outward_weight: params.outward_weight,
        face_sign: &[],
        solid: None,
        rim_weight: params.rim_weight,
        face_adj: FaceAdjacency::default(),
        free_merges: params.free_merges,
        join_plates: params.free_merges,
        flush_plates: params.flush_plates,
    }
}

/// Volume of each face's own primitive, in parallel.
pub fn seed_volumes(ev: &Evaluator, q: &[crate::math::Sym3]) -> Vec<f64> {
    (0..q.len())
        .into_par_iter()
        .with_min_len(1024)
        .map_init(Workspace::default, |ws, f| {
            let fit = ev.fit_face(f as u32, &q[f], ws);
            fit.volume * ev.air(&fit.prim)
        })
        .collect()
}

/// Post-processes one snapshot and moves it to world coordinates.
fn finish_level(mesh: &Mesh, snap: &crate::merge::Snapshot, params: &Params, diag: f64) -> Level {
    let cleanup = Cleanup {
        diagonal: diag,
        remove_contained: params.remove_contained,
        thin_box_half: params.remove_thin_boxes.map(|t| t * diag),
    };
    let keep = keep_mask(mesh, &snap.prims, &snap.verts, &snap.members, cleanup);
    let mut level = Level {
        target: snap.target,
        merged_to: snap.target,
        ..Default::default()
    };
    for (i, p) in snap.prims.iter().enumerate() {
        if keep[i] {
            level.primitives.push(p.to_world(mesh.offset));
            level.faces.push(snap.faces[i]);
        }
    }
    level
}
