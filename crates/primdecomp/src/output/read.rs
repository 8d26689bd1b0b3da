//! Reading a result back: the JSON result contract's documents parsed into
//! primitives and objects with their frames ([`ResultFile::read`]), after the header check of [`super::contract`], with every
//! number checked finite and within the limits of input meshes, so nothing read
//! overflows the arithmetic of the tools that use it.

use super::body::Body;
use super::contract::check_header;
use super::frame::Frame;
use super::json::{ObjectJson, PrimJson};
use crate::error::{Error, Result as CrateResult};
use crate::math::quat::axes_from_quat;
use crate::math::short as show;
use crate::math::V3;
use crate::primitive::{Capsule, Cylinder, Frustum, Obb, Primitive, Prism, Sphere};
use serde::Deserialize;
use std::path::Path;

#[derive(Deserialize)]
struct DocumentIn {
    #[serde(default)]
    format: Option<serde_json::Value>,
    #[serde(default)]
    version: Option<serde_json::Value>,
    primitives: Vec<PrimJson>,
    #[serde(default)]
    objects: Option<Vec<ObjectJson>>,
}

/// Farthest coordinate and largest size a result may hold: the limits of input
/// meshes (`mesh::MAX_POSITION`, `mesh::MAX_EXTENT`), so whatever a decomposition
/// writes reads back, and nothing read overflows the arithmetic of the tools that
/// use it.
fn check_values(p: &Primitive, scale: f64, offset: f64) -> Result<(), String> {
    use crate::input::mesh::{MAX_EXTENT, MAX_POSITION};
    let coords: Vec<f64> = match *p {
        Primitive::Box(Obb { center, .. })
        | Primitive::Sphere(Sphere { center, .. })
        | Primitive::Prism(Prism { center, .. }) => center.to_vec(),
        Primitive::Capsule(Capsule { p0, p1, .. })
        | Primitive::Cylinder(Cylinder { p0, p1, .. })
        | Primitive::Frustum(Frustum { p0, p1, .. }) => [p0, p1].concat(),
    };
    let mut sz = sizes(p);
    if let Primitive::Prism(q) = p {
        sz.push(q.shift.abs());
    }
    if let Some(x) = coords.iter().chain(&sz).find(|x| !x.is_finite()) {
        return Err(format!("a number is {x}, not finite"));
    }
    let size = sz.iter().fold(0.0f64, |m, x| m.max(*x));
    let far = coords.iter().fold(0.0f64, |m, x| m.max(x.abs())) + size;
    if scale * size > MAX_EXTENT {
        return Err(format!(
            "a radius or half-extent of {} is beyond {}, the largest a result may hold",
            show(scale * size),
            show(MAX_EXTENT)
        ));
    }
    if offset + scale * far > MAX_POSITION {
        return Err(format!(
            "it reaches {} from the origin, beyond ±{}, the farthest a result may place a \
             primitive",
            show(offset + scale * far),
            show(MAX_POSITION)
        ));
    }
    Ok(())
}

impl PrimJson {
    /// The primitive read, its sizes checked.
    fn into_primitive(self) -> Result<Primitive, String> {
        let p = self.into_shape()?;
        if sizes(&p).iter().any(|&x| x < 0.0) {
            return Err("a radius or half-extent is negative".into());
        }
        Ok(p)
    }

    /// The primitive as written (its rotation checked, negative zeros made positive).
    fn into_shape(self) -> Result<Primitive, String> {
        Ok(match self {
            PrimJson::Box {
                center,
                rotation,
                half_extents,
                ..
            } => Primitive::Box(Obb {
                center,
                axes: rotation_axes(rotation)?,
                half: half_extents.map(plus_zero),
            }),
            PrimJson::Sphere { center, radius, .. } => Primitive::Sphere(Sphere {
                center,
                radius: plus_zero(radius),
            }),
            PrimJson::Capsule { p0, p1, radius, .. } => Primitive::Capsule(Capsule {
                p0,
                p1,
                radius: plus_zero(radius),
            }),
            PrimJson::Cylinder { p0, p1, radius, .. } => Primitive::Cylinder(Cylinder {
                p0,
                p1,
                radius: plus_zero(radius),
            }),
            PrimJson::Frustum {
                p0,
                p1,
                radius0,
                radius1,
                ..
            } => Primitive::Frustum(Frustum {
                p0,
                p1,
                r0: plus_zero(radius0),
                r1: plus_zero(radius1),
            }),
            PrimJson::Prism {
                center,
                rotation,
                half_x,
                half_y,
                half_z_top,
                half_z_bottom,
                shift_z,
                ..
            } => Primitive::Prism(Prism {
                center,
                axes: rotation_axes(rotation)?,
                hx: plus_zero(half_x),
                hy: plus_zero(half_y),
                hz_top: plus_zero(half_z_top),
                hz_bottom: plus_zero(half_z_bottom),
                shift: shift_z,
            }),
        })
    }
}

