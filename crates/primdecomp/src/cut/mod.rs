//! Cutting the merge tree where the error is (a deviation from §3.3, which
//! outputs the clusters alive when N remain: docs/decisions/0032 and 0034). The pass's
//! merges form a forest whose leaves are the faces ([`tree`]); each node's primitive
//! gets an error, the one-way distance from its surface to the input's (as
//! `primdecomp eval` defines Hausdorff, bounded from above, [`error`]). From the
//! roots the worst node is split until the largest count is reached or every node is
//! within the tolerance; each level then takes, of the cuts of the nodes reached, the
//! fewest nodes within its tolerance, or the least worst error its count and bytes
//! allow, filled up to its count; with counts alone, the count that least worst
//! error leaves goes to the mean distance ([`past_worst`]). A node over a tolerance that
//! splitting cannot bring nearer gets its nearest fit instead of its least k·V
//! ([`nearest`]). Every node's primitive encloses its faces, so every cut encloses
//! the mesh.

mod carried_parts;
mod cell_shadow;
mod chamfer;
mod choose;
mod corners;
pub(crate) mod error;
mod error_memo;
mod hulls;
pub(crate) mod limits;
mod nearest;
mod next_splits;
mod past_worst;
mod pieces;
pub(crate) mod recut;
mod short_count;
pub(crate) mod tree;

use crate::input::triangles::Triangles;
use crate::math::{Sym3, V3};
use crate::merge::{Fitter, Snapshot, Workspace};
use crate::output::result::Shortfall;
use crate::primitive::Primitive;
pub(crate) use chamfer::mean_distance;
pub(crate) use choose::fits;
use choose::worst;
#[cfg(test)]
use error::error_of;
use error::{error_until_checked, StopAt};
use hulls::{HullScratch, NodeHulls};
pub(crate) use past_worst::LOOSE_FACTOR;
use past_worst::{Order, Queued};
use rayon::prelude::*;
use std::cmp::Ordering;
use std::collections::{BinaryHeap, HashMap};
use std::sync::atomic::AtomicBool;
pub(crate) use tree::MergeTree;

/// With spatial parts merged first, the tree's leaves are the clusters of the
/// snapshot at this many times the largest target (deep enough that a cut of N rarely
/// reaches them), but for the large ones, taken apart down to their faces
/// (`tree::Split`). Otherwise the leaves are the faces.
pub(crate) const LEAVES_PER_TARGET: usize = 4;

/// Nodes whose error is at most this many minimum half-extents are not split: a
/// flush plate already stands two of them off its faces, and the estimate's own
/// tessellation error is of that order.
const FLOOR_HALVES: f64 = 4.0;

/// [`Cutter::ahead`] lowers its threshold by this factor a step: the finer, the fewer
/// fits wasted where the count runs out, the more rounds (docs/decisions/0043).
const AHEAD_STEP: f64 = 0.85;

/// [`Cutter::explore`] splits at most this many times the largest count: splits
/// whose parts are carried add no node ([`carried_parts`]).
const SPLITS_PER_COUNT: usize = 8;

/// The tests compare the cuts with [`Cutter::ahead`] and `Cutter::fit_next` fitting
/// nothing ([`off`]).
static AHEAD_OFF: AtomicBool = AtomicBool::new(false);

/// The tests compare the cuts with [`Cutter::group_fits`] keeping nothing ([`off`]),
/// and count the fits it gave back.
static GROUP_FITS_OFF: AtomicBool = AtomicBool::new(false);
#[cfg(test)]
static GROUP_FITS_REUSED: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);

/// Whether a test turned `switch` off: never outside the tests, where this is a
/// constant `false`.
fn off(switch: &AtomicBool) -> bool {
    cfg!(test) && switch.load(std::sync::atomic::Ordering::Relaxed)
}

/// Nodes' fits by node id.
type Fits = HashMap<u32, Entry>;
/// Each request's cut: its nodes.
type Cuts = Vec<Vec<u32>>;

