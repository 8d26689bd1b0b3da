//! The merge loop of Alg. 1: seed the queue with every adjacent pair, pop the cheapest
//! valid merge, apply it, re-price the merged cluster's neighbours (or, for a deferred
//! merge under `Params::reprice`, leave its pairs' old entries as keys and re-price
//! each when popped: lazy greedy, `lazy.rs`); record a snapshot at
//! every requested target on the way down (one bottom-up pass serves all targets). When
//! adjacency runs out above the target, bridge components (§3.4 "Pairwise Component
//! Merging") by linking each cluster to its nearest clusters (`bridge.rs`), O(C log C)
//! instead of the paper's O(C²) all pairs.

use super::bridge::{nearest_pairs, BRIDGE_K};
use super::cluster::Clusters;
use super::cost::{Fitter, Workspace};
use super::heap::{Candidate, Queue, RadixHeap};
use super::lazy::{valid, Lazy, Pop};
use super::worker::{with_pricer, Pricer, PricerCounts};
use crate::math::hull::{hull_vertices, HullWorkspace};
use crate::primitive::Primitive;
use crate::progress::Checkpoint;
use rayon::prelude::*;

/// Pairs priced per parallel task.
const CHUNK: usize = 1024;
/// The loop reports progress and checks whether to stop every this many steps: a
/// few milliseconds of a part's loop, and well under a second of the global loop's
/// after parts of a 56M-face input (about 2 ms a merge there: large clusters).
const CHECK_EVERY: usize = 256;
/// Point lists up to this size are not worth reducing to their hull: fitting a few
/// extra points costs less than the hull. The hull's vertices are a subset of the
/// points, so the fits agree up to the hull's tolerance (docs/decisions/perf-point-reduction.md).
const HULL_MIN: usize = 32;
/// Stale entries [`look_ahead`] pops past to find a fresh one.
const LOOK_PAST: usize = 8;
/// Pairs priced per block when seeding the queue.
const PRICE_BLOCK: usize = 1 << 16;
/// The queue is purged of stale entries when it grows by a quarter, but never below
/// this size (a purge is one sequential pass; the stale entries would cost memory).
const PURGE_MIN: usize = 1 << 16;

/// The clusters alive when a target was reached (or when merging stopped above it).
#[derive(Clone, Debug, Default)]
pub struct Snapshot {
    pub target: usize,
    pub prims: Vec<Primitive>,
    pub faces: Vec<u32>,
    /// Distinct vertices of each primitive's faces (for post-processing).
    pub verts: Vec<Vec<u32>>,
    /// The faces of each primitive (post-processing checks coverage face by face).
    pub members: Vec<Vec<u32>>,
    /// Each primitive's operator (the sum of its faces' quadrics), for refits after
    /// the loop (`postprocess`).
    pub q: Vec<crate::math::Sym3>,
}

#[derive(Clone, Debug, Default)]
pub struct MergeOutput {
    /// One per target, in decreasing target order.
    pub snapshots: Vec<Snapshot>,
    pub merges: usize,
    pub bridge_edges: usize,
    pub fits: FitCounts,
    /// Merges whose points [`look_ahead`] had reduced (while a batch was priced).
    pub ahead: usize,
    /// Every merge in order, with its place in the global order (`Scope::Traced` only).
    pub trace: Vec<Traced>,
    /// The run was told to stop ([`crate::progress`]): snapshots are missing.
    pub stopped: bool,
}

/// What the loop for the merge tree ([`run_for_tree`]) records besides its output:
/// the merges the tree is built of (`cut::tree`).
#[derive(Clone, Debug, Default)]
pub struct MergeLog {
    /// Every merge of the whole input's loop in order, as a face of each merged
    /// cluster: the merge tree's nodes. 8 bytes a merge.
    pub merges: Vec<(u32, u32)>,
    /// How many of `merges` came before the loop's first snapshot.
    pub at_first: usize,
    /// `merges` holds every merge from one cluster per face (no spatial parts first):
    /// the merge tree's leaves are the faces.
    pub from_faces: bool,
    /// The points clusters were priced by, kept for the merge tree.
    pub hulls: TreeHulls,
}

