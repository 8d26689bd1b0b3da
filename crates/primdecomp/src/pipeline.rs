//! One bottom-up pass (the paper's Algorithm 1), read top to bottom: weld, adjacency,
//! quadrics, the surface around each face, seed primitives, the merge loop through
//! every target, post-processing. Each stage is one call; [`Clock`] times it, reports
//! it to the caller's [`Progress`] and stops the run when it is cancelled.

use crate::cut::Request;
use crate::error::{Error, Result};
use crate::input::mesh::Mesh;
use crate::input::solid::{self, Solid};
use crate::input::triangles::Triangles;
use crate::input::{adjacency, dedup, orient};
use crate::math::{Sym3, V3};
use crate::merge::rim::FaceAdjacency;
use crate::merge::{components, partition, Clusters, Evaluator, MergeOutput, Workspace};
use crate::output::result::{Decomposition, InputInfo, Stats, Timings};
use crate::params::{Params, Reprice};
use crate::postprocess;
use crate::primitive::fit::{FitConfig, FrameSearch};
use crate::progress::wallclock::Instant;
use crate::progress::{GoOn, Progress, Stage};
use crate::seed::quadric;
use rayon::prelude::*;

/// One pass through the goal's targets (a fill's further passes are the caller's: `budget`).
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
        hulls_over: tree_hulls_over(mesh, params, largest),
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
    let requests = requests(params, mesh);
    // The cut of the merge tree at each target where the error is (docs/decisions/0032), its
    // counts and bytes spent on what post-processing keeps.
    if let (true, Some(tris)) = (cut, &tris) {
        merged.snapshots = clock.stage(Stage::Postprocess, "cut", |_, _| {
            let tree = merge_tree(&ev, &mut merged, &face_q);
            crate::recut::snapshots(&ev, &tree, &requests, tris, params, &post)
        })?;
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
            crate::cut::record_limits(&mut levels, &requests, &known, mesh, tris)
        })?;
    }
    Ok(Decomposition {
        input: input_info(mesh, bounds),
        levels,
        timings: clock.timings,
        stats,
    })
}

/// The tree of `merged`'s merges (leaves: its first snapshot's clusters, or the faces
/// when every merge was logged), with the points the loop kept for its nodes.
fn merge_tree(ev: &Evaluator, merged: &mut MergeOutput, face_q: &[Sym3]) -> crate::cut::MergeTree {
    let faces = ev.mesh.face_count();
    let hulls = std::mem::take(&mut merged.hulls);
    if merged.log_from_faces {
        // Every merge is known: the leaves are single faces, so any cluster can be
        // taken apart down to its faces (the loop's first snapshot is not the leaves).
        let singles: Vec<Vec<u32>> = (0..faces as u32).map(|f| vec![f]).collect();
        let merges = crate::merge::TreeHulls {
            leaves: Vec::new(),
            ..hulls
        };
        crate::cut::MergeTree::build(&singles, face_q, &merged.log, merges, faces)
    } else {
        let leaves = &merged.snapshots[0];
        let log = &merged.log[merged.log_at_first..];
        let hulls = hulls.after(merged.log_at_first);
        crate::cut::MergeTree::build(&leaves.members, &leaves.q, log, hulls, faces)
    }
}

/// The face count over which the merge loop keeps a cluster's points for the merge
/// tree: a cut's mean node's (the cut finds the hulls of larger nodes, `cut::hulls`).
/// `None` (found from the faces) without a cut, or where the welded vertices (whose
/// ids the loop keeps) may stand apart from the faces' own: a tolerance weld.
fn tree_hulls_over(mesh: &Mesh, params: &Params, largest: usize) -> Option<usize> {
    let welded_in_place =
        !matches!(params.fit.dedup, crate::params::Dedup::Tolerance(t) if t > 0.0);
    (params.uses_cut() && welded_in_place).then(|| mesh.face_count() / largest.max(1))
}

/// Each target's request of the cut, its tolerance in the mesh's units.
fn requests(params: &Params, mesh: &Mesh) -> Vec<Request> {
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

/// Times each stage, reports it to the caller, and turns a cancellation into
/// [`Error::Cancelled`] between stages (and within them through the callback).
struct Clock<'p> {
    progress: &'p dyn Progress,
    timings: Timings,
    /// The stage reported last: a stage run in several steps starts (0) once.
    current: Option<Stage>,
}

impl<'p> Clock<'p> {
    fn new(progress: &'p dyn Progress) -> Self {
        Clock {
            progress,
            timings: Timings::default(),
            current: None,
        }
    }