/// What one level asks of the cut: at most `count` nodes and `bytes` bytes (the
/// paper's Table 2), and with a `tolerance` (the mesh's units) the fewest nodes whose
/// every primitive is within it; without one, the least worst error the caps allow.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Request {
    pub count: usize,
    pub bytes: Option<usize>,
    pub tolerance: Option<f64>,
}

/// One level's cut of the merge tree: its nodes' clusters and primitives as the merge
/// loop's snapshots hold them, with what only a cut knows.
#[derive(Clone, Debug)]
pub(crate) struct LevelCut {
    /// The cut's nodes as clusters with their primitives (the mesh's frame).
    pub snapshot: Snapshot,
    /// The farthest its primitives may stand from the input (its tolerance, or the
    /// farthest its nodes stand), which post-processing must keep
    /// (`postprocess::plates`).
    pub bound: f64,
    /// For a cut over its tolerance: what stopped it nearer; `None` otherwise.
    pub shortfall: Option<Shortfall>,
    /// Each primitive as the cut made it (the mesh's frame) with the upper bound of its
    /// error the cut proved, where it proved one; post-processing leaves it as it is,
    /// so `limits::record_limits` measures again only what it changed.
    pub known: Vec<(Primitive, f64)>,
}

impl LevelCut {
    /// The snapshot to post-process, its faces' lists (members and vertices, about
    /// 6 bytes a face) moved out rather than copied: a cut once post-processed is
    /// read only for its primitives, counts and bounds, so the lists of the kept
    /// cut, the new one and their post-processed copies are not alive together.
    pub(crate) fn take_for_postprocess(&mut self) -> Snapshot {
        let s = &mut self.snapshot;
        Snapshot {
            target: s.target,
            prims: s.prims.clone(),
            faces: s.faces.clone(),
            verts: std::mem::take(&mut s.verts),
            members: std::mem::take(&mut s.members),
            q: s.q.clone(),
        }
    }
}

/// A node of the cut with its fitted primitive and estimated error (`exact`: else
/// only a lower bound, over the exploration's early-exit level; `closest`: the
/// primitive is the candidate of least error, [`Cutter::closest`]).
#[derive(Clone, Debug)]
struct Entry {
    error: f64,
    node: u32,
    prim: Primitive,
    exact: bool,
    closest: bool,
}

impl Entry {
    fn bytes(&self) -> usize {
        self.prim.bytes()
    }
}

