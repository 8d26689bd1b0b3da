//! The merge loop of Alg. 1: seed the queue with every adjacent pair, pop the cheapest
//! valid merge, apply it, re-price the merged cluster's neighbours (or, for a deferred
//! merge under `Params::reprice`, leave its pairs' old entries as keys and re-price
//! each when popped: lazy greedy, `lazy.rs`); record a snapshot at
//! every requested target on the way down (one bottom-up pass serves all targets). When
//! adjacency runs out above the target, bridge components (§3.4 "Pairwise Component
//! Merging") by linking each cluster to its nearest clusters (`bridge.rs`), O(C log C)
//! instead of the paper's O(C²) all pairs.

use super::cluster::Clusters;
use super::cost::{Fitter, Workspace};
use super::heap::{Candidate, Queue, RadixHeap};
use super::lazy::{Lazy, Pop};
use super::worker::{with_pricer, Pricer, PricerCounts};
use crate::primitive::Primitive;
use crate::progress::Checkpoint;
use pairs::{bridge, price, purge, seed_queue};
use points::MergedPoints;
use rayon::prelude::*;

mod pairs;
mod points;

/// The loop reports progress and checks whether to stop every this many steps: a
/// few milliseconds of a part's loop, and well under a second of the global loop's
/// after parts of a 56M-face input (about 2 ms a merge there: large clusters).
const CHECK_EVERY: usize = 256;
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
    /// Merges whose points the look-ahead had reduced while a batch was priced
    /// (`MergedPoints::look_ahead`).
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
    /// cluster: the merge tree's nodes; after the first phase's (the components' or
    /// the spatial parts', `merge::stage::Keep::join`). 8 bytes a merge.
    pub merges: Vec<(u32, u32)>,
    /// How many of `merges` came before the loop's first snapshot.
    pub at_first: usize,
    /// No spatial parts ran first: the merge tree's leaves are the faces (after
    /// parts, the first snapshot's clusters, the large ones taken apart:
    /// `cut::tree::Split`).
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
    #[cfg(test)]
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
    cl: Clusters,
    targets: &[usize],
    go_on: Checkpoint,
    pricer: &mut Pricer,
    scope: Scope,
    log: &mut MergeLog,
) -> (MergeOutput, Clusters) {
    let mut lp = Loop::<Q>::new(fitter, cl, targets, go_on, scope, log);
    // Every adjacent pair priced into the queue (Alg. 1, line 3).
    if !lp.seed() {
        return lp.stopped();
    }
    loop {
        // Progress, and whether to stop, every few steps.
        if !lp.tick() {
            return lp.stopped();
        }
        let reached = lp.reached();
        // A target's snapshot waits for free merges into plates
        // (docs/decisions/0025-free-merges-into-plates.md); the
        // queue running dry there does not bridge components first.
        if reached && (lp.held.is_some() || lp.heap.is_empty()) {
            if !lp.snapshots(false) {
                return lp.stopped();
            }
            if lp.next == targets.len() {
                break;
            }
        }
        // The cheapest fresh merge: the one held at a target, else the queue's next
        // (stale entries re-priced or dropped, components bridged when it runs dry).
        let c = match lp.next_step() {
            Step::Merge(c) => c,
            Step::Again => continue,
            Step::Stop => break,
        };
        // At a target only free merges run before its snapshot.
        if reached && !(fitter.pricing.free_merges && free(&c)) {
            lp.held = Some(c);
            continue;
        }
        // A traced part records the merge with its place in the global order.
        lp.trace(&c);
        // Lazy deletion's stale entries dropped once the queue has grown a quarter.
        lp.purge_if_grown();
        // Alg. 1: the pair becomes one cluster.
        let root = lp.merge(&c);
        // Its pairs re-priced now, unless left to when they pop (`lazy.rs`).
        lp.reprice(root, pricer);
    }
    // The targets merging stopped above (adjacency ran out): what is left.
    match lp.snapshots(true) {
        true => (lp.out, lp.cl),
        false => lp.stopped(),
    }
}