    /// Runs `work`, a step of `stage` before the one [`Clock::stage`] runs, timed as
    /// `name`: it reports the stage's start, not its end.
    fn step<T>(&mut self, stage: Stage, name: &str, work: impl FnOnce() -> T) -> Result<T> {
        self.start(stage)?;
        let now = Instant::now();
        let out = work();
        self.timings.push(name, now.elapsed().as_secs_f64());
        match self.progress.cancelled() {
            true => Err(Error::Cancelled),
            false => Ok(out),
        }
    }

    /// [`Clock::step`] whose `work` gets a callback that says whether to go on (it
    /// reports no fraction: the step is part of a stage that reports its own).
    fn step_checked<T>(
        &mut self,
        stage: Stage,
        name: &str,
        work: impl FnOnce(GoOn) -> T,
    ) -> Result<T> {
        let p = self.progress;
        self.step(stage, name, || work(&|_| !p.cancelled()))
    }

    /// Reports `stage`'s start unless it has started already; `Cancelled` first if so.
    fn start(&mut self, stage: Stage) -> Result<()> {
        if self.progress.cancelled() {
            return Err(Error::Cancelled);
        }
        if self.current != Some(stage) {
            self.progress.update(stage, 0.0);
            self.current = Some(stage);
        }
        Ok(())
    }

    /// Runs `work` as (the last step of) `stage`, timed as `name`. `work` gets a callback for
    /// the fraction of the stage done that says whether to go on, and [`Laps`] to time
    /// phases of its own (recorded before `name`, which keeps the rest).
    fn stage<T>(
        &mut self,
        stage: Stage,
        name: &str,
        work: impl FnOnce(GoOn, &mut Laps) -> T,
    ) -> Result<T> {
        self.start(stage)?;
        let p = self.progress;
        let go_on = |fraction: f64| {
            p.update(stage, fraction.clamp(0.0, 1.0));
            !p.cancelled()
        };
        let now = Instant::now();
        let mut laps = Laps::default();
        let out = work(&go_on, &mut laps);
        let mut rest = now.elapsed().as_secs_f64();
        for (lap, secs) in laps.0 {
            self.timings.push(lap, secs);
            rest -= secs;
        }
        self.timings.push(name, rest.max(0.0));
        if p.cancelled() {
            return Err(Error::Cancelled);
        }
        p.update(stage, 1.0);
        Ok(out)
    }
}

