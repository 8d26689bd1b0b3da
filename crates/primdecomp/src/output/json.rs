//! The JSON result contract: one document per target level with the input's
//! description, every effective setting, statistics and the primitives (stage timings
//! under `stats.seconds` only when asked for, [`to_json_timed`]: without them the
//! document is byte-identical across runs and thread counts),
//! rotations as scalar-last unit quaternions. The reverse direction is
//! [`super::read`].

use crate::decompose::objects::{ObjectResult, Objects, SHARE_RULE};
use crate::math::quat::quat_from_axes;
use crate::math::V3;
use crate::output::result::{Decomposition, InputInfo, Level};
use crate::params::Params;
use crate::params::Target;
use crate::primitive::{Kind, Primitive};
use serde::ser::{SerializeMap, Serializer};
use serde::{Deserialize, Serialize};

/// One primitive as it appears in the `primitives` array.
#[derive(Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "lowercase")]
pub(super) enum PrimJson {
    Box {
        center: V3,
        rotation: [f64; 4],
        half_extents: V3,
        #[serde(default)]
        faces: u32,
    },
    Sphere {
        center: V3,
        radius: f64,
        #[serde(default)]
        faces: u32,
    },
    Capsule {
        p0: V3,
        p1: V3,
        radius: f64,
        #[serde(default)]
        faces: u32,
    },
    Cylinder {
        p0: V3,
        p1: V3,
        radius: f64,
        #[serde(default)]
        faces: u32,
    },
    Frustum {
        p0: V3,
        p1: V3,
        radius0: f64,
        radius1: f64,
        #[serde(default)]
        faces: u32,
    },
    Prism {
        center: V3,
        rotation: [f64; 4],
        half_x: f64,
        half_y: f64,
        half_z_top: f64,
        half_z_bottom: f64,
        /// z of the top side's midpoint (the bottom's is −shift_z); absent for the
        /// paper's isosceles prism.
        #[serde(default, skip_serializing_if = "is_zero")]
        shift_z: f64,
        #[serde(default)]
        faces: u32,
    },
}

fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

impl PrimJson {
    pub(super) fn new(p: &Primitive, faces: u32) -> PrimJson {
        match *p {
            Primitive::Box(b) => PrimJson::Box {
                center: b.center,
                rotation: quat_from_axes(&b.axes),
                half_extents: b.half,
                faces,
            },
            Primitive::Sphere(s) => PrimJson::Sphere {
                center: s.center,
                radius: s.radius,
                faces,
            },
            Primitive::Capsule(c) => PrimJson::Capsule {
                p0: c.p0,
                p1: c.p1,
                radius: c.radius,
                faces,
            },
            Primitive::Cylinder(c) => PrimJson::Cylinder {
                p0: c.p0,
                p1: c.p1,
                radius: c.radius,
                faces,
            },
            Primitive::Frustum(f) => PrimJson::Frustum {
                p0: f.p0,
                p1: f.p1,
                radius0: f.r0,
                radius1: f.r1,
                faces,
            },
            Primitive::Prism(p) => PrimJson::Prism {
                center: p.center,
                rotation: quat_from_axes(&p.axes),
                half_x: p.hx,
                half_y: p.hy,
                half_z_top: p.hz_top,
                half_z_bottom: p.hz_bottom,
                shift_z: p.shift,
                faces,
            },
        }
    }
}

/// Primitive counts keyed by kind name, in [`Kind::ALL`] order.
struct Counts([usize; 6]);

impl Serialize for Counts {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut m = s.serialize_map(Some(6))?;
        for k in Kind::ALL {
            m.serialize_entry(k.name(), &self.0[k as usize])?;
        }
        m.end()
    }
}

/// Stage timings in run order, then `"total"`.
struct Seconds<'a>(&'a Decomposition);

impl Serialize for Seconds<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut m = s.serialize_map(Some(self.0.timings.len() + 1))?;
        for (stage, secs) in &self.0.timings {
            m.serialize_entry(stage, secs)?;
        }
        m.serialize_entry("total", &self.0.seconds())?;
        m.end()
    }
}

