//! Coarse-grained parallel first phase of the merge loop (`Params::partitions`, a
//! speed/accuracy setting; docs/decisions/0017-partitioned-first-phase.md and
//! docs/decisions/0019-large-inputs-merged-in-parts.md). Alg. 1 (§3.3) is a
//! sequential greedy; here it runs in two phases:
//!
//! 1. the faces are split into K spatial parts ([`split`]: recursive median split of
//!    face centroids along the longest extent, ties broken by face index, so the parts
//!    depend only on the input and K); in each part, as one rayon task, the unchanged
//!    merge loop runs on the part's faces alone (a sub-mesh with local ids, only pairs
//!    of faces in that part) down to its share of [`GROUPS_PER_TARGET`] × the largest
//!    target, without bridging, and lazily: every merge's re-pricing is deferred
//!    (`Reprice::Deferred { min_degree: 0 }`) unless the run asked for exact
//!    re-pricing (docs/decisions/0019-large-inputs-merged-in-parts.md);
//! 2. one global [`Clusters`] starts from phase 1's groups (Q, hull-reduced points and
//!    priced volume as the part's loop left them, neighbours = adjacency between
//!    groups), and the normal merge loop (with its worker) runs to the targets.
//!
//! Output primitives are still `fit_cluster_exact` of the final clusters, so the
//! enclosure guarantee does not depend on this; only the merge order does (merges
//! across part boundaries wait for phase 2).

use super::cluster::{Clusters, Group};
use super::cost::{Fitter, InputView, Pricing};
use super::driver::{merge_part, FitCounts, MergeOutput, Traced};
use super::median::{self, BLOCK};
use crate::input::dedup::Weld;
use crate::input::mesh::Mesh;
use crate::math::Sym3;
use crate::progress::Checkpoint;
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering::Relaxed};

/// The input's adjacency as shared CSR neighbour lists (offsets, neighbours).
pub type Lists = (std::sync::Arc<[u32]>, std::sync::Arc<[u32]>);

/// Phase 1 stops at about this many clusters per unit of the largest target (F2 =
/// 16 × N, never fewer than the target); the choice against 8× is measured in
/// docs/results/partitions.md.
pub const GROUPS_PER_TARGET: usize = 16;

/// One part's clusters after phase 1, in the input's ids.
#[derive(Debug, Default)]
struct Groups {
    /// The faces of each group (increasing within a group), as CSR.
    faces: Vec<u32>,
    offsets: Vec<u32>,
    q: Vec<Sym3>,
    volume: Vec<f64>,
    /// Hull-reduced welded vertices of each group; empty for a single face.
    verts: Vec<Vec<u32>>,
    /// Each group's neighbour list as its part's loop left it (input face ids) and its
    /// length when last resolved, for groups of whole components (`merge::components`):
    /// phase 2 then holds the lists the global loop would, so it decides deferrals
    /// (`merge::driver::defer`) as that loop does. Empty for spatial parts.
    neighbors: Vec<(Vec<u32>, u32)>,
    /// Every merge of the group's loop in order, in input ids (whole components only).
    trace: Vec<Traced>,
    /// Every merge of a traced spatial part's loop in order, as a face of each merged
    /// cluster in input ids (the merge tree's, `cut::tree`); empty otherwise.
    merges: Vec<(u32, u32)>,
}

/// Phase 1's result: every part's groups, and the merges it did.
#[derive(Debug, Default)]
pub struct Phase1 {
    parts: Vec<Groups>,
    pub merges: usize,
    pub fits: FitCounts,
    /// A part's loop was told to stop ([`crate::progress`]): the groups are partial.
    pub stopped: bool,
}

impl Phase1 {
    /// Each group's merges in order (traced [`Kind::Components`], else empty).
    pub(super) fn traces(&self) -> Vec<&[Traced]> {
        self.parts.iter().map(|g| g.trace.as_slice()).collect()
    }

