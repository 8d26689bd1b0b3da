//! Per-object decomposition (`--per-object`): each named part of the input
//! (a glTF mesh node, an OBJ `o`/`g` group) is decomposed on its own with
//! [`decompose`](crate::decompose()) and keeps its name. A glTF node's faces are
//! decomposed in the node's own frame (its world transform's similarity part, see
//! [`Frame::from_matrix`]), so the colliders move with the node; OBJ groups have the
//! identity frame.
//!
//! A target given as a total count is shared by [`share_targets`]: one primitive per
//! object, the rest in proportion to the objects' surface areas, rounded by largest
//! remainder (ties to the earlier object) so the shares add up to the total exactly
//! ([`SHARE_RULE`]). A percentage applies to each object's own face count.

use crate::decompose::decompose;
use crate::error::Result;
use crate::input::mesh::Mesh;
use crate::output::body::Body;
use crate::output::frame::{conservative, Frame};
use crate::output::result::{Decomposition, InputInfo};
use crate::params::{Params, Target};
use crate::primitive::Primitive;

/// The sharing rule of a total target, as stated in the JSON and `--help`.
pub const SHARE_RULE: &str = "a total count N is shared by the objects: one each, the other N - k (k objects) in proportion to surface area, largest remainder (ties to the earlier object); with N < k each object still gets one. A percentage applies to each object's faces.";

/// One object's whole result ([`Objects::objects`]): its name, frame, size and
/// decomposition, every level. One level of it, as the exporters take it, is a
/// [`Body`] ([`Objects::bodies`]).
///
/// ```
/// use primdecomp::{Mesh, MeshFormat, Objects, Params, Target};
///
/// let obj = b"o a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n\
///             o b\nv 5 0 0\nv 7 0 0\nv 5 2 0\nv 5 0 2\nf 5 7 6\nf 5 6 8\nf 5 8 7\nf 6 7 8\n";
/// let mesh = Mesh::parse(obj, MeshFormat::Obj, "two.obj".as_ref())?;
/// let objects = Objects::decompose(&mesh, &Params::default(), &[Target::Count(2)])?;
/// let b = &objects.objects[1];
/// assert_eq!((b.name.as_str(), b.faces), ("b", 4));
/// assert!(b.area > objects.objects[0].area); // twice the size: four times the area
/// assert_eq!(b.decomposition.levels.len(), 1);
/// # Ok::<(), primdecomp::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct ObjectResult {
    /// The name the file gives it (empty for faces before the first OBJ name).
    pub name: String,
    /// Where its primitives live: world = `frame.point(local)`.
    pub frame: Frame,
    /// Its input faces.
    pub faces: usize,
    /// Its surface area (in world units), the share rule's weight.
    pub area: f64,
    /// Its decomposition, primitives in the object's frame; `levels[i]` answers the
    /// `i`-th target of [`Objects::targets`].
    pub decomposition: Decomposition,
}

/// The per-object result of a whole input: each named part (an OBJ `o`/`g`, a glTF
/// mesh node, [`Mesh::objects`]) decomposed on its own and named
/// ([`Objects::decompose`]); written as one JSON by [`Objects::to_json`].
///
/// ```
/// use primdecomp::{Mesh, MeshFormat, Objects, Params, Target};
///
/// let obj = b"o a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n\
///             o b\nv 5 0 0\nv 7 0 0\nv 5 2 0\nv 5 0 2\nf 5 7 6\nf 5 6 8\nf 5 8 7\nf 6 7 8\n";
/// let mesh = Mesh::parse(obj, MeshFormat::Obj, "two.obj".as_ref())?;
/// // 4 primitives shared by the two objects, and 100% of each object's faces.
/// let targets = [Target::Count(4), Target::Percent(100.0)];
/// let objects = Objects::decompose(&mesh, &Params::default(), &targets)?;
/// assert_eq!(objects.levels(), 2);
/// let names: Vec<&str> = objects.objects.iter().map(|o| o.name.as_str()).collect();
/// assert_eq!(names, ["a", "b"]);
/// assert!(!objects.world_primitives(0).is_empty());
/// # Ok::<(), primdecomp::Error>(())
/// ```
#[derive(Clone, Debug, Default)]
pub struct Objects {
    /// The whole input (as [`Decomposition::input`]).
    pub input: InputInfo,
    /// The targets as given, one per level, largest first.
    pub targets: Vec<Target>,
    /// Each object's result, in the file's order.
    pub objects: Vec<ObjectResult>,
}

impl Objects {
    /// Number of levels (one per distinct target).
    pub fn levels(&self) -> usize {
        self.targets.len()
    }