impl PartialEq for Entry {
    fn eq(&self, o: &Self) -> bool {
        self.cmp(o) == Ordering::Equal
    }
}
impl Eq for Entry {}
impl PartialOrd for Entry {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Entry {
    /// Worst error first; ties to the lower node id (deterministic).
    fn cmp(&self, o: &Self) -> Ordering {
        self.error.total_cmp(&o.error).then(o.node.cmp(&self.node))
    }
}

/// The part of the tree the splits reached: its roots, every node fitted (roots and
/// the children of split nodes), the nodes a cut can take in post-order
/// ([`Explored::post_order`]), the nodes split, in order, with their parts, the
/// nodes each node carries, the groups' members and bounding boxes, the hull points
/// of nodes tested for carrying ([`carried_parts`]) and whether the count ran out while a node was
/// still over the tolerance.
#[derive(Default)]
struct Explored {
    roots: Vec<u32>,
    fitted: HashMap<u32, Entry>,
    ids: Vec<u32>,
    splits: Vec<u32>,
    parts: HashMap<u32, Vec<u32>>,
    carried: HashMap<u32, Vec<u32>>,
    groups: HashMap<u32, Vec<u32>>,
    bounds: HashMap<u32, (V3, V3)>,
    points: HashMap<u32, Vec<V3>>,
    capped: bool,
}

/// What a cut is made from: the fit settings, the tree, its nodes' hulls and the
/// input's surface.
pub(crate) struct Cutter<'a> {
    fitter: &'a Fitter<'a>,
    tree: &'a MergeTree,
    hulls: NodeHulls<'a>,
    /// What [`Cutter::snapshots`] was last asked.
    requests: Vec<Request>,
    /// Every node fitted by the calls before, kept for the next.
    fitted: HashMap<u32, Entry>,
    surface: &'a Triangles<'a>,
    /// Errors at most this are not split by any request: measured only as far as it
    /// takes to know that (the smallest tolerance when every request has one, else
    /// the floor).
    enough: f64,
    /// Whether a count the cut falls short of goes to the cut's other nodes
    /// ([`Cutter::spend`], [`Cutter::snapshots_filled`]).
    fill_short: bool,
    /// Whether a cut of counts alone is explored again in a loose order
    /// ([`Cutter::snapshot_loose`]).
    loose: bool,
    /// Each node's bounding box ([`carried_parts`]).
    boxes: Vec<(V3, V3)>,
    /// The errors measured so far ([`error_memo`]).
    measures: error_memo::Measures,
    /// Each group's fit on all its points so far, by the nodes it covers
    /// ([`Cutter::covered`]), which decide it: explorations number groups anew, and a
    /// run's several explorations halve the same groups again.
    group_fits: std::sync::Mutex<HashMap<Vec<u32>, Primitive>>,
    /// Asked whether to go on before each split and each round of fits ahead.
    go_on: crate::progress::Checkpoint<'a>,
    /// `go_on` said stop: what the cutter returns since is not a cut to keep.
    stopped: AtomicBool,
}

/// One thread's buffers for fitting nodes.
#[derive(Default)]
struct Scratch {
    ws: Workspace,
    hull: HullScratch,
    candidates: Vec<Primitive>,
}

impl<'a> Cutter<'a> {
    /// The cutter of `tree` for `requests` (their counts and bytes may be raised
    /// later, [`Cutter::snapshots`]; their tolerances stay).
    pub(crate) fn new(
        fitter: &'a Fitter<'a>,
        tree: &'a MergeTree,
        surface: &'a Triangles,
        requests: &[Request],
        go_on: crate::progress::Checkpoint<'a>,
    ) -> Self {
        let largest = largest(requests);
        // Nodes of fewer faces than a cut of `largest` nodes holds on average have no
        // hull kept: exploring fits few of them (a tolerance's cut is mostly smaller
        // than its cap), and those are gathered from their faces when fitted.
        let stored = tree.order.len() / largest.max(1);
        let (hulls, whole) = NodeHulls::build_checked(
            tree,
            fitter.input.mesh,
            fitter.input.face_adj,
            fitter.pricing.hull_eps,
            stored,
            go_on,
        );
        Cutter {
            fitter,
            tree,
            hulls,
            requests: requests.to_vec(),
            fitted: HashMap::new(),
            surface,
            enough: requests
                .iter()
                .map(|r| r.tolerance)
                .try_fold(f64::INFINITY, |m, t| t.map(|t| m.min(t)))
                .unwrap_or(0.0)
                .max(FLOOR_HALVES * fitter.pricing.fit.min_half),
            fill_short: false,
            loose: false,
            boxes: carried_parts::node_boxes(tree, fitter.input.mesh),
            measures: error_memo::Measures::default(),
            group_fits: Default::default(),
            go_on,
            stopped: AtomicBool::new(!whole),
        }
    }

    /// Whether `go_on` has said stop (the snapshots since are not cuts to keep).
    pub(crate) fn stopped(&self) -> bool {
        self.stopped.load(std::sync::atomic::Ordering::Relaxed)
    }

    /// Asks `go_on` (once it said stop, no more): whether to go on.
    fn goes_on(&self) -> bool {
        if !self.stopped() && !(self.go_on)(0.0) {
            self.stopped
                .store(true, std::sync::atomic::Ordering::Relaxed);
        }
        !self.stopped()
    }