    /// Every merge of the traced spatial parts ([`Kind::Spatial`]), part after part,
    /// each part's in its own order, as a face of each merged cluster in input ids.
    /// Parts share no face, so any order of the parts is one the merge tree can replay.
    /// Room is made for the global loop's merges after them (fewer than the groups):
    /// they are appended without moving these (8 bytes a face).
    pub(super) fn take_merges(&mut self) -> Vec<(u32, u32)> {
        let parts: usize = self.parts.iter().map(|g| g.merges.len()).sum();
        let mut out = Vec::with_capacity(parts + self.groups());
        for g in &mut self.parts {
            out.append(&mut g.merges);
            // Each part's freed as it is copied: the two are never both held whole.
            g.merges = Vec::new();
        }
        out
    }

    /// Number of groups phase 2 starts from.
    pub fn groups(&self) -> usize {
        self.parts.iter().map(|g| g.verts.len()).sum()
    }
}

/// Splits the faces of `mesh` into `k` parts by recursive median split of their
/// centroids along the longest extent of the centroids' box (lowest axis on ties),
/// ordering faces by (coordinate, face index). Each part's faces are increasing; every
/// face is in exactly one part; part sizes differ by at most one per level of
/// splitting (`k` not a power of two: proportional shares). Independent of threads.
#[cfg(test)]
pub fn split(mesh: &Mesh, k: usize) -> Vec<Vec<u32>> {
    split_checked(mesh, k, &|_| true).expect("never told to stop")
}

/// `split` asking `go_on` every `median::BLOCK` faces of a pass; `None` when it
/// said stop.
fn split_checked(mesh: &Mesh, k: usize, go_on: Checkpoint) -> Option<Vec<Vec<u32>>> {
    let n = mesh.face_count();
    let mut centroids: Vec<[f64; 3]> = Vec::with_capacity(n);
    for f0 in (0..n).step_by(BLOCK) {
        let fs = (f0..(f0 + BLOCK).min(n)).into_par_iter().with_min_len(4096);
        centroids.par_extend(fs.map(|f| centroid(mesh, f)));
        if !go_on(0.0) {
            return None;
        }
    }
    let mut ids: Vec<u32> = (0..n as u32).collect();
    split_into(&mut ids, &centroids, k.max(1), go_on)
}

fn centroid(mesh: &Mesh, f: usize) -> [f64; 3] {
    let vs = mesh.face(f);
    let mut s = [0.0; 3];
    for &v in vs {
        let p = mesh.pos(v);
        (0..3).for_each(|i| s[i] += p[i]);
    }
    s.map(|x| x / vs.len().max(1) as f64)
}

/// The parts of `ids` in order; the two halves of each split are split in parallel
/// (their results do not depend on which thread runs them).
fn split_into(
    ids: &mut [u32],
    c: &[[f64; 3]],
    k: usize,
    go_on: Checkpoint,
) -> Option<Vec<Vec<u32>>> {
    // A check per node: below a block, a node's passes ask nothing themselves.
    go_on(0.0).then_some(())?;
    if k == 1 {
        let mut part = ids.to_vec();
        part.sort_unstable();
        return Some(vec![part]);
    }
    let axis = longest_axis(ids, c, go_on)?;
    let left = k / 2;
    let m = (ids.len() as u128 * left as u128 / k as u128) as usize;
    let order = |a: u32, b: u32| {
        c[a as usize][axis]
            .total_cmp(&c[b as usize][axis])
            .then(a.cmp(&b))
    };
    if !median::select(ids, m, &order, go_on) {
        return None;
    }
    let (lo, hi) = ids.split_at_mut(m);
    let (parts, rest) = rayon::join(
        || split_into(lo, c, left, go_on),
        || split_into(hi, c, k - left, go_on),
    );
    let mut parts = parts?;
    parts.extend(rest?);
    Some(parts)
}

/// The axis along which the centroids of `ids` spread farthest (the lowest on ties);
/// `None` when `go_on`, asked after each full block of faces, said stop.
fn longest_axis(ids: &[u32], c: &[[f64; 3]], go_on: Checkpoint) -> Option<usize> {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for block in ids.chunks(BLOCK) {
        for &f in block {
            for k in 0..3 {
                lo[k] = lo[k].min(c[f as usize][k]);
                hi[k] = hi[k].max(c[f as usize][k]);
            }
        }
        if block.len() == BLOCK && !go_on(0.0) {
            return None;
        }
    }
    let ext = [0, 1, 2].map(|k| hi[k] - lo[k]);
    Some((0..3).fold(0, |best, k| if ext[k] > ext[best] { k } else { best }))
}