/// The points the loop priced clusters by ([`Fitter::verts`]: the hull vertices of
/// their faces, as welded vertex ids), kept for the merge tree so that the cut need not
/// find its nodes' hulls again (`cut::hulls`, docs/decisions/0052): those of the first
/// snapshot's clusters, in its order, and of each logged merge's cluster of more than
/// the asked faces, with its index in [`MergeLog::merges`].
#[derive(Clone, Debug, Default)]
pub struct TreeHulls {
    pub leaves: Vec<Vec<u32>>,
    pub merges: Vec<(u32, Vec<u32>)>,
}

impl TreeHulls {
    /// Those of the merges from `merges[first]` on, their indices counted from there.
    pub fn after(self, first: usize) -> TreeHulls {
        let merges = self.merges.into_iter();
        TreeHulls {
            merges: merges
                .filter_map(|(at, h)| Some((at.checked_sub(first as u32)?, h)))
                .collect(),
            ..self
        }
    }
}

impl MergeOutput {
    /// The output of a loop told to stop before its first target.
    pub(crate) fn stopped() -> MergeOutput {
        MergeOutput {
            stopped: true,
            ..MergeOutput::default()
        }
    }
}

/// One merge of a traced loop: the pair merged, and the key at which a global loop
/// holding this loop's entries among others does it. Entries of other loops never
/// change this loop's, so the global loop pops each loop's entries in that loop's own
/// order, and merges when the popped entry is fresh; an entry can come out after a
/// cheaper one of the same loop only because it was pushed later, by an entry popped
/// before it. So the global loop does this merge after every other loop's entries
/// that pop before the latest (in pop order) of this loop's entries popped so far —
/// the key. Entries dropped when popped change nothing and are left out (the next
/// entry acted on pops no earlier than they did: it was queued when they were popped).
/// Ids are the loop's own until `merge::partition` maps them to the input's.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Traced {
    pub cost: f64,
    pub key_a: u32,
    pub key_b: u32,
    pub a: u32,
    pub b: u32,
    /// Whether the merge itself is [`free`]: it runs before a target's snapshot.
    pub free: bool,
}

impl Traced {
    /// Global merge order between loops: by key (cost, then ids); two loops' keys are
    /// never equal (their pairs differ), and one loop's keys never decrease.
    pub fn cmp_key(&self, o: &Traced) -> std::cmp::Ordering {
        self.cost
            .total_cmp(&o.cost)
            .then(self.key_a.cmp(&o.key_a))
            .then(self.key_b.cmp(&o.key_b))
    }
}

/// The latest entry in pop order that a traced loop popped and acted on.
#[derive(Clone, Copy, Debug, Default)]
struct Top(Option<Candidate>);

impl Top {
    /// `c` was popped and acted on (merged or re-priced).
    fn popped(&mut self, c: &Candidate) {
        // `Candidate`'s order is reversed for `BinaryHeap`: the least pops last.
        if self.0.is_none_or(|t| *c < t) {
            self.0 = Some(*c);
        }
    }
}

/// Candidate merges priced by the merge loop, by occasion.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FitCounts {
    /// Pairs priced when seeding the queue and when bridging.
    pub seed: usize,
    /// Pairs re-priced right after a merge.
    pub eager: usize,
    /// Stale entries re-priced when popped (deferred merges).
    pub lazy: usize,
}

impl std::ops::AddAssign for FitCounts {
    /// Counts of two runs together (the phases of `Params::partitions`).
    fn add_assign(&mut self, o: FitCounts) {
        self.seed += o.seed;
        self.eager += o.eager;
        self.lazy += o.lazy;
    }
}

