//! What a run is asked for: counts, a tolerance or a byte budget, as one [`Goal`], so
//! that combinations the engine cannot meet (a greedy tolerance, a filled cut, a
//! tolerance that is also greedy) cannot be written. Counts come from the paper's
//! bottom-up pass (§3.3); tolerances and byte budgets are cuts of its merge tree
//! (docs/decisions/0034).

use super::{Tolerance, DEFAULT_TOLERANCE, MAX_LEVELS, MAX_PRIMITIVES};
use crate::error::{Error, Result};

/// A count as a user gives it (`-n 100`, `-n 1%`): a number of primitives, or a
/// percentage of the input's faces, resolved once the input is known
/// ([`Target::count`]). For a per-object run ([`crate::Objects::decompose`]) a count
/// is the total over the objects and a percentage applies to each object's faces.
/// Spelled `100` or `1%` ([`FromStr`](std::str::FromStr), [`Display`](std::fmt::Display)).
///
/// ```
/// use primdecomp::Target;
///
/// let targets: Vec<Target> = ["200", "1%"].iter().map(|t| t.parse()).collect::<Result<_, _>>()?;
/// assert_eq!(targets, [Target::Count(200), Target::Percent(1.0)]);
/// assert_eq!(targets[1].count(50_000), 500); // 1% of 50,000 faces
/// assert_eq!(targets[1].to_string(), "1%");
/// assert!("0".parse::<Target>().is_err() && "150%".parse::<Target>().is_err());
/// # Ok::<(), primdecomp::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Target {
    /// This many primitives (for a per-object run, shared by the objects: one each, the
    /// rest in proportion to surface area).
    Count(usize),
    /// This percentage (above 0, at most 100) of the faces (of each object's faces, for a
    /// per-object run), at least one primitive.
    Percent(f64),
}

impl Target {
    /// The count for an input of `faces` faces: a percentage's rounded, at least 1.
    pub fn count(self, faces: usize) -> usize {
        match self {
            Target::Count(n) => n,
            Target::Percent(p) => ((faces as f64 * p / 100.0).round() as usize).max(1),
        }
    }
}

/// What the user asks of a run, one level (one result) per count, tolerance or byte
/// budget. The default: the fewest primitives within [`Tolerance::DEFAULT`] of the
/// input, at most [`Goal::MAX_PRIMITIVES`].
///
/// ```
/// use primdecomp::{decompose, demo_scene, Goal, Params, Tolerance};
///
/// // Two levels of at most 200 and 50 primitives.
/// let counts = Params { goal: Goal::counts([200, 50]), ..Params::default() };
/// // Every primitive within 0.5% of the diagonal, at most 300 of them.
/// let within = Params {
///     goal: Goal::Within {
///         caps: vec![300],
///         tolerance: vec![Tolerance::Diagonal(0.005)],
///         max_bytes: vec![],
///     },
///     ..Params::default()
/// };
/// assert_eq!(decompose(&demo_scene(), &counts)?.levels.len(), 2);
/// assert!(decompose(&demo_scene(), &within)?.levels[0].primitives.len() <= 300);
/// # Ok::<(), primdecomp::Error>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub enum Goal {
    /// One level per count, each of at most that many primitives: fewer where nested
    /// primitives are removed and where coplanar faces merge for free
    /// ([`Plates::join_coplanar`](crate::Plates::join_coplanar)). Each is the greedy
    /// pass's level at N ([`Goal::Greedy`]), cut from the merge tree instead
    /// ([`Goal::Cut`]) where that level loses what the count asked for: on an input of
    /// several separate parts (the parts nested in one large primitive are dropped, so
    /// -n 32 could give 5), or where post-processing left it short of N by more than a
    /// few (docs/decisions/0054-counts-on-several-parts.md).
    Counts {
        /// The counts, one level each, in the order given.
        counts: Vec<usize>,
    },
    /// Counts taken from the greedy pass's levels, never cut again: the paper's, the
    /// fastest (`--greedy`).
    ///
    /// ```
    /// use primdecomp::{decompose, demo_scene, Goal, Params};
    ///
    /// let goal = Goal::Greedy { counts: vec![40] };
    /// let level = &decompose(&demo_scene(), &Params { goal, ..Params::default() })?.levels[0];
    /// assert!(level.primitives.len() <= 40);
    /// assert_eq!(level.distance, None); // only a cut measures its distance
    /// # Ok::<(), primdecomp::Error>(())
    /// ```
    Greedy {
        /// The counts, one level each, in the order given.
        counts: Vec<usize>,
    },
    /// Counts that are always cuts of the merge tree (`--cut`): the node whose
    /// primitive stands farthest from the input (a bound of the one-way distance,
    /// docs/decisions/0040) is split until N remain or none is worth splitting; of the
    /// cuts reached, the one of at most N nodes whose worst node stands nearest is
    /// kept, then filled to N (docs/decisions/0032 and 0034).
    ///
    /// ```
    /// use primdecomp::{decompose, demo_scene, Goal, Params};
    ///
    /// let goal = Goal::Cut { counts: vec![40] };
    /// let level = &decompose(&demo_scene(), &Params { goal, ..Params::default() })?.levels[0];
    /// assert!(level.primitives.len() <= 40);
    /// assert!(level.distance.is_some()); // a cut measures how far it stands
    /// # Ok::<(), primdecomp::Error>(())
    /// ```
    Cut {
        /// The counts, one level each, in the order given.
        counts: Vec<usize>,
    },
    /// Greedy levels filled to their counts: where removing nested primitives leaves
    /// fewer than N, merge less (up to 8N) so the level holds as many primitives as fit
    /// within N; up to four more merge passes (docs/decisions/0020).
    Fill {
        /// The counts, one level each, in the order given.
        counts: Vec<usize>,
    },
    /// Each level's primitives within a distance of the input, or stored in at most a
    /// number of bytes, or both: the fewest primitives of the merge tree's cuts whose
    /// every primitive is within the tolerance, and of those the one of least worst
    /// distance that fits the bytes (docs/decisions/0034). `tolerance` and `max_bytes`
    /// each hold no value, one for every level, or one per level; at least one of them
    /// holds a value.
    Within {
        /// The most primitives of each level: none ([`Goal::MAX_PRIMITIVES`] each), one for
        /// every level, or one per level.
        caps: Vec<usize>,
        /// How far every primitive of a level may stand from the input (the one-way
        /// distance `primdecomp eval` reports as Hausdorff, docs/decisions/0034).
        tolerance: Vec<Tolerance>,
        /// A level's storage by the paper's Table 2 (4 bytes a float).
        max_bytes: Vec<usize>,
    },
}