/// Phase 2's starting size: `GROUPS_PER_TARGET` × the largest target.
pub fn phase1_size(largest_target: usize) -> usize {
    largest_target.saturating_mul(GROUPS_PER_TARGET)
}

/// Phase 1: splits the faces into `k` parts and merges each (in parallel, one task per
/// part) down to its share of [`phase1_size`] of `largest_target`, in proportion to
/// its faces (at least one cluster). `q` and `volume` are the faces' operators and
/// seed volumes, `pairs` the input's adjacent face pairs; `merged` is told, now and
/// then, how many merges all parts have done so far (progress only). `then` runs once,
/// on the first thread to find no part left, while the others finish theirs (work the
/// parts do not need, which would otherwise leave a thread idle: [`in_turn`]); it gets
/// whether to go on. With `traced`, each part's merges are kept
/// ([`Phase1::take_merges`]).
pub fn merge_parts(
    fitter: &Fitter,
    faces: FaceData,
    (largest_target, k, traced): (usize, usize, bool),
    merged: &(dyn Fn(usize) -> bool + Sync),
    then: &(dyn Fn(Checkpoint) + Sync),
) -> Phase1 {
    let Some(parts) = split_checked(fitter.input.mesh, k, &|_| merged(0)) else {
        then(&|_| false);
        return Phase1 {
            stopped: true,
            ..Phase1::default()
        };
    };
    let all = fitter.input.mesh.face_count() as u128;
    let size = phase1_size(largest_target) as u128;
    let targets = parts
        .iter()
        .map(|part| (size * part.len() as u128).div_ceil(all.max(1)).max(1) as usize)
        .collect();
    merge_groups(
        fitter,
        faces,
        &parts,
        (targets, Kind::Spatial { traced }),
        merged,
        then,
    )
}

/// What phase 1 reads of each face: its operator, seed volume and adjacent pairs.
#[derive(Clone, Copy)]
pub enum FaceData<'a> {
    /// Computed for the whole input already.
    Given {
        q: &'a [Sym3],
        volume: &'a [f64],
        pairs: &'a [(u32, u32)],
    },
    /// Computed by each part for its own faces, as the whole input's stages compute
    /// them (`seed::quadric::face_quadric` with this tangent weight,
    /// [`Fitter::seed_volume`], the pairs from `lists`): no per-face operator,
    /// volume or pair outlives its part (56 bytes a face held through phase 1
    /// before).
    PerPart { tangent_eps: f64, lists: &'a Lists },
}

/// What phase 1's groups of faces are.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Kind {
    /// Spatial parts ([`split`]): merged lazily (every merge deferred,
    /// docs/decisions/0019-large-inputs-merged-in-parts.md)
    /// unless the run re-prices exactly; each part's merges kept if `traced`.
    Spatial { traced: bool },
    /// Whole connected components (`merge::components`): merged with the run's own
    /// settings, each group's neighbour lists kept, and its merges traced if `traced`.
    Components { traced: bool },
}

