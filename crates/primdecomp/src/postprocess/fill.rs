//! Filling the primitive budget ([`Goal::Fill`]), an extension of §3.4 "Removing
//! Redundant Primitives". The merge loop stops at N clusters and post-processing then
//! drops the primitives nested in others, so a run asked for N can return far fewer:
//! truck_shrec at N = 64 keeps 19 (its cab interior and wheels sit inside the body's
//! box), engine_2cylinder 19. With `fill`, each target N is met by merging less: the
//! search looks for the merge target T ≥ N whose post-processed count is the largest
//! not above N, and returns that level (`Level::merged_to` = T). Every level comes
//! from the ordinary engine, so enclosure and determinism carry over unchanged.
//!
//! The search runs the whole engine once per round with a ladder of candidate targets
//! (one bottom-up pass yields every rung), narrowing a bracket [best T, first T that
//! overshoots N). The post-processed count is not monotone in T, so the result is the
//! best rung found, not a proven optimum.

use crate::error::Result;
use crate::input::mesh::Mesh;
use crate::output::result::{Decomposition, Level};
use crate::params::{Goal, Params};
use crate::progress::wallclock::Instant;
use crate::progress::{Progress, Stage};

/// Candidate targets per round (one merge pass gives them all).
const LADDER: usize = 12;
/// Rounds after the first pass: a ladder of 12 shrinks a bracket ~13× per round.
const ROUNDS: usize = 4;
/// The search looks at merge targets up to this multiple of N.
const REACH: usize = 8;

/// The search for one requested target.
struct FillSearch {
    /// The N asked for.
    want: usize,
    /// Best level so far: the most primitives not above `want`, smallest T on ties.
    best: Level,
    /// Exclusive upper end of the targets still worth trying.
    hi: usize,
    /// The last round found nothing better and narrowed nothing.
    done: bool,
}

impl FillSearch {
    fn new(level: Level, faces: usize) -> FillSearch {
        let want = level.target;
        let short = level.primitives.len() < want;
        // Targets above the face count merge nothing more than the face count itself.
        let hi = if short {
            faces.min(want.saturating_mul(REACH)) + 1
        } else {
            want + 1
        };
        FillSearch {
            want,
            best: level,
            hi,
            done: false,
        }
    }

    fn kept(&self) -> usize {
        self.best.primitives.len()
    }

    /// Targets strictly between the best so far and `hi`, spaced geometrically.
    fn ladder(&self) -> Vec<usize> {
        let lo = self.best.merged_to;
        if self.done || self.kept() >= self.want || self.hi <= lo + 1 {
            return Vec::new();
        }
        if self.hi - lo - 1 <= LADDER {
            return (lo + 1..self.hi).collect();
        }
        let ratio = self.hi as f64 / lo as f64;
        let mut out: Vec<usize> = (1..=LADDER)
            .map(|k| (lo as f64 * ratio.powf(k as f64 / (LADDER + 1) as f64)).round() as usize)
            .map(|t| t.clamp(lo + 1, self.hi - 1))
            .collect();
        out.dedup();
        out
    }

    /// Takes the best of a round's levels (sorted by target, ascending) in the
    /// bracket and narrows it; a round that moves nothing ends this search.
    fn update(&mut self, levels: &[Level]) {
        let (lo, hi) = (self.best.merged_to, self.hi);
        let rungs = || {
            levels
                .iter()
                .filter(|l| l.merged_to > lo && l.merged_to < hi)
        };
        let mut better: Option<&Level> = None;
        for l in rungs().filter(|l| l.primitives.len() <= self.want) {
            if l.primitives.len() > better.map_or(self.kept(), |b| b.primitives.len()) {
                better = Some(l);
            }
        }
        if let Some(l) = better {
            self.best = Level {
                target: self.want,
                ..l.clone()
            };
        }
        let lo = self.best.merged_to;
        let over = rungs().find(|l| l.merged_to > lo && l.primitives.len() > self.want);
        if let Some(l) = over {
            self.hi = l.merged_to;
        }
        self.done = better.is_none() && over.is_none();
    }
}

/// One bottom-up pass through a goal's targets (`decompose::pass`).
pub(crate) type Pass = dyn Fn(&Mesh, &Params, &dyn Progress) -> Result<Decomposition>;

/// [`crate::decompose_with`] for a [`Goal::Fill`]: the first pass at the requested
/// targets, then up to [`ROUNDS`] ladder passes (`pass`) for the targets the
/// post-processing left short; the merge stage's progress runs over all of them.
pub(crate) fn fill(
    mesh: &Mesh,
    params: &Params,
    progress: &dyn Progress,
    pass: &Pass,
) -> Result<Decomposition> {
    // The passes are greedy levels, which fill refines (never cuts, 0054).
    let once = Params {
        goal: Goal::Greedy {
            counts: params.goal.targets(),
        },
        ..params.clone()
    };
    // Progress: the first pass is the first half, each round an equal share of the rest.
    let mut dec = pass(mesh, &once, &Share::new(progress, 0.0, 0.5))?;
    let faces = mesh.face_count();
    let levels = std::mem::take(&mut dec.levels);
    let mut searches: Vec<FillSearch> = levels
        .into_iter()
        .map(|l| FillSearch::new(l, faces))
        .collect();
    for round in 1..=ROUNDS {
        let mut targets: Vec<usize> = searches.iter().flat_map(FillSearch::ladder).collect();
        targets.sort_unstable();
        targets.dedup();
        if targets.is_empty() {
            break;
        }
        let now = Instant::now();
        let share = 0.5 / ROUNDS as f64;
        let start = 0.5 + share * (round - 1) as f64;
        let ladder = Params {
            goal: once.goal.with_targets(targets),
            ..once.clone()
        };
        let run = pass(mesh, &ladder, &Share::new(progress, start, share))?;
        dec.stats.merges += run.stats.merges;
        dec.stats.fits_seeded += run.stats.fits_seeded;
        dec.stats.fits_at_once += run.stats.fits_at_once;
        dec.stats.fits_when_popped += run.stats.fits_when_popped;
        for s in &mut searches {
            s.update(&run.levels);
        }
        dec.timings
            .push((format!("fill {round}"), now.elapsed().as_secs_f64()));
    }
    dec.levels = searches.into_iter().map(|s| s.best).collect();
    progress.update(Stage::Merge, 1.0);
    Ok(dec)
}

/// One pass's share of the whole search's merge progress: its merge stage's fraction
/// f is reported as `start + share·f`; other stages pass through, as does cancelling.
struct Share<'p> {
    inner: &'p dyn Progress,
    start: f64,
    share: f64,
}

impl<'p> Share<'p> {
    fn new(inner: &'p dyn Progress, start: f64, share: f64) -> Self {
        Share {
            inner,
            start,
            share,
        }
    }
}

impl Progress for Share<'_> {
    fn update(&self, stage: Stage, fraction: f64) {
        match stage {
            Stage::Merge => self.inner.update(stage, self.start + self.share * fraction),
            _ => self.inner.update(stage, fraction),
        }
    }
    fn cancelled(&self) -> bool {
        self.inner.cancelled()
    }
}
