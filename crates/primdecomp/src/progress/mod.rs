//! Progress reports and cancellation of a run ([`crate::decompose_with`]). The driver
//! reports each stage as it starts and ends, and the merge stage as it goes; kernels
//! never see this type, only a callback that tells them whether to go on, so a
//! cancelled run stops within one check interval of every loop (a few thousand merges,
//! a block of seed fits) and returns [`crate::Error::Cancelled`].

pub(crate) mod clock;
pub(crate) mod wallclock;

/// A stage of a run, in the order they run, as [`Progress::update`] reports it.
///
/// ```
/// use primdecomp::Stage;
///
/// let names: Vec<&str> = Stage::ALL.iter().map(|s| s.name()).collect();
/// assert_eq!(names, ["dedup", "adjacency", "quadrics", "seed", "merge", "postprocess"]);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Stage {
    /// Welding vertices at the same position (§3.4).
    Dedup,
    /// Finding faces that share an edge (§3.3).
    Adjacency,
    /// One quadric per face (§3.1).
    Quadrics,
    /// One primitive per face, and the inputs of the merge loop (Alg. 1, line 2).
    Seed,
    /// The greedy merges through every target (Alg. 1's loop); the longest stage.
    Merge,
    /// Nested primitives removed, plates joined, levels written out (§3.4).
    Postprocess,
}

impl Stage {
    /// Every stage, in run order.
    pub const ALL: [Stage; 6] = [
        Stage::Dedup,
        Stage::Adjacency,
        Stage::Quadrics,
        Stage::Seed,
        Stage::Merge,
        Stage::Postprocess,
    ];

    /// A short lower-case name (`"merge"`), as the timings use.
    pub fn name(self) -> &'static str {
        match self {
            Stage::Dedup => "dedup",
            Stage::Adjacency => "adjacency",
            Stage::Quadrics => "quadrics",
            Stage::Seed => "seed",
            Stage::Merge => "merge",
            Stage::Postprocess => "postprocess",
        }
    }
}

/// Receives a run's progress and says whether to cancel it. Both methods have
/// defaults, so an implementation gives only what it needs; any `Fn(Stage, f64)`
/// closure is a `Progress` that never cancels.
///
/// ```
/// use primdecomp::{decompose_with, demo_scene, Error, Goal, Params, Progress, Stage};
/// use std::sync::atomic::{AtomicBool, Ordering};
///
/// /// Cancels the run once the merge stage is half done.
/// struct HalfWay(AtomicBool);
///
/// impl Progress for HalfWay {
///     fn update(&self, stage: Stage, fraction: f64) {
///         if stage == Stage::Merge && fraction >= 0.5 {
///             self.0.store(true, Ordering::Relaxed);
///         }
///     }
///     fn cancelled(&self) -> bool {
///         self.0.load(Ordering::Relaxed)
///     }
/// }
///
/// let params = Params { goal: Goal::counts([10]), ..Params::default() };
/// let run = decompose_with(&demo_scene(), &params, &HalfWay(AtomicBool::new(false)));
/// assert!(matches!(run, Err(Error::Cancelled)));
///
/// // A closure reports progress and never cancels.
/// let done = decompose_with(&demo_scene(), &params, &|stage: Stage, f: f64| {
///     eprintln!("{} {:.0}%", stage.name(), 100.0 * f)
/// });
/// assert!(done.is_ok());
/// ```
pub trait Progress: Sync {
    /// `stage` has done `fraction` (0 to 1) of its work. Called from the thread that
    /// called [`crate::decompose_with`] or from the library's worker threads, often
    /// (keep it cheap).
    fn update(&self, stage: Stage, fraction: f64) {
        let _ = (stage, fraction);
    }

    /// Whether the run should stop; checked at least every few thousand merges and
    /// between stages. Once it returns true the run returns
    /// [`crate::Error::Cancelled`].
    fn cancelled(&self) -> bool {
        false
    }
}

impl<F: Fn(Stage, f64) + Sync> Progress for F {
    fn update(&self, stage: Stage, fraction: f64) {
        self(stage, fraction)
    }
}