/// Visited-marks for deduplicating vertex unions without clearing a whole array.
struct Stamps {
    mark: Vec<u32>,
    epoch: u32,
}

impl Stamps {
    fn next(&mut self) {
        if self.epoch == u32::MAX {
            self.mark.iter_mut().for_each(|m| *m = 0);
            self.epoch = 0;
        }
        self.epoch += 1;
    }
    /// True the first time `v` is seen in this epoch.
    fn first(&mut self, v: u32) -> bool {
        let m = &mut self.mark[v as usize];
        let fresh = *m != self.epoch;
        *m = self.epoch;
        fresh
    }
}

/// Prices pairs in parallel chunks, in place; the output order equals the input order.
fn price(fitter: &Fitter, cl: &Clusters, pairs: &[(u32, u32)]) -> Vec<Candidate> {
    let none = Candidate {
        cost: f64::NAN,
        volume: 0.0,
        a: 0,
        b: 0,
        t: 0,
        flat: false,
    };
    let mut out = vec![none; pairs.len()];
    out.par_chunks_mut(CHUNK)
        .zip(pairs.par_chunks(CHUNK))
        .for_each_init(Workspace::default, |ws, (slots, chunk)| {
            for (slot, &(a, b)) in slots.iter_mut().zip(chunk) {
                if let Some((c, _)) = fitter.candidate(cl, a, b, ws) {
                    *slot = c;
                }
            }
        });
    // Merges over the excess-volume cap were left as NaN placeholders.
    out.retain(|c| !c.cost.is_nan());
    out
}

/// Runs the merge loop down to the smallest target; `targets` sorted decreasing.
pub fn run(fitter: &Fitter, cl: Clusters, targets: &[usize], go_on: Checkpoint) -> MergeOutput {
    run_with::<RadixHeap>(fitter, cl, targets, go_on)
}

/// [`run`] for the merge tree (`cut`): the same merges, but each target's snapshot
/// holds only its clusters' faces and operators — the cut fits the nodes it keeps, so
/// fitting the leaves and the root here would be thrown away. With `hulls_over`, the
/// points of the first snapshot's clusters and of merged clusters of more faces are
/// kept too ([`TreeHulls`]). Returns every merge too ([`MergeLog`]).
pub fn run_for_tree(
    fitter: &Fitter,
    cl: Clusters,
    targets: &[usize],
    hulls_over: Option<usize>,
    go_on: Checkpoint,
) -> (MergeOutput, MergeLog) {
    with_pricer(fitter, |p| {
        let mut log = MergeLog::default();
        let scope = Scope::Tree(hulls_over);
        let out = merge_loop::<RadixHeap>(fitter, cl, targets, go_on, p, scope, &mut log).0;
        (out, log)
    })
}

/// [`run`] with a chosen queue (the benchmarks compare them; the order is the same).
pub fn run_with<Q: Queue>(
    fitter: &Fitter,
    cl: Clusters,
    targets: &[usize],
    go_on: Checkpoint,
) -> MergeOutput {
    run_counted::<Q>(fitter, cl, targets, go_on).0
}

/// [`run_with`], sharing re-pricing batches with a worker thread (`merge::worker`) when
/// rayon's pool has two threads or more; also returns the pricer's counters.
fn run_counted<Q: Queue>(
    fitter: &Fitter,
    cl: Clusters,
    targets: &[usize],
    go_on: Checkpoint,
) -> (MergeOutput, PricerCounts) {
    with_pricer(fitter, |p| {
        let mut log = MergeLog::default();
        let out = merge_loop::<Q>(fitter, cl, targets, go_on, p, Scope::Whole, &mut log).0;
        (out, p.stats)
    })
}

