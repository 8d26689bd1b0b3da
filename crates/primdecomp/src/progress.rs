//! Progress reports and cancellation of a run ([`crate::decompose_with`]). The driver
//! reports each stage as it starts and ends, and the merge stage as it goes; kernels
//! never see this type, only a callback that tells them whether to go on, so a
//! cancelled run stops within one check interval of every loop (a few thousand merges,
//! a block of seed fits) and returns [`crate::Error::Cancelled`].

/// A stage of a run, in the order they run.
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
/// use primdecomp::{decompose_with, demo_scene, Error, Params, Progress, Stage};
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
/// let params = Params { targets: vec![10], ..Params::default() };
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

/// A [`Progress`] that reports nothing and never cancels.
pub(crate) struct Silent;

impl Progress for Silent {}

/// The callback kernels take: report a fraction of the current stage, and learn
/// whether to go on (false = stop now).
pub(crate) type GoOn<'a> = &'a (dyn Fn(f64) -> bool + Sync);
