//! A cut's caps spent on what post-processing keeps (docs/decisions/0044). A cut of
//! the merge tree counts its nodes against a level's count and bytes; post-processing
//! (§3.4) then removes the primitives nested in others and joins coplanar plates, so
//! the file holds less than the caps allowed. A level a cap stopped short of its
//! tolerance (or that has none) is cut again with the cap raised by what was freed,
//! halfway back where that goes over, until it settles. Levels of counts alone are
//! then cut once more, each on its own, with the count its worst error leaves spent
//! on the mean, kept where its post-processed level holds as many primitives no more
//! than a quarter farther and nearer on the mean (docs/decisions/0051).

use crate::cut::LevelCut;
use crate::cut::{mean_distance, Cutter, MergeTree, Request, LOOSE_FACTOR};
use crate::input::triangles::Triangles;
use crate::merge::{Fitter, Snapshot};
use crate::output::result::{Level, Shortfall};
use crate::primitive::Primitive;

/// A cut is made again at most this many times with counts and bytes raised.
const MAX_RECUTS: usize = 4;

/// The raises end at a round that gains less than 1/`LEAST_GAIN_ONE_IN` of its raise
/// ([`gained_little`]; an eighth: docs/decisions/0044, amended).
const LEAST_GAIN_ONE_IN: usize = 8;

/// Post-processing (§3.4) of each level's cut into its level, handed in by the caller:
/// the caps are spent on what it keeps. It takes each cut's faces' lists
/// ([`LevelCut::take_for_postprocess`]); the cut keeps its primitives.
pub(crate) type Postprocess<'a> = dyn Fn(&mut [LevelCut]) -> Vec<Level> + 'a;

/// The kept cuts, one per request, and their post-processed levels where the search
/// made them (`None` where every level was cut once: those cuts keep their faces'
/// lists, to be post-processed by the caller).
pub(crate) type Kept = (Vec<LevelCut>, Option<Vec<Level>>);

/// One snapshot per request cut from `tree`, each kept from the last cut whose level
/// is within the request, carrying the request's own count, with its level
/// ([`Kept`]); `None` when `go_on` said stop (asked between the cutter's splits and
/// between cuts).
pub(crate) fn snapshots(
    fitter: &Fitter,
    tree: &MergeTree,
    requests: &[Request],
    tris: &Triangles,
    postprocess: &Postprocess<'_>,
    go_on: crate::progress::Checkpoint,
) -> Option<Kept> {
    let mut cutter = Cutter::new(fitter, tree, tris, requests, go_on);
    let mut first = cutter.snapshots(requests);
    if cutter.stopped() {
        return None;
    }
    // Every level within its tolerance or stopped by its faces: cut once.
    if !first.iter().zip(requests).any(|(s, r)| capped(r, s)) {
        return Some((first, None));
    }
    let levels = postprocess(&mut first);
    let mut searches: Vec<LevelRecut> = (first.into_iter().zip(&levels).zip(requests))
        .map(|((snap, level), r)| LevelRecut::first(r, snap, level))
        .collect();
    raise_caps(&mut cutter, &mut searches, requests, postprocess)?;
    // The short levels filled, then the counts' levels explored loosely; each step
    // ends at once when told to stop.
    for step in [fill_short, loosen] {
        if cutter.stopped() {
            return None;
        }
        step(
            &mut cutter,
            &mut searches,
            requests,
            (fitter, tris),
            postprocess,
        );
    }
    if cutter.stopped() {
        return None;
    }
    Some(kept_at_requests(searches, requests))
}

/// The capped levels cut again with their caps raised by what post-processing freed
/// (halfway back where that goes over), at most [`MAX_RECUTS`] times, until every
/// search settles; `None` when `go_on` said stop.
fn raise_caps(
    cutter: &mut Cutter,
    searches: &mut [LevelRecut],
    requests: &[Request],
    postprocess: &Postprocess<'_>,
) -> Option<()> {
    for _ in 0..MAX_RECUTS {
        if searches.iter().all(|s| s.settled) {
            break;
        }
        let asked: Vec<Request> = searches.iter().map(|s| s.asked).collect();
        let mut snaps = cutter.snapshots(&asked);
        if cutter.stopped() {
            return None;
        }
        let levels = postprocess(&mut snaps);
        for ((s, snap), (level, r)) in searches
            .iter_mut()
            .zip(snaps)
            .zip(levels.iter().zip(requests))
        {
            s.step(r, snap, level);
        }
    }
    Some(())
}

/// Each kept cut's level as post-processing made it, for the request's own count
/// (post-processing reads the count only to name the level).
fn kept_at_requests(searches: Vec<LevelRecut>, requests: &[Request]) -> Kept {
    let kept = (searches.into_iter().zip(requests)).map(|(s, r)| {
        let cut = LevelCut {
            snapshot: Snapshot {
                target: r.count,
                ..s.kept.snapshot
            },
            ..s.kept
        };
        let level = Level {
            target: r.count,
            merged_to: r.count,
            ..s.level
        };
        (cut, level)
    });
    let (cuts, levels) = kept.unzip();
    (cuts, Some(levels))
}