    /// Node `n`'s output fit on its hull's vertices and boundary faces, and its error
    /// up to `above` ([`error_until`]): what exploring needs, without gathering every
    /// face below the node again at every level. A node in `known` keeps its fit.
    fn entry(&self, n: u32, s: &mut Scratch, above: f64, known: &HashMap<u32, Entry>) -> Entry {
        if let Some(e) = known.get(&n) {
            return self.remeasured(e, above);
        }
        let prim = self.fit(n, s);
        self.measured(n, prim, above)
    }

    /// Node `n`'s output fit on its hull's vertices and boundary faces (a stand-in
    /// once told to stop: [`STAND_IN`]).
    fn fit(&self, n: u32, s: &mut Scratch) -> Primitive {
        if !self.goes_on() {
            return STAND_IN;
        }
        let sets = self.hulls.of(n, &mut s.hull);
        let faces = self.tree.faces(n).iter().copied();
        let q = &self.tree.q(n, self.fitter.input.mesh);
        let outside = |g| self.hulls.outside(n, g);
        (self.fitter)
            .fit_on_vertices(faces, sets.hull, sets.boundary, outside, q, &mut s.ws)
            .prim
    }

    /// `e`'s primitive if it encloses every point of its node's faces (a nearest fit,
    /// [`Cutter::closest`], was made on every point of them already) and of the nodes
    /// it carries ([`carried_parts`]: a nearest fit kept from an earlier cut may not have
    /// had them), else the output fit on all of them. Enclosing is up to the point
    /// reduction's own tolerance (`Fitter::hull_eps`): a fit on every point is no
    /// nearer than that either (its extreme points stand outside it by round-off),
    /// and would be the same.
    fn enclosing(&self, ex: &Explored, e: &Entry, ws: &mut Workspace) -> Primitive {
        let mesh = self.fitter.input.mesh;
        let inside = |&f: &u32| {
            mesh.face(f as usize)
                .iter()
                .all(|&v| e.prim.contains(mesh.pos(v), self.fitter.pricing.hull_eps))
        };
        let nodes = self.covered(ex, e.node);
        let own = self.members(ex, e.node).len();
        let (own, carried) = nodes.split_at(own);
        // Asking every `FACES_PER_CHECK` faces (a node may hold millions); false
        // once told to stop, which returns the fit (no stopped cut is kept).
        let within = |nodes: &[u32]| {
            let mut faces = nodes.iter().flat_map(|&c| self.tree.faces(c)).enumerate();
            faces.all(|(i, f)| (i % FACES_PER_CHECK != 0 || self.goes_on()) && inside(f))
        };
        if !self.goes_on() || (e.closest || within(own)) && within(carried) || self.stopped() {
            return e.prim;
        }
        self.fit_over(&nodes, ws).map_or(STAND_IN, |f| f.prim)
    }

    /// `e` with its error measured up to `above`, unless it is already exact.
    fn remeasured(&self, e: &Entry, above: f64) -> Entry {
        match e.exact {
            true => e.clone(),
            false => self.measured(e.node, e.prim, above),
        }
    }

    fn measured(&self, node: u32, prim: Primitive, above: f64) -> Entry {
        if !self.goes_on() {
            // Told to stop: nothing measured is kept.
            let error = 0.0;
            let (exact, closest) = (true, false);
            return Entry {
                error,
                node,
                prim,
                exact,
                closest,
            };
        }
        let ask = StopAt {
            level: self.enough,
            above,
            coarse: true,
        };
        let measure = || error_until_checked(&prim, self.surface, ask, &|| self.goes_on());
        let error = (self.measures).of(&prim, above, measure);
        Entry {
            error,
            node,
            prim,
            exact: error <= above,
            closest: false,
        }
    }