impl Default for Goal {
    fn default() -> Self {
        Goal::tolerance(DEFAULT_TOLERANCE)
    }
}

impl Goal {
    /// The most primitives a level holds when no count is given (1024): the cap of a
    /// [`Goal::Within`] without caps.
    ///
    /// ```
    /// assert_eq!(primdecomp::Goal::MAX_PRIMITIVES, 1024);
    /// ```
    pub const MAX_PRIMITIVES: usize = crate::params::MAX_PRIMITIVES;

    /// Levels of at most these counts, found as [`Goal::Counts`] says.
    pub fn counts(counts: impl Into<Vec<usize>>) -> Goal {
        Goal::Counts {
            counts: counts.into(),
        }
    }

    /// One level of the fewest primitives within `tolerance` (at most
    /// [`Goal::MAX_PRIMITIVES`]).
    pub fn tolerance(tolerance: Tolerance) -> Goal {
        Goal::Within {
            caps: Vec::new(),
            tolerance: vec![tolerance],
            max_bytes: Vec::new(),
        }
    }

    /// One level of the closest fit in at most `bytes` bytes (at most
    /// [`Goal::MAX_PRIMITIVES`] primitives).
    pub fn max_bytes(bytes: usize) -> Goal {
        Goal::Within {
            caps: Vec::new(),
            tolerance: Vec::new(),
            max_bytes: vec![bytes],
        }
    }

    /// The number of levels (results) this goal makes.
    pub fn levels(&self) -> usize {
        match self {
            Goal::Counts { counts }
            | Goal::Greedy { counts }
            | Goal::Cut { counts }
            | Goal::Fill { counts } => counts.len(),
            Goal::Within {
                caps,
                tolerance,
                max_bytes,
            } => caps.len().max(tolerance.len()).max(max_bytes.len()),
        }
    }

    /// Each level's count (the most primitives it holds): the counts as given, or each
    /// level's cap ([`Goal::MAX_PRIMITIVES`] where none is given).
    ///
    /// ```
    /// use primdecomp::{Goal, Tolerance};
    ///
    /// assert_eq!(Goal::default().targets(), vec![Goal::MAX_PRIMITIVES]);
    /// let chain = Goal::Within {
    ///     caps: vec![300],
    ///     tolerance: vec![Tolerance::Diagonal(0.02), Tolerance::Diagonal(0.005)],
    ///     max_bytes: vec![],
    /// };
    /// assert_eq!(chain.targets(), vec![300, 300]);
    /// ```
    pub fn targets(&self) -> Vec<usize> {
        match self {
            Goal::Counts { counts }
            | Goal::Greedy { counts }
            | Goal::Cut { counts }
            | Goal::Fill { counts } => counts.clone(),
            Goal::Within { caps, .. } => match caps.len() {
                0 => vec![MAX_PRIMITIVES; self.levels()],
                1 => vec![caps[0]; self.levels()],
                _ => caps.clone(),
            },
        }
    }