/// A level of a count alone that the raises left short of it (its worst node's
/// subtree splits no nearer, and a larger exploration is spent there too) cut once
/// more at its own count, the rest of the count spent on the cut's other nodes
/// (`Cutter::snapshots_filled`, docs/decisions/0048), and kept where its level holds
/// more primitives within the count and its nodes stand no farther, or no more than
/// [`LOOSE_FACTOR`] times farther and nearer on the mean (as [`loosen`]'s levels): a count's
/// worst error can sit on one feature no split brings nearer, and a bound a hair
/// lower then kept one primitive of the eight asked for (docs/decisions/0054).
fn fill_short(
    cutter: &mut Cutter,
    searches: &mut [LevelRecut],
    requests: &[Request],
    (fitter, tris): (&Fitter, &Triangles),
    postprocess: &Postprocess<'_>,
) {
    let short = |s: &LevelRecut, r: &Request| {
        r.tolerance.is_none() && r.bytes.is_none() && s.level.primitives.len() < r.count
    };
    if !searches.iter().zip(requests).any(|(s, r)| short(s, r)) {
        return;
    }
    let asked: Vec<Request> = searches
        .iter()
        .zip(requests)
        .map(|(s, r)| if short(s, r) { *r } else { s.before })
        .collect();
    let mut snaps = cutter.snapshots_filled(&asked);
    if cutter.stopped() {
        return;
    }
    let levels = postprocess(&mut snaps);
    for ((s, r), (snap, level)) in searches
        .iter_mut()
        .zip(requests)
        .zip(snaps.into_iter().zip(&levels))
    {
        let (new, old) = (snap.bound, s.kept.bound);
        let more = level.primitives.len() > s.level.primitives.len();
        let nearer = || {
            new <= old
                || (new <= LOOSE_FACTOR * old
                    && mean(fitter, tris, level) < mean(fitter, tris, &s.level))
        };
        if short(s, r) && more && within(r, level) && nearer() {
            (s.kept, s.level) = (snap, level.clone());
        }
    }
}

/// One level's search: the request the cutter gets next, the one its kept cut came
/// from, the least found over the user's caps, whether it is settled, and the kept
/// cut with its post-processed level.
struct LevelRecut {
    asked: Request,
    before: Request,
    over: Option<Request>,
    settled: bool,
    kept: LevelCut,
    level: Level,
}

impl LevelRecut {
    /// The search after the cut for the user's request `r` itself.
    fn first(r: &Request, snap: LevelCut, level: &Level) -> LevelRecut {
        let asked = raise(r, r, &snap, level).unwrap_or(*r);
        LevelRecut {
            asked,
            before: *r,
            over: None,
            settled: asked == *r,
            kept: snap,
            level: level.clone(),
        }
    }

    /// The primitives and bytes the kept cut's level holds.
    fn spent(&self) -> (usize, usize) {
        (self.level.primitives.len(), self.level.bytes())
    }

    /// Takes the cut for `self.asked` (`snap`, post-processed to `level`) and says
    /// what to ask next.
    fn step(&mut self, r: &Request, snap: LevelCut, level: &Level) {
        if self.settled {
            return;
        }
        // No more nodes than the cut kept: raising the caps does not help.
        if snap.snapshot.prims.len() <= self.kept.snapshot.prims.len() {
            self.settled = true;
            return;
        }
        if !within(r, level) {
            self.over = Some(self.asked);
            self.asked = halfway(&self.before, &self.asked);
            self.settled = self.asked == self.before;
            return;
        }
        let raised = raise(r, &self.asked, &snap, level);
        let now = (level.primitives.len(), level.bytes());
        // Most of the raise went to primitives post-processing drops again.
        let slow = gained_little(self.spent(), now, &self.before, &self.asked);
        (self.kept, self.level, self.before) = (snap, level.clone(), self.asked);
        self.asked = match (raised, self.over) {
            (None, _) => self.asked,
            _ if slow => self.asked,
            (Some(a), None) => a,
            (Some(_), Some(o)) => halfway(&self.asked, &o),
        };
        self.settled = self.asked == self.before;
    }
}

/// The request halfway from `lo` to `hi` in count and bytes (`lo` once they meet).
fn halfway(lo: &Request, hi: &Request) -> Request {
    let mid = |a: usize, b: usize| a + b.saturating_sub(a) / 2;
    Request {
        count: mid(lo.count, hi.count),
        bytes: lo.bytes.zip(hi.bytes).map(|(a, b)| mid(a, b)),
        ..*lo
    }
}

