//! Settings of a decomposition: what the user asks for ([`Goal`]: counts, a tolerance
//! or a byte budget), then two groups named for what they do: [`Fit`] (which
//! primitives and how a merge is priced: §3.3 weights, §3.4 deduplication and tangent
//! term) and [`Plates`] (how flat parts, holes and nested primitives come out: §3.4's
//! clean-up and our fixes to it, each on by default and each recorded under
//! `docs/decisions/`), and how the merge loop runs ([`Reprice`], [`Partitions`]). A
//! run's settings are written into its JSON (`settings`, the flat shape of
//! `params/json.rs`) and read back by
//! [`Params::from_json`], so a result can be reproduced from its own file.

mod goal;
mod json;
mod spelling;

pub use goal::{Goal, Target};

use crate::error::{Error, Result};
use crate::primitive::Kind;
use serde::{Deserialize, Serialize};

/// The tolerance of the default [`Goal`]: every primitive within this much of the
/// input's diagonal, chosen from measurements over the corpus (docs/decisions/0037).
pub(crate) const DEFAULT_TOLERANCE: Tolerance = Tolerance::Diagonal(0.02);

/// The most primitives a level holds when no count is given: the cap of a
/// [`Goal::Within`] without caps.
pub(crate) const MAX_PRIMITIVES: usize = 1024;

/// The farthest any primitive of a level may stand from the input: the one-way
/// distance from each primitive's surface to the input's surface, the quantity
/// `primdecomp eval` reports as Hausdorff, estimated by sampling (docs/decisions/0034).
///
/// ```
/// use primdecomp::Tolerance;
///
/// assert_eq!("1%".parse::<Tolerance>().unwrap(), Tolerance::Diagonal(0.01));
/// assert_eq!("0.5".parse::<Tolerance>().unwrap(), Tolerance::Units(0.5));
/// assert_eq!(Tolerance::Diagonal(0.01).in_units(200.0), 2.0);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Tolerance {
    /// A distance in the input's units.
    Units(f64),
    /// A fraction of the input's bounding-box diagonal (0.01 = 1%).
    Diagonal(f64),
}

impl Tolerance {
    /// The tolerance of the default [`Goal`]: every primitive within 2% of the input's
    /// diagonal, chosen from measurements over the corpus (docs/decisions/0037).
    ///
    /// ```
    /// use primdecomp::Tolerance;
    ///
    /// assert_eq!(Tolerance::DEFAULT, Tolerance::Diagonal(0.02));
    /// assert_eq!(Tolerance::DEFAULT.to_string(), "2%");
    /// ```
    pub const DEFAULT: Tolerance = DEFAULT_TOLERANCE;

    /// The distance in the input's units for an input whose diagonal is `diagonal`.
    ///
    /// ```
    /// use primdecomp::Tolerance;
    /// assert_eq!(Tolerance::Diagonal(0.01).in_units(200.0), 2.0);
    /// assert_eq!(Tolerance::Units(0.5).in_units(200.0), 0.5);
    /// ```
    pub fn in_units(self, diagonal: f64) -> f64 {
        match self {
            Tolerance::Units(d) => d,
            Tolerance::Diagonal(f) => f * diagonal,
        }
    }

    pub(crate) fn value(self) -> f64 {
        match self {
            Tolerance::Units(d) | Tolerance::Diagonal(d) => d,
        }
    }
}

/// How vertices at (nearly) the same position are merged before building adjacency (§3.4).
///
/// ```
/// use primdecomp::{Dedup, Fit, Params};
///
/// // Weld vertices within 1e-6 of each other (a mesh exported with cracks).
/// let p = Params { fit: Fit { dedup: Dedup::Tolerance(1e-6), ..Fit::default() }, ..Params::default() };
/// assert!(p.validate().is_ok());
/// assert_eq!("exact".parse::<Dedup>()?, Fit::default().dedup);
/// # Ok::<(), primdecomp::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Dedup {
    /// No merging: topology exactly as in the file.
    Off,
    /// Merge vertices with bit-identical coordinates (the paper's default).
    Exact,
    /// Merge vertices closer than this distance (world units).
    Tolerance(f64),
}

