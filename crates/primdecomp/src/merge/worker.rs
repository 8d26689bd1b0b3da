//! Re-pricing a merged cluster's neighbours on two cores. After each merge of
//! Alg. 1 the new cluster's merges with its 4–16 neighbours are re-priced: a few
//! microseconds of fits per neighbour, too little to pay for a rayon task
//! (docs/decisions/perf-repricing-worker-and-look-ahead.md). Here one persistent worker thread
//! lives as long as the merge loop
//! and shares each batch with the main thread through atomics:
//!
//! - the main thread copies what pricing needs of the root and of each neighbour (a
//!   [`Side`] snapshot: ids, vertex ids, operator, volume, clock) into the batch's
//!   job (two jobs, alternating by epoch, each behind a mutex), then publishes the
//!   batch by resetting the claim counter to `epoch << 32`;
//! - both threads claim neighbours one at a time from that counter, so a worker that
//!   wakes late only takes what is left;
//! - the main thread prices from the clusters, the worker from the snapshot (the same
//!   arithmetic, `Fitter::candidate_of`); the worker's results go back through the
//!   job with their neighbour index, and the main thread pushes every candidate in
//!   neighbour order: the queue sees exactly the serial sequence, on any thread count;
//! - if the worker has not finished its share a few fits' time after the main thread
//!   ran out of neighbours (it was descheduled: a busy machine), the main thread prices
//!   that share again itself and moves on; the worker's late results are ignored, and
//!   the job it still holds is skipped (the batch is priced serially) until it lets go.
//!
//! The worker spins briefly for the next batch, then parks, so an idle phase (bridging,
//! snapshots) does not keep a core busy. No `unsafe`: the worker never sees the
//! clusters, only the copy.

use super::cluster::Clusters;
use super::cost::{Fitter, Side, Workspace};
use super::heap::Candidate;
use crate::input::dedup::Corners;
use crate::math::Sym3;
use crate::progress::wallclock::Instant;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering::*};
use std::sync::Mutex;
use std::thread::{self, Thread};
use std::time::Duration;

/// How long the idle worker spins for the next batch before it yields its core, and
/// until when it keeps yielding before it parks: merges come every few microseconds,
/// and spinning longer takes time slices the main thread needs on a busy machine
/// (docs/decisions/perf-repricing-worker-and-look-ahead.md).
const SPIN_FOR: Duration = Duration::from_micros(5);
const YIELD_UNTIL: Duration = Duration::from_micros(50);
/// The least the main thread waits for the worker's share before pricing it itself.
const MIN_WAIT: Duration = Duration::from_micros(10);

/// One neighbour in the job: its snapshot, its vertex ids at `verts[start..end]`.
#[derive(Clone, Copy, Debug)]
struct Slot {
    id: u32,
    start: u32,
    end: u32,
    q: Sym3,
    volume: f64,
    t: u32,
}

/// A published batch: the root's and the neighbours' snapshots; the worker's results.
#[derive(Default)]
struct Job {
    epoch: u32,
    /// Slot 0 is the root, then the neighbours in order.
    slots: Vec<Slot>,
    verts: Vec<u32>,
    /// (neighbour index, candidate) for every neighbour the worker priced.
    results: Vec<(u32, Option<Candidate>)>,
}

impl Job {
    fn side(&self, i: usize) -> Side<'_> {
        let s = &self.slots[i];
        Side {
            id: s.id,
            verts: Corners::plain(&self.verts[s.start as usize..s.end as usize]),
            q: s.q,
            volume: s.volume,
            t: s.t,
        }
    }

    fn push(&mut self, s: Side) {
        let start = self.verts.len() as u32;
        self.verts.extend(s.verts.iter());
        self.slots.push(Slot {
            id: s.id,
            start,
            end: self.verts.len() as u32,
            q: s.q,
            volume: s.volume,
            t: s.t,
        });
    }
}

/// An atomic on a cache line of its own (the two threads hammer different ones).
#[repr(align(64))]
#[derive(Default)]
struct Line<T>(T);

/// State shared by the main thread and the worker.
#[derive(Default)]
struct Shared {
    /// `epoch << 32 | next unclaimed neighbour`.
    claim: Line<AtomicU64>,
    /// `epoch << 32 | neighbours the worker finished` in that epoch.
    done: Line<AtomicU64>,
    sleeping: AtomicBool,
    quit: AtomicBool,
    /// Set if the worker unwinds (a bug): the main thread must not wait for it.
    dead: AtomicBool,
    /// Batch `e` lives in `jobs[e & 1]`, so a worker still busy with (or descheduled
    /// in) one batch never holds up the publication of the next.
    jobs: [Mutex<Job>; 2],
}