/// A size as read, `-0.0` made `0.0` (a negative zero passes the sign check but makes
/// engines' positive-size assertions fail).
fn plus_zero(x: f64) -> f64 {
    x + 0.0
}

/// Axes of a stored rotation; refuses quaternions too short to be unit ones.
fn rotation_axes(q: [f64; 4]) -> Result<[V3; 3], String> {
    let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
    if n.is_finite() && n > 1e-6 {
        Ok(axes_from_quat(q))
    } else {
        Err(format!("rotation {q:?} is not a unit quaternion"))
    }
}

/// Radii and half-extents of a primitive.
fn sizes(p: &Primitive) -> Vec<f64> {
    match *p {
        Primitive::Box(b) => b.half.to_vec(),
        Primitive::Sphere(Sphere { radius, .. })
        | Primitive::Capsule(Capsule { radius, .. })
        | Primitive::Cylinder(Cylinder { radius, .. }) => vec![radius],
        Primitive::Frustum(f) => vec![f.r0, f.r1],
        Primitive::Prism(q) => vec![q.hx, q.hy, q.hz_top, q.hz_bottom],
    }
}

/// A primdecomp JSON result read back ([`ResultFile::read`]): its primitives in world
/// coordinates and its objects, each with its frame and its primitives in that frame.
///
/// ```
/// use primdecomp::{Kind, ResultFile};
///
/// let doc = r#"{"format": "primdecomp", "version": 1,
///   "primitives": [{"kind": "sphere", "center": [1, 2, 3], "radius": 0.5}]}"#;
/// let read = ResultFile::read(doc, "r.json".as_ref())?;
/// assert_eq!(read.primitives[0].kind(), Kind::Sphere);
/// # Ok::<(), primdecomp::Error>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct ResultFile {
    /// Every primitive in world coordinates (the document's `primitives`).
    pub primitives: Vec<Primitive>,
    /// One per object of a per-object result; for a result without `objects`, one
    /// unnamed object in the world frame holding `primitives`.
    pub objects: Vec<Body>,
}

impl ResultFile {
    /// The largest result, evaluation or settings file the tools read (with
    /// [`primdecomp_files::read_regular`]): 256 MiB holds about a million primitives, far more
    /// than any export or viewer page takes, and parsing it stays within about a GiB.
    pub const MAX_BYTES: u64 = 256 << 20;

    /// Parses a primdecomp JSON document (`path` names it in messages). Refuses a
    /// document whose `format` is not `"primdecomp"` or whose `version` is not 1, and
    /// primitives or object frames with numbers that are not finite or beyond the
    /// limits of input meshes (coordinates within ±1e70, sizes up to 1e60, in world
    /// coordinates), with an [`Error::Format`] naming the primitive or the JSON
    /// position.
    ///
    /// ```
    /// use primdecomp::ResultFile;
    ///
    /// let doc = r#"{"format": "primdecomp", "version": 1,
    ///   "primitives": [{"kind": "sphere", "center": [1, 2, 3], "radius": 0.5}]}"#;
    /// let read = ResultFile::read(doc, "result.json".as_ref())?;
    /// assert_eq!(read.primitives.len(), 1);
    /// assert_eq!(read.objects[0].primitives, read.primitives);
    /// let newer = doc.replace(r#""version": 1"#, r#""version": 2"#);
    /// assert!(ResultFile::read(&newer, "result.json".as_ref()).is_err());
    /// # Ok::<(), primdecomp::Error>(())
    /// ```
    pub fn read(json: &str, path: &Path) -> CrateResult<ResultFile> {
        read_document(json)
            .map(|(primitives, objects)| ResultFile {
                primitives,
                objects,
            })
            .map_err(|msg| Error::format(path, msg))
    }
}