/// Merges each of `parts` (faces increasing within a part) down to its target, in
/// parallel, one task per part, as `kind` says; `then` runs once meanwhile, on the
/// first thread out of parts ([`merge_parts`]).
pub(super) fn merge_groups(
    fitter: &Fitter,
    faces: FaceData,
    parts: &[Vec<u32>],
    (targets, kind): (Vec<usize>, Kind),
    merged: &(dyn Fn(usize) -> bool + Sync),
    then: &(dyn Fn(Checkpoint) + Sync),
) -> Phase1 {
    let local_pairs = match faces {
        FaceData::Given { pairs, .. } => {
            pairs_by_part(parts, pairs, fitter.input.mesh.face_count())
        }
        FaceData::PerPart { .. } => vec![Vec::new(); parts.len()],
    };
    let done: Vec<AtomicUsize> = parts.iter().map(|_| AtomicUsize::new(0)).collect();
    let local_pairs: Vec<std::sync::Mutex<Vec<(u32, u32)>>> =
        local_pairs.into_iter().map(Into::into).collect();
    let run = |i: usize| {
        let (part, target) = (&parts[i], targets[i]);
        // The loop reports the fraction of its part's merges to the target.
        let span = part.len().saturating_sub(target).max(1) as f64;
        let report = |f: f64| {
            done[i].store((f * span).round() as usize, Relaxed);
            merged(done.iter().map(|d| d.load(Relaxed)).sum())
        };
        // A part that has not started when the run is cancelled does no work.
        if !merged(done.iter().map(|d| d.load(Relaxed)).sum()) {
            return (Groups::default(), MergeOutput::stopped());
        }
        let lp = std::mem::take(&mut *local_pairs[i].lock().unwrap_or_else(|e| e.into_inner()));
        merge_one(fitter, faces, part, lp, target, kind, &report)
    };
    let go_on = |_: f64| merged(done.iter().map(|d| d.load(Relaxed)).sum());
    let mut results: Vec<(usize, (Groups, MergeOutput))> =
        in_turn(parts.len(), run, || then(&go_on));
    // Each part's result in its place: what follows never depends on which thread
    // merged which part, or when.
    results.sort_unstable_by_key(|r| r.0);
    let mut out = Phase1::default();
    for (_, (groups, m)) in results {
        out.merges += m.merges;
        out.fits += m.fits;
        out.stopped |= m.stopped;
        out.parts.push(groups);
    }
    out
}

/// Runs `run` on every index below `n`, each once, on every thread of rayon's pool:
/// each thread takes the next index not yet taken when it is free (list scheduling in
/// index order), so the threads finish within about one part of each other. rayon's
/// `par_iter` over a few items splits them between the threads up front (on two: the
/// halves, each run through in order unless the other thread idles while a half's
/// later items wait), which left one thread idle for the difference between the
/// halves' sums: 0.23 of 3.48 CPU seconds on the dragon
/// (docs/decisions/perf-partitions.md, "Parts taken in turn"). `then` runs once, on
/// the first thread to find no index left, while the others finish their last run:
/// the last part otherwise ran alone (docs/decisions/perf-partitions.md, "Work
/// beside the last parts"); what it runs in parallel itself the others join as they
/// finish. Returns each index with its result, in no particular order.
fn in_turn<R: Send>(
    n: usize,
    run: impl Fn(usize) -> R + Sync,
    then: impl Fn() + Sync,
) -> Vec<(usize, R)> {
    let next = AtomicUsize::new(0);
    let taken = AtomicBool::new(false);
    let threads = rayon::current_num_threads().clamp(1, n.max(1));
    (0..threads)
        .into_par_iter()
        .with_max_len(1)
        .flat_map_iter(|_| {
            let mut mine = Vec::new();
            loop {
                let i = next.fetch_add(1, Relaxed);
                if i >= n {
                    if !taken.swap(true, Relaxed) {
                        then();
                    }
                    break mine;
                }
                mine.push((i, run(i)));
            }
        })
        .collect()
}

/// Each part's adjacent pairs in its local face ids (a face's index in its part).
fn pairs_by_part(parts: &[Vec<u32>], pairs: &[(u32, u32)], faces: usize) -> Vec<Vec<(u32, u32)>> {
    let (mut part_of, mut local) = (vec![0u32; faces], vec![0u32; faces]);
    for (p, fs) in parts.iter().enumerate() {
        for (i, &f) in fs.iter().enumerate() {
            part_of[f as usize] = p as u32;
            local[f as usize] = i as u32;
        }
    }
    let mut out = vec![Vec::new(); parts.len()];
    for &(a, b) in pairs {
        let p = part_of[a as usize];
        if p == part_of[b as usize] {
            out[p as usize].push((local[a as usize], local[b as usize]));
        }
    }
    out
}