/// What the merge loop runs on: the whole input, or one spatial part of it in phase 1
/// of `Params::partitions` (`partition.rs`), which fits no snapshots (only the
/// clusters are kept) and never bridges (linking components is a global decision).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Scope {
    Whole,
    /// The whole input for the merge tree: snapshots without fits, and the clusters'
    /// points kept above this many faces ([`run_for_tree`]).
    Tree(Option<usize>),
    Part,
    /// A part that also records its merges (`MergeOutput::trace`).
    Traced,
}

impl Scope {
    /// The loop runs on the whole input: it logs its merges and bridges components.
    fn whole(self) -> bool {
        matches!(self, Scope::Whole | Scope::Tree(_))
    }
}

/// Phase 1 of `Params::partitions`: merges `cl` (one part's clusters) down to
/// `target` on this thread alone (no worker: the parts run in parallel), or until
/// adjacency runs out, reporting progress as [`run`] does; returns the clusters and
/// the merge counts (and, when `traced`, every merge: [`Traced`]).
pub(super) fn merge_part(
    fitter: &Fitter,
    cl: Clusters,
    target: usize,
    traced: bool,
    go_on: Checkpoint,
) -> (Clusters, MergeOutput) {
    let mut pricer = Pricer::serial(fitter);
    let scope = if traced { Scope::Traced } else { Scope::Part };
    let mut log = MergeLog::default();
    let (out, cl) =
        merge_loop::<RadixHeap>(fitter, cl, &[target], go_on, &mut pricer, scope, &mut log);
    (cl, out)
}