/// A document's objects ([`ResultFile::objects`]).
#[cfg(test)]
pub(crate) fn read_objects(json: &str) -> Result<Vec<Body>, String> {
    read_document(json).map(|(_, objects)| objects)
}

/// A document's world primitives ([`ResultFile::primitives`]).
#[cfg(test)]
pub(crate) fn read_primitives(json: &str) -> Result<Vec<Primitive>, String> {
    read_document(json).map(|(primitives, _)| primitives)
}

/// The world primitives and the objects of a document, or what is wrong with it.
fn read_document(json: &str) -> Result<(Vec<Primitive>, Vec<Body>), String> {
    let doc: DocumentIn =
        serde_json::from_str(json).map_err(|e| format!("invalid primdecomp JSON: {e}"))?;
    check_header(doc.format.as_ref(), doc.version.as_ref())?;
    let prims = |v: Vec<PrimJson>, what: &str, scale: f64, offset: f64| {
        v.into_iter()
            .enumerate()
            .map(|(i, p)| {
                let kind = kind_name(&p);
                p.into_primitive()
                    .and_then(|p| check_values(&p, scale, offset).map(|()| p))
                    .map_err(|e| format!("{what}primitive {i} ({kind}): {e}"))
            })
            .collect::<Result<Vec<Primitive>, String>>()
    };
    let world = prims(doc.primitives, "", 1.0, 0.0)?;
    let objects = match doc.objects {
        None => vec![Body {
            name: String::new(),
            frame: Frame::IDENTITY,
            primitives: world.clone(),
        }],
        Some(objs) => objs
            .into_iter()
            .enumerate()
            .map(|(i, o)| {
                let what = format!("object {i} ({:?}): ", o.name);
                let finite = o.translation.iter().all(|x| x.is_finite())
                    && o.scale.is_finite()
                    && o.scale > 0.0;
                if !finite {
                    return Err(format!(
                        "{what}translation or scale is not finite and positive"
                    ));
                }
                let n = o.rotation.iter().map(|x| x * x).sum::<f64>().sqrt();
                if !(n.is_finite() && (n - 1.0).abs() < 1e-6) {
                    return Err(format!(
                        "{what}rotation {:?} is not a unit quaternion",
                        o.rotation
                    ));
                }
                let offset = o.translation.iter().fold(0.0f64, |m, x| m.max(x.abs()));
                Ok(Body {
                    frame: Frame {
                        translation: o.translation,
                        rotation: o.rotation.map(|x| x / n),
                        scale: o.scale,
                    },
                    primitives: prims(o.primitives, &what, o.scale, offset)?,
                    name: o.name,
                })
            })
            .collect::<Result<Vec<Body>, String>>()?,
    };
    Ok((world, objects))
}

/// The `kind` of a primitive as the document names it.
fn kind_name(p: &PrimJson) -> &'static str {
    match p {
        PrimJson::Box { .. } => "box",
        PrimJson::Sphere { .. } => "sphere",
        PrimJson::Capsule { .. } => "capsule",
        PrimJson::Cylinder { .. } => "cylinder",
        PrimJson::Frustum { .. } => "frustum",
        PrimJson::Prism { .. } => "prism",
    }
}

#[cfg(test)]
mod tests {
    use super::super::json::tests::sample_decomposition;
    use super::super::json::to_json;
    use super::*;
    use crate::params::Params;

    fn close(a: &[f64], b: &[f64], tol: f64) -> bool {
        a.iter().zip(b).all(|(x, y)| (x - y).abs() <= tol)
    }

    /// Every number of a primitive's JSON form.
    fn flat(p: &Primitive) -> Vec<f64> {
        let v = serde_json::to_value(PrimJson::new(p, 0)).unwrap();
        let mut out = Vec::new();
        for x in v.as_object().unwrap().values() {
            match x {
                serde_json::Value::Array(a) => out.extend(a.iter().map(|n| n.as_f64().unwrap())),
                serde_json::Value::Number(n) => out.push(n.as_f64().unwrap()),
                _ => {}
            }
        }
        out
    }