/// The faces `part` (increasing) as a mesh of their own: local face ids in order,
/// local vertex ids for the faces' own and welded vertices (same positions and
/// offset); returns it with its weld and each local vertex's input id.
///
/// Local ids are given in order of first use. A table by the part's own vertices,
/// not one over the whole input's: a part per 65,536 faces each clearing a table of
/// every input vertex grew as the square of the input (56M faces: 855 parts × 28M
/// vertices).
fn sub_mesh(mesh: &Mesh, weld: &Weld, part: &[u32]) -> (Mesh, Weld, Vec<u32>) {
    let corners: usize = part.iter().map(|&f| mesh.face(f as usize).len()).sum();
    let mut local: rustc_hash::FxHashMap<u32, u32> = Default::default();
    local.reserve(corners);
    let mut global = Vec::new();
    let mut id = |v: u32| {
        *local.entry(v).or_insert_with(|| {
            global.push(v);
            (global.len() - 1) as u32
        })
    };
    let mut sub = Mesh {
        offset: mesh.offset,
        ..Mesh::default()
    };
    sub.face_offsets.push(0);
    for &f in part {
        for &v in mesh.face(f as usize) {
            sub.face_indices.push(id(v));
            // The target's local id is given here, in the order a copy of the welded
            // corners gave it.
            id(weld.of(v));
        }
        sub.face_offsets.push(sub.face_indices.len() as u32);
    }
    // A local vertex's target is local too (a target is its own).
    let sub_weld = weld.restricted(&global, |v| local[&v]);
    sub.x = global.iter().map(|&v| mesh.x[v as usize]).collect();
    sub.y = global.iter().map(|&v| mesh.y[v as usize]).collect();
    sub.z = global.iter().map(|&v| mesh.z[v as usize]).collect();
    (sub, sub_weld, global)
}

/// The adjacent pairs of `part`'s faces (increasing) in its local ids, from the
/// input's neighbour lists, in the order of the input's sorted pairs.
fn part_pairs(part: &[u32], (offsets, adj): &Lists) -> Vec<(u32, u32)> {
    let mut out = Vec::new();
    for (i, &f) in part.iter().enumerate() {
        let around = &adj[offsets[f as usize] as usize..offsets[f as usize + 1] as usize];
        // A face's list is increasing: the faces after it, in the part, in order.
        for &g in around.iter().filter(|&&g| g > f) {
            if let Ok(j) = part.binary_search(&g) {
                out.push((i as u32, j as u32));
            }
        }
    }
    out
}

/// `part`'s operators and seed volumes, from `faces` or computed for it.
fn part_seeds(fitter: &Fitter, faces: FaceData, part: &[u32]) -> (Vec<Sym3>, Vec<f64>) {
    match faces {
        FaceData::Given { q, volume, .. } => (
            part.iter().map(|&f| q[f as usize]).collect(),
            part.iter().map(|&f| volume[f as usize]).collect(),
        ),
        FaceData::PerPart { tangent_eps, .. } => {
            let mesh = fitter.input.mesh;
            let q: Vec<Sym3> = part
                .iter()
                .map(|&f| {
                    crate::seed::quadric::face_quadric(
                        mesh.face(f as usize),
                        |v| mesh.pos(v),
                        tangent_eps,
                    )
                })
                .collect();
            let mut ws = super::Workspace::default();
            let volume = part
                .iter()
                .zip(&q)
                .map(|(&f, q)| fitter.seed_volume(f, q, &mut ws))
                .collect();
            (q, volume)
        }
    }
}

/// Runs the merge loop on one part down to `target` and returns its groups; `pairs`
/// are its adjacent pairs in local ids when `faces` gives them.
#[allow(clippy::too_many_arguments)]
fn merge_one(
    fitter: &Fitter,
    faces: FaceData,
    part: &[u32],
    mut pairs: Vec<(u32, u32)>,
    target: usize,
    kind: Kind,
    progress: crate::progress::Checkpoint,
) -> (Groups, MergeOutput) {
    if let FaceData::PerPart { lists, .. } = faces {
        pairs = part_pairs(part, lists);
    }
    let (q, volume) = part_seeds(fitter, faces, part);
    let (sub, sub_weld, global) = sub_mesh(fitter.input.mesh, fitter.input.weld, part);
    let sub_ev = part_fitter(fitter, InputView::new(&sub, &sub_weld), kind);
    let cl = Clusters::new(q, volume, &pairs);
    drop(pairs);
    let traced = matches!(
        kind,
        Kind::Components { traced: true } | Kind::Spatial { traced: true }
    );
    let (cl, mut out) = merge_part(&sub_ev, cl, target, traced, progress);
    let trace = std::mem::take(&mut out.trace);
    (part_groups(&cl, trace, part, &global, kind), out)
}