fn split(v: u64) -> (u32, usize) {
    ((v >> 32) as u32, (v & u32::MAX as u64) as usize)
}

/// What the pricer shared with its worker thread, for tests and measurements.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PricerCounts {
    /// Batches shared with the worker.
    pub shared: u64,
    /// Neighbours the worker priced (and the main thread used).
    pub by_worker: u64,
    /// Batches whose worker share the main thread priced again because the worker was
    /// late (descheduled on a busy machine).
    pub taken_back: u64,
}

/// Re-prices batches of merges, on two threads when it has a worker.
pub struct Pricer<'p> {
    fitter: &'p Fitter<'p>,
    ws: Workspace,
    link: Option<(&'p Shared, Thread)>,
    epoch: u32,
    found: Vec<Option<Candidate>>,
    /// Which neighbours of the batch this thread priced.
    mine: Vec<bool>,
    pub stats: PricerCounts,
}

/// Runs `f` with a [`Pricer`] that has a worker thread when rayon's pool has two or
/// more threads (none under `--threads 1`); the worker stops when `f` returns or
/// unwinds.
pub fn with_pricer<R>(fitter: &Fitter, f: impl FnOnce(&mut Pricer<'_>) -> R) -> R {
    if rayon::current_num_threads() < 2 {
        return f(&mut Pricer::new(fitter, None));
    }
    let shared = Shared::default();
    thread::scope(|s| {
        // No thread to be had: everything is priced here (same results).
        let link = thread::Builder::new()
            .name("primdecomp-reprice".into())
            .spawn_scoped(s, || work(fitter, &shared))
            .ok()
            .map(|h| (&shared, h.thread().clone()));
        // The pricer drops when `f` returns or unwinds, which stops the worker before
        // the scope joins it.
        f(&mut Pricer::new(fitter, link))
    })
}

impl Drop for Pricer<'_> {
    fn drop(&mut self) {
        if let Some((sh, t)) = &self.link {
            sh.quit.store(true, SeqCst);
            t.unpark();
        }
    }
}

impl<'p> Pricer<'p> {
    /// A pricer without a worker (phase 1 of `Params::partitions`: one per part, the
    /// parts themselves run in parallel).
    pub(super) fn serial(fitter: &'p Fitter<'p>) -> Self {
        Pricer::new(fitter, None)
    }