/// Phases a stage times on its own (`partitions`, `regroup`, `components`).
#[derive(Default)]
struct Laps(Vec<(&'static str, f64)>);

impl Laps {
    fn time<T>(&mut self, name: &'static str, work: impl FnOnce() -> T) -> T {
        let now = Instant::now();
        let out = work();
        self.0.push((name, now.elapsed().as_secs_f64()));
        out
    }
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

/// The targets in the order the merge loop reaches them: decreasing, each once.
fn merge_order(targets: &[usize]) -> Vec<usize> {
    let mut t = targets.to_vec();
    t.sort_unstable_by(|a, b| b.cmp(a));
    t.dedup();
    t
}

/// What the output fits need of the faces around each cluster: the faces' neighbour
/// lists and which side of each is outside (empty when no output fit reads them).
struct Surface {
    offsets: std::sync::Arc<[u32]>,
    adj: std::sync::Arc<[u32]>,
    signs: Vec<i8>,
    /// Whether an output fit reads the surface (else only the clusters do).
    used: bool,
}

impl Surface {
    /// From the faces' neighbour lists (`adjacency::neighbour_lists`); `None` when
    /// `go_on` said stop.
    fn build(
        mesh: &Mesh,
        welded: &[u32],
        (offsets, adj): (Vec<u32>, Vec<u32>),
        params: &Params,
        go_on: GoOn,
    ) -> Option<Surface> {
        let used = params.plates.rim_weight != 0.0 || params.plates.flush_plates;
        let signs = match used {
            true => orient::face_signs_checked(mesh, welded, &offsets, &adj, go_on)?,
            false => Vec::new(),
        };
        Some(Surface {
            offsets: offsets.into(),
            adj: adj.into(),
            signs,
            used,
        })
    }

    fn adjacency(&self) -> FaceAdjacency<'_> {
        match self.used {
            true => FaceAdjacency {
                offsets: &self.offsets,
                adj: &self.adj,
            },
            false => FaceAdjacency::default(),
        }
    }
}

/// What the merge loop consumes: the faces' operators and seed volumes, and the
/// adjacent pairs (its clusters take the adjacency over).
struct MergeInput {
    q: Vec<Sym3>,
    volumes: Vec<f64>,
    pairs: Vec<(u32, u32)>,
    /// The pairs as neighbour lists, shared with the surface.
    lists: partition::Lists,
    /// Every merge is logged for the merge tree (a goal that [`Goal::uses_cut`](crate::Goal::uses_cut)).
    tree: bool,
    /// The clusters' points are kept for the tree's nodes of more faces
    /// (`merge::TreeHulls`).
    hulls_over: Option<usize>,
    /// `Fit::tangent_eps`, for spatial parts' own operators.
    tangent_eps: f64,
}

/// How the merge loop starts, chosen once per run from the input and settings.
enum FirstPhase {
    /// Alg. 1 as is: one cluster per face.
    Faces,
    /// `parts` spatial parts merged in parallel first, down to their share of
    /// `target`'s groups (`merge::partition`; docs/decisions/0017, 0019 and 0042).
    Parts { parts: usize, target: usize },
    /// Each connected component merged whole first, groups of them in parallel
    /// (`merge::components`); the same clusters the global loop reaches.
    Components(Vec<Vec<u32>>),
}

impl FirstPhase {
    /// `first`: the loop's first target; `largest`: the largest count requested.
    fn choose(
        mesh: &Mesh,
        params: &Params,
        pairs: &[(u32, u32)],
        first: usize,
        largest: usize,
    ) -> Self {
        let faces = mesh.face_count();
        // Parts only where the faces outnumber what phase 1 would leave.
        let parts = if faces > partition::phase1_size(first) {
            params.speed.partitions.parts(faces)
        } else {
            1
        };
        if parts > 1 {
            return FirstPhase::Parts {
                parts,
                target: largest.min(first),
            };
        }
        // A cap can refuse merges and leave a component in pieces, which the
        // components phase does not claim to reproduce.
        if faces < components::MIN_FACES || params.fit.max_excess_volume.is_some() {
            return FirstPhase::Faces;
        }
        let comps = components::components(faces, pairs);
        let largest_comp = comps.iter().map(Vec::len).max().unwrap_or(0);
        if components::applies(faces, comps.len(), largest_comp, false) {
            FirstPhase::Components(comps)
        } else {
            FirstPhase::Faces
        }
    }

    /// Spatial parts merged in parallel first (1 = none).
    fn parts(&self) -> usize {
        match self {
            FirstPhase::Parts { parts, .. } => *parts,
            _ => 1,
        }
    }
}

/// The merge stage: the first phase, then the global loop through the targets it did
/// not reach. Progress is the fraction of the merges down to the last target.
fn merge(
    ev: &Evaluator,
    input: MergeInput,
    first: FirstPhase,
    targets: &[usize],
    stats: &mut Stats,
    go_on: GoOn,
    laps: &mut Laps,
) -> MergeOutput {
    let MergeInput {
        q,
        volumes,
        pairs,
        lists,
        tree,
        hulls_over,
        tangent_eps,
    } = input;
    let last = *targets.last().expect("validated: one target or more");
    let total = ev.mesh.face_count().saturating_sub(last).max(1) as f64;
    let merged_so_far = |m: usize| go_on(m as f64 / total);
    // Every merge the replayed components did, in the global order.
    let mut tree_log = Vec::new();
    let from_faces = !matches!(first, FirstPhase::Parts { .. });
    let (clusters, early) = match first {
        FirstPhase::Faces => (Some(Clusters::with_lists(q, volumes, lists)), Vec::new()),
        FirstPhase::Parts { parts, target } => {
            let p1 = laps.time("partitions", || {
                let faces = partition::FaceData::PerPart {
                    tangent_eps,
                    lists: &lists,
                };
                partition::merge_parts(ev, faces, target, parts, &merged_so_far)
            });
            stats.merges = p1.merges;
            add_fits(stats, p1.fits);
            if p1.stopped {
                return MergeOutput::stopped();
            }
            // Phase 2 starts from one cluster per group (linear in the faces). The
            // faces' pairs, operators and volumes are done with: the groups hold theirs.
            drop((pairs, q, volumes));
            let so_far = stats.merges;
            let faces = ev.mesh.face_count();
            let clusters = laps.time("regroup", || {
                partition::group_clusters(p1, faces, &lists, &|_| merged_so_far(so_far))
            });
            let Some(clusters) = clusters else {
                return MergeOutput::stopped();
            };
            (Some(clusters), Vec::new())
        }
        FirstPhase::Components(comps) => {
            let count = comps.len();
            // The merge tree needs every merge traced, whatever the targets.
            let trace_from = if tree { usize::MAX } else { targets[0] };
            let p1 = laps.time("components", || {
                let (q, v, p) = (&q, &volumes, &pairs);
                components::merge_components(ev, q, v, p, comps, trace_from, &merged_so_far)
            });
            stats.merges = p1.merges;
            add_fits(stats, p1.fits);
            if p1.stopped {
                return MergeOutput::stopped();
            }
            let (early, replayed, after) =
                components::snapshots(ev, &p1, &q, &volumes, &pairs, targets, count);
            tree_log = after;
            if early.len() == targets.len() {
                // Every target reached: the output holds the replayed merges only.
                (stats.merges, stats.merges_past) = (replayed, p1.merges - replayed);
                (None, early)
            } else {
                // The global loop goes on to the targets below the component count.
                let so_far = stats.merges;
                match partition::clusters(p1, q, volumes, lists, &|_| merged_so_far(so_far)) {
                    Some(cl) => (Some(cl), early),
                    None => return MergeOutput::stopped(),
                }
            }
        }
    };
    let Some(clusters) = clusters else {
        return MergeOutput {
            snapshots: early,
            log: tree_log,
            log_from_faces: true,
            ..MergeOutput::default()
        };
    };
    let done = stats.merges as f64;
    let rest = clusters.live.saturating_sub(last) as f64;
    let phase2 = |f: f64| go_on((done + f * rest) / total);
    let mut out = if tree {
        crate::merge::run_for_tree(ev, clusters, &targets[early.len()..], hulls_over, &phase2)
    } else {
        crate::merge::run(ev, clusters, &targets[early.len()..], &phase2)
    };
    // The components' merges come first in the global order.
    let before = tree_log.len() as u32;
    out.hulls
        .merges
        .iter_mut()
        .for_each(|(at, _)| *at += before);
    out.log.splice(0..0, tree_log);
    out.log_from_faces = from_faces;
    out.snapshots.splice(0..0, early);
    stats.bridge_edges = out.bridge_edges;
    stats.merges += out.merges;
    stats.merges_ahead += out.ahead;
    add_fits(stats, out.fits);
    out
}

fn add_fits(stats: &mut Stats, fits: crate::merge::FitCounts) {
    stats.fits_seeded += fits.seed;
    stats.fits_at_once += fits.eager;
    stats.fits_when_popped += fits.lazy;
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
const COST_GRID: f64 = 1.0 / (1u64 << 40) as f64;

/// Fit settings with the minimum extent and excess cap made absolute for this input,
/// whose used vertices span `bounds` (re-centred, from [`Mesh::aabb`]). The surface
/// and interior fields are left empty for the caller.
pub fn evaluator<'a>(
    mesh: &'a Mesh,
    welded: &'a [u32],
    params: &Params,
    bounds: (V3, V3),
) -> Evaluator<'a> {
    let (lo, hi) = bounds;
    let diag = crate::math::norm(crate::math::sub(hi, lo));
    let min_half = (params.fit.min_extent * diag).max(MIN_HALF);
    let aabb_volume: f64 = (0..3)
        .map(|k| (hi[k] - lo[k]).max(2.0 * min_half))
        .product();
    Evaluator {
        mesh,
        welded,
        cfg: FitConfig {
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
        defer_degree: match params.speed.reprice {
            Reprice::Deferred { min_degree } => min_degree,
            Reprice::Exact => u32::MAX,
        },
        // Never 0 (at least 2^-40 × MIN_HALF³ ≈ 1e-282): a zero grid priced every merge
        // 0/0 = NaN, which the merge loop drops like a merge over the excess cap.
        cost_unit: COST_GRID * diag.max(min_half).powi(3),
        hull_eps: 1e-12 * diag.max(min_half),
        face_sign: &[],
        solid: None,
        rim_weight: params.plates.rim_weight,
        face_adj: FaceAdjacency::default(),
        free_merges: params.plates.join_coplanar,
        join_plates: params.plates.join_coplanar,
        flush_plates: params.plates.flush_plates,
    }
}

/// Faces per block of seed fits between progress reports and cancellation checks.
const SEED_BLOCK: usize = 1 << 16;

/// Volume of each face's own primitive, in parallel, a block at a time (stops early,
/// with the rest left 0, when `go_on` says so; the caller then returns cancelled).
pub(crate) fn seed_volumes(ev: &Evaluator, q: &[Sym3], go_on: GoOn) -> Vec<f64> {
    let mut out = vec![0.0; q.len()];
    for (b, block) in out.chunks_mut(SEED_BLOCK).enumerate() {
        let start = b * SEED_BLOCK;
        block
            .par_iter_mut()
            .enumerate()
            .with_min_len(1024)
            .for_each_init(Workspace::default, |ws, (i, v)| {
                let f = start + i;
                *v = ev.seed_volume(f as u32, &q[f], ws);
            });
        if !go_on((start + block.len()) as f64 / q.len().max(1) as f64) {
            break;
        }
    }
    out
}
