//! Writes random results in every export format and reads each file back with a
//! parser of that format (`crates/testkit/src/exports.rs`, compiled here as is:
//! quick-xml for MJCF and URDF, the `gltf` crate's schema checks and the physics
//! extensions' constraints for glTF, the USD text and `.tscn` grammars as the writers
//! emit them). Inputs: up to 4 objects with random names (any string, a hostile one
//! from a list, or a long one), frames and up to 6 primitives each, every number
//! either typical (a multiple of 1/64 within ±512) or any finite f64 (1e308, 1e-310,
//! …), about half and half; random
//! options (up axis, scale, detail, physics extensions, previews, URDF capsules) and
//! a random model and output file name. Invariants:
//! - no panic;
//! - an error is `Error::Format` naming the output (exit code 2), and only for a
//!   result with a number outside the typical range (or a hull too small for MuJoCo);
//! - a file written is well formed for its format, every number finite within f32,
//!   names unique, one name per object, every file beside it (URDF meshes) a valid
//!   relative file name whose OBJ parses with finite coordinates.
#![no_main]

#[allow(dead_code)]
#[path = "../../crates/testkit/src/exports.rs"]
mod exports;

use arbitrary::{Arbitrary, Unstructured};
use libfuzzer_sys::fuzz_target;
use primdecomp::{Body, Frame, Up};
use primdecomp_export::{render, ExportOptions, Format, Physics};
use primdecomp_math::quat_from_axes;
use primdecomp::{Capsule, Cylinder, Error, Frustum, Obb, Primitive, Prism, Sphere};
use std::path::Path;

/// Names that broke the writers before: XML-forbidden characters, markup, MuJoCo's
/// world body, quotes, escapes, bidirectional overrides, duplicates.
const HOSTILE: [&str; 14] = [
    "world",
    "a\u{0}b",
    "\u{1b}[31mred\u{7}",
    "<!--<script>",
    "</script>",
    "a\u{fffe}b\u{ffff}",
    "q\"'&<>",
    "back\\slash\\u{1b}",
    "tab\tnl\ncr\r",
    "\u{202e}evil",
    "dup",
    "",
    "../../etc/passwd",
    "object0",
];

/// A number: typical (a multiple of 1/64 within ±512) or any finite f64.
#[derive(Arbitrary, Debug)]
enum F {
    Typical(i16),
    Any(f64),
}

impl F {
    fn get(&self) -> f64 {
        match *self {
            F::Typical(k) => k as f64 / 64.0,
            F::Any(x) if x.is_finite() => x,
            F::Any(_) => 0.0,
        }
    }
    fn typical(&self) -> bool {
        matches!(self, F::Typical(_))
    }
}

#[derive(Arbitrary, Debug)]
enum Name {
    Given(String),
    Hostile(u8),
    Long(u16, char),
}

impl Name {
    fn get(&self) -> String {
        match self {
            Name::Given(s) => s.clone(),
            Name::Hostile(i) => HOSTILE[*i as usize % HOSTILE.len()].to_string(),
            Name::Long(n, c) => std::iter::repeat_n(*c, *n as usize % 600).collect(),
        }
    }
}

#[derive(Arbitrary, Debug)]
struct Prim {
    kind: u8,
    v: [F; 12],
}

#[derive(Arbitrary, Debug)]
struct Obj {
    name: Name,
    t: [F; 3],
    q: [F; 4],
    s: F,
    prims: Vec<Prim>,
}

#[derive(Arbitrary, Debug)]
struct Input {
    objects: Vec<Obj>,
    up_z: bool,
    scale: F,
    detail: u8,
    omi: bool,
    preview: bool,
    urdf_capsule: bool,
    model: Name,
    stem: Name,
}