/// The fitter of a part (`sub`: its own mesh and weld): same fit settings, cost grid
/// and hull tolerance as the whole input's `fitter`.
fn part_fitter<'a>(fitter: &Fitter<'a>, sub: InputView<'a>, kind: Kind) -> Fitter<'a> {
    Fitter {
        // No surface (indexed by the whole input's faces; a part fits no output
        // primitives), the same interior.
        input: InputView {
            solid: fitter.input.solid,
            ..sub
        },
        pricing: Pricing {
            // Lazy greedy for every merge of a part unless re-pricing is exact: faster at
            // about the same quality (docs/decisions/0019-large-inputs-merged-in-parts.md).
            defer_degree: if matches!(kind, Kind::Spatial { .. })
                && fitter.pricing.defer_degree != u32::MAX
            {
                0
            } else {
                fitter.pricing.defer_degree
            },
            ..fitter.pricing
        },
    }
}

/// The groups a part's merge left (`cl`, and its `trace`), in the input's face and
/// vertex ids: `part` maps the part's faces to the input's (increasing with the
/// part's own, so the same order), `global` its vertices.
fn part_groups(
    cl: &Clusters,
    trace: Vec<Traced>,
    part: &[u32],
    global: &[u32],
    kind: Kind,
) -> Groups {
    let global_id = |f: u32| part[f as usize];
    let spatial = matches!(kind, Kind::Spatial { .. });
    let mut g = Groups {
        offsets: vec![0],
        ..Groups::default()
    };
    if spatial {
        // The tree needs only which clusters merged, by a face of each.
        g.merges = (trace.iter())
            .map(|t| (global_id(t.a), global_id(t.b)))
            .collect();
    } else {
        let trace = trace.into_iter().map(|t| Traced {
            key_a: global_id(t.key_a),
            key_b: global_id(t.key_b),
            a: global_id(t.a),
            b: global_id(t.b),
            ..t
        });
        g.trace = trace.collect();
    }
    for r in cl.roots() {
        let start = g.faces.len();
        g.faces.extend(cl.faces(r).map(global_id));
        g.faces[start..].sort_unstable();
        g.offsets.push(g.faces.len() as u32);
        g.q.push(cl.q[r as usize]);
        g.volume.push(cl.volume[r as usize]);
        g.verts
            .push(cl.verts(r).iter().map(|&v| global[v as usize]).collect());
        if !spatial {
            let (n, resolved) = cl.neighbor_list(r);
            g.neighbors
                .push((n.iter().map(|&f| global_id(f)).collect(), resolved));
        }
    }
    g
}

