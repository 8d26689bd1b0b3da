//! The merge stage as one pass runs it: how the loop starts (one cluster per face,
//! spatial parts or connected components first, [`FirstPhase`]), what it consumes
//! ([`MergeInput`], the faces' [`Surface`]) and the loop through the targets.

use super::components;
use super::partition;
use super::rim::FaceAdjacency;
use super::{Clusters, Fitter, MergeLog, MergeOutput, Snapshot};
use crate::input::dedup::Weld;
use crate::input::mesh::Mesh;
use crate::input::orient;
use crate::math::Sym3;
use crate::output::result::Stats;
use crate::params::Params;
use crate::progress::clock::PhaseTimes;
use crate::progress::Checkpoint;

/// The targets in the order the merge loop reaches them: decreasing, each once.
pub(crate) fn merge_order(targets: &[usize]) -> Vec<usize> {
    let mut t = targets.to_vec();
    t.sort_unstable_by(|a, b| b.cmp(a));
    t.dedup();
    t
}

/// What the output fits need of the faces around each cluster: the faces' neighbour
/// lists and which side of each is outside (empty when no output fit reads them).
pub(crate) struct Surface {
    pub(crate) offsets: std::sync::Arc<[u32]>,
    pub(crate) adj: std::sync::Arc<[u32]>,
    pub(crate) signs: Vec<i8>,
    /// Whether an output fit reads the surface (else only the clusters do).
    used: bool,
    /// `signs` are still to come: left to the merge stage, which finds them beside
    /// the spatial parts ([`MergeInput::late_signs`]).
    late: bool,
}

impl Surface {
    /// From the faces' neighbour lists (`adjacency::neighbour_lists`); `None` when
    /// `go_on` said stop. With `late`, which side of each face is outside is left to
    /// the merge stage ([`MergeInput::late_signs`]); the surface then waits for
    /// [`Surface::with_signs`].
    pub(crate) fn build(
        mesh: &Mesh,
        weld: &Weld,
        (offsets, adj): (Vec<u32>, Vec<u32>),
        params: &Params,
        late: bool,
        go_on: Checkpoint,
    ) -> Option<Surface> {
        let used = params.plates.rim_weight != 0.0 || params.plates.flush_plates;
        let signs = match used && !late {
            true => orient::face_signs_checked(mesh, weld, &offsets, &adj, go_on)?,
            false => Vec::new(),
        };
        Some(Surface {
            offsets: offsets.into(),
            adj: adj.into(),
            signs,
            used,
            late: used && late,
        })
    }

    /// Whether the faces' outer sides are still to come from the merge stage.
    pub(crate) fn signs_late(&self) -> bool {
        self.late
    }

    /// The surface with the outer sides the merge stage found (`None`: it had them
    /// already).
    pub(crate) fn with_signs(self, signs: Option<Vec<i8>>) -> Surface {
        match signs {
            Some(signs) => Surface {
                signs,
                late: false,
                ..self
            },
            None => self,
        }
    }

    pub(crate) fn adjacency(&self) -> FaceAdjacency<'_> {
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
pub(crate) struct MergeInput {
    pub(crate) q: Vec<Sym3>,
    pub(crate) volumes: Vec<f64>,
    pub(crate) pairs: Vec<(u32, u32)>,
    /// The pairs as neighbour lists, shared with the surface.
    pub(crate) lists: partition::Lists,
    /// `Fit::tangent_eps`, for spatial parts' own operators.
    pub(crate) tangent_eps: f64,
    /// Which side of each face is outside is found here, not before: only output
    /// fits read it, and the merge loop fits none until its first target. After
    /// spatial parts it is found on the first of rayon's threads that runs out of
    /// parts, while the others finish theirs ([`partition::merge_parts`]'s `then`):
    /// the orientation walk is serial, and the parts' last one ran alone.
    pub(crate) late_signs: bool,
}

/// What a pass keeps of the merge loop besides the clusters at its targets: nothing
/// (the greedy pass, [`AtTargets`]) or every merge, the merge tree (the cut's,
/// [`ForTree`]). The merge stage runs alike for both but for these three points.
pub(crate) trait Keep {
    /// What the merge stage returns besides its output.
    type Log: Default;
    /// Whether the components phase traces every merge (the tree needs every one
    /// whatever the targets), not only those from the first target on, and spatial
    /// parts keep theirs.
    fn traces_every_merge(&self) -> bool;
    /// The global loop from `cl` through `targets` (decreasing).
    fn run(
        &self,
        fitter: &Fitter,
        cl: Clusters,
        targets: &[usize],
        go_on: Checkpoint,
    ) -> (MergeOutput, Self::Log);
    /// The stage's log: the first phase's merges `replayed` (the components' in the
    /// global order, or the spatial parts' part after part) before the global loop's
    /// `log`; `from_faces`: no spatial parts ran first.
    fn join(replayed: Vec<(u32, u32)>, log: Self::Log, from_faces: bool) -> Self::Log;
}

/// The greedy pass keeps the clusters at its targets only (the snapshots).
#[derive(Clone, Copy, Debug)]
pub(crate) struct AtTargets;

impl Keep for AtTargets {
    type Log = ();