#[derive(Serialize)]
struct Settings<'a> {
    #[serde(flatten)]
    params: &'a Params,
    target: usize,
    /// With `--per-object` and a total count: how it was shared.
    #[serde(skip_serializing_if = "Option::is_none")]
    share_rule: Option<&'static str>,
    /// With `--per-object` and a percentage: the percentage (`target` is the sum of
    /// the objects' shares).
    #[serde(skip_serializing_if = "Option::is_none")]
    percent: Option<f64>,
    /// Where the merge loop stopped, when `fill` made it differ from `target`.
    #[serde(skip_serializing_if = "Option::is_none")]
    merge_target: Option<usize>,
}

#[derive(Serialize)]
struct Stats<'a> {
    counts: Counts,
    primitives: usize,
    bytes: usize,
    /// Spatial parts merged in parallel first (1 = none).
    partitions: usize,
    #[serde(skip_serializing_if = "Option::is_none")]
    seconds: Option<Seconds<'a>>,
    /// A cut's limits and the distance it reached (a cut of the merge tree: `Goal`'s `tolerance`,
    /// `max_bytes`).
    #[serde(skip_serializing_if = "Option::is_none")]
    distance: Option<Distance>,
}

/// How far a cut's primitives stand from the input, and what was asked.
#[derive(Serialize)]
struct Distance {
    /// The estimated farthest any primitive stands from the input, input units.
    worst: f64,
    /// The same over the input's bounding-box diagonal.
    of_diagonal: f64,
    /// The level's tolerance, input units.
    #[serde(skip_serializing_if = "Option::is_none")]
    tolerance: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    max_bytes: Option<usize>,
    /// Over the tolerance: what stopped the cut nearer (`count`, `bytes` or `faces`).
    #[serde(skip_serializing_if = "Option::is_none")]
    limited_by: Option<crate::output::result::Shortfall>,
    /// `"solid"` where `worst` is measured to the input's solid, not its surface
    /// (`Level::distance_to_solid`); absent for the surface.
    #[serde(skip_serializing_if = "Option::is_none")]
    measured_to: Option<&'static str>,
    method: &'static str,
}

/// How [`Distance::worst`] is measured (`cut::error`).
const DISTANCE_METHOD: &str = "an upper bound of the one-way distance from each primitive's \
     surface to the input's surface (docs/decisions/0040): its conservative tessellation (fine \
     enough to stand at most 0.1% of the input's diagonal outside a round primitive, which is \
     added) cut into triangles refined best-first, each bounded by its centroid's exact \
     distance plus its size, or by its corners' distances to the input triangle nearest its \
     centroid, or (a round primitive's, once its search has run long) by the distances along \
     its normal to the input triangles below it (docs/decisions/0047); refined until within \
     2% (or 0.02% of the diagonal) of the farthest point measured, and until it is on one \
     side of the tolerance; the largest over all primitives (at least `primdecomp eval`'s \
     sampled Hausdorff)";

/// How [`Distance::worst`] is measured under `--solid` on an input with an inside
/// (`cut::error`, docs/decisions/0056).
const DISTANCE_METHOD_SOLID: &str = "an upper bound of the one-way distance from each \
     primitive's surface to the input's solid (--solid, docs/decisions/0056): as to the \
     surface (docs/decisions/0040), but a point proven inside the input stands at 0 (the \
     --solid grid's cell holding it is inside by the vote of its six axis rays, and the \
     point is nearer that cell's centre than the surface is), and a cell of the \
     tessellation within its centroid's distance to the surface of a centroid proven \
     inside lies wholly inside; at least `primdecomp eval --solid`'s sampled Hausdorff";

impl Distance {
    /// A per-object level's: the farthest object's distance, without the tolerance or
    /// byte budget (each object's is its own share); measured to the solid where some
    /// object's was (`to_solid`).
    fn farthest(worst: f64, to_solid: bool, input: &InputInfo) -> Distance {
        let diagonal = input.diagonal();
        Distance {
            worst,
            of_diagonal: if diagonal > 0.0 {
                worst / diagonal
            } else {
                0.0
            },
            tolerance: None,
            max_bytes: None,
            limited_by: None,
            measured_to: to_solid.then_some("solid"),
            method: match to_solid {
                true => DISTANCE_METHOD_SOLID,
                false => DISTANCE_METHOD,
            },
        }
    }

    fn of(lv: &Level, input: &InputInfo) -> Option<Distance> {
        Some(Distance {
            tolerance: lv.tolerance,
            max_bytes: lv.max_bytes,
            limited_by: lv.shortfall,
            ..Distance::farthest(lv.distance?, lv.distance_to_solid, input)
        })
    }
}