/// The loop of [`run_with`]; `pricer` re-prices each merged cluster's neighbours; the
/// whole input's loop logs its merges in `log`.
fn merge_loop<Q: Queue>(
    fitter: &Fitter,
    mut cl: Clusters,
    targets: &[usize],
    go_on: Checkpoint,
    pricer: &mut Pricer,
    scope: Scope,
    log: &mut MergeLog,
) -> (MergeOutput, Clusters) {
    let mut out = MergeOutput::default();
    let mut heap = Q::default();
    match seed_queue(fitter, &cl, &mut heap, go_on) {
        Some(priced) => out.fits.seed += priced,
        None => {
            out.stopped = true;
            return (out, cl);
        }
    }
    let mut purge_at = (heap.len() + heap.len() / 4).max(PURGE_MIN);
    let mut stamps = Stamps {
        mark: vec![0; fitter.input.mesh.vertex_count()],
        epoch: 0,
    };
    let mut reducer = Reducer::default();
    let mut lazy = Lazy::default();
    // Entries re-priced when popped are priced one at a time, here.
    let mut ws = Workspace::default();
    // The points of a merge reduced ahead of its turn ([`look_ahead`]); batch buffer.
    let mut ahead: Option<Ahead> = None;
    let mut batch = Vec::new();
    // The latest entry acted on, in pop order (`Scope::Traced`).
    let mut top = Top::default();
    let start = cl.live;
    let last = *targets.last().expect("at least one target");
    let mut next = 0;
    // The greedy order's next merge, popped at a target but not free: applied after
    // that target's snapshot.
    let mut held: Option<Candidate> = None;
    // Steps of the loop (a merge, or an entry re-priced or dropped when popped).
    let mut steps = 0usize;
    loop {
        steps += 1;
        if steps % CHECK_EVERY == 0 && !go_on(fraction(start, cl.live, last)) {
            out.stopped = true;
            return (out, cl);
        }
        let reached = next < targets.len() && cl.live <= targets[next];
        // A target's snapshot waits for free merges into plates
        // (docs/decisions/0025-free-merges-into-plates.md); the
        // queue running dry there does not bridge components first.
        if reached && (held.is_some() || heap.is_empty()) {
            if next == 0 {
                log.at_first = log.merges.len();
            }
            let go_on_here = || go_on(fraction(start, cl.live, last));
            while next < targets.len() && cl.live <= targets[next] {
                let Some(snap) = snapshot(fitter, &cl, targets[next], scope, &go_on_here) else {
                    out.stopped = true;
                    return (out, cl);
                };
                if next == 0 {
                    keep_leaf_hulls(fitter, &cl, scope, &mut log.hulls);
                }
                out.snapshots.push(snap);
                next += 1;
            }
            if next == targets.len() {
                break;
            }
        }
        let c = match held.take() {
            Some(c) => c,
            None => match next_step(
                fitter, &mut cl, &mut heap, &mut lazy, &mut ws, &mut out, scope,
            ) {
                Step::Merge(c) => c,
                Step::Repriced(c) => {
                    top.popped(&c);
                    continue;
                }
                Step::Again => continue,
                Step::Stop => break,
            },
        };
        if reached && !(fitter.pricing.free_merges && free(&c)) {
            held = Some(c);
            continue;
        }
        if scope == Scope::Traced {
            top.popped(&c);
            let k = top.0.unwrap_or(c);
            out.trace.push(Traced {
                cost: k.cost,
                key_a: k.a,
                key_b: k.b,
                a: c.a,
                b: c.b,
                free: free(&c),
            });
        }
        if heap.len() > purge_at {
            purge(fitter, &cl, &mut lazy, &mut heap);
            purge_at = (heap.len() + heap.len() / 4).max(PURGE_MIN);
        }
        // Fresh, so neither cluster changed since it was priced: a look-ahead's points hold.
        let verts = match ahead.take_if(|k| k.c == c) {
            Some(k) => {
                out.ahead += 1;
                k.verts
            }
            None => merged_points(fitter, &cl, c.a, c.b, &mut stamps, &mut reducer),
        };
        let root = cl.merge(c.a, c.b, verts, c.volume);
        out.merges += 1;
        if scope.whole() {
            log.merges.push((cl.head(c.a), cl.head(c.b)));
            keep_hull(
                fitter,
                &cl,
                root,
                scope,
                log.merges.len() - 1,
                &mut log.hulls,
            );
        }
        if !defer(fitter, &mut cl, root) {
            let nbrs = cl.resolved_neighbors(root);
            // While the worker prices the batch, reduce the points of the likely next
            // merge (the serial part of the next step).
            let meanwhile = || {
                look_ahead(
                    fitter,
                    &cl,
                    &mut heap,
                    &mut ahead,
                    &mut stamps,
                    &mut reducer,
                )
            };
            pricer.price(&cl, root, &nbrs, meanwhile, |c| batch.push(c));
            out.fits.eager += nbrs.len();
            cl.mark_repriced(root);
            batch.drain(..).for_each(|c| heap.push(c));
        }
    }
    if next == 0 {
        log.at_first = log.merges.len();
    }
    let go_on_here = || go_on(fraction(start, cl.live, last));
    while next < targets.len() {
        let Some(snap) = snapshot(fitter, &cl, targets[next], scope, &go_on_here) else {
            out.stopped = true;
            return (out, cl);
        };
        if next == 0 {
            keep_leaf_hulls(fitter, &cl, scope, &mut log.hulls);
        }
        out.snapshots.push(snap);
        next += 1;
    }
    (out, cl)
}

/// The points of the live clusters, the first snapshot's (the merge tree's leaves),
/// where `scope` keeps hulls.
fn keep_leaf_hulls(fitter: &Fitter, cl: &Clusters, scope: Scope, hulls: &mut TreeHulls) {
    if let Scope::Tree(Some(_)) = scope {
        hulls.leaves = cl
            .roots()
            .iter()
            .map(|&r| fitter.verts(cl, r).to_vec())
            .collect();
    }
}

/// The points of `root`, just merged as `log.merges[at]`, where `scope` keeps hulls of its
/// size.
fn keep_hull(
    fitter: &Fitter,
    cl: &Clusters,
    root: u32,
    scope: Scope,
    at: usize,
    hulls: &mut TreeHulls,
) {
    if let Scope::Tree(Some(over)) = scope {
        if cl.face_count[root as usize] as usize > over {
            hulls
                .merges
                .push((at as u32, fitter.verts(cl, root).to_vec()));
        }
    }
}