    /// One snapshot per request, in order, from one sequence of splits: the worst node
    /// each time, until the largest count is reached, every node is within the
    /// smallest tolerance (when every request has one) or nothing is left worth
    /// splitting. Each request then takes the best cut of the nodes reached
    /// ([`Cutter::choose`]). `requests` are [`Cutter::new`]'s with the same
    /// tolerances, their counts and bytes maybe raised; the nodes fitted for earlier
    /// requests keep their fits.
    pub(crate) fn snapshots(&mut self, requests: &[Request]) -> Vec<LevelCut> {
        self.requests = requests.to_vec();
        let (explored, cuts, spare) = self.explore_and_choose(largest(requests), self.enough);
        let snaps = self.cut_snapshots(&explored, cuts);
        // Groups are numbered anew by each exploration.
        let tree = self.tree.nodes.len() as u32;
        let fits = spare.into_iter().chain(explored.fitted);
        self.fitted.extend(fits.filter(|(n, _)| *n < tree));
        snaps
    }

    /// [`Cutter::snapshots`] of one request, with the count the least worst error
    /// leaves spent on the mean where it is a count alone ([`past_worst`]).
    pub(crate) fn snapshot_loose(&mut self, request: &Request) -> LevelCut {
        self.loose = true;
        let snap = self.snapshots(std::slice::from_ref(request)).pop();
        self.loose = false;
        snap.expect("one snapshot per request")
    }

    /// [`Cutter::snapshots`] with the rest of a count alone its cut falls short of
    /// spent on the cut's other nodes ([`Cutter::spend`]).
    pub(crate) fn snapshots_filled(&mut self, requests: &[Request]) -> Vec<LevelCut> {
        self.fill_short = true;
        let snaps = self.snapshots(requests);
        self.fill_short = false;
        snaps
    }

    /// Each request's snapshot from its cut of `explored`.
    fn cut_snapshots(&self, explored: &Explored, cuts: Vec<Vec<u32>>) -> Vec<LevelCut> {
        let requests = &self.requests;
        if self.stopped() {
            // Told to stop: every caller asks `stopped` before reading a snapshot, so
            // none gathers the faces and points of every node of the cut.
            let empty = |r: &Request| LevelCut {
                snapshot: Snapshot {
                    target: r.count,
                    ..Snapshot::default()
                },
                bound: 0.0,
                shortfall: None,
                known: Vec::new(),
            };
            return requests.iter().map(empty).collect();
        }
        // A chosen node's fit on its hull's vertices, unless one of its faces' points
        // (left out of the hull within its tolerance) is outside it beyond round-off:
        // then its fit on every point ([`Cutter::enclosing`]).
        let mut chosen: Vec<u32> = cuts.iter().flatten().copied().collect();
        chosen.sort_unstable();
        chosen.dedup();
        let output: HashMap<u32, Primitive> = chosen
            .par_iter()
            .map_init(Workspace::default, |ws, &n| {
                let e = &explored.fitted[&n];
                (n, self.enclosing(explored, e, ws))
            })
            .collect();
        requests
            .iter()
            .zip(cuts)
            .map(|(r, cut)| {
                let shortfall = self.shortfall(explored, r, &cut);
                // The bound proved for a node's fit holds for its output where that
                // is the same primitive.
                let known = cut
                    .iter()
                    .map(|n| (&explored.fitted[n], output[n]))
                    .filter(|(e, p)| e.exact && e.prim == *p)
                    .map(|(e, p)| (p, e.error))
                    .collect();
                let entries = cut
                    .iter()
                    .map(|n| Entry {
                        prim: output[n],
                        ..explored.fitted[n].clone()
                    })
                    .collect();
                LevelCut {
                    shortfall,
                    known,
                    ..self.snapshot(explored, r, entries)
                }
            })
            .collect()
    }