    fn traces_every_merge(&self) -> bool {
        false
    }

    fn run(
        &self,
        fitter: &Fitter,
        cl: Clusters,
        targets: &[usize],
        go_on: Checkpoint,
    ) -> (MergeOutput, ()) {
        (super::run(fitter, cl, targets, go_on), ())
    }

    fn join(_: Vec<(u32, u32)>, _: (), _: bool) {}
}

/// The cut keeps every merge ([`MergeLog`]), and the points of the clusters of more
/// than `hulls_over` faces (`merge::TreeHulls`; `None`: none).
#[derive(Clone, Copy, Debug)]
pub(crate) struct ForTree {
    pub(crate) hulls_over: Option<usize>,
}

impl Keep for ForTree {
    type Log = MergeLog;

    fn traces_every_merge(&self) -> bool {
        true
    }

    fn run(
        &self,
        fitter: &Fitter,
        cl: Clusters,
        targets: &[usize],
        go_on: Checkpoint,
    ) -> (MergeOutput, MergeLog) {
        super::run_for_tree(fitter, cl, targets, self.hulls_over, go_on)
    }

    fn join(replayed: Vec<(u32, u32)>, mut log: MergeLog, from_faces: bool) -> MergeLog {
        // The first phase's merges come first: the components' in the global order,
        // the spatial parts' before any of the global loop's (which join parts).
        let before = replayed.len() as u32;
        log.hulls
            .merges
            .iter_mut()
            .for_each(|(at, _)| *at += before);
        log.at_first += before as usize;
        // The global loop's (the fewer) appended to the first phase's, which made room.
        let mut merges = replayed;
        merges.extend_from_slice(&log.merges);
        log.merges = merges;
        log.from_faces = from_faces;
        log
    }
}

/// How the merge loop starts, chosen once per run from the input and settings.
pub(crate) enum FirstPhase {
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
    pub(crate) fn choose(
        mesh: &Mesh,
        params: &Params,
        pairs: &[(u32, u32)],
        first: usize,
        largest: usize,
    ) -> Self {
        let faces = mesh.face_count();
        // Parts only where the faces outnumber what phase 1 would leave.
        let parts = if faces > partition::phase1_size(first) {
            params.partitions.parts(faces)
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
    pub(crate) fn parts(&self) -> usize {
        match self {
            FirstPhase::Parts { parts, .. } => *parts,
            _ => 1,
        }
    }
}

/// What the merge stage returns: the loop's output, what the pass keeps besides
/// ([`Keep::Log`]), and the faces' outer sides where they were left to it
/// ([`MergeInput::late_signs`]; `None` otherwise, or when told to stop).
pub(crate) type Merged<L> = (MergeOutput, L, Option<Vec<i8>>);

/// The merge stage: the first phase, then the global loop through the targets it did
/// not reach, and what `keep` asks besides ([`Keep`]). Progress is the fraction of the
/// merges down to the last target.
#[allow(clippy::too_many_arguments)]
pub(crate) fn merge<K: Keep>(
    fitter: &Fitter,
    input: MergeInput,
    first: FirstPhase,
    targets: &[usize],
    keep: K,
    stats: &mut Stats,
    go_on: Checkpoint,
    laps: &mut PhaseTimes,
) -> Merged<K::Log> {
    let last = *targets.last().expect("validated: one target or more");
    let total = fitter.input.mesh.face_count().saturating_sub(last).max(1) as f64;
    let merged_so_far = |m: usize| go_on(m as f64 / total);
    let from_faces = !matches!(first, FirstPhase::Parts { .. });
    // The merge tree needs every merge traced, whatever the targets (`Keep`).
    let every = keep.traces_every_merge();
    let run = (&mut *stats, &mut *laps, go_on);
    let Some(((clusters, early, replayed), signs)) =
        start(fitter, input, first, targets, every, run, &merged_so_far)
    else {
        return (MergeOutput::stopped(), K::Log::default(), None);
    };
    let Some(clusters) = clusters else {
        // Every target reached: the output holds the replayed merges only.
        let out = MergeOutput {
            snapshots: early,
            ..MergeOutput::default()
        };
        return (out, K::join(replayed, K::Log::default(), true), signs);
    };
    // The loop's output fits read the faces' outer sides.
    let full;
    let fitter = match &signs {
        Some(s) => {
            full = with_signs(fitter, s);
            &full
        }
        None => fitter,
    };
    // The global loop through the targets left, its progress counted on from the first
    // phase's merges.
    let done = stats.merges as f64;
    let rest = clusters.live.saturating_sub(last) as f64;
    let phase2 = |f: f64| go_on((done + f * rest) / total);
    let (mut out, log) = keep.run(fitter, clusters, &targets[early.len()..], &phase2);
    let log = K::join(replayed, log, from_faces);
    out.snapshots.splice(0..0, early);
    add_loop(stats, &out);
    (out, log, signs)
}

/// The faces' outer sides where they were left to the stage (beside spatial parts, in
/// `after_parts`, else here), and where the global loop starts: one cluster per face,
/// or after spatial parts or whole components were merged first (every merge traced
/// when `every`). `None` when told to stop.
fn start(
    fitter: &Fitter,
    input: MergeInput,
    first: FirstPhase,
    targets: &[usize],
    every: bool,
    (stats, laps, go_on): (&mut Stats, &mut PhaseTimes, Checkpoint),
    merged_so_far: &(dyn Fn(usize) -> bool + Sync),
) -> Option<(Started, Option<Vec<i8>>)> {
    let mut signs = None;
    if input.late_signs && !matches!(first, FirstPhase::Parts { .. }) {
        signs = Some(late_signs(fitter, &input.lists, go_on)?);
    }
    let started = match first {
        FirstPhase::Faces => Some(one_per_face(input)),
        FirstPhase::Parts { parts, target } => after_parts(
            fitter,
            input,
            (parts, target, every),
            &mut signs,
            stats,
            laps,
            merged_so_far,
        ),
        FirstPhase::Components(comps) => after_components(
            fitter,
            input,
            comps,
            targets,
            every,
            stats,
            laps,
            merged_so_far,
        ),
    }?;
    Some((started, signs))
}

/// `fitter` reading `signs` as the faces' outer sides.
fn with_signs<'s>(fitter: &Fitter<'s>, signs: &'s [i8]) -> Fitter<'s> {
    Fitter {
        input: super::cost::InputView {
            face_sign: signs,
            ..fitter.input
        },
        pricing: fitter.pricing,
    }
}

/// The faces' outer sides (`orient`), from the input's neighbour lists; `None` when
/// `go_on` said stop.
fn late_signs(
    fitter: &Fitter,
    (offsets, adj): &partition::Lists,
    go_on: Checkpoint,
) -> Option<Vec<i8>> {
    let (mesh, weld) = (fitter.input.mesh, fitter.input.weld);
    orient::face_signs_checked(mesh, weld, offsets, adj, go_on)
}

/// Where the first phase leaves the merge stage: the clusters the global loop goes on
/// from (`None`: every target was reached), the snapshots of the targets it reached,
/// and every merge the replayed components did after them, in the global order (or
/// the traced spatial parts' merges, part after part).
type Started = (Option<Clusters>, Vec<Snapshot>, Vec<(u32, u32)>);

/// Alg. 1 as is: one cluster per face.
fn one_per_face(input: MergeInput) -> Started {
    let MergeInput {
        q, volumes, lists, ..
    } = input;
    (
        Some(Clusters::with_lists(q, volumes, lists)),
        Vec::new(),
        Vec::new(),
    )
}

/// Spatial parts merged in parallel down to their share of `target` first, then one
/// cluster per group, with the parts' merges part after part when `traced` (else
/// none); `None` when told to stop.
fn after_parts(
    fitter: &Fitter,
    input: MergeInput,
    (parts, target, traced): (usize, usize, bool),
    signs: &mut Option<Vec<i8>>,
    stats: &mut Stats,
    laps: &mut PhaseTimes,
    merged_so_far: &(dyn Fn(usize) -> bool + Sync),
) -> Option<Started> {
    let MergeInput {
        q,
        volumes,
        pairs,
        lists,
        tangent_eps,
        late_signs: late,
    } = input;
    // The faces' outer sides, if left to the stage, on the first thread out of parts.
    let found = std::sync::Mutex::new(None);
    let then = |go_on: Checkpoint| {
        if late {
            let s = late_signs(fitter, &lists, go_on);
            *found.lock().unwrap_or_else(|e| e.into_inner()) = Some(s);
        }
    };
    let mut p1 = laps.time("partitions", || {
        let faces = partition::FaceData::PerPart {
            tangent_eps,
            lists: &lists,
        };
        let plan = (target, parts, traced);
        partition::merge_parts(fitter, faces, plan, merged_so_far, &then)
    });
    stats.merges = p1.merges;
    add_fits(stats, p1.fits);
    if p1.stopped {
        return None;
    }
    if late {
        // `None` inside: the walk was told to stop.
        *signs = Some(found.into_inner().unwrap_or_else(|e| e.into_inner())??);
    }
    // Phase 2 starts from one cluster per group (linear in the faces). The
    // faces' pairs, operators and volumes are done with: the groups hold theirs.
    drop((pairs, q, volumes));
    let so_far = stats.merges;
    let faces = fitter.input.mesh.face_count();
    let merges = p1.take_merges();
    let clusters = laps.time("regroup", || {
        partition::group_clusters(p1, faces, &lists, &|_| merged_so_far(so_far))
    })?;
    Some((Some(clusters), Vec::new(), merges))
}

/// Each connected component merged whole first (every merge traced when
/// `trace_every`, else from the first target on), replayed in the global order through
/// the targets it reaches; `None` when told to stop.
#[allow(clippy::too_many_arguments)]
fn after_components(
    fitter: &Fitter,
    input: MergeInput,
    comps: Vec<Vec<u32>>,
    targets: &[usize],
    trace_every: bool,
    stats: &mut Stats,
    laps: &mut PhaseTimes,
    merged_so_far: &(dyn Fn(usize) -> bool + Sync),
) -> Option<Started> {
    let MergeInput {
        q,
        volumes,
        pairs,
        lists,
        ..
    } = input;
    let count = comps.len();
    let trace_from = if trace_every { usize::MAX } else { targets[0] };
    let p1 = laps.time("components", || {
        let (q, v, p) = (&q, &volumes, &pairs);
        components::merge_components(fitter, q, v, p, comps, trace_from, merged_so_far)
    });
    stats.merges = p1.merges;
    add_fits(stats, p1.fits);
    if p1.stopped {
        return None;
    }
    let (early, replayed, components_log) =
        components::snapshots(fitter, &p1, &q, &volumes, &pairs, targets, count);
    let clusters = if early.len() == targets.len() {
        // Every target reached: the output holds the replayed merges only.
        (stats.merges, stats.merges_past) = (replayed, p1.merges - replayed);
        None
    } else {
        // The global loop goes on to the targets below the component count.
        let so_far = stats.merges;
        let go_on = |_: f64| merged_so_far(so_far);
        Some(partition::clusters(p1, q, volumes, lists, &go_on)?)
    };
    Some((clusters, early, components_log))
}

/// Adds the global loop's counts to the stage's.
fn add_loop(stats: &mut Stats, out: &MergeOutput) {
    stats.bridge_edges = out.bridge_edges;
    stats.merges += out.merges;
    stats.merges_ahead += out.ahead;
    add_fits(stats, out.fits);
}

pub(crate) fn add_fits(stats: &mut Stats, fits: crate::merge::FitCounts) {
    stats.fits_seeded += fits.seed;
    stats.fits_at_once += fits.eager;
    stats.fits_when_popped += fits.lazy;
}

#[cfg(test)]
mod tests;