/// Whether a merge is free: coplanar points (a plate) and no added volume (k·V of the
/// union at most the parts' volumes). The greedy order's next merge runs before a
/// target's snapshot while it is free, so a target is reached with the same faces in
/// fewer plates of no more area (docs/decisions/0025-free-merges-into-plates.md);
/// without it, `-n` at the face count merges nothing and leaves a plate per triangle where coplanar
/// triangles make one. Only plates: parts that overlap count their common volume
/// twice, so a solid merge can cost ≤ 0 and still cover space neither part did (two
/// cubes sharing an edge into one box over both empty corners, tiny_shared_edge).
pub fn free(c: &Candidate) -> bool {
    c.flat && c.cost <= 0.0
}

/// What the merge loop does next ([`next_step`]).
enum Step {
    /// Apply this fresh merge.
    Merge(Candidate),
    /// This stale entry was re-priced: pop again.
    Repriced(Candidate),
    /// A stale entry was dropped, or components were bridged: pop again.
    Again,
    /// Nothing left to merge (a part's adjacency, or the whole input's after bridging).
    Stop,
}

/// Pops the queue's next entry and classifies it (lazy deletion, `lazy.rs`); when the
/// queue runs dry, bridges components (§3.4) — except in a part, which just stops.
fn next_step<Q: Queue>(
    fitter: &Fitter,
    cl: &mut Clusters,
    heap: &mut Q,
    lazy: &mut Lazy,
    ws: &mut Workspace,
    out: &mut MergeOutput,
    scope: Scope,
) -> Step {
    let Some(c) = heap.pop() else {
        if !scope.whole() {
            return Step::Stop;
        }
        let bridged = bridge(fitter, cl);
        out.bridge_edges += bridged.len();
        out.fits.seed += bridged.len();
        let fresh = price(fitter, cl, &bridged);
        if fresh.is_empty() {
            return Step::Stop;
        }
        fresh.into_iter().for_each(|c| heap.push(c));
        return Step::Again;
    };
    match lazy.classify(cl, &c) {
        Pop::Fresh => Step::Merge(c),
        Pop::Drop => Step::Again,
        Pop::Reprice(a, b) => {
            out.fits.lazy += 1;
            if let Some((fresh, _)) = fitter.candidate(cl, a, b, ws) {
                heap.push(fresh);
            }
            Step::Repriced(c)
        }
    }
}

/// Prices the input's adjacent pairs into `heap` in blocks, so that only one block of
/// pairs and candidates exists outside the queue; returns how many were priced.
/// The loop's progress: merges done of those from `start` clusters down to `last`.
fn fraction(start: usize, live: usize, last: usize) -> f64 {
    (start - live) as f64 / (start - last.min(start)).max(1) as f64
}

/// `None` when `go_on` (asked between blocks, reporting no progress yet) says stop.
fn seed_queue<Q: Queue>(
    fitter: &Fitter,
    cl: &Clusters,
    heap: &mut Q,
    go_on: Checkpoint,
) -> Option<usize> {
    let (n, mut priced) = (cl.len() as u32, 0);
    let mut block = Vec::with_capacity(PRICE_BLOCK);
    for a in 0..n {
        // Roots' neighbour lists: the input's adjacency, or (phase 2 of
        // `Params::partitions`) the resolved adjacency between groups of faces, or
        // (after `merge::components`) whole components' lists as their loops left them,
        // whose merged-away ids name the component itself.
        let nbrs = if cl.is_root(a) { cl.neighbors(a) } else { &[] };
        let pair = |&b: &u32| b > a && cl.is_root(b);
        block.extend(nbrs.iter().copied().filter(|b| pair(b)).map(|b| (a, b)));
        if block.len() >= PRICE_BLOCK || a + 1 == n {
            priced += block.len();
            price(fitter, cl, &block)
                .into_iter()
                .for_each(|c| heap.push(c));
            block.clear();
            if !go_on(0.0) {
                return None;
            }
        }
    }
    Some(priced)
}