    fn new(fitter: &'p Fitter<'p>, link: Option<(&'p Shared, Thread)>) -> Self {
        Pricer {
            fitter,
            ws: Workspace::default(),
            link,
            epoch: 0,
            found: Vec::new(),
            mine: Vec::new(),
            stats: PricerCounts::default(),
        }
    }

    /// Prices the merges of `root` with each of `nbrs` and hands the candidates to
    /// `push` in neighbour order (merges over the excess cap are skipped), exactly as
    /// a serial loop over `nbrs` would. `meanwhile` runs on this thread while the
    /// worker starts on the batch, and only then: with no worker to overlap, work done
    /// ahead is only overhead (the caller's results must not depend on it).
    pub fn price(
        &mut self,
        cl: &Clusters,
        root: u32,
        nbrs: &[u32],
        meanwhile: impl FnOnce(),
        mut push: impl FnMut(Candidate),
    ) {
        let shared = match self.link {
            // Every batch of two or more is shared: a threshold on the batch's points
            // made the merge stage slower (docs/decisions/perf-repricing-worker-and-look-ahead.md).
            Some((sh, _)) if nbrs.len() >= 2 => self.publish(sh, cl, root, nbrs).then_some(sh),
            _ => None,
        };
        let fitter = self.fitter;
        let Some(sh) = shared else {
            for &n in nbrs {
                if let Some((c, _)) = fitter.candidate(cl, root, n, &mut self.ws) {
                    push(c);
                }
            }
            return;
        };
        meanwhile();
        self.found.clear();
        self.found.resize(nbrs.len(), None);
        self.mine.clear();
        self.mine.resize(nbrs.len(), false);
        let start = Instant::now();
        let mut mine = 0;
        loop {
            let (_, i) = split(sh.claim.0.fetch_add(1, AcqRel));
            if i >= nbrs.len() {
                break;
            }
            self.found[i] = fitter
                .candidate(cl, root, nbrs[i], &mut self.ws)
                .map(|c| c.0);
            self.mine[i] = true;
            mine += 1;
        }
        if mine < nbrs.len() {
            let per_fit = start.elapsed() / mine.max(1) as u32;
            if !self.collect(sh, nbrs.len() - mine, per_fit) {
                self.take_back(cl, root, nbrs);
            }
        }
        self.found.iter().flatten().for_each(|&c| push(c));
    }

    /// Copies the batch into the next epoch's job and opens it for claiming; false
    /// (nothing published) when the worker still holds that job or has died.
    fn publish(&mut self, sh: &Shared, cl: &Clusters, root: u32, nbrs: &[u32]) -> bool {
        let epoch = self.epoch.wrapping_add(1);
        if sh.dead.load(Relaxed) {
            return false;
        }
        let Ok(mut job) = sh.jobs[(epoch & 1) as usize].try_lock() else {
            return false;
        };
        job.epoch = epoch;
        job.slots.clear();
        job.verts.clear();
        job.results.clear();
        job.push(self.fitter.side(cl, root));
        for &n in nbrs {
            job.push(self.fitter.side(cl, n));
        }
        drop(job);
        self.epoch = epoch;
        self.stats.shared += 1;
        // SeqCst pairs with the worker's `sleeping` store then `claim` load: either it
        // sees this batch before parking or we see it asleep and wake it.
        sh.claim.0.store((epoch as u64) << 32, SeqCst);
        if sh.sleeping.load(SeqCst) {
            if let Some((_, t)) = &self.link {
                t.unpark();
            }
        }
        true
    }

    /// Waits (briefly: a few of this batch's fits) for the worker's `theirs`
    /// neighbours and files them by index; false if the worker is late.
    fn collect(&mut self, sh: &Shared, theirs: usize, per_fit: Duration) -> bool {
        let want = (self.epoch as u64) << 32 | theirs as u64;
        let deadline = Instant::now() + (per_fit * 8).max(MIN_WAIT);
        let mut spins = 0u32;
        loop {
            if sh.done.0.load(Acquire) == want {
                if let Ok(job) = sh.jobs[(self.epoch & 1) as usize].try_lock() {
                    for &(i, c) in &job.results {
                        self.found[i as usize] = c;
                    }
                    self.stats.by_worker += theirs as u64;
                    return true;
                }
            }
            spins += 1;
            if spins % 64 == 0 && (Instant::now() > deadline || sh.dead.load(Relaxed)) {
                return false;
            }
            std::hint::spin_loop();
        }
    }

    /// Prices the worker's share here (the same results): it was descheduled mid-fit
    /// and waiting for it would cost a scheduler time slice.
    fn take_back(&mut self, cl: &Clusters, root: u32, nbrs: &[u32]) {
        for (i, &n) in nbrs.iter().enumerate() {
            if !self.mine[i] {
                self.found[i] = self
                    .fitter
                    .candidate(cl, root, n, &mut self.ws)
                    .map(|c| c.0);
            }
        }
        self.stats.taken_back += 1;
    }
}

/// Marks the worker dead if it unwinds, so the main thread stops sharing with it.
struct DeadOnUnwind<'a>(&'a Shared);

impl Drop for DeadOnUnwind<'_> {
    fn drop(&mut self) {
        if thread::panicking() {
            self.0.dead.store(true, SeqCst);
        }
    }
}

/// The worker: waits for a batch, prices the neighbours it claims from the snapshot.
fn work(fitter: &Fitter, sh: &Shared) {
    let _guard = DeadOnUnwind(sh);
    let mut ws = Workspace::default();
    let mut seen = 0u32;
    while wait(sh, seen) {
        let epoch = split(sh.claim.0.load(Acquire)).0;
        let mut job = sh.jobs[(epoch & 1) as usize]
            .lock()
            .unwrap_or_else(|e| e.into_inner());
        // Otherwise the job was refilled for a later batch: go round again.
        if job.epoch == epoch {
            seen = epoch;
            price_claimed(fitter, sh, &mut job, &mut ws);
        }
    }
}

