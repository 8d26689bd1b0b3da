//! Settings of a decomposition. `Params::default()` equals the paper's settings
//! (§3.3 weights, §3.4 deduplication and tangent term), except where the paper's
//! choice made results depend on units (the minimum extent, here relative) and in
//! deferring the re-pricing of clusters with 64 or more neighbours (ARCHITECTURE.md,
//! "Where we deviate", 15: the flat-grid limit; the corpus at 1% is unchanged), in
//! pricing merges of coplanar clusters at a thicker floor (18: rims stay rims), and in
//! merging inputs of 524,288 faces or more in 16 parallel parts first (19), and in
//! choosing each output primitive by k·V plus its rim reach (24: no curbs standing
//! past the faces beside a cluster), and in letting merges into plates that add no
//! area run before a target's snapshot (25: at most N primitives, no seams where
//! coplanar faces merge for free), and in laying output plates flush on their faces
//! (26: their outer side where the surface is).
//!
//! | setting | default | raising it | lowering it |
//! |---|---|---|---|
//! | `targets` | `[32]` | more, smaller primitives: tighter fit, more bytes | coarser colliders |
//! | `max_excess_volume` | none | (when set) allows costlier merges; `None` = unlimited | stops merging earlier, may leave more than N primitives |
//! | `weights[kind]` | box/sphere/capsule 1.0, cylinder 1.05, frustum 2.1, prism 1.4 | that kind is chosen less often | that kind is chosen more often |
//! | `kinds` | all six | — | a disabled kind is never fitted (faster) |
//! | `tangent_eps` | 0.01 | primitives align more with quad edge directions | at 0, orientation of flat clusters depends on round-off (§3.4) |
//! | `dedup` | exact | `Tolerance(d)` also welds vertices closer than d (fuses parts) | `Off` keeps duplicate vertices: fewer merges across seams |
//! | `min_extent_rel` | 5e-4 | flat clusters cost more: fewer coplanar "free" merges | flatter primitives; 0 is refused |
//! | `merge_min_extent_rel` | none (= `min_extent_rel`) | merges are priced as if primitives were at least this thick: coplanar merges across gaps and holes (a roof's rim into a lid) cost more; output thickness unchanged | — (below `min_extent_rel` it has no effect) |
//! | `flat_merge_extent_rel` | 0.01 | merges of coplanar clusters only are priced as if primitives were this thick (fraction of the diagonal): holes and gaps bridged in a plane cost more, so a roof's rim stays a rim instead of closing into a lid; other merges keep their prices | coplanar merges cost less; 0 = off (the paper's pricing: rims close into lids at low counts) |
//! | `remove_contained` | true | — | keeps nested primitives |
//! | `reprice` | `Deferred { min_degree: 64 }` | merges of clusters with at least `min_degree` neighbours leave their pairs' old queue entries as keys and re-price each when popped; a higher `min_degree` defers fewer merges (`Exact`: none, the paper's order, F^1.5 on large flat regions) | defers more merges: fewer fits, faster, the order drifts from exact greedy; `min_degree: 0` defers all (about 0.8× the time on the corpus, quality mixed: docs/results/reprice.md) |
//! | `partitions` | `Auto` (from 524,288 faces, 16 parts or one per 65,536 faces if more; else 1) | `Fixed(K)`: the faces are split into K spatial parts, merged in parallel (one task each, re-pricing lazily unless `reprice` is `Exact`) to 16× the largest target before the global merge loop: faster on 2+ cores, merges across part boundaries wait (docs/results/partitions.md) | `Fixed(1)`: one global greedy, Alg. 1, on every input |
//! | `reduction` | `Hull` | — | `Extremes`: clusters keep only their extreme points along 13 fixed axes (≤ 26): no convex hull per merge, cheaper fits; merges are priced on an inner approximation, so the order (and the fit) changes: dragon merge stage 9.85 → 8.53 s on one thread (one run), corpus quality no worse on average but mixed per mesh (docs/results/reduction.md) |
//! | `fill` | false | (when set) a target N the post-processing left short of is met by merging less: up to N primitives, each covering fewer faces (tighter fit); costs one merge pass per search round (up to 4 more) | — |
//! | `outward_weight` | 0 | output fits also price how far a primitive reaches past its faces' outer side (the volume balls and bodies meet): w·Σ area·gap is added to k·V when choosing an output frame; merges are priced as before | 0 = off: output frames chosen by k·V alone |
//! | `rim_weight` | 1 | output primitives avoid reaching past the faces just outside their cluster more strongly (a side plate standing past a wall's top as a curb): w·Σ len·gap² over convex boundary edges (creases past 20°, and gentler bends past 2°: a plate standing past a rounded roof's next face) is added to k·V when choosing an output frame and kind; merges are priced as before | less; 0 = off (k·V alone: the least-area plate around a sliver triangle may stand past the neighbouring face) |
//! | `free_merges` | true | — | false: a target N stops at exactly N clusters (the paper) even where the next merges join coplanar clusters into a plate of no more area, e.g. `-n` at the face count merges nothing and leaves a plate per triangle where coplanar triangles make one (seams a rolling ball catches on), and plates in one plane that the merge left apart (not adjacent) stay apart, overlapping where their faces' slivers interleave |
//! | `flush_plates` | true | — | false: an output plate is centred on its faces, standing half the floor thickness (`min_extent_rel`) proud of the surface on its outer side; a ball rests that much higher than on the mesh |
//! | `solid` | false | (when set) merges are priced by the volume their primitive adds outside the input (interior by ray parity on a 64-cell grid) rather than its whole volume: closed parts become one solid primitive instead of a shell of plates, fewer shapes per part in a physics scene; holes and gaps are priced as before | — |
//! | `remove_thin_boxes` | None | (when set) drops boxes thinner than this fraction of the diagonal if still covered | — |