    /// Every primitive of level `level` in world coordinates, object after object,
    /// each grown by the rounding margin of the engine exports so that it contains the
    /// object-frame primitive moved into the world.
    pub fn world_primitives(&self, level: usize) -> Vec<Primitive> {
        self.objects
            .iter()
            .flat_map(|o| {
                o.decomposition.levels[level]
                    .primitives
                    .iter()
                    .map(|p| conservative(p, &o.frame, 0.0))
            })
            .collect()
    }

    /// Level `level` as the exporters take it: each object's name, frame and primitives
    /// in that frame, object after object (what [`crate::ResultFile::read`] gives back
    /// from [`Objects::to_json`]).
    ///
    /// ```
    /// use primdecomp::{Mesh, MeshFormat, Objects, Params, Target};
    ///
    /// let obj = b"o a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    /// let mesh = Mesh::parse(obj, MeshFormat::Obj, "one.obj".as_ref())?;
    /// let objects = Objects::decompose(&mesh, &Params::default(), &[Target::Count(1)])?;
    /// let bodies = objects.bodies(0);
    /// assert_eq!((bodies[0].name.as_str(), bodies[0].primitives.len()), ("a", 1));
    /// # Ok::<(), primdecomp::Error>(())
    /// ```
    pub fn bodies(&self, level: usize) -> Vec<Body> {
        self.objects
            .iter()
            .map(|o| Body {
                name: o.name.clone(),
                frame: o.frame,
                primitives: o.decomposition.levels[level].primitives.clone(),
            })
            .collect()
    }

    /// The farthest any primitive of level `level` stands from its object, in world
    /// units (each object's [`crate::Level::distance`] times its frame's scale): the
    /// largest over the objects, `None` when no object's level measured one (counts
    /// taken greedily).
    ///
    /// ```
    /// use primdecomp::{Mesh, MeshFormat, Objects, Params, Target};
    ///
    /// let obj = b"o a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n\
    ///             o b\nv 5 0 0\nv 7 0 0\nv 5 2 0\nv 5 0 2\nf 5 7 6\nf 5 6 8\nf 5 8 7\nf 6 7 8\n";
    /// let mesh = Mesh::parse(obj, MeshFormat::Obj, "two.obj".as_ref())?;
    /// // The default goal: within 2% of each object's diagonal.
    /// let objects = Objects::decompose(&mesh, &Params::default(), &[Target::Count(4)])?;
    /// let farthest = objects.distance(0).expect("a tolerance run measures its distance");
    /// let each = objects.objects.iter().map(|o| o.decomposition.levels[0].distance.unwrap());
    /// assert_eq!(farthest, each.fold(0.0, f64::max));
    /// # Ok::<(), primdecomp::Error>(())
    /// ```
    pub fn distance(&self, level: usize) -> Option<f64> {
        self.objects
            .iter()
            .filter_map(|o| Some(o.decomposition.levels[level].distance? * o.frame.scale))
            .reduce(f64::max)
    }
}

/// Shares `total` primitives among objects of the given surface areas
/// ([`SHARE_RULE`]). Areas that are all zero (or not finite) share equally.
pub fn share_targets(total: usize, areas: &[f64]) -> Vec<usize> {
    let k = areas.len();
    if k == 0 {
        return Vec::new();
    }
    let mut out = vec![1usize; k];
    let rest = total.saturating_sub(k);
    if rest == 0 {
        return out;
    }
    let sum: f64 = areas.iter().filter(|a| a.is_finite() && **a > 0.0).sum();
    let weights: Vec<f64> = if sum > 0.0 && sum.is_finite() {
        areas
            .iter()
            .map(|&a| {
                if a.is_finite() && a > 0.0 {
                    a / sum
                } else {
                    0.0
                }
            })
            .collect()
    } else {
        vec![1.0 / k as f64; k]
    };
    let exact: Vec<f64> = weights.iter().map(|w| w * rest as f64).collect();
    let mut given = 0usize;
    for (o, e) in out.iter_mut().zip(&exact) {
        let f = e.floor() as usize;
        *o += f;
        given += f;
    }
    let mut order: Vec<usize> = (0..k).collect();
    // Largest remainder first; ties to the earlier object (stable sort).
    order.sort_by(|&a, &b| {
        let (ra, rb) = (exact[a] - exact[a].floor(), exact[b] - exact[b].floor());
        rb.total_cmp(&ra)
    });
    for &i in order.iter().cycle().take(rest.saturating_sub(given)) {
        out[i] += 1;
    }
    out
}

/// Surface area of faces `faces` of `mesh` (world units: re-centring does not
/// change areas).
fn area(mesh: &Mesh, faces: std::ops::Range<usize>) -> f64 {
    faces.map(|f| 0.5 * crate::math::norm(mesh.newell(f))).sum()
}

/// The most objects [`Objects::decompose`] takes: each object is a decomposition of
/// its own (about 0.3 ms of set-up each, measured on 40,000 one-triangle groups), so a
/// million groups would run for minutes to give a million single primitives.
pub(crate) const MAX_OBJECTS: usize = 65_536;