/// Drops stale entries: lazy deletion's would otherwise outnumber the live pairs many
/// times over (memory); dropping them keeps the order unchanged. Deferred pairs'
/// entries are kept: they are the pairs' only keys.
fn purge<Q: Queue>(fitter: &Fitter, cl: &Clusters, lazy: &mut Lazy, heap: &mut Q) {
    if fitter.pricing.defer_degree == u32::MAX {
        heap.retain(|c| valid(cl, c));
    } else {
        heap.retain(|c| lazy.keep(cl, c));
        lazy.prune(cl);
    }
}

/// Whether the merge that made `root` leaves its pairs to [`Lazy`] instead of
/// re-pricing them at once: its neighbour list (resolved once it doubles) reaches
/// `fitter.pricing.defer_degree`.
fn defer(fitter: &Fitter, cl: &mut Clusters, root: u32) -> bool {
    let limit = fitter.pricing.defer_degree as usize;
    if cl.neighbor_len(root) < limit {
        return false;
    }
    cl.compact_neighbors(root);
    cl.neighbor_len(root) >= limit
}

/// Buffers for reducing a merged cluster's points to its hull vertices.
#[derive(Default)]
struct Reducer {
    x: Vec<f64>,
    y: Vec<f64>,
    z: Vec<f64>,
    keep: Vec<u32>,
    hull: HullWorkspace,
}

/// The points to price a merged cluster by: the distinct vertices of both clusters'
/// point lists, reduced to the vertices of their convex hull. Every fit maximises a
/// convex function (or minimises a concave one) over the points, so the hull vertices
/// give the same primitive as all points (docs/decisions/0010).
fn merged_points(
    fitter: &Fitter,
    cl: &Clusters,
    a: u32,
    b: u32,
    st: &mut Stamps,
    r: &mut Reducer,
) -> Vec<u32> {
    st.next();
    let (va, vb) = (fitter.verts(cl, a), fitter.verts(cl, b));
    let mut out = Vec::with_capacity(va.len() + vb.len());
    out.extend(va.iter().chain(vb).copied().filter(|&v| st.first(v)));
    if out.len() <= HULL_MIN {
        return out;
    }
    r.x.clear();
    r.y.clear();
    r.z.clear();
    for &v in &out {
        let p = fitter.input.mesh.pos(v);
        r.x.push(p[0]);
        r.y.push(p[1]);
        r.z.push(p[2]);
    }
    hull_vertices(
        &r.x,
        &r.y,
        &r.z,
        fitter.pricing.hull_eps,
        &mut r.hull,
        &mut r.keep,
    );
    r.keep.iter().map(|&i| out[i as usize]).collect()
}

/// A fresh queue entry and its merged point list, reduced before its turn.
struct Ahead {
    c: Candidate,
    verts: Vec<u32>,
}

/// Reduces the merged points of the queue's first fresh entry into `ahead` (kept if
/// it already holds that entry) while a re-pricing batch is out: the serial part of
/// the next merge, done while the worker prices. Entries are only looked at: every one
/// popped here goes back, so the queue, and with it the merge order, stays exactly as
/// without the look-ahead. The entry is often the next merge
/// (docs/decisions/perf-repricing-worker-and-look-ahead.md);
/// otherwise its points wait until it is popped still fresh (neither cluster changed
/// since it was priced, so the same points) or another entry takes its place.
fn look_ahead<Q: Queue>(
    fitter: &Fitter,
    cl: &Clusters,
    heap: &mut Q,
    ahead: &mut Option<Ahead>,
    st: &mut Stamps,
    r: &mut Reducer,
) {
    // Stale entries on top (often the merged cluster's old pairs) are passed over.
    let mut seen = [None; LOOK_PAST];
    let mut found = None;
    for slot in &mut seen {
        let Some(c) = heap.pop() else { break };
        *slot = Some(c);
        if valid(cl, &c) {
            found = Some(c);
            break;
        }
    }
    seen.into_iter().flatten().for_each(|c| heap.push(c));
    let Some(c) = found else { return };
    if ahead.as_ref().is_some_and(|k| k.c == c) {
        return;
    }
    let verts = merged_points(fitter, cl, c.a, c.b, st, r);
    *ahead = Some(Ahead { c, verts });
}