    #[test]
    fn read_back_round_trip() {
        let dec = sample_decomposition();
        let text = to_json(&dec, 0, &Params::default());
        let back = read_primitives(&text).unwrap();
        let orig = &dec.levels[0].primitives;
        assert_eq!(back.len(), orig.len());
        // serde_json's default float parser may be 1 ulp off (its `float_roundtrip`
        // feature makes it exact), hence the tolerance.
        for (a, b) in orig.iter().zip(&back) {
            assert_eq!(a.kind(), b.kind());
            let (na, nb) = (flat(a), flat(b));
            assert!(close(&na, &nb, 1e-12), "{a:?} vs {b:?}");
        }
    }

    #[test]
    fn read_rejects_bad_input() {
        let doc = |prims: &str| {
            format!(r#"{{"format":"primdecomp","version":1,"primitives":[{prims}]}}"#)
        };
        assert!(read_primitives("not json").is_err());
        assert!(read_primitives(&doc(r#"{"kind":"cone"}"#)).is_err());
        let neg = doc(r#"{"kind":"sphere","center":[0,0,0],"radius":-1}"#);
        assert!(read_primitives(&neg).unwrap_err().contains("primitive 0"));
        let zero_q =
            doc(r#"{"kind":"box","center":[0,0,0],"rotation":[0,0,0,0],"half_extents":[1,1,1]}"#);
        assert!(read_primitives(&zero_q).is_err());
        let ok = doc(r#"{"kind":"sphere","center":[1,2,3],"radius":0.5}"#);
        let p = read_primitives(&ok).unwrap();
        assert_eq!(
            p,
            vec![Primitive::Sphere(Sphere {
                center: [1.0, 2.0, 3.0],
                radius: 0.5
            })]
        );
        // Numbers beyond the limits of input meshes, and a negative zero made zero.
        let far = doc(r#"{"kind":"sphere","center":[1e308,0,0],"radius":1}"#);
        let e = read_primitives(&far).unwrap_err();
        assert!(
            e.starts_with("primitive 0 (sphere): it reaches 1e308"),
            "{e}"
        );
        let big = doc(r#"{"kind":"sphere","center":[0,0,0],"radius":1e65}"#);
        assert!(read_primitives(&big).unwrap_err().contains("beyond 1e60"));
        let nz = doc(r#"{"kind":"sphere","center":[0,0,0],"radius":-0.0}"#);
        match read_primitives(&nz).unwrap()[0] {
            Primitive::Sphere(s) => assert!(s.radius.is_sign_positive()),
            ref p => panic!("{p:?}"),
        }
    }

    /// `format` and `version` are checked strictly wherever a result is read.
    #[test]
    fn format_and_version_are_checked() {
        let body = r#""primitives":[{"kind":"sphere","center":[0,0,0],"radius":1}]"#;
        let with = |head: &str| format!("{{{head}{body}}}");
        let cases = [
            ("", "not a primdecomp result: it has no \"format\""),
            (
                r#""format":"other","version":1,"#,
                r#"its "format" is "other", not "primdecomp""#,
            ),
            (r#""format":7,"version":1,"#, r#"its "format" is 7"#),
            (
                r#""format":"primdecomp","#,
                r#"the result has no "version""#,
            ),
            (
                r#""format":"primdecomp","version":2,"#,
                r#""version" is 2; this primdecomp reads version 1"#,
            ),
            (
                r#""format":"primdecomp","version":"1","#,
                r#""version" is "1", not the integer 1"#,
            ),
            (
                r#""format":"primdecomp","version":-1,"#,
                r#""version" is -1, not the integer 1"#,
            ),
            (
                r#""format":"primdecomp","version":1.5,"#,
                r#""version" is 1.5, not the integer 1"#,
            ),
            (
                r#""format":"primdecomp","version":1.0,"#,
                r#""version" is 1.0, not the integer 1"#,
            ),
            (
                r#""format":"primdecomp","version":1e400,"#,
                "number out of range",
            ),
        ];
        for (head, want) in cases {
            for e in [
                read_primitives(&with(head)).unwrap_err(),
                read_objects(&with(head)).unwrap_err(),
            ] {
                assert!(e.contains(want), "{head}: {e}");
            }
        }
        assert!(read_primitives(&with(r#""format":"primdecomp","version":1,"#)).is_ok());
    }
}