/// Claims neighbours of `job` one at a time while its batch is open, prices each from
/// the snapshot and reports progress through `done`.
fn price_claimed(fitter: &Fitter, sh: &Shared, job: &mut Job, ws: &mut Workspace) {
    let mut finished = 0u64;
    loop {
        let cur = sh.claim.0.load(Acquire);
        let (epoch, i) = split(cur);
        // A compare-exchange, not `fetch_add`: a claim must never take an index of a
        // batch other than this job's (the main thread would wait for it in vain).
        if epoch != job.epoch || i + 1 >= job.slots.len() {
            return;
        }
        if sh
            .claim
            .0
            .compare_exchange_weak(cur, cur + 1, AcqRel, Acquire)
            .is_err()
        {
            continue;
        }
        let c = fitter.candidate_of(job.side(0), job.side(i + 1), ws);
        job.results.push((i as u32, c.map(|c| c.0)));
        finished += 1;
        sh.done.0.store((epoch as u64) << 32 | finished, Release);
    }
}

/// Spins, then yields, then parks, until a batch other than `seen` is published
/// (true) or the pricer is dropped (false). Yielding lets a main thread that shares
/// this core (a busy machine) run instead of us spinning through its time slice.
fn wait(sh: &Shared, seen: u32) -> bool {
    let mut since = Instant::now();
    loop {
        for _ in 0..64 {
            if sh.quit.load(Acquire) {
                return false;
            }
            if split(sh.claim.0.load(Acquire)).0 != seen {
                return true;
            }
            std::hint::spin_loop();
        }
        let idle = since.elapsed();
        if idle < SPIN_FOR {
            continue;
        }
        if idle < YIELD_UNTIL {
            thread::yield_now();
            continue;
        }
        sh.sleeping.store(true, SeqCst);
        if split(sh.claim.0.load(SeqCst)).0 == seen && !sh.quit.load(SeqCst) {
            thread::park();
        }
        sh.sleeping.store(false, SeqCst);
        since = Instant::now();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::merge::driver::tests::{in_pool, with_demo};

    /// A few batches of the demo scene after some merges: (root, its neighbours).
    fn batches(cl: &mut Clusters) -> Vec<(u32, Vec<u32>)> {
        for f in (0..cl.len() as u32).step_by(7) {
            let (a, b) = (cl.find(f), cl.find((f + 1) % cl.len() as u32));
            if a != b {
                cl.merge(a, b, Vec::new(), 1.0);
            }
        }
        let roots = cl.roots();
        roots
            .iter()
            .map(|&r| (r, cl.resolved_neighbors(r)))
            .collect()
    }

    /// The pricer hands over the same candidates, in the same order, as the serial loop.
    #[test]
    fn shared_batches_price_like_the_serial_loop() {
        with_demo(|fitter, fresh| {
            let mut cl = fresh();
            let batches = batches(&mut cl);
            let mut ws = Workspace::default();
            let serial: Vec<Candidate> = batches
                .iter()
                .flat_map(|(r, ns)| ns.iter().map(|&n| (*r, n)).collect::<Vec<_>>())
                .filter_map(|(r, n)| fitter.candidate(&cl, r, n, &mut ws).map(|c| c.0))
                .collect();
            let (shared, stats) = in_pool(2, || {
                with_pricer(fitter, |p| {
                    let mut out = Vec::new();
                    for (r, ns) in &batches {
                        p.price(&cl, *r, ns, || {}, |c| out.push(c));
                    }
                    (out, p.stats)
                })
            });
            assert_eq!(serial, shared);
            assert!(stats.shared > 0, "{stats:?}");
        });
    }

    /// A panic in the merge loop stops the worker: the scope joins it, no hang.
    #[test]
    fn a_panic_in_the_loop_stops_the_worker() {
        with_demo(|fitter, fresh| {
            let mut cl = fresh();
            let batches = batches(&mut cl);
            let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                in_pool(2, || {
                    with_pricer(fitter, |p| {
                        let (r, ns) = &batches[0];
                        p.price(&cl, *r, ns, || {}, |_| {});
                        panic!("the loop fails");
                    })
                })
            }));
            assert!(r.is_err());
        });
    }

    /// A loop that ends before any batch, and a worker never woken, shut down too;
    /// one thread starts no worker at all.
    #[test]
    fn early_exit_and_one_thread() {
        with_demo(|fitter, _| {
            assert!(in_pool(2, || with_pricer(fitter, |p| p.link.is_some())));
            assert!(in_pool(1, || with_pricer(fitter, |p| p.link.is_none())));
        });
    }
}