/// Phase 2's starting clusters after spatial parts: one per group of phase 1, ids in
/// the order of their lowest faces ([`Clusters::of_groups`]), with the group's
/// operator, priced volume and hull-reduced points, and neighbours = the groups
/// adjacent to it through `lists` (the input's adjacency as neighbour lists of its
/// `faces` faces), resolved; the merge clock starts at 0 as for single faces. The
/// same clusters, ids renamed in order, as [`clusters`] makes one face at a time, in
/// memory for the groups and 8 bytes a face (4 for the loop, 4 while it is built).
///
/// `go_on` is asked between blocks of groups (reporting no progress); `None` when it
/// says stop.
pub fn group_clusters(
    p1: Phase1,
    faces: usize,
    lists: &Lists,
    go_on: crate::progress::Checkpoint,
) -> Option<Clusters> {
    // Every group as (its lowest face, its part, its index there), in face order.
    let mut order: Vec<(u32, u32, u32)> = Vec::with_capacity(p1.groups());
    for (p, g) in p1.parts.iter().enumerate() {
        let heads = g.offsets[..g.offsets.len() - 1].iter();
        order.extend((heads.enumerate()).map(|(i, &o)| (g.faces[o as usize], p as u32, i as u32)));
    }
    order.sort_unstable();
    let mut group_of = vec![u32::MAX; faces];
    for (id, &(_, p, i)) in order.iter().enumerate() {
        let g = &p1.parts[p as usize];
        let members = &g.faces[g.offsets[i as usize] as usize..g.offsets[i as usize + 1] as usize];
        members
            .iter()
            .for_each(|&f| group_of[f as usize] = id as u32);
    }
    let (offsets, adj) = (&lists.0, &lists.1);
    let mut groups = Vec::with_capacity(order.len());
    for block in order.chunks(4096) {
        if !go_on(0.0) {
            return None;
        }
        let made: Vec<Group> = block
            .par_iter()
            .map(|&(_, p, i)| {
                let g = &p1.parts[p as usize];
                let i = i as usize;
                let members = &g.faces[g.offsets[i] as usize..g.offsets[i + 1] as usize];
                let own = group_of[members[0] as usize];
                let mut neighbors: Vec<u32> = members
                    .iter()
                    .flat_map(|&f| {
                        &adj[offsets[f as usize] as usize..offsets[f as usize + 1] as usize]
                    })
                    .map(|&n| group_of[n as usize])
                    .filter(|&n| n != own)
                    .collect();
                neighbors.sort_unstable();
                neighbors.dedup();
                Group {
                    faces: members.to_vec(),
                    q: g.q[i],
                    volume: g.volume[i],
                    verts: g.verts[i].clone(),
                    resolved: neighbors.len() as u32,
                    neighbors,
                }
            })
            .collect();
        groups.extend(made);
    }
    drop((p1, group_of));
    Some(Clusters::of_groups(groups))
}

/// Phase 2's starting clusters: one per group of phase 1 (named by its lowest face),
/// with the group's operator, priced volume and hull-reduced points, and neighbours =
/// the groups adjacent to it through `pairs`; the merge clock starts at 0 as for
/// single faces. `q` and `volume` are the per-face arrays (reused as storage),
/// `lists` the input's adjacency as neighbour lists (shared).
///
/// `go_on` is asked between parts (reporting no progress); `None` when it says stop.
pub fn clusters(
    p1: Phase1,
    q: Vec<Sym3>,
    volume: Vec<f64>,
    lists: Lists,
    go_on: crate::progress::Checkpoint,
) -> Option<Clusters> {
    let mut cl = Clusters::with_lists(q, volume, lists);
    let mut unresolved = Vec::with_capacity(p1.groups());
    for mut g in p1.parts {
        if !go_on(0.0) {
            return None;
        }
        let mut lists = std::mem::take(&mut g.neighbors).into_iter();
        for (i, verts) in g.verts.into_iter().enumerate() {
            let faces = &g.faces[g.offsets[i] as usize..g.offsets[i + 1] as usize];
            let root = faces[0];
            // Replaying the group's union through `merge` splices its face list and
            // gathers its faces' neighbours; the last merge stores its points.
            let mut pts = Some(verts);
            for (j, &f) in faces.iter().enumerate().skip(1) {
                let last = j + 1 == faces.len();
                let v = if last { pts.take() } else { None };
                cl.merge(root, f, v.unwrap_or_default(), 0.0);
            }
            cl.q[root as usize] = g.q[i];
            cl.volume[root as usize] = g.volume[i];
            match lists.next() {
                // Whole components: the list as the global loop would hold it.
                Some((n, resolved)) if faces.len() > 1 => cl.set_neighbor_list(root, n, resolved),
                Some(_) => {}
                None => unresolved.push(root),
            }
        }
    }
    // Seeding reads every root's neighbour list: resolve the spatial parts' lists to
    // groups, once every group is merged.
    for (i, r) in unresolved.into_iter().enumerate() {
        if i % 4096 == 0 && !go_on(0.0) {
            return None;
        }
        cl.resolved_neighbors(r);
    }
    cl.reset_clock();
    Some(cl)
}

#[cfg(test)]
mod tests;