    /// The explored tree and each request's cut ([`Cutter::choose`]). When every
    /// request has a tolerance and none a byte target, a node's error is measured only
    /// until it is known to be over the loosest tolerance: such a node is split
    /// whatever its error, so where the splits end within the tolerances and each
    /// request's cut within its tolerance fits its count, the cuts are those exact
    /// errors give. Otherwise the tree is explored again with exact errors, keeping
    /// the fits.
    fn explore_and_choose(&self, largest: usize, enough: f64) -> (Explored, Cuts, Fits) {
        let above = self.requests.iter().try_fold(enough, |m, r| match r.bytes {
            None => r.tolerance.map(|t| m.max(t)),
            Some(_) => None,
        });
        let mut known = self.fitted.clone();
        if let Some(above) = above {
            let mut ex = self.explore(largest, enough, above, &known, Order::Worst);
            if !ex.capped {
                self.refine(&mut ex, above);
                let within: Option<Vec<Vec<u32>>> =
                    self.requests.iter().map(|r| self.within(&ex, r)).collect();
                if let Some(cuts) = within {
                    return (ex, cuts, Fits::new());
                }
            }
            known = ex.fitted;
        }
        let mut ex = self.explore(largest, enough, f64::INFINITY, &known, Order::Worst);
        let mut cuts: Vec<Vec<u32>> = self.requests.iter().map(|r| self.choose(&ex, r)).collect();
        // A count's cut spends what the worst error leaves on the mean ([`past_worst`]).
        let mut spare = Fits::new();
        let loosened = self
            .loose
            .then(|| self.loosened((&ex, &cuts), enough, known));
        if let Some((loose, again)) = loosened.flatten() {
            spare = std::mem::replace(&mut ex, loose).fitted;
            cuts = vec![again];
        }
        // Nodes kept over a tolerance because splitting them does not bring them
        // nearer get their nearest fit, and the cuts are chosen again.
        self.nearest_where_kept(&mut ex, &mut cuts);
        // A count the cut falls short of goes to its other nodes, where the cut then
        // chosen has more nodes and stands no farther.
        if self.fill_short && self.spend(&mut ex, &cuts) {
            let again: Vec<Vec<u32>> = self.requests.iter().map(|r| self.choose(&ex, r)).collect();
            for (cut, new) in cuts.iter_mut().zip(again) {
                if new.len() > cut.len() && worst(&ex, &new) <= worst(&ex, cut) {
                    *cut = new;
                }
            }
            self.nearest_where_kept(&mut ex, &mut cuts);
        }
        (ex, cuts, spare)
    }

    /// Exact errors where the cuts need them after an exploration whose errors over
    /// `above` are lower bounds: the nodes not split, and split nodes whose subtree
    /// reaches no cut within `above` (their error decides between them and their
    /// subtree's best). Elsewhere a split node's error only has to be over `above`.
    fn refine(&self, ex: &mut Explored, above: f64) {
        let mut reach: HashMap<u32, bool> = HashMap::with_capacity(ex.ids.len());
        let mut redo = Vec::new();
        for &n in &ex.ids {
            let e = &ex.fitted[&n];
            let kids = ex.parts.get(&n).is_some_and(|p| p.iter().all(|c| reach[c]));
            if !(e.exact || kids) {
                redo.push(n);
            }
            reach.insert(n, e.error <= above || kids);
        }
        let exact: Vec<Entry> = redo
            .par_iter()
            .map(|n| self.measured(*n, ex.fitted[n].prim, f64::INFINITY))
            .collect();
        for e in exact {
            ex.fitted.insert(e.node, e);
        }
    }