impl Objects {
    /// Decomposes each object of `mesh` ([`Mesh::objects`]) on its own, with `params`
    /// but the targets of `targets` (shared or per object, see the module doc); levels
    /// come largest target first, as `decompose`'s. Deterministic: the objects run one
    /// after another, each on all threads.
    pub fn decompose(mesh: &Mesh, params: &Params, targets: &[Target]) -> Result<Objects> {
        let parts = mesh.parts();
        if parts.len() > MAX_OBJECTS {
            return Err(crate::error::Error::InvalidParams(format!(
                "the mesh has {} objects; per-object decomposition takes at most {MAX_OBJECTS} \
                 (each is decomposed on its own): decompose the mesh whole",
                parts.len()
            )));
        }
        let areas: Vec<f64> = parts.iter().map(|o| area(mesh, o.faces.clone())).collect();
        let targets = in_level_order(targets, mesh.face_count());
        // Per target, each object's share.
        let shares: Vec<Vec<usize>> = targets
            .iter()
            .map(|t| match *t {
                Target::Count(n) => share_targets(n, &areas),
                Target::Percent(_) => parts.iter().map(|o| t.count(o.faces.len())).collect(),
            })
            .collect();
        let mut objects = Vec::with_capacity(parts.len());
        for (i, part) in parts.iter().enumerate() {
            let frame = part.transform.map(Frame::from_matrix).unwrap_or_default();
            let sub = sub_mesh(mesh, part.faces.clone(), &frame)?;
            let mine: Vec<usize> = shares.iter().map(|s| s[i]).collect();
            let p = Params {
                goal: params.goal.with_targets(mine.clone()),
                ..params.clone()
            };
            let dec = decompose(&sub, &p)?;
            // decompose gives one level per distinct target, largest first; expand to
            // one per requested target.
            let levels = mine
                .iter()
                .map(|t| {
                    dec.levels
                        .iter()
                        .find(|l| l.target == *t)
                        .cloned()
                        .unwrap_or_default()
                })
                .collect();
            objects.push(ObjectResult {
                name: part.name.to_string(),
                frame,
                faces: part.faces.len(),
                area: areas[i],
                decomposition: Decomposition { levels, ..dec },
            });
        }
        Ok(Objects {
            input: crate::decompose::stages::input_info(mesh, mesh.aabb()),
            targets,
            objects,
        })
    }
}

/// `targets` in decompose's order of levels: largest first (percentages of `faces` by
/// their value, counts by theirs; a mix keeps the given order among equals), each
/// once.
fn in_level_order(targets: &[Target], faces: usize) -> Vec<Target> {
    let mut targets = targets.to_vec();
    let key = |t: &Target| match *t {
        Target::Count(n) => n as f64,
        Target::Percent(p) => p * faces as f64 / 100.0,
    };
    targets.sort_by(|a, b| key(b).total_cmp(&key(a)));
    targets.dedup();
    targets
}

/// The faces `faces` of `mesh` with only their vertices, in `frame`'s coordinates.
fn sub_mesh(mesh: &Mesh, faces: std::ops::Range<usize>, frame: &Frame) -> Result<Mesh> {
    let mut map = rustc_hash::FxHashMap::default();
    let mut positions = Vec::new();
    let polys: Vec<Vec<u32>> = faces
        .map(|f| {
            mesh.face(f)
                .iter()
                .map(|&v| {
                    *map.entry(v).or_insert_with(|| {
                        positions.push(frame.inverse_point(mesh.world_pos(v)));
                        (positions.len() - 1) as u32
                    })
                })
                .collect()
        })
        .collect();
    Mesh::from_polygons(&positions, &polys)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shares_add_up_and_follow_area() {
        assert_eq!(share_targets(10, &[1.0, 1.0]), vec![5, 5]);
        assert_eq!(share_targets(10, &[3.0, 1.0]), vec![7, 3]);
        assert_eq!(share_targets(2, &[100.0, 1.0, 1.0]), vec![1, 1, 1]);
        assert_eq!(share_targets(5, &[0.0, 0.0]), vec![3, 2]);
        let s = share_targets(100, &[1.0, 2.0, 3.0, 0.5, 7.25]);
        assert_eq!(s.iter().sum::<usize>(), 100);
        assert!(s.iter().all(|&x| x >= 1));
        assert!(s[4] > s[2] && s[2] > s[1] && s[1] > s[0] && s[0] > s[3]);
        assert!(share_targets(3, &[]).is_empty());
    }

    #[test]
    fn ties_go_to_the_earlier_object() {
        // 1 + 1 + 1 each, one left over, equal remainders.
        assert_eq!(share_targets(4, &[1.0, 1.0, 1.0]), vec![2, 1, 1]);
    }
}