/// When a merged cluster's candidate merges with its neighbours are re-priced (§3.3, Alg. 1).
///
/// ```
/// use primdecomp::{Params, Reprice};
///
/// // The paper's exact order of merges (needed by `Fit::max_excess_volume`).
/// let p = Params { reprice: Reprice::Exact, ..Params::default() };
/// assert!(p.validate().is_ok());
/// assert_eq!(Reprice::default(), Reprice::Deferred { min_degree: 64 });
/// assert_eq!(Reprice::default().to_string(), "64");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Reprice {
    /// Right after every merge: each merge is the cheapest at that moment (the paper).
    Exact,
    /// Merges of clusters with at least `min_degree` neighbours leave their pairs'
    /// queue entries as they were and re-price each when it is popped (0 = every
    /// merge): large flat regions cost F log F instead of F^1.5
    /// (docs/decisions/0015-deferred-repricing-of-high-degree-clusters.md).
    Deferred {
        /// Neighbour count from which a merge's re-pricing is deferred.
        min_degree: u32,
    },
}

/// Re-pricing is deferred from 64 neighbours: the same quality within measurement
/// noise, large flat regions in F log F (docs/decisions/0015).
impl Default for Reprice {
    fn default() -> Self {
        Reprice::Deferred { min_degree: 64 }
    }
}

/// How many spatial parts the faces are split into and merged in parallel before the
/// global merge loop (docs/decisions/0017 and 0019).
///
/// ```
/// use primdecomp::{Params, Partitions};
///
/// // One global greedy loop, as the paper's Alg. 1, whatever the input's size.
/// let p = Params { partitions: Partitions::Fixed(1), ..Params::default() };
/// assert!(p.validate().is_ok());
/// assert_eq!(Params::default().partitions, Partitions::Auto);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Partitions {
    /// Inputs of at least 524,288 faces: 16 parts, or one per 65,536 faces if more
    /// (large scans, where the parts cost no measurable quality); smaller inputs: one,
    /// the paper's Alg. 1 as is.
    #[default]
    Auto,
    /// Exactly this many parts (1 to 4096); 1 = one global greedy.
    Fixed(usize),
}

/// Inputs with at least this many faces are split under [`Partitions::Auto`].
pub const AUTO_MIN_FACES: usize = 1 << 19;

/// The fewest parts [`Partitions::Auto`] uses on large inputs.
pub const AUTO_PARTS: usize = 16;

/// [`Partitions::Auto`] gives a part at most about this many faces, so that a part's
/// loop keeps its working set near one core's 1 MiB L2 cache and the first phase's
/// time grows with the input's size, not faster (docs/decisions/0019).
pub(crate) const AUTO_PART_FACES: usize = 1 << 16;

/// The most parts [`Partitions::Fixed`] may ask for.
pub(crate) const MAX_PARTITIONS: usize = 4096;

/// The most levels (targets, tolerances or byte targets) one run makes: every level
/// is a result of its own (a file each from the command line, every one recording
/// all the targets), so thousands of levels cost time and files quadratic in their
/// number for nothing a collider needs.
pub(crate) const MAX_LEVELS: usize = 256;

impl Partitions {
    /// The number of parts for an input of `faces` faces.
    pub(crate) fn parts(self, faces: usize) -> usize {
        match self {
            Partitions::Auto if faces >= AUTO_MIN_FACES => {
                AUTO_PARTS.max(faces.div_ceil(AUTO_PART_FACES))
            }
            Partitions::Auto => 1,
            Partitions::Fixed(k) => k,
        }
    }
}

/// `"auto"` or the fixed count.
impl Serialize for Partitions {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        match self {
            Partitions::Auto => s.serialize_str("auto"),
            Partitions::Fixed(k) => s.serialize_u64(*k as u64),
        }
    }
}

impl<'de> Deserialize<'de> for Partitions {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        #[derive(Deserialize)]
        #[serde(untagged)]
        enum Raw {
            Count(usize),
            Word(String),
        }
        match Raw::deserialize(d)? {
            Raw::Count(k) => Ok(Partitions::Fixed(k)),
            Raw::Word(w) if w == "auto" => Ok(Partitions::Auto),
            Raw::Word(w) => Err(serde::de::Error::custom(format!(
                "partitions must be \"auto\" or a count, got \"{w}\""
            ))),
        }
    }
}