#[derive(Serialize)]
struct Document<'a> {
    format: &'static str,
    version: u32,
    input: &'a crate::output::result::InputInfo,
    settings: Settings<'a>,
    stats: Stats<'a>,
    primitives: Vec<PrimJson>,
    /// With `--per-object` only: each object with its frame and its primitives in
    /// that frame (`primitives` above holds them all in world coordinates).
    #[serde(skip_serializing_if = "Option::is_none")]
    objects: Option<Vec<ObjectJson>>,
}

/// One object of a per-object result: world = translation + scale · R(rotation) ·
/// local, rotation a scalar-last unit quaternion.
#[derive(Serialize, Deserialize)]
pub(super) struct ObjectJson {
    pub(super) name: String,
    pub(super) translation: V3,
    pub(super) rotation: [f64; 4],
    pub(super) scale: f64,
    #[serde(default)]
    faces: usize,
    #[serde(default)]
    pub(super) target: usize,
    /// The farthest any of its primitives stands from it, world units (a level that
    /// measured it: a tolerance or byte budget).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    distance: Option<f64>,
    pub(super) primitives: Vec<PrimJson>,
}

impl Decomposition {
    /// The JSON document of `self.levels[level]` (panics if `level` is out of range),
    /// the result contract every tool reads ([`crate::ResultFile::read`]):
    /// pretty-printed, 2-space indent, arrays of plain numbers on one line, ending in a
    /// newline. `params` are the settings the run was given, recorded under
    /// `settings`. It depends only on the input and the settings (byte-identical
    /// across runs and thread counts): no timings.
    ///
    /// ```
    /// use primdecomp::{decompose, Goal, Mesh, Params, ResultFile};
    ///
    /// let corners = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    /// let tetrahedron = Mesh::from_triangles(&corners, &[[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])?;
    /// let params = Params { goal: Goal::counts([1]), ..Params::default() };
    /// let result = decompose(&tetrahedron, &params)?;
    /// let json = result.to_json(0, &params);
    /// assert!(json.starts_with("{\n  \"format\": \"primdecomp\""));
    /// let back = ResultFile::read(&json, "result.json".as_ref())?;
    /// assert_eq!(back.primitives.len(), result.levels[0].primitives.len());
    /// # Ok::<(), primdecomp::Error>(())
    /// ```
    pub fn to_json(&self, level: usize, params: &Params) -> String {
        document(self, level, params, false)
    }

    /// [`Decomposition::to_json`] plus the stage timings under `stats.seconds`
    /// (the command line's `--timings`): no longer byte-identical between runs.
    ///
    /// ```
    /// use primdecomp::{decompose, Goal, Mesh, Params};
    ///
    /// let corners = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    /// let tetrahedron = Mesh::from_triangles(&corners, &[[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])?;
    /// let params = Params { goal: Goal::counts([1]), ..Params::default() };
    /// let result = decompose(&tetrahedron, &params)?;
    /// assert!(result.to_json_timed(0, &params).contains("\"seconds\""));
    /// assert!(!result.to_json(0, &params).contains("\"seconds\""));
    /// # Ok::<(), primdecomp::Error>(())
    /// ```
    pub fn to_json_timed(&self, level: usize, params: &Params) -> String {
        document(self, level, params, true)
    }
}

/// [`Decomposition::to_json`].
#[cfg(test)]
pub(crate) fn to_json(dec: &Decomposition, level: usize, params: &Params) -> String {
    document(dec, level, params, false)
}

fn document(dec: &Decomposition, level: usize, params: &Params, timed: bool) -> String {
    let lv = &dec.levels[level];
    debug_assert_eq!(
        lv.faces.len(),
        lv.primitives.len(),
        "one face count per primitive"
    );
    let primitives: Vec<PrimJson> = lv
        .primitives
        .iter()
        .enumerate()
        .map(|(i, p)| PrimJson::new(p, lv.faces.get(i).copied().unwrap_or(0)))
        .collect();
    // serde_json writes non-finite floats as `null`, which no primitive field holds.
    debug_assert!(
        !serde_json::to_string(&primitives)
            .unwrap_or_default()
            .contains("null"),
        "non-finite number in a primitive"
    );
    debug_assert!(
        dec.input
            .aabb_min
            .iter()
            .chain(&dec.input.aabb_max)
            .all(|x| x.is_finite()),
        "non-finite input bounds"
    );
    let doc = Document {
        format: super::contract::FORMAT,
        version: super::contract::VERSION as u32,
        input: &dec.input,
        settings: Settings {
            params,
            target: lv.target,
            share_rule: None,
            percent: None,
            merge_target: (lv.merged_to > lv.target).then_some(lv.merged_to),
        },
        stats: Stats {
            counts: Counts(lv.counts()),
            primitives: lv.primitives.len(),
            bytes: lv.bytes(),
            partitions: dec.stats.partitions,
            seconds: timed.then_some(Seconds(dec)),
            distance: Distance::of(lv, &dec.input),
        },
        primitives,
        objects: None,
    };
    finish(&doc)
}