/// The merge loop's state ([`merge_loop`]): the clusters, the queue, the buffers each
/// merge reuses, what it hands on, and how far down the targets it got.
struct Loop<'a, Q> {
    fitter: &'a Fitter<'a>,
    cl: Clusters,
    heap: Q,
    lazy: Lazy,
    /// Entries re-priced when popped are priced one at a time, here.
    ws: Workspace,
    points: MergedPoints,
    /// The re-pricing batch, pushed into the queue in neighbour order.
    batch: Vec<Candidate>,
    /// The latest entry acted on, in pop order (`Scope::Traced`).
    top: Top,
    /// The queue's length over which stale entries are purged.
    purge_at: usize,
    scope: Scope,
    out: MergeOutput,
    log: &'a mut MergeLog,
    targets: &'a [usize],
    /// The next target to reach (its index in `targets`).
    next: usize,
    /// The greedy order's next merge, popped at a target but not free: applied after
    /// that target's snapshot.
    held: Option<Candidate>,
    /// Steps of the loop (a merge, or an entry re-priced or dropped when popped).
    steps: usize,
    /// Live clusters at the start, and the last target (progress).
    start: usize,
    last: usize,
    go_on: Checkpoint<'a>,
}

impl<'a, Q: Queue> Loop<'a, Q> {
    fn new(
        fitter: &'a Fitter<'a>,
        cl: Clusters,
        targets: &'a [usize],
        go_on: Checkpoint<'a>,
        scope: Scope,
        log: &'a mut MergeLog,
    ) -> Self {
        Loop {
            points: MergedPoints::new(fitter.input.mesh.vertex_count()),
            start: cl.live,
            last: *targets.last().expect("at least one target"),
            fitter,
            cl,
            heap: Q::default(),
            lazy: Lazy::default(),
            ws: Workspace::default(),
            batch: Vec::new(),
            top: Top::default(),
            purge_at: 0,
            scope,
            out: MergeOutput::default(),
            log,
            targets,
            next: 0,
            held: None,
            steps: 0,
            go_on,
        }
    }

    /// Prices every adjacent pair into the queue; `false` when told to stop.
    fn seed(&mut self) -> bool {
        let Some(priced) = seed_queue(self.fitter, &self.cl, &mut self.heap, self.go_on) else {
            return false;
        };
        self.out.fits.seed += priced;
        self.purge_at = (self.heap.len() + self.heap.len() / 4).max(PURGE_MIN);
        true
    }

    /// Counts a step; every [`CHECK_EVERY`] steps, reports progress and asks whether
    /// to go on.
    fn tick(&mut self) -> bool {
        self.steps += 1;
        self.steps % CHECK_EVERY != 0 || (self.go_on)(fraction(self.start, self.cl.live, self.last))
    }

    /// The live clusters are down to the next target.
    fn reached(&self) -> bool {
        self.next < self.targets.len() && self.cl.live <= self.targets[self.next]
    }

    /// The output so far, of a loop told to stop.
    fn stopped(mut self) -> (MergeOutput, Clusters) {
        self.out.stopped = true;
        (self.out, self.cl)
    }

    /// Snapshots of the targets reached (`all`: of every target left); `false` when
    /// told to stop while fitting them.
    fn snapshots(&mut self, all: bool) -> bool {
        if self.next == 0 {
            self.log.at_first = self.log.merges.len();
        }
        let (go_on, done) = (self.go_on, fraction(self.start, self.cl.live, self.last));
        let go_on_here = || go_on(done);
        while self.next < self.targets.len() && (all || self.reached()) {
            let target = self.targets[self.next];
            let fitter = self.fitter;
            let Some(snap) = snapshot(fitter, &self.cl, target, self.scope, &go_on_here) else {
                return false;
            };
            if self.next == 0 {
                keep_leaf_hulls(fitter, &self.cl, self.scope, &mut self.log.hulls);
            }
            self.out.snapshots.push(snap);
            self.next += 1;
        }
        true
    }