/// Links every live cluster to its nearest clusters by centroid (`bridge.rs`).
fn bridge(fitter: &Fitter, cl: &mut Clusters) -> Vec<(u32, u32)> {
    let roots = cl.roots();
    let centroids: Vec<[f64; 3]> = roots.iter().map(|&r| centroid(fitter, cl, r)).collect();
    let pairs: Vec<(u32, u32)> = nearest_pairs(&centroids, BRIDGE_K)
        .into_iter()
        .map(|(i, j)| (roots[i as usize], roots[j as usize]))
        .collect();
    // Roots increase with their index, so the pairs stay sorted and distinct.
    debug_assert!(pairs.windows(2).all(|w| w[0] < w[1]));
    for &(a, b) in &pairs {
        cl.link(a, b);
    }
    pairs
}

fn centroid(fitter: &Fitter, cl: &Clusters, c: u32) -> [f64; 3] {
    let vs = fitter.verts(cl, c);
    let mut s = [0.0; 3];
    for &v in vs {
        let p = fitter.input.mesh.pos(v);
        (0..3).for_each(|k| s[k] += p[k]);
    }
    s.map(|x| x / vs.len().max(1) as f64)
}

/// Fits every live cluster (in root order) on all of its faces' vertices, for output
/// (a part's loop only records that the target was reached; the tree's keeps each
/// cluster's faces and operator, unfitted).
/// `None` when `go_on` says stop while the output primitives are fitted (asked
/// before every 64 clusters on each thread).
pub(super) fn snapshot(
    fitter: &Fitter,
    cl: &Clusters,
    target: usize,
    scope: Scope,
    go_on: &(dyn Fn() -> bool + Sync),
) -> Option<Snapshot> {
    let roots = cl.roots();
    match scope {
        Scope::Whole => {}
        Scope::Tree(_) => {
            return Some(Snapshot {
                target,
                members: roots.par_iter().map(|&r| cl.faces(r).collect()).collect(),
                q: roots.iter().map(|&r| cl.q[r as usize]).collect(),
                ..Snapshot::default()
            })
        }
        Scope::Part | Scope::Traced => {
            return Some(Snapshot {
                target,
                ..Snapshot::default()
            })
        }
    }
    let prims: Vec<Primitive> = roots
        .par_chunks(64)
        .map_init(Workspace::default, |ws, chunk| {
            go_on().then(|| {
                chunk
                    .iter()
                    .map(|&r| fitter.fit_cluster_exact(cl, r, ws).prim)
                    .collect::<Vec<_>>()
            })
        })
        .collect::<Option<Vec<_>>>()?
        .into_iter()
        .flatten()
        .collect();
    let mut snap = Snapshot {
        target,
        prims,
        faces: roots.iter().map(|&r| cl.face_count[r as usize]).collect(),
        verts: roots.par_iter().map(|&r| fitter.all_verts(cl, r)).collect(),
        members: roots.par_iter().map(|&r| cl.faces(r).collect()).collect(),
        q: Vec::new(),
    };
    snap.q = roots.iter().map(|&r| cl.q[r as usize]).collect();
    Some(snap)
}

#[cfg(test)]
pub(super) mod tests;