fn finish(doc: &Document) -> String {
    let pretty = serde_json::to_string_pretty(doc).expect("serializing plain data cannot fail");
    let mut out = inline_scalar_arrays(&pretty);
    out.push('\n');
    out
}

impl Objects {
    /// The JSON document of level `level` of a per-object result (`--per-object`): as
    /// [`Decomposition::to_json`], with `primitives` holding every object's primitives
    /// in world coordinates ([`Objects::world_primitives`]) and `objects` each object's
    /// name, frame, share of the target and primitives in its frame.
    /// `settings.target` is the total as given (or the sum of the shares for a
    /// percentage).
    ///
    /// ```
    /// use primdecomp::{Mesh, Objects, Params, ResultFile, Target};
    ///
    /// let obj = b"o left\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n\
    ///             o right\nv 5 0 0\nv 6 0 0\nv 5 1 0\nv 5 0 1\nf 5 7 6\nf 5 6 8\nf 5 8 7\nf 6 7 8\n";
    /// let mesh = Mesh::parse(obj, primdecomp::MeshFormat::Obj, "two.obj".as_ref())?;
    /// let params = Params::default();
    /// let objects = Objects::decompose(&mesh, &params, &[Target::Count(2)])?;
    /// let back = ResultFile::read(&objects.to_json(0, &params), "two.json".as_ref())?;
    /// assert_eq!(back.objects.len(), 2);
    /// assert_eq!(back.objects[0].name, "left");
    /// # Ok::<(), primdecomp::Error>(())
    /// ```
    pub fn to_json(&self, level: usize, params: &Params) -> String {
        to_json_objects(self, level, params)
    }
}

impl ObjectJson {
    /// Object `o`'s level `level`: its name, frame, share and primitives in its frame.
    fn new(o: &ObjectResult, level: usize) -> ObjectJson {
        let lv = &o.decomposition.levels[level];
        ObjectJson {
            name: o.name.clone(),
            translation: o.frame.translation,
            rotation: o.frame.rotation,
            scale: o.frame.scale,
            faces: o.faces,
            target: lv.target,
            distance: lv.distance.map(|d| d * o.frame.scale),
            primitives: (lv.primitives.iter().enumerate())
                .map(|(i, p)| PrimJson::new(p, lv.faces.get(i).copied().unwrap_or(0)))
                .collect(),
        }
    }
}

/// [`Objects::to_json`].
pub(crate) fn to_json_objects(objs: &Objects, level: usize, params: &Params) -> String {
    let world = objs.world_primitives(level);
    let objects: Vec<ObjectJson> = (objs.objects.iter())
        .map(|o| ObjectJson::new(o, level))
        .collect();
    let levels = || objs.objects.iter().map(|o| &o.decomposition.levels[level]);
    let mut counts = [0usize; 6];
    for (c, n) in levels().flat_map(|lv| lv.counts().into_iter().enumerate()) {
        counts[c] += n;
    }
    let bytes = levels().map(|lv| lv.bytes()).sum();
    let to_solid = levels().any(|lv| lv.distance_to_solid);
    let faces_of: Vec<u32> = levels()
        .flat_map(|lv| (0..lv.primitives.len()).map(|i| lv.faces.get(i).copied().unwrap_or(0)))
        .collect();
    let primitives: Vec<PrimJson> = world
        .iter()
        .zip(&faces_of)
        .map(|(p, &f)| PrimJson::new(p, f))
        .collect();
    let (target, share_rule, percent) = match objs.targets[level] {
        Target::Count(n) => (n, Some(SHARE_RULE), None),
        Target::Percent(p) => (objects.iter().map(|o| o.target).sum(), None, Some(p)),
    };
    let doc = Document {
        format: super::contract::FORMAT,
        version: super::contract::VERSION as u32,
        input: &objs.input,
        settings: Settings {
            params,
            target,
            share_rule,
            percent,
            merge_target: None,
        },
        stats: Stats {
            counts: Counts(counts),
            primitives: world.len(),
            bytes,
            partitions: 1,
            seconds: None,
            distance: objs
                .distance(level)
                .map(|worst| Distance::farthest(worst, to_solid, &objs.input)),
        },
        primitives,
        objects: Some(objects),
    };
    finish(&doc)
}