    /// The merge held at a target, else pops the queue's next entry and classifies it
    /// (lazy deletion, `lazy.rs`); when the queue runs dry, bridges components (§3.4) —
    /// except in a part, which just stops.
    fn next_step(&mut self) -> Step {
        if let Some(c) = self.held.take() {
            return Step::Merge(c);
        }
        let (fitter, cl) = (self.fitter, &mut self.cl);
        let Some(c) = self.heap.pop() else {
            if !self.scope.whole() {
                return Step::Stop;
            }
            let bridged = bridge(fitter, cl);
            self.out.bridge_edges += bridged.len();
            self.out.fits.seed += bridged.len();
            let fresh = price(fitter, cl, &bridged);
            if fresh.is_empty() {
                return Step::Stop;
            }
            fresh.into_iter().for_each(|c| self.heap.push(c));
            return Step::Again;
        };
        match self.lazy.classify(cl, &c) {
            Pop::Fresh => Step::Merge(c),
            Pop::Drop => Step::Again,
            Pop::Reprice(a, b) => {
                self.out.fits.lazy += 1;
                if let Some((fresh, _)) = fitter.candidate(cl, a, b, &mut self.ws) {
                    self.heap.push(fresh);
                }
                self.top.popped(&c);
                Step::Again
            }
        }
    }

    /// Records merge `c` with its key in the global order, in a traced part ([`Traced`]).
    fn trace(&mut self, c: &Candidate) {
        if self.scope != Scope::Traced {
            return;
        }
        self.top.popped(c);
        let k = self.top.0.unwrap_or(*c);
        self.out.trace.push(Traced {
            cost: k.cost,
            key_a: k.a,
            key_b: k.b,
            a: c.a,
            b: c.b,
            free: free(c),
        });
    }

    /// Drops the queue's stale entries once it has grown by a quarter ([`purge`]).
    fn purge_if_grown(&mut self) {
        if self.heap.len() > self.purge_at {
            purge(self.fitter, &self.cl, &mut self.lazy, &mut self.heap);
            self.purge_at = (self.heap.len() + self.heap.len() / 4).max(PURGE_MIN);
        }
    }

    /// Merges fresh entry `c`'s clusters on their merged points (reduced ahead of
    /// its turn if the look-ahead held it), logging the merge in the whole input's loop;
    /// returns the merged cluster.
    fn merge(&mut self, c: &Candidate) -> u32 {
        let (verts, ahead) = self.points.of(self.fitter, &self.cl, c);
        self.out.ahead += ahead as usize;
        let root = self.cl.merge(c.a, c.b, verts, c.volume);
        self.out.merges += 1;
        if self.scope.whole() {
            let log = &mut *self.log;
            log.merges.push((self.cl.head(c.a), self.cl.head(c.b)));
            let at = log.merges.len() - 1;
            keep_hull(self.fitter, &self.cl, root, self.scope, at, &mut log.hulls);
        }
        root
    }

    /// Re-prices `root`'s pairs with `pricer` unless they are deferred ([`defer`]);
    /// meanwhile, reduces the points of the likely next merge (the serial part of the
    /// next step).
    fn reprice(&mut self, root: u32, pricer: &mut Pricer) {
        if defer(self.fitter, &mut self.cl, root) {
            return;
        }
        let nbrs = self.cl.resolved_neighbors(root);
        let (fitter, cl, heap) = (self.fitter, &self.cl, &mut self.heap);
        let (points, batch) = (&mut self.points, &mut self.batch);
        let meanwhile = || points.look_ahead(fitter, cl, heap);
        pricer.price(cl, root, &nbrs, meanwhile, |c| batch.push(c));
        self.out.fits.eager += nbrs.len();
        self.cl.mark_repriced(root);
        self.batch.drain(..).for_each(|c| self.heap.push(c));
    }
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

/// What the merge loop does next ([`Loop::next_step`]).
enum Step {
    /// Apply this fresh merge.
    Merge(Candidate),
    /// A stale entry was re-priced or dropped, or components were bridged: pop again.
    Again,
    /// Nothing left to merge (a part's adjacency, or the whole input's after bridging).
    Stop,
}

/// The loop's progress: merges done of those from `start` clusters down to `last`.
fn fraction(start: usize, live: usize, last: usize) -> f64 {
    (start - live) as f64 / (start - last.min(start)).max(1) as f64
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