/// Shares of a greedy run (a count): dedup, adjacency, quadrics, seed, merge,
/// post-processing.
const GREEDY_SHARES: [f64; 6] = [0.02, 0.04, 0.02, 0.12, 0.78, 0.02];
/// Shares of a run that cuts the merge tree (its cut is post-processing's).
const CUT_SHARES: [f64; 6] = [0.02, 0.03, 0.01, 0.09, 0.55, 0.30];

impl Stage {
    /// The fraction of a whole run of `params` done, 0 to 1, when this stage has done
    /// `fraction` (0 to 1) of its work ([`Progress::update`]'s report). Each stage
    /// counts for its share of a run's time, as the scale ladder measured it from 871k
    /// to 56M faces (`cargo bench -p primdecomp-cli --bench ladder`), a cut's share
    /// where the run cuts the merge tree (a tolerance, a byte target or the default
    /// run).
    ///
    /// ```
    /// use primdecomp::{Goal, Params, Stage};
    ///
    /// let params = Params { goal: Goal::counts([100]), ..Params::default() };
    /// let overall = Stage::Merge.overall(0.5, &params);
    /// assert!(overall > 0.3 && overall < 0.9);
    /// assert_eq!(Stage::Postprocess.overall(1.0, &params), 1.0);
    /// ```
    pub fn overall(self, fraction: f64, params: &crate::params::Params) -> f64 {
        let shares = match params.uses_cut() {
            true => CUT_SHARES,
            false => GREEDY_SHARES,
        };
        let fraction = fraction.clamp(0.0, 1.0);
        let i = Stage::ALL.iter().position(|&s| s == self).unwrap_or(0);
        let done: f64 = shares[..i].iter().sum::<f64>() + shares[i] * fraction;
        (done / shares.iter().sum::<f64>()).clamp(0.0, 1.0)
    }

    /// The seconds left in a run of `params` that has spent `spent` seconds when this
    /// stage has done `fraction` of its work, extrapolated from the time spent on what
    /// is done ([`Stage::overall`]); `None` until a second has passed and a percent is
    /// done.
    ///
    /// ```
    /// use primdecomp::{Goal, Params, Stage};
    ///
    /// let params = Params { goal: Goal::counts([100]), ..Params::default() };
    /// assert_eq!(Stage::Merge.seconds_left(0.5, &params, 0.2), None); // too early to say
    /// let overall = Stage::Merge.overall(0.5, &params);
    /// let left = Stage::Merge.seconds_left(0.5, &params, 10.0).unwrap();
    /// assert!((left - 10.0 * (1.0 - overall) / overall).abs() < 1e-9);
    /// ```
    pub fn seconds_left(
        self,
        fraction: f64,
        params: &crate::params::Params,
        spent: f64,
    ) -> Option<f64> {
        let overall = self.overall(fraction, params);
        (spent >= 1.0 && overall >= 0.01).then(|| spent * (1.0 - overall) / overall)
    }
}

/// A [`Progress`] that reports nothing and never cancels.
pub(crate) struct Silent;

impl Progress for Silent {}

/// The callback kernels take: report a fraction of the current stage, and learn
/// whether to go on (false = stop now).
pub(crate) type Checkpoint<'a> = &'a (dyn Fn(f64) -> bool + Sync);

/// What a step of bounded work asks before the next: whether to go on (false =
/// stop now; what the step returns since is not kept).
pub(crate) type Ask<'a> = &'a (dyn Fn() -> bool + Sync);

/// A [`Checkpoint`] asked from many places, reporting nothing new: once it said
/// stop it is not asked again, so threads still finishing their step do not each
/// report (a cancelled run returns after a few reports).
pub(crate) struct Latch<'a> {
    go_on: Checkpoint<'a>,
    fraction: f64,
    stopped: std::sync::atomic::AtomicBool,
}

impl<'a> Latch<'a> {
    /// `go_on`, reporting `fraction` of the stage at each ask.
    pub(crate) fn new(go_on: Checkpoint<'a>, fraction: f64) -> Self {
        Latch {
            go_on,
            fraction,
            stopped: std::sync::atomic::AtomicBool::new(false),
        }
    }

    /// Whether to go on: false once `go_on` said stop.
    pub(crate) fn goes_on(&self) -> bool {
        use std::sync::atomic::Ordering::Relaxed;
        if !self.stopped.load(Relaxed) && !(self.go_on)(self.fraction) {
            self.stopped.store(true, Relaxed);
        }
        !self.stopped.load(Relaxed)
    }
}