use crate::error::{Error, Result};
use crate::primitive::Kind;
use serde::Serialize;

/// How vertices at (nearly) the same position are merged before building adjacency (§3.4).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Dedup {
    /// No merging: topology exactly as in the file.
    Off,
    /// Merge vertices with bit-identical coordinates (the paper's default).
    Exact,
    /// Merge vertices closer than this distance (world units).
    Tolerance(f64),
}

/// When a merged cluster's merges with its neighbours are re-priced (§3.3, Alg. 1).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Reprice {
    /// Right after every merge: each pop is the cheapest merge at that moment.
    Exact,
    /// Lazy greedy for merges whose clusters' neighbour lists hold at least `min_degree`
    /// entries (about their degree; 0 = every merge): the pairs' old queue entries stay
    /// as their keys, and each is re-priced when popped and pushed back with its fresh
    /// cost. Smaller merges are re-priced at once. Ignored (exact) when
    /// `max_excess_volume` is set: a pair over the cap has no entry to defer.
    Deferred { min_degree: u32 },
}

/// How a merged cluster's points are reduced before its merges are priced (the output
/// is always fitted on all of its faces' vertices, whatever this says).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Reduction {
    /// The vertices of the convex hull: every fit equals the fit on all points.
    #[default]
    Hull,
    /// The extreme points along the 13 axes of a 26-DOP (`math::extremes`): no hull per
    /// merge and at most 26 points per fit, but merges are priced on an inner
    /// approximation of each cluster (docs/results/reduction.md).
    Extremes,
}

/// How many spatial parts the faces are split into and merged in parallel before the
/// global merge loop (`merge::partition`; ARCHITECTURE.md, deviations 17 and 19).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Partitions {
    /// For inputs of at least [`AUTO_MIN_FACES`] faces (large scans, where the parts
    /// cost no measurable quality), [`AUTO_PARTS`] parts or one per [`AUTO_PART_FACES`]
    /// faces if that is more; else one: Alg. 1 as is.
    #[default]
    Auto,
    /// Exactly this many parts; 1 = one global greedy (Alg. 1).
    Fixed(usize),
}

