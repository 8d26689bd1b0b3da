//! The settings as results record them (a result's `settings` object, the settings
//! the C ABI and WebAssembly take): the flat shape of every version so far, so old
//! files still read and results stay byte-identical. [`Params`] is read from and
//! written as this shape; the goal's keys (`targets`, `tolerance`, `max_bytes`, `cut`,
//! `greedy`, `fill`) become one [`Goal`], and a combination no goal can be
//! (a greedy or filled tolerance, fill without counts) is refused with its reason.

use super::{Dedup, Fit, Goal, Params, Partitions, Plates, Reprice, Tolerance};
use serde::{Deserialize, Serialize};

/// Every setting under its JSON key, in the order results write them.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub(crate) struct Settings {
    targets: Vec<usize>,
    #[serde(with = "by_kind")]
    kinds: [bool; 6],
    #[serde(with = "by_kind")]
    weights: [f64; 6],
    tangent_eps: f64,
    dedup: Dedup,
    min_extent: f64,
    max_excess_volume: Option<f64>,
    remove_nested: bool,
    remove_thin_boxes: Option<f64>,
    open_holes: f64,
    rim_weight: f64,
    flush_plates: bool,
    join_coplanar: bool,
    solid: bool,
    // A setting left off is not written, so documents made before it existed stay
    // byte-identical.
    #[serde(skip_serializing_if = "is_zero")]
    min_thickness: f64,
    fill: bool,
    #[serde(skip_serializing_if = "is_false")]
    greedy: bool,
    cut: bool,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    tolerance: Vec<Tolerance>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    max_bytes: Vec<usize>,
    reprice: Reprice,
    partitions: Partitions,
}

impl Default for Settings {
    fn default() -> Self {
        let p = Params::default();
        Settings {
            // Keys of the goal left out: a run of the default goal.
            targets: Vec::new(),
            fill: false,
            greedy: false,
            cut: false,
            tolerance: Vec::new(),
            max_bytes: Vec::new(),
            ..Settings::from(p)
        }
    }
}

/// Whether `x` is 0.
fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

/// Whether `b` is false.
fn is_false(b: &bool) -> bool {
    !*b
}

/// The settings a run records: the goal's counts or caps for every level, and
/// whether its levels are cuts of the merge tree.
impl From<Params> for Settings {
    fn from(p: Params) -> Settings {
        let (mut tolerance, mut max_bytes) = (Vec::new(), Vec::new());
        let (mut fill, mut greedy) = (false, false);
        match &p.goal {
            Goal::Greedy { .. } => greedy = true,
            Goal::Counts { .. } | Goal::Cut { .. } => {}
            Goal::Fill { .. } => fill = true,
            Goal::Within {
                tolerance: t,
                max_bytes: b,
                ..
            } => (tolerance, max_bytes) = (t.clone(), b.clone()),
        }
        Settings {
            targets: p.goal.targets(),
            kinds: p.fit.kinds,
            weights: p.fit.weights,
            tangent_eps: p.fit.tangent_eps,
            dedup: p.fit.dedup,
            min_extent: p.fit.min_extent,
            max_excess_volume: p.fit.max_excess_volume,
            remove_nested: p.plates.remove_nested,
            remove_thin_boxes: p.plates.remove_thin_boxes,
            open_holes: p.plates.open_holes,
            rim_weight: p.plates.rim_weight,
            flush_plates: p.plates.flush_plates,
            join_coplanar: p.plates.join_coplanar,
            solid: p.plates.solid,
            min_thickness: p.plates.min_thickness,
            fill,
            greedy,
            cut: p.goal.uses_cut(),
            tolerance,
            max_bytes,
            reprice: p.reprice,
            partitions: p.partitions,
        }
    }
}

impl TryFrom<Settings> for Params {
    type Error = String;

    fn try_from(s: Settings) -> Result<Params, String> {
        Ok(Params {
            goal: goal(&s)?,
            fit: Fit {
                kinds: s.kinds,
                weights: s.weights,
                tangent_eps: s.tangent_eps,
                dedup: s.dedup,
                min_extent: s.min_extent,
                max_excess_volume: s.max_excess_volume,
            },
            plates: Plates {
                open_holes: s.open_holes,
                rim_weight: s.rim_weight,
                flush_plates: s.flush_plates,
                join_coplanar: s.join_coplanar,
                solid: s.solid,
                min_thickness: s.min_thickness,
                remove_nested: s.remove_nested,
                remove_thin_boxes: s.remove_thin_boxes,
            },
            reprice: s.reprice,
            partitions: s.partitions,
        })
    }
}

/// The goal the flat keys describe: a tolerance or byte budget (the counts its caps),
/// a fill or greedy counts, counts cut from the merge tree (`cut`), counts, or without
/// any of them the default goal (`cut` alone asks for nothing more).
fn goal(s: &Settings) -> Result<Goal, String> {
    let within = !s.tolerance.is_empty() || !s.max_bytes.is_empty();
    if s.fill && s.targets.is_empty() {
        return Err("fill needs targets: the counts whose levels it fills".into());
    }
    if s.fill && (within || s.cut) {
        return Err(
            "fill refines the greedy snapshot; cut, tolerance and max_bytes already fill \
             each target from the merge tree"
                .into(),
        );
    }
    if s.greedy && (within || s.cut) {
        return Err(
            "greedy takes the greedy pass's levels: not with cut, tolerance or max_bytes".into(),
        );
    }
    if s.greedy && s.targets.is_empty() {
        return Err("greedy needs targets: the counts whose greedy levels it takes".into());
    }
    let counts = s.targets.clone();
    Ok(match () {
        () if within => Goal::Within {
            caps: counts,
            tolerance: s.tolerance.clone(),
            max_bytes: s.max_bytes.clone(),
        },
        () if s.fill => Goal::Fill { counts },
        () if counts.is_empty() => Goal::default(),
        () if s.greedy => Goal::Greedy { counts },
        () if s.cut => Goal::cut_counts(counts),
        () => Goal::counts(counts),
    })
}

/// Per-kind arrays as `{"box": …, "sphere": …, …}` (every kind named, in order).
mod by_kind {
    use crate::primitive::Kind;
    use serde::de::{Deserialize, Deserializer, Error};
    use serde::ser::{SerializeMap, Serializer};
    use serde::Serialize;
    use std::collections::BTreeMap;

    pub fn serialize<T: Serialize, S: Serializer>(v: &[T; 6], s: S) -> Result<S::Ok, S::Error> {
        let mut m = s.serialize_map(Some(6))?;
        for k in Kind::ALL {
            m.serialize_entry(k.name(), &v[k as usize])?;
        }
        m.end()
    }

    pub fn deserialize<'de, T, D>(d: D) -> Result<[T; 6], D::Error>
    where
        T: Deserialize<'de> + Copy,
        D: Deserializer<'de>,
    {
        let map = BTreeMap::<String, T>::deserialize(d)?;
        for name in map.keys() {
            if Kind::from_name(name).is_none() {
                return Err(D::Error::custom(format!(
                    "unknown primitive kind \"{name}\" (expected box, sphere, capsule, \
                     cylinder, frustum or prism)"
                )));
            }
        }
        let get = |k: Kind| map.get(k.name()).copied();
        let missing = Kind::ALL.into_iter().find(|&k| get(k).is_none());
        if let Some(k) = missing {
            return Err(D::Error::custom(format!(
                "kind \"{}\" is missing",
                k.name()
            )));
        }
        Ok(Kind::ALL.map(|k| get(k).expect("checked above")))
    }
}