    /// Splits the node of the cut first in `order` (the worst, [`past_worst`]) from the
    /// roots on until `largest` nodes remain or every node is within `enough` or
    /// cannot be split; errors up to `above` ([`Cutter::entry`]), fits of the nodes
    /// in `known` kept.
    fn explore(
        &self,
        largest: usize,
        enough: f64,
        above: f64,
        known: &HashMap<u32, Entry>,
        order: Order,
    ) -> Explored {
        let (roots, mut ex) = self.explore_roots(above, known);
        // Fitting ahead follows the worst-first order; a loose order's nodes are
        // mostly known.
        let mut ready = match order {
            Order::Worst => self.ahead(&roots, largest, enough, above, known),
            Order::Loose(_) => HashMap::new(),
        };
        let mut count = roots.len();
        let tree = self.tree.nodes.len() as u32;
        let queued = |e: Entry| order.queued(e, tree);
        let mut heap: BinaryHeap<Queued> = roots.into_iter().map(queued).collect();
        let (mut sa, mut sb) = (Scratch::default(), Scratch::default());
        let mut leaves = Vec::new();
        // Splits whose parts are carried add no node; the chains they walk down are
        // long but not endless.
        let most = largest.saturating_mul(SPLITS_PER_COUNT);
        while count < largest && ex.splits.len() < most && self.goes_on() {
            let Some(Queued { e, .. }) = heap.pop() else {
                break;
            };
            if e.error <= enough {
                match order {
                    Order::Worst => break,
                    Order::Loose(_) => continue,
                }
            }
            // The children of this split and of the next ones, fitted together.
            let next = (&e, &mut heap);
            self.fit_next(next, (&ex, &mut ready), (enough, above, known));
            let split = (&mut sa, &mut sb);
            let Some(parts) = self.divide(&mut ex, &e, &ready, split, (above, known)) else {
                // A leaf cannot be split: its least-error fit (below) is what its part
                // can reach.
                if !e.closest {
                    leaves.push(e.node);
                }
                continue;
            };
            count += parts.len() - 1;
            heap.extend(parts.into_iter().map(queued));
        }
        let stopped = count >= largest || ex.splits.len() >= most;
        ex.capped = stopped && heap.iter().any(|q| q.e.error > enough);
        // Refitted together: a leaf's fit changes nothing the splits above looked at.
        self.refit_nearest(&mut ex, &leaves);
        ex.ids = ex.post_order();
        ex
    }

    /// The roots' entries (errors up to `above`, fits of the nodes in `known` kept),
    /// and the exploration they start: the cut of the roots alone.
    fn explore_roots(&self, above: f64, known: &HashMap<u32, Entry>) -> (Vec<Entry>, Explored) {
        let roots: Vec<Entry> = self
            .tree
            .roots
            .par_iter()
            .map_init(Scratch::default, |s, &r| self.entry(r, s, above, known))
            .collect();
        let ex = Explored {
            roots: self.tree.roots.clone(),
            fitted: roots.iter().map(|e| (e.node, e.clone())).collect(),
            ..Explored::default()
        };
        (roots, ex)
    }

    /// The children of nodes [`Cutter::explore`]'s worst-first splits will split,
    /// fitted a batch at a time with every thread. Over any threshold, the nodes whose
    /// ancestors are all over it are split by the worst-first order before any node
    /// under it, whatever the order among them; so while the count allows all of them,
    /// they are split here together, round after round until none is left over the
    /// threshold, which is then lowered a step towards `enough`. Where the count runs
    /// out first a round is not started: the splits then go on alone from what is
    /// ready, and only the rounds of the last step may have fitted nodes they never
    /// split (docs/decisions/0043).
    fn ahead(
        &self,
        roots: &[Entry],
        largest: usize,
        enough: f64,
        above: f64,
        known: &HashMap<u32, Entry>,
    ) -> HashMap<u32, Entry> {
        let splits = |e: &Entry| e.error > enough && !self.tree.nodes[e.node as usize].is_leaf();
        let mut frontier: Vec<(f64, u32)> = roots
            .iter()
            .filter(|e| splits(e))
            .map(|e| (e.error, e.node))
            .collect();
        let top = frontier.iter().map(|f| f.0).fold(enough, f64::max);
        let mut threshold = (top * AHEAD_STEP).max(enough);
        let mut count = roots.len();
        let mut ready = HashMap::new();
        while !frontier.is_empty() && self.goes_on() {
            let (batch, rest): (Vec<_>, Vec<_>) =
                frontier.into_iter().partition(|f| f.0 > threshold);
            frontier = rest;
            if batch.is_empty() {
                if threshold <= enough {
                    break;
                }
                threshold = (threshold * AHEAD_STEP).max(enough);
                continue;
            }
            if count + batch.len() > largest || off(&AHEAD_OFF) {
                break;
            }
            let kids: Vec<([Entry; 2], bool)> = batch
                .par_iter()
                .map_init(Scratch::default, |s, &(_, n)| {
                    let [a, b] = self.tree.nodes[n as usize].children;
                    let kids = [a, b].map(|c| self.entry(c, s, above, known));
                    let chain = self.carries([&kids[0], &kids[1]], &mut s.hull);
                    (kids, chain)
                })
                .collect();
            count += batch.len();
            // A chain's next nodes are found by [`Cutter::descend`], not one by one.
            let next = kids.iter().filter(|k| !k.1).flat_map(|k| &k.0);
            frontier.extend(next.filter(|e| splits(e)).map(|e| (e.error, e.node)));
            ready.extend(kids.into_iter().flat_map(|k| k.0).map(|e| (e.node, e)));
        }
        ready
    }