/// Axes of a quaternion, or the identity for a zero one.
fn axes(q: [f64; 4]) -> [[f64; 3]; 3] {
    let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
    if n.is_finite() && n > 1e-3 {
        primdecomp_math::axes_from_quat(q.map(|x| x / n))
    } else {
        [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
    }
}

fn primitive(p: &Prim) -> Primitive {
    let v: Vec<f64> = p.v.iter().map(F::get).collect();
    let c = [v[0], v[1], v[2]];
    let d = [v[3], v[4], v[5]];
    let size = |i: usize| v[i].abs();
    match p.kind % 6 {
        0 => Primitive::Box(Obb {
            center: c,
            axes: axes([v[6], v[7], v[8], v[9]]),
            half: [size(3), size(4), size(5)],
        }),
        1 => Primitive::Sphere(Sphere {
            center: c,
            radius: size(3),
        }),
        2 => Primitive::Capsule(Capsule {
            p0: c,
            p1: d,
            radius: size(6),
        }),
        3 => Primitive::Cylinder(Cylinder {
            p0: c,
            p1: d,
            radius: size(6),
        }),
        4 => Primitive::Frustum(Frustum {
            p0: c,
            p1: d,
            r0: size(6),
            r1: size(7),
        }),
        _ => Primitive::Prism(Prism {
            center: c,
            axes: axes([v[6], v[7], v[8], v[9]]),
            hx: size(3),
            hy: size(4),
            hz_top: size(5),
            hz_bottom: size(10),
            shift: v[11] * (p.kind & 8) as f64,
        }),
    }
}

/// The largest coordinate plus size of a primitive, for telling typical inputs apart.
fn magnitude(p: &Primitive) -> f64 {
    let (lo, hi) = p.aabb();
    lo.iter().chain(&hi).fold(0.0f64, |m, x| m.max(x.abs()))
}

fn check(input: &Input) {
    let objects: Vec<Body> = input
        .objects
        .iter()
        .take(4)
        .map(|o| {
            let q = [o.q[0].get(), o.q[1].get(), o.q[2].get(), o.q[3].get()];
            Body {
                name: o.name.get(),
                frame: Frame {
                    translation: o.t.each_ref().map(F::get),
                    rotation: quat_from_axes(&axes(q)),
                    scale: o.s.get().abs().max(1e-300),
                },
                primitives: o.prims.iter().take(6).map(primitive).collect(),
            }
        })
        .collect();
    let scale = input.scale.get().abs();
    let opts = ExportOptions {
        up: if input.up_z { Up::Z } else { Up::Y },
        scale: if scale > 0.0 { scale } else { 1.0 },
        detail: 3 + input.detail as usize % 30,
        physics: if input.omi { Physics::Omi } else { Physics::Khr },
        preview: input.preview,
        urdf_capsule: input.urdf_capsule,
        model: input.model.get(),
        input_mesh: None,
    };
    // A file name: no `/` or NUL, not empty, within 255 bytes.
    let mut stem: String = input.stem.get().replace(['/', '\0'], "_");
    while stem.len() > 240 {
        stem.pop();
    }
    if stem.is_empty() {
        stem.push('x');
    }
    // Typical: a primitive at least, every number typical, every primitive and frame
    // of a reasonable size.
    let typical = objects.iter().any(|o| !o.primitives.is_empty())
        && input.scale.typical()
        && opts.scale >= 0.05
        && input.objects.iter().take(4).all(|o| {
            o.t.iter().chain(&o.q).chain([&o.s]).all(F::typical)
                && o.s.get().abs() >= 0.05
                && o.prims.iter().take(6).all(|p| p.v.iter().all(F::typical))
        })
        && objects
            .iter()
            .flat_map(|o| &o.primitives)
            .all(|p| magnitude(p) >= 0.05);
    for format in Format::ALL {
        let ext = match format {
            Format::Mjcf => "xml",
            f => f.name(),
        };
        let path = format!("{stem}.{ext}");
        match render(&objects, format, &opts, Path::new(&path)) {
            Err(Error::Format { path: p, msg }) => {
                assert_eq!(p, Path::new(&path));
                let mujoco = format == Format::Mjcf && msg.contains("MuJoCo refuses meshes");
                assert!(!typical || mujoco, "{format:?}: a typical result refused: {msg}");
            }
            Err(e) => panic!("{format:?}: not a format error: {e}"),
            Ok(files) => {
                let text = || std::str::from_utf8(&files.main).expect("UTF-8");
                let got = match format {
                    Format::Gltf | Format::Glb => exports::gltf(&files.main),
                    Format::Mjcf => exports::mjcf(text()),
                    Format::Urdf => exports::urdf(text()),
                    Format::Usda => exports::usda(text()),
                    Format::Tscn => exports::tscn(text()),
                };
                let got = got.unwrap_or_else(|e| panic!("{format:?} does not read back: {e}\n{}", String::from_utf8_lossy(&files.main)));
                assert_eq!(got.names.len(), objects.len(), "{format:?}: {:?}", got.names);
                for (rel, bytes) in &files.beside {
                    exports::file_name(rel).unwrap();
                    assert!(got.files.contains(rel), "{rel} is not referred to");
                    let mesh = primdecomp::Mesh::parse(bytes, primdecomp::MeshFormat::Obj, Path::new(rel))
                        .expect("a URDF mesh parses");
                    for i in 0..mesh.vertex_count() as u32 {
                        assert!(mesh.world_pos(i).iter().all(|x| x.abs() <= f32::MAX as f64));
                    }
                }
            }
        }
    }
}

fuzz_target!(|data: &[u8]| {
    if std::env::var_os("PD_FUZZ_PRINT").is_some() {
        eprintln!("{:?}", Input::arbitrary(&mut Unstructured::new(data)));
    }
    if let Ok(input) = Input::arbitrary(&mut Unstructured::new(data)) {
        check(&input);
    }
});