/// All settings of a run: what is asked for ([`Goal`]), then what the primitives may
/// be ([`Fit`]), how flat parts, holes and nested primitives come out ([`Plates`]),
/// and how the merge loop runs ([`Reprice`], [`Partitions`]: the same quality within
/// measurement noise). `Params::default()` is the recommended
/// configuration: the fewest primitives within [`Tolerance::DEFAULT`] of the input, at
/// most [`Goal::MAX_PRIMITIVES`]. Change only what you need, as in
/// `Params { goal: Goal::counts([200, 50]), ..Params::default() }` (two levels of at
/// most 200 and 50 primitives) or
/// `Params { goal: Goal::tolerance(Tolerance::Diagonal(0.005)), ..Params::default() }`.
/// Results record the settings in the JSON shape [`Params::from_json`] reads.
///
/// | setting | default | raising it | lowering it |
/// |---|---|---|---|
/// | `goal`'s tolerance | 2% of the diagonal | fewer, larger primitives | tighter fit, more primitives |
/// | `goal`'s counts | none: the tolerance decides | more, smaller primitives: tighter fit, more bytes | coarser colliders |
/// | `fit.weights[kind]` | box, sphere, capsule 1; cylinder 1.05; frustum 2.1; prism 1.4 | that kind is chosen less often | that kind is chosen more often |
/// | `fit.min_extent` | 5e-4 | thin parts get thicker primitives | flatter plates |
/// | `plates.open_holes` | 0.01 | holes and gaps in flat surfaces stay open at lower counts | 0: the paper's pricing (a roof's rim closes into a lid) |
/// | `plates.rim_weight` | 1 | primitives keep further off the faces beside them | 0: volume alone (a plate may stand past a wall's top as a curb) |
///
/// ```
/// use primdecomp::{Goal, Params, Tolerance};
///
/// let params = Params { goal: Goal::tolerance(Tolerance::Diagonal(0.01)), ..Params::default() };
/// assert!(params.validate().is_ok());
/// assert_eq!(params.goal.targets(), vec![Goal::MAX_PRIMITIVES]); // the default cap
/// ```
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "json::Settings", into = "json::Settings")]
pub struct Params {
    /// What the run is asked for: counts, a tolerance or a byte budget, one
    /// [`crate::Level`] each.
    pub goal: Goal,
    /// Which primitives may be fitted and how a merge is priced (§3.3, §3.4).
    pub fit: Fit,
    /// How flat parts, holes, rims and nested primitives come out: the paper's
    /// clean-up (§3.4) and our fixes to it, each on by default and each recorded under
    /// `docs/decisions/`.
    pub plates: Plates,
    /// When merged clusters' candidate merges are re-priced (how fast the merge runs,
    /// the same quality within measurement noise).
    pub reprice: Reprice,
    /// Spatial parts merged in parallel before the global loop (how fast the merge
    /// runs on large inputs, the same quality within measurement noise).
    pub partitions: Partitions,
}

/// Which primitives may be fitted and how a merge is priced (§3.3, §3.4).
///
/// ```
/// use primdecomp::{Fit, Kind, Params};
///
/// let mut kinds = [false; 6];
/// kinds[Kind::Box as usize] = true;
/// let boxes = Params { fit: Fit { kinds, ..Fit::default() }, ..Params::default() };
/// assert!(boxes.validate().is_ok());
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Fit {
    /// Which kinds may be fitted, indexed by `Kind as usize` ([`Kind::ALL`] order).
    pub kinds: [bool; 6],
    /// Cost weight k(kind) per kind, indexed by `Kind as usize`: a merge costs k·V, V
    /// the volume of the primitive it makes (§3.3).
    pub weights: [f64; 6],
    /// ε of the tangent term in each face's quadric Q = area·(nnᵀ + ε·ttᵀ) (§3.4
    /// "Coplanar Vertices"): flat clusters align with their edges; 0 disables it.
    pub tangent_eps: f64,
    /// Which vertices count as one before adjacency (§3.4): what the merge sees as
    /// connected.
    pub dedup: Dedup,
    /// Smallest half-extent of any primitive, as a fraction of the input's bounding-box
    /// diagonal (the paper's absolute 1e-3, made relative so that results do not
    /// depend on units: docs/decisions/0001).
    pub min_extent: f64,
    /// Refuse merges adding more than this fraction of the input's bounding-box volume
    /// (§3.3); `None` = unlimited. A capped merge has no queue entry to defer, so this
    /// needs [`Reprice::Exact`] (checked by [`Params::validate`]).
    pub max_excess_volume: Option<f64>,
}