    /// The same goal at other counts: a count goal's counts, a fill's, or the caps of
    /// a tolerance or byte budget (as [`crate::Objects::decompose`] shares a count
    /// among objects).
    ///
    /// ```
    /// use primdecomp::Goal;
    ///
    /// assert_eq!(Goal::counts([40, 10]).with_targets(vec![4, 1]), Goal::counts([4, 1]));
    /// ```
    pub fn with_targets(&self, targets: Vec<usize>) -> Goal {
        match self {
            Goal::Counts { .. } => Goal::Counts { counts: targets },
            Goal::Greedy { .. } => Goal::Greedy { counts: targets },
            Goal::Cut { .. } => Goal::Cut { counts: targets },
            Goal::Fill { .. } => Goal::Fill { counts: targets },
            Goal::Within {
                tolerance,
                max_bytes,
                ..
            } => Goal::Within {
                caps: targets,
                tolerance: tolerance.clone(),
                max_bytes: max_bytes.clone(),
            },
        }
    }

    /// Whether levels are cuts of the merge tree (a tolerance, a byte budget or
    /// [`Goal::Cut`]), which needs more memory than the greedy merge alone
    /// ([`LoadOptions::greedy_only`](crate::LoadOptions::greedy_only)).
    ///
    /// ```
    /// use primdecomp::Goal;
    ///
    /// assert!(!Goal::counts([2000]).uses_cut());
    /// assert!(Goal::default().uses_cut(), "a tolerance is a cut of the merge tree");
    /// ```
    pub fn uses_cut(&self) -> bool {
        matches!(self, Goal::Within { .. } | Goal::Cut { .. })
    }

    /// Whether counts may become cuts of the merge tree where the greedy level falls
    /// short ([`Goal::Counts`]).
    pub(crate) fn count_cut(&self) -> bool {
        matches!(self, Goal::Counts { .. })
    }

    /// The counts of these levels, met by a cut of the merge tree.
    pub(crate) fn cut_counts(counts: Vec<usize>) -> Goal {
        Goal::Cut { counts }
    }

    /// This goal with its counts found by a cut of the merge tree (a tolerance or byte
    /// budget already is one).
    pub(crate) fn as_cut(&self) -> Goal {
        match self {
            Goal::Within { .. } => self.clone(),
            _ => Goal::cut_counts(self.targets()),
        }
    }

    /// Level `i`'s tolerance and byte budget (one value applies to every level).
    pub(crate) fn level_limits(&self, i: usize) -> (Option<Tolerance>, Option<usize>) {
        let Goal::Within {
            tolerance,
            max_bytes,
            ..
        } = self
        else {
            return (None, None);
        };
        let pick = |len: usize| (len > 0).then_some(if len == 1 { 0 } else { i });
        (
            pick(tolerance.len()).map(|k| tolerance[k]),
            pick(max_bytes.len()).map(|k| max_bytes[k]),
        )
    }

    /// Checks the counts, the number of levels and each tolerance and byte budget.
    pub(crate) fn validate(&self) -> Result<()> {
        let bad = |m: String| Err(Error::InvalidParams(m));
        self.validate_lengths()?;
        let targets = self.targets();
        if targets.is_empty() || targets.contains(&0) {
            return bad("targets must be one or more positive counts".into());
        }
        if self.levels() > MAX_LEVELS {
            return bad(format!(
                "{} levels (targets, tolerances or byte targets) asked for; a run makes \
                 at most {MAX_LEVELS}, each a result of its own",
                self.levels()
            ));
        }
        if let Goal::Within {
            tolerance,
            max_bytes,
            ..
        } = self
        {
            if let Some(t) = tolerance
                .iter()
                .find(|t| !(t.value().is_finite() && t.value() > 0.0))
            {
                return bad(format!("tolerance must be a positive distance, got {t:?}"));
            }
            if max_bytes.contains(&0) {
                return bad("max_bytes must be positive".into());
            }
        }
        Ok(())
    }

    /// A tolerance or byte goal holds a tolerance or a byte budget, each with no
    /// value, one, or one per level.
    fn validate_lengths(&self) -> Result<()> {
        let Goal::Within {
            caps,
            tolerance,
            max_bytes,
        } = self
        else {
            return Ok(());
        };
        let bad = |m: String| Err(Error::InvalidParams(m));
        if tolerance.is_empty() && max_bytes.is_empty() {
            return bad(
                "a tolerance or byte goal needs a tolerance or a byte budget; without \
                 either, ask for counts"
                    .into(),
            );
        }
        // A chain of tolerances or byte budgets under one cap: the cap applies to each.
        let n = if caps.len() > 1 {
            caps.len()
        } else {
            self.levels()
        };
        for (name, len) in [
            ("tolerance", tolerance.len()),
            ("max_bytes", max_bytes.len()),
        ] {
            if len > 1 && len != n {
                return bad(format!(
                    "{name} has {len} values for {n} targets: give one value, or one per target"
                ));
            }
        }
        Ok(())
    }
}