    /// The snapshot of one cut for `r`, its nodes in order of their faces' ranges; its
    /// bound is `r`'s tolerance or the farthest its nodes stand, if farther.
    fn snapshot(&self, ex: &Explored, r: &Request, mut cut: Vec<Entry>) -> LevelCut {
        let worst = cut.iter().map(|e| e.error).fold(0.0, f64::max);
        cut.sort_unstable_by_key(|e| self.start(ex, e.node));
        let mesh = self.fitter.input.mesh;
        // Asking before each node and within a large one's corners: once told to
        // stop, nothing is gathered (no caller reads a stopped cutter's snapshot).
        // Both lists held at their length (a level's cuts and their post-processed
        // copies are alive together): a collect of chained ranges keeps up to twice
        // the faces' room, and the corners' up to three times the distinct vertices'.
        let members: Vec<Vec<u32>> = (cut.par_iter())
            .map(|e| match self.goes_on() {
                true => {
                    let faces = self.faces_of(ex, e.node);
                    let mut m = Vec::with_capacity(faces.clone().count());
                    m.extend(faces);
                    m
                }
                false => Vec::new(),
            })
            .collect();
        let verts = (members.par_iter())
            .map(|faces| corners::distinct_corners(mesh, faces, || self.goes_on()))
            .map(|v| {
                let mut v = v.unwrap_or_default();
                v.shrink_to_fit();
                v
            })
            .collect();
        let snapshot = Snapshot {
            target: r.count,
            prims: cut.iter().map(|e| e.prim).collect(),
            faces: members.iter().map(|m| m.len() as u32).collect(),
            verts,
            members,
            q: cut
                .iter()
                .map(|e| self.q_of(ex, e.node))
                .collect::<Vec<Sym3>>(),
        };
        LevelCut {
            snapshot,
            bound: r.tolerance.map_or(worst, |t| t.max(worst)),
            shortfall: None,
            known: Vec::new(),
        }
    }
}

/// What the cutter returns for a fit once it was told to stop: a fit or a
/// measure over millions of faces takes seconds, and nothing the cutter makes after
/// the stop is kept (a cancel answers without them).
const STAND_IN: Primitive = Primitive::Sphere(crate::primitive::sphere::Sphere {
    center: [0.0; 3],
    radius: 0.0,
});

/// Faces tested for containment between two asks of `go_on` (milliseconds).
const FACES_PER_CHECK: usize = 1 << 16;

/// The largest count the requests ask for.
fn largest(requests: &[Request]) -> usize {
    requests.iter().map(|r| r.count).max().unwrap_or(1)
}

#[cfg(test)]
mod tests;