/// Inputs with at least this many faces are split under [`Partitions::Auto`].
pub const AUTO_MIN_FACES: usize = 1 << 19;

/// The fewest parts [`Partitions::Auto`] uses on large inputs.
pub const AUTO_PARTS: usize = 16;

/// [`Partitions::Auto`] gives a part at most about this many faces, so that a part's
/// loop keeps its working set near one core's 1 MiB L2 cache and phase 1's time grows
/// with the input's size, not faster (ARCHITECTURE.md, deviation 19): the 3.5M-face
/// dragon ×4 in 54 parts instead of 16.
pub const AUTO_PART_FACES: usize = 1 << 16;

impl Partitions {
    /// The number of parts for an input of `faces` faces.
    pub fn parts(self, faces: usize) -> usize {
        match self {
            Partitions::Auto if faces >= AUTO_MIN_FACES => {
                AUTO_PARTS.max(faces.div_ceil(AUTO_PART_FACES))
            }
            Partitions::Auto => 1,
            Partitions::Fixed(k) => k,
        }
    }

    /// Whether this setting never splits (serialized settings then omit it).
    fn is_default_like(&self) -> bool {
        matches!(self, Partitions::Auto | Partitions::Fixed(1))
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

/// All settings of a run.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Params {
    /// Target primitive counts; one result per target from a single bottom-up pass.
    pub targets: Vec<usize>,
    /// Optional cap on one merge's excess volume, as a fraction of the input's AABB volume (§3.3).
    pub max_excess_volume: Option<f64>,
    /// Cost weight k(kind) per kind, indexed by `Kind as usize` (§3.3).
    #[serde(serialize_with = "by_kind")]
    pub weights: [f64; 6],
    /// Which kinds may be fitted, indexed by `Kind as usize`.
    #[serde(serialize_with = "by_kind")]
    pub kinds: [bool; 6],
    /// ε of the tangent term in Q = area·(nnᵀ + ε·ttᵀ) (§3.4); 0 disables it.
    pub tangent_eps: f64,
    /// Vertex deduplication (§3.4).
    pub dedup: Dedup,
    /// Minimum half-extent of any primitive as a fraction of the input's AABB diagonal
    /// (the paper's absolute 1e-3, made relative so results do not depend on units).
    pub min_extent_rel: f64,
    /// Minimum half-extent when *pricing* merges, as a fraction of the diagonal (the
    /// larger of this and `min_extent_rel` applies); output primitives keep
    /// `min_extent_rel`. `None`: the same as `min_extent_rel` (the paper's single floor).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub merge_min_extent_rel: Option<f64>,
    /// Minimum half-extent when pricing merges of *coplanar* clusters only, as a
    /// fraction of the diagonal (their cost is scaled as if priced at this floor; the
    /// larger of this and the pricing floor applies; 0 = no special case). Default
    /// 0.01 (ARCHITECTURE.md, deviation 18: rims no longer close into lids).
    pub flat_merge_extent_rel: f64,
    /// Remove primitives whose points lie inside another primitive (§3.4).
    pub remove_contained: bool,
    /// Remove boxes whose smallest half-extent is below this fraction of the diagonal,
    /// when every one of their points lies in another primitive (the Bistro figure's rule).
    pub remove_thin_boxes: Option<f64>,
    /// When merged clusters' pairs are re-priced (exact greedy order or lazy).
    pub reprice: Reprice,
    /// Spatial parts merged in parallel before the global merge loop (`merge::partition`).
    /// Serialized only when it fixes more than one part (the JSON's `stats.partitions`
    /// says how many a run used), so that default runs' output stays as it was.
    #[serde(skip_serializing_if = "Partitions::is_default_like")]
    pub partitions: Partitions,
    /// How merged clusters' points are reduced for pricing; serialized only when not
    /// the exact default.
    #[serde(skip_serializing_if = "is_hull")]
    pub reduction: Reduction,
    /// Fill the budget: when removing nested primitives leaves fewer than a target N,
    /// merge to a larger count whose post-processed result has the most primitives
    /// not above N (budget.rs). Serialized only when set.
    #[serde(skip_serializing_if = "is_false")]
    pub fill: bool,
    /// Weight of the outward reach in the output fit's frame choice: each output
    /// cluster's frame minimises k·V + w·Σ_f area_f·(h(n_f) − n_f·f), h the primitive's
    /// support function, n_f each face's outward normal (its winding). 0 = off; only
    /// serialized when set.
    #[serde(skip_serializing_if = "is_zero")]
    pub outward_weight: f64,
    /// Price merges by the volume their primitive adds outside the input (its interior
    /// from ray parity on a voxel grid, `mesh::solid`) instead of its whole volume:
    /// closed parts fill into solid primitives, gaps and holes are still priced.
    /// Serialized only when set.
    #[serde(skip_serializing_if = "is_false")]
    pub solid: bool,
    /// Weight of the rim reach in the output fit's choice of frame and kind (deviation
    /// 24): each output cluster's primitive minimises k·V + w·Σ_e len_e·gap_e², gap_e
    /// how far it reaches past the plane of the face across each convex boundary edge
    /// e (a crease, or a gentle bend of more than 2°, deviation 29), on the side away
    /// from the cluster (a curb along a wall's top). 0 = off (k·V
    /// alone, the paper's criterion); only serialized when not the default.
    #[serde(skip_serializing_if = "is_default_rim_weight")]
    pub rim_weight: f64,
    /// Whether a target's snapshot waits for the greedy order's next merges while they
    /// are free: coplanar points and cost ≤ 0, a plate of no more area than its parts
    /// (deviation 25). A target N then gives at most N primitives, fewer where faces
    /// merge for free (coplanar triangles into one plate); then plates in one plane
    /// whose boxes touch are joined where one plate covers both with no more k·V and
    /// almost nothing else (deviation 28, `merge::plates`). false = exactly N
    /// clusters, the paper's stop. Serialized only when off.
    #[serde(skip_serializing_if = "is_true")]
    pub free_merges: bool,
    /// Whether an output plate (a primitive at the `min_extent_rel` floor thickness,
    /// its faces all facing one way along its thin axis) lies flush on its faces,
    /// reaching inward from them, instead of centred on them (deviation 26): its outer
    /// side is where the mesh's surface is. false = centred, half the floor proud of
    /// the surface. Serialized only when off.
    #[serde(skip_serializing_if = "is_true")]
    pub flush_plates: bool,
}

/// [`Params::rim_weight`]'s default.
pub const RIM_WEIGHT: f64 = 1.0;

fn is_default_rim_weight(x: &f64) -> bool {
    *x == RIM_WEIGHT
}

fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

fn is_false(b: &bool) -> bool {
    !*b
}

fn is_true(b: &bool) -> bool {
    *b
}

fn is_hull(r: &Reduction) -> bool {
    *r == Reduction::Hull
}

/// The most parts `partitions` may ask for.
pub const MAX_PARTITIONS: usize = 4096;

/// Serializes a per-kind array as `{"box": …, "sphere": …, …}`.
fn by_kind<T: Serialize, S: serde::Serializer>(
    v: &[T; 6],
    s: S,
) -> std::result::Result<S::Ok, S::Error> {
    use serde::ser::SerializeMap;
    let mut m = s.serialize_map(Some(6))?;
    for k in Kind::ALL {
        m.serialize_entry(k.name(), &v[k as usize])?;
    }
    m.end()
}

impl Default for Params {
    fn default() -> Self {
        Params {
            targets: vec![32],
            max_excess_volume: None,
            weights: [1.0, 1.0, 1.0, 1.05, 2.1, 1.4],
            kinds: [true; 6],
            tangent_eps: 0.01,
            dedup: Dedup::Exact,
            min_extent_rel: 5e-4,
            merge_min_extent_rel: None,
            flat_merge_extent_rel: 0.01,
            remove_contained: true,
            remove_thin_boxes: None,
            reprice: Reprice::Deferred { min_degree: 64 },
            partitions: Partitions::Auto,
            reduction: Reduction::Hull,
            fill: false,
            outward_weight: 0.0,
            solid: false,
            rim_weight: RIM_WEIGHT,
            free_merges: true,
            flush_plates: true,
        }
    }
}

impl Params {
    pub fn weight(&self, k: Kind) -> f64 {
        self.weights[k as usize]
    }
    pub fn enabled(&self, k: Kind) -> bool {
        self.kinds[k as usize]
    }
    /// Checks every setting; the driver calls this before any work.
    pub fn validate(&self) -> Result<()> {
        let bad = |m: String| Err(Error::InvalidParams(m));
        if self.targets.is_empty() || self.targets.contains(&0) {
            return bad("targets must be one or more positive counts".into());
        }
        if !self.kinds.iter().any(|&k| k) {
            return bad("at least one primitive kind must be enabled".into());
        }
        for k in Kind::ALL {
            let w = self.weight(k);
            if !(w.is_finite() && w > 0.0) {
                return bad(format!(
                    "weight of {} must be a positive number, got {w}",
                    k.name()
                ));
            }
        }
        if !(self.tangent_eps.is_finite() && self.tangent_eps >= 0.0) {
            return bad(format!("tangent-eps must be ≥ 0, got {}", self.tangent_eps));
        }
        if !(self.min_extent_rel.is_finite()
            && self.min_extent_rel > 0.0
            && self.min_extent_rel < 1.0)
        {
            return bad(format!(
                "min-extent must be in (0, 1), got {}",
                self.min_extent_rel
            ));
        }
        if let Some(m) = self.merge_min_extent_rel {
            if !(m.is_finite() && (0.0..1.0).contains(&m)) {
                return bad(format!("merge-min-extent must be in [0, 1), got {m}"));
            }
        }
        let w = self.outward_weight;
        if !(w.is_finite() && w >= 0.0) {
            return bad(format!("outward-weight must be ≥ 0, got {w}"));
        }
        let w = self.rim_weight;
        if !(w.is_finite() && w >= 0.0) {
            return bad(format!("rim-weight must be ≥ 0, got {w}"));
        }
        let m = self.flat_merge_extent_rel;
        if !(m.is_finite() && (0.0..1.0).contains(&m)) {
            return bad(format!("flat-merge-extent must be in [0, 1), got {m}"));
        }
        if let Some(m) = self.max_excess_volume {
            if !(m.is_finite() && m >= 0.0) {
                return bad(format!("max-excess-volume must be ≥ 0, got {m}"));
            }
        }
        if let Partitions::Fixed(k) = self.partitions {
            if !(1..=MAX_PARTITIONS).contains(&k) {
                return bad(format!(
                    "partitions must be auto or from 1 to {MAX_PARTITIONS}, got {k}"
                ));
            }
        }
        if let Dedup::Tolerance(t) = self.dedup {
            if !(t.is_finite() && t >= 0.0) {
                return bad(format!("dedup tolerance must be ≥ 0, got {t}"));
            }
        }
        if let Some(t) = self.remove_thin_boxes {
            if !(t.is_finite() && t >= 0.0) {
                return bad(format!("thin-box threshold must be ≥ 0, got {t}"));
            }
        }
        Ok(())
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

    /// Settings name the partitions only when they fix more than one part.
    #[test]
    fn partitions_serialize_only_when_fixed_above_one() {
        let json = |k| {
            let p = Params {
                partitions: k,
                ..Default::default()
            };
            serde_json::to_string(&p).unwrap()
        };
        assert!(!json(Partitions::Auto).contains("partitions"));
        assert!(!json(Partitions::Fixed(1)).contains("partitions"));
        assert!(json(Partitions::Fixed(8)).contains("\"partitions\":8"));
        let zero = Params {
            partitions: Partitions::Fixed(0),
            ..Default::default()
        };
        assert!(zero.validate().is_err());
    }
}