impl Default for Fit {
    fn default() -> Self {
        Fit {
            kinds: [true; 6],
            weights: [1.0, 1.0, 1.0, 1.05, 2.1, 1.4],
            tangent_eps: 0.01,
            dedup: Dedup::Exact,
            min_extent: 5e-4,
            max_excess_volume: None,
        }
    }
}

/// How flat parts, holes, rims and nested primitives come out.
///
/// ```
/// use primdecomp::{Params, Plates};
///
/// let thick = Params { plates: Plates { min_thickness: 0.3, ..Plates::default() }, ..Params::default() };
/// assert!(thick.validate().is_ok());
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Plates {
    /// Keeps holes and gaps in flat surfaces open: merges of coplanar clusters are
    /// priced as if the primitive were at least this thick (half-extent, a fraction of
    /// the diagonal), so a roof's rim stays a rim instead of closing into a lid; other
    /// merges keep their prices. 0 = the paper's pricing (docs/decisions/0018).
    pub open_holes: f64,
    /// How strongly output primitives keep off the faces just outside their cluster: a
    /// primitive's frame and kind minimise k·V + w·Σ len·gap² over the cluster's
    /// convex boundary edges, gap how far it stands past the next face's plane (a curb
    /// along a wall's top). 0 = volume alone (docs/decisions/0024 and 0029).
    pub rim_weight: f64,
    /// Output plates (primitives at the `min_extent` thickness) lie flush on their
    /// faces, reaching inward, instead of centred on them half their thickness proud
    /// of the surface (docs/decisions/0026).
    pub flush_plates: bool,
    /// Coplanar faces and plates merge for free: a target's level waits for the next
    /// merges while they join coplanar clusters into a plate of no more area, then
    /// plates in one plane are joined where one covers both with no more k·V. So a
    /// target N gives at most N primitives, without seams where coplanar faces meet.
    /// false = exactly N clusters, the paper's stop (docs/decisions/0025 and 0028).
    pub join_coplanar: bool,
    /// Prices merges by the volume their primitive adds outside the input (its
    /// interior by ray parity on a voxel grid) instead of its whole volume: closed
    /// parts become solid primitives instead of shells of plates; costs time
    /// (docs/decisions/0023).
    pub solid: bool,
    /// Plates thinner than this (a fraction of the diagonal) reach inward to it where
    /// the input is closed behind them, their outer side where it was, filling at
    /// most 0.6 of the part's depth: fast bodies stop at them between discrete physics
    /// steps. 0 = off, plates 2 × `min_extent` thick (docs/decisions/0033).
    pub min_thickness: f64,
    /// Remove primitives whose faces all lie inside another primitive (§3.4
    /// "Removing Redundant Primitives"); never loses coverage.
    pub remove_nested: bool,
    /// Also remove boxes whose smallest half-extent is below this fraction of the
    /// diagonal when other primitives cover all their faces (the paper's Bistro figure).
    pub remove_thin_boxes: Option<f64>,
}

impl Default for Plates {
    fn default() -> Self {
        Plates {
            open_holes: 0.01,
            rim_weight: 1.0,
            flush_plates: true,
            join_coplanar: true,
            solid: false,
            min_thickness: 0.0,
            remove_nested: true,
            remove_thin_boxes: None,
        }
    }
}

/// Whether a level of `primitives` falls short of its count `target` by more than a
/// few (2, or 1/32 of the count if more), on an input of `faces` faces: the greedy
/// level's post-processing removed what the count asked for.
pub(crate) fn short_of(primitives: usize, target: usize, faces: usize) -> bool {
    let want = target.min(faces);
    primitives + (want / 32).max(2) < want
}