/// Levels of counts alone cut once more, each for the request its kept cut came from
/// on its own (as that count alone would be cut), the count the least worst error
/// leaves spent on the mean (`Cutter::snapshot_loose`, docs/decisions/0051). A
/// level takes its loose cut if that is within its request, holds as many
/// primitives as before, stands within [`LOOSE_FACTOR`] times its kept cut and nearer on
/// the mean ([`mean_distance`]), and no level then stands farther than one that
/// stood farther before (the largest counts first). Compared after post-processing:
/// a cut that loses fewer primitives to nesting is raised less, so comparing the
/// cuts alone let levels stand farther.
fn loosen(
    cutter: &mut Cutter,
    searches: &mut [LevelRecut],
    requests: &[Request],
    (fitter, tris): (&Fitter, &Triangles),
    postprocess: &Postprocess<'_>,
) {
    if (requests.iter()).any(|r| r.tolerance.is_some() || r.bytes.is_some()) {
        return;
    }
    let mut snaps: Vec<LevelCut> = (searches.iter())
        .map(|s| cutter.snapshot_loose(&s.before))
        .collect();
    if cutter.stopped() {
        return;
    }
    let levels = postprocess(&mut snaps);
    let mean = |l: &Level| mean(fitter, tris, l);
    let old: Vec<f64> = searches.iter().map(|s| s.kept.bound).collect();
    let n = old.len();
    let mut now = old.clone();
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by_key(|&i| std::cmp::Reverse((requests[i].count, i)));
    for i in order {
        let (level, new, s) = (&levels[i], snaps[i].bound, &mut searches[i]);
        let near = within(&requests[i], level)
            && level.primitives.len() >= s.level.primitives.len()
            && new <= LOOSE_FACTOR * old[i]
            && mean(level) < mean(&s.level);
        let was = std::mem::replace(&mut now[i], new);
        let ordered = (0..n).all(|a| (0..n).all(|b| old[a] > old[b] || now[a] <= now[b]));
        if !(near && ordered) {
            now[i] = was;
            continue;
        }
        (s.kept, s.level) = (snaps[i].clone(), level.clone());
    }
}

/// A level's mean distance to the input ([`mean_distance`]); levels are in world
/// coordinates, the input's triangles in its re-centred frame.
fn mean(fitter: &Fitter, tris: &Triangles, l: &Level) -> f64 {
    let back = fitter.input.mesh.offset.map(|x| -x);
    let prims: Vec<Primitive> = l.primitives.iter().map(|p| p.translated(back)).collect();
    mean_distance(&prims, tris)
}

/// Whether a cut for `now` (from `from`'s caps raised to `to`'s) holds less than
/// 1/[`LEAST_GAIN_ONE_IN`] of the raise more than the level of `from` held (`was`): where nested
/// primitives eat the raise, rounds cost more than they bring.
fn gained_little(was: (usize, usize), now: (usize, usize), from: &Request, to: &Request) -> bool {
    let gain = |a: usize, b: usize, raise: usize| {
        raise > 0 && LEAST_GAIN_ONE_IN * b.saturating_sub(a) < raise
    };
    let bytes = to
        .bytes
        .unwrap_or(0)
        .saturating_sub(from.bytes.unwrap_or(0));
    gain(was.0, now.0, to.count.saturating_sub(from.count))
        && (bytes == 0 || gain(was.1, now.1, bytes))
}

/// Whether `level` keeps to `r`'s count and bytes.
fn within(r: &Request, level: &Level) -> bool {
    crate::cut::fits(r, (level.primitives.len(), level.bytes()))
}

/// Whether a cap stopped `snap`, the cut for `r`: it has no tolerance, or the count
/// or the bytes came first.
fn capped(r: &Request, snap: &LevelCut) -> bool {
    r.tolerance.is_none() || matches!(snap.shortfall, Some(Shortfall::Count | Shortfall::Bytes))
}

/// `asked` (what the cutter got for `user`) with its count and bytes raised by what
/// post-processing freed of `user`'s, where it freed some (`snap`'s nodes against
/// `level`'s primitives) and the cut stopped short of its tolerance (or has none);
/// `None` otherwise.
fn raise(user: &Request, asked: &Request, snap: &LevelCut, level: &Level) -> Option<Request> {
    if !capped(user, snap) {
        return None;
    }
    let node_bytes: usize = snap.snapshot.prims.iter().map(|p| p.bytes()).sum();
    if snap.snapshot.prims.len() == level.primitives.len() && node_bytes == level.bytes() {
        return None;
    }
    let free_count = user.count.saturating_sub(level.primitives.len());
    let free_bytes = user.bytes.map_or(0, |b| b.saturating_sub(level.bytes()));
    (free_count > 0 || free_bytes > 0).then(|| Request {
        count: asked.count + free_count,
        bytes: asked.bytes.map(|b| b + free_bytes),
        ..*asked
    })
}