/// Joins arrays whose elements are all scalars onto their opening line. In
/// serde_json's pretty output a line ending in `[` always opens an array (string
/// values end in `"`), and a container element's line ends in `{` or `[`.
fn inline_scalar_arrays(pretty: &str) -> String {
    let lines: Vec<&str> = pretty.lines().collect();
    let mut out = String::with_capacity(pretty.len());
    let mut i = 0;
    while i < lines.len() {
        let line = lines[i];
        i += 1;
        if line.ends_with('[') {
            let close = (i..lines.len()).find(|&j| matches!(lines[j].trim(), "]" | "],"));
            let scalars = |end: usize| {
                lines[i..end]
                    .iter()
                    .all(|l| !l.ends_with('[') && !l.ends_with('{'))
            };
            if let Some(end) = close.filter(|&end| scalars(end)) {
                out.push_str(line);
                let items: Vec<&str> = lines[i..end].iter().map(|l| l.trim()).collect();
                out.push_str(&items.join(" "));
                out.push_str(lines[end].trim());
                out.push('\n');
                i = end + 1;
                continue;
            }
        }
        out.push_str(line);
        out.push('\n');
    }
    out.pop();
    out
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::output::result::{InputInfo, Level};
    use crate::primitive::{Capsule, Cylinder, Frustum, Obb, Prism, Sphere};
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// A uniformly random rotation's axes.
    fn random_axes(rng: &mut ChaCha8Rng) -> [V3; 3] {
        loop {
            let q: [f64; 4] = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
            let n2: f64 = q.iter().map(|x| x * x).sum();
            if n2 > 1e-4 && n2 <= 1.0 {
                return crate::math::axes_from_quat(q);
            }
        }
    }

    fn sample_primitives() -> Vec<Primitive> {
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let mut v = || -> V3 { std::array::from_fn(|_| rng.gen_range(-5.0..5.0)) };
        let (c0, c1, c2, c3, c4, c5, c6, c7) = (v(), v(), v(), v(), v(), v(), v(), v());
        let mut rng = ChaCha8Rng::seed_from_u64(4);
        vec![
            Primitive::Box(Obb {
                center: c0,
                axes: random_axes(&mut rng),
                half: [0.5, 1.25, 0.1],
            }),
            Primitive::Sphere(Sphere {
                center: c1,
                radius: 0.3,
            }),
            Primitive::Capsule(Capsule {
                p0: c2,
                p1: c3,
                radius: 0.2,
            }),
            Primitive::Cylinder(Cylinder {
                p0: c4,
                p1: c5,
                radius: 0.7,
            }),
            Primitive::Frustum(Frustum {
                p0: c6,
                p1: c7,
                r0: 0.4,
                r1: 0.1,
            }),
            Primitive::Prism(Prism {
                center: c0,
                axes: random_axes(&mut rng),
                hx: 1.0,
                hy: 0.5,
                hz_top: 0.01,
                hz_bottom: 0.75,
                shift: -0.3,
            }),
            Primitive::Box(Obb {
                center: c1,
                axes: random_axes(&mut rng),
                half: [1.0, 1.0, 1.0],
            }),
        ]
    }

    pub(in crate::output) fn sample_decomposition() -> Decomposition {
        let primitives = sample_primitives();
        let level = Level {
            target: 7,
            faces: (1..=7).collect(),
            primitives,
            ..Default::default()
        };
        Decomposition {
            input: InputInfo {
                path: Some("scene \"1\".obj".into()),
                faces: 28,
                vertices: 30,
                aabb_min: [-5.0, -5.0, -5.0],
                aabb_max: [5.0, 5.0, 5.0],
                ..Default::default()
            },
            levels: vec![level],
            timings: vec![("load".into(), 0.25), ("merge".into(), 1.5)],
            ..Default::default()
        }
    }

    #[test]
    fn document_contract() {
        let dec = sample_decomposition();
        let text = dec.to_json_timed(0, &Params::default());
        assert!(text.ends_with("}\n"));
        let v: serde_json::Value = serde_json::from_str(&text).unwrap();
        assert_eq!(v["format"], "primdecomp");
        assert_eq!(v["version"], 1);
        assert_eq!(v["input"]["path"], "scene \"1\".obj");
        assert_eq!(v["input"]["faces"], 28);
        assert_eq!(v["settings"]["target"], 7);
        // The settings the run used: the default's tolerance under its cap.
        assert_eq!(v["settings"]["targets"], serde_json::json!([1024]));
        assert_eq!(
            v["settings"]["tolerance"],
            serde_json::json!([{"diagonal": 0.02}])
        );
        assert_eq!(v["settings"]["dedup"], "exact");
        assert_eq!(v["settings"]["weights"]["prism"], 1.4);
        assert_eq!(v["settings"]["kinds"]["frustum"], true);
        let counts =
            serde_json::json!({"box":2,"sphere":1,"capsule":1,"cylinder":1,"frustum":1,"prism":1});
        assert_eq!(v["stats"]["counts"], counts);
        assert_eq!(v["stats"]["primitives"], 7);
        // The prism is skewed: 11 floats and its shift.
        assert_eq!(v["stats"]["bytes"], 4 * (10 * 2 + 4 + 7 + 7 + 8 + 12));
        assert_eq!(v["stats"]["seconds"]["merge"], 1.5);
        assert_eq!(v["stats"]["seconds"]["total"], 1.75);
        let prims = v["primitives"].as_array().unwrap();
        assert_eq!(prims[4]["kind"], "frustum");
        assert_eq!(prims[4]["radius1"], 0.1);
        assert_eq!(prims[6]["faces"], 7);
        assert!(
            text.contains("\"half_extents\": [0.5, 1.25, 0.1],"),
            "{text}"
        );
    }

    #[test]
    fn key_order() {
        let text = sample_decomposition().to_json_timed(0, &Params::default());
        // Within each group, every pattern must occur after the previous one.
        let groups = [
            r#""format"|"version"|"input"|"settings"|"stats"|"primitives": ["#,
            r#""path"|"aabb_min"|"aabb_max"|"tangent_eps"|"remove_thin_boxes"|"target""#,
            r#""counts"|"box":|"prism":|"bytes"|"seconds"|"load"|"merge"|"total""#,
            r#""kind": "prism"|"center"|"rotation"|"half_x"|"half_y"|"half_z_top"|"half_z_bottom"|"shift_z""#,
        ];
        for g in groups {
            let mut at = 0;
            for p in g.split('|') {
                let found = text[at..].find(p);
                assert!(found.is_some(), "{p} missing or out of order in {g}");
                at += found.unwrap_or(0) + p.len();
            }
        }
    }

    #[test]
    fn timings_only_when_asked() {
        let mut dec = sample_decomposition();
        let a = to_json(&dec, 0, &Params::default());
        let ta = dec.to_json_timed(0, &Params::default());
        dec.timings[0].1 = 123.0;
        // Without timings the document depends only on input and settings.
        assert_eq!(a, to_json(&dec, 0, &Params::default()));
        assert!(!a.contains("\"seconds\""), "{a}");
        let tb = dec.to_json_timed(0, &Params::default());
        assert_ne!(ta, tb);
        let strip = |s: &str| {
            let mut v: serde_json::Value = serde_json::from_str(s).unwrap();
            v["stats"].as_object_mut().unwrap().remove("seconds");
            v.to_string()
        };
        let plain: serde_json::Value = serde_json::from_str(&a).unwrap();
        assert_eq!(strip(&ta), plain.to_string());
        assert_eq!(strip(&tb), plain.to_string());
    }

    #[test]
    fn inlines_only_scalar_arrays() {
        let v = serde_json::json!({"a": [1, 2], "b": [{"c": [3]}], "d": [], "e": ["x[", "]"]});
        let s = inline_scalar_arrays(&serde_json::to_string_pretty(&v).unwrap());
        assert!(s.contains("\"a\": [1, 2],"), "{s}");
        assert!(s.contains("\"c\": [3]"), "{s}");
        assert!(s.contains("\"e\": [\"x[\", \"]\"]"), "{s}");
        assert_eq!(serde_json::from_str::<serde_json::Value>(&s).unwrap(), v);
    }
}