impl Params {
    /// The settings of a primdecomp JSON result (its `settings` object), or a JSON
    /// object of settings alone; keys left out keep their defaults, unknown keys are
    /// an error. A result's own settings give back its primitives.
    ///
    /// ```
    /// use primdecomp::{decompose, demo_scene, Goal, Params, Plates};
    ///
    /// let plates = Plates { rim_weight: 0.5, ..Plates::default() };
    /// let params = Params { goal: Goal::counts([40]), plates, ..Params::default() };
    /// let first = decompose(&demo_scene(), &params)?;
    /// let json = first.to_json(0, &params);
    /// let again = Params::from_json(&json)?;
    /// assert_eq!(again, params);
    /// assert_eq!(decompose(&demo_scene(), &again)?.levels, first.levels);
    /// # Ok::<(), primdecomp::Error>(())
    /// ```
    pub fn from_json(text: &str) -> Result<Params> {
        let bad = |e: serde_json::Error| Error::InvalidParams(format!("settings: {e}"));
        let value: serde_json::Value = serde_json::from_str(text).map_err(bad)?;
        // A result (it says which `format` it is) gives its `settings`; anything else
        // is settings alone.
        let mut settings = match value.get("format") {
            Some(_) => {
                crate::output::contract::check_header(value.get("format"), value.get("version"))
                    .map_err(Error::InvalidParams)?;
                value.get("settings").cloned().ok_or_else(|| {
                    Error::InvalidParams("settings: the result has no \"settings\"".into())
                })?
            }
            None => value,
        };
        // A result's settings also say which target its level is for.
        if let Some(obj) = settings.as_object_mut() {
            obj.remove("target");
            obj.remove("merge_target");
        }
        let settings: json::Settings = serde_json::from_value(settings).map_err(bad)?;
        let params = Params::try_from(settings).map_err(Error::InvalidParams)?;
        params.validate()?;
        Ok(params)
    }

    /// Checks every setting; [`crate::decompose`] calls this before any work.
    pub fn validate(&self) -> Result<()> {
        let bad = |m: String| Err(Error::InvalidParams(m));
        let fraction = |name: &str, x: f64, zero_ok: bool| {
            let ok = x.is_finite() && x < 1.0 && (x > 0.0 || (zero_ok && x == 0.0));
            let range = if zero_ok { "[0, 1)" } else { "(0, 1)" };
            if ok {
                Ok(())
            } else {
                bad(format!("{name} must be in {range}, got {x}"))
            }
        };
        self.goal.validate()?;
        self.validate_fit()?;
        fraction("open_holes", self.plates.open_holes, true)?;
        fraction("min_thickness", self.plates.min_thickness, true)?;
        if let Some(m) = self.fit.max_excess_volume {
            if !(m.is_finite() && m >= 0.0) {
                return bad(format!("max_excess_volume must be ≥ 0, got {m}"));
            }
            if self.reprice != Reprice::Exact {
                return bad(
                    "max_excess_volume needs reprice: exact (a merge over the cap has no queue \
                     entry whose re-pricing could be deferred)"
                        .into(),
                );
            }
        }
        if let Partitions::Fixed(k) = self.partitions {
            if !(1..=MAX_PARTITIONS).contains(&k) {
                return bad(format!(
                    "partitions must be auto or from 1 to {MAX_PARTITIONS}, got {k}"
                ));
            }
        }
        if let Dedup::Tolerance(t) = self.fit.dedup {
            if !(t.is_finite() && t >= 0.0) {
                return bad(format!("dedup tolerance must be ≥ 0, got {t}"));
            }
        }
        if let Some(t) = self.plates.remove_thin_boxes {
            if !(t.is_finite() && t >= 0.0) {
                return bad(format!("remove_thin_boxes must be ≥ 0, got {t}"));
            }
        }
        Ok(())
    }

    /// Checks the fit's kinds and weights, the two non-negative weights and the
    /// smallest extent (in the order [`Params::validate`] reports them).
    fn validate_fit(&self) -> Result<()> {
        let bad = |m: String| Err(Error::InvalidParams(m));
        if !self.fit.kinds.iter().any(|&k| k) {
            return bad("at least one primitive kind must be enabled".into());
        }
        for k in Kind::ALL {
            let w = self.fit.weights[k as usize];
            if !(w.is_finite() && w > 0.0) {
                return bad(format!(
                    "weight of {} must be a positive number, got {w}",
                    k.name()
                ));
            }
        }
        for (name, x) in [
            ("tangent_eps", self.fit.tangent_eps),
            ("rim_weight", self.plates.rim_weight),
        ] {
            if !(x.is_finite() && x >= 0.0) {
                return bad(format!("{name} must be ≥ 0, got {x}"));
            }
        }
        let m = self.fit.min_extent;
        if !(m.is_finite() && m < 1.0 && m > 0.0) {
            return bad(format!("min_extent must be in (0, 1), got {m}"));
        }
        Ok(())
    }

    /// Whether levels are cuts of the merge tree ([`Goal::uses_cut`]).
    pub fn uses_cut(&self) -> bool {
        self.goal.uses_cut()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Auto splits only large inputs, into `AUTO_PARTS` or more for the largest; a
    /// fixed count is used as given.
    #[test]
    fn partitions_auto_splits_large_inputs_only() {
        assert_eq!(Partitions::Auto.parts(AUTO_MIN_FACES - 1), 1);
        assert_eq!(Partitions::Auto.parts(AUTO_MIN_FACES), AUTO_PARTS);
        assert_eq!(
            Partitions::Auto.parts(AUTO_PARTS * AUTO_PART_FACES),
            AUTO_PARTS
        );
        assert_eq!(Partitions::Auto.parts(871_414), AUTO_PARTS);
        assert_eq!(Partitions::Auto.parts(3_485_656), 54);
        assert_eq!(Partitions::Auto.parts(17 * AUTO_PART_FACES + 1), 18);
        assert_eq!(Partitions::Fixed(1).parts(10 * AUTO_MIN_FACES), 1);
        assert_eq!(Partitions::Fixed(8).parts(10), 8);
    }

    /// Settings round-trip through JSON exactly, partitions as "auto" or a count,
    /// and a zero count is refused.
    #[test]
    fn settings_round_trip_through_json() {
        for partitions in [Partitions::Auto, Partitions::Fixed(1), Partitions::Fixed(8)] {
            let p = Params {
                goal: Goal::counts([7, 3]),
                fit: Fit {
                    kinds: [true, false, true, true, false, true],
                    dedup: Dedup::Tolerance(0.25),
                    max_excess_volume: Some(0.1),
                    ..Default::default()
                },
                plates: Plates {
                    remove_thin_boxes: Some(0.01),
                    ..Default::default()
                },
                partitions,
                reprice: Reprice::Exact,
            };
            let json = serde_json::to_string(&p).unwrap();
            assert_eq!(Params::from_json(&json).unwrap(), p, "{json}");
        }
        let zero = Params {
            partitions: Partitions::Fixed(0),
            ..Default::default()
        };
        assert!(zero.validate().is_err());
        assert!(serde_json::to_string(&Params::default())
            .unwrap()
            .contains("\"partitions\":\"auto\""));
    }

    /// Unknown keys, unknown kinds and a cap without exact re-pricing are errors that
    /// say what is wrong; a partial object keeps the other defaults.
    #[test]
    fn bad_settings_are_named() {
        let err = |s: &str| Params::from_json(s).unwrap_err().to_string();
        assert!(err(r#"{"targets": [3], "rim_wieght": 1}"#).contains("rim_wieght"));
        assert!(err(r#"{"fill": true}"#).contains("fill needs targets"));
        assert!(err(r#"{"targets": [3], "greedy": true, "cut": true}"#).contains("greedy"));
        assert!(err(r#"{"weights": {"box": 1, "cone": 2}}"#).contains("cone"));
        assert!(err(r#"{"max_excess_volume": 0.1}"#).contains("reprice: exact"));
        let p = Params::from_json(r#"{"targets": [5], "solid": true}"#).unwrap();
        assert_eq!(
            (p.goal, p.plates.solid, p.plates.rim_weight),
            (Goal::counts([5]), true, 1.0)
        );
    }
}
