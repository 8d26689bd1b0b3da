//! MuJoCo MJCF export: one `<body>` per object (no joint: welded to the
//! world, i.e. static) placed by `pos` and a scalar-first `quat` (MJCF's order:
//! w x y z), holding one `<geom>` per primitive: `box` with half sizes, `sphere`,
//! `capsule` and `cylinder` by `fromto` (the segment's or axis' ends) with the
//! radius as `size` (by `pos`, `quat` and `size="r half"` when the ends are too close
//! for MuJoCo, [`MIN_FROMTO_REL`]); frustums and prisms as `mesh` geoms over an inline `<mesh
//! vertex="…">` asset, the conservative tessellation's vertices, of which MuJoCo
//! takes the convex hull. MJCF is +Z up (gravity −z): `--up y` results are turned.

use super::engine::{prepare, quat_between, ExportOptions, Format, Prepared, Shape};
use super::xml::{nums, Xml};
use primdecomp::{Body, Kind};
use primdecomp_files::visible;
use primdecomp_math::V3;

/// Shortest `fromto` written, relative to the radius (and at least 1e-6 long):
/// MuJoCo refuses end points too close ("fromto points too close in geom"), so a
/// shorter segment is placed by `pos`, `quat` and its half length in `size`.
pub const MIN_FROMTO_REL: f64 = 1e-4;

/// A capsule or cylinder geom: by `fromto` where long enough, else by `pos`,
/// `quat` (local z along the axis) and `size="r half"`.
fn segment(x: &mut Xml, name: &str, ty: &str, p0: V3, p1: V3, r: f64) {
    let (c, a, h) = Shape::axis(p0, p1);
    if 2.0 * h >= (MIN_FROMTO_REL * r).max(1e-6) {
        let fromto = nums(&[p0[0], p0[1], p0[2], p1[0], p1[1], p1[2]]);
        x.empty(
            "geom",
            &[
                ("name", name),
                ("type", ty),
                ("fromto", &fromto),
                ("size", &nums(&[r])),
            ],
        );
    } else {
        let [qx, qy, qz, qw] = quat_between([0.0, 0.0, 1.0], a);
        x.empty(
            "geom",
            &[
                ("name", name),
                ("type", ty),
                ("pos", &nums(&c)),
                ("quat", &nums(&[qw, qx, qy, qz])),
                ("size", &nums(&[r, h])),
            ],
        );
    }
}

/// The MJCF document, or why it cannot be written ([`prepare`]).
pub fn to_mjcf(objects: &[Body], opts: &ExportOptions) -> Result<String, String> {
    let prepared = prepare(objects, Format::Mjcf, opts, false)?;
    let mut x = Xml::new();
    x.open("mujoco", &[("model", &visible(&opts.model))]);
    x.comment(
        "primdecomp colliders: one static body per object (docs/decisions/exports-engine-conventions.md)",
    );
    x.empty("compiler", &[("angle", "radian")]);
    assets(&mut x, &prepared);
    x.open("worldbody", &[]);
    for (oi, o) in prepared.iter().enumerate() {
        body(&mut x, oi, o);
    }
    x.close("worldbody");
    x.close("mujoco");
    Ok(x.finish())
}

/// The name of the `<mesh>` asset of object `oi`'s shape `i`.
fn mesh_name(oi: usize, kind: Kind, i: usize) -> String {
    format!("mesh{oi}_{}_{i}", kind.name())
}

/// The `<asset>` of every hull's `<mesh>`, if any.
fn assets(x: &mut Xml, prepared: &[Prepared]) {
    let mut meshes = Vec::new();
    for (oi, o) in prepared.iter().enumerate() {
        for (i, (kind, s)) in o.shapes.iter().enumerate() {
            if let Shape::Hull(t) = s {
                let v: Vec<f64> = t.vertices.iter().flatten().copied().collect();
                meshes.push((mesh_name(oi, *kind, i), nums(&v)));
            }
        }
    }
    if meshes.is_empty() {
        return;
    }
    x.open("asset", &[]);
    for (name, v) in &meshes {
        // Shell inertia: thin hulls have next to no volume, and static bodies
        // need no mass anyway.
        x.empty(
            "mesh",
            &[("name", name), ("vertex", v), ("inertia", "shell")],
        );
    }
    x.close("asset");
}

/// Object `oi`'s static `<body>` and its geoms.
fn body(x: &mut Xml, oi: usize, o: &Prepared) {
    let [qx, qy, qz, qw] = o.frame.rotation;
    let pos = nums(&o.frame.translation);
    let quat = nums(&[qw, qx, qy, qz]);
    x.open("body", &[("name", &o.name), ("pos", &pos), ("quat", &quat)]);
    for (i, (kind, s)) in o.shapes.iter().enumerate() {
        let name = format!("{}/{}_{i}", o.name, kind.name());
        match s {
            Shape::Box {
                center,
                rotation,
                half,
            } => {
                let [qx, qy, qz, qw] = *rotation;
                x.empty(
                    "geom",
                    &[
                        ("name", &name),
                        ("type", "box"),
                        ("pos", &nums(center)),
                        ("quat", &nums(&[qw, qx, qy, qz])),
                        ("size", &nums(half)),
                    ],
                );
            }
            Shape::Sphere { center, radius } => x.empty(
                "geom",
                &[
                    ("name", &name),
                    ("type", "sphere"),
                    ("pos", &nums(center)),
                    ("size", &nums(&[*radius])),
                ],
            ),
            Shape::Capsule { p0, p1, radius } => {
                segment(x, &name, "capsule", *p0, *p1, *radius);
            }
            Shape::Round { p0, p1, r0, r1 } => {
                segment(x, &name, "cylinder", *p0, *p1, r0.max(*r1));
            }
            Shape::Hull(_) => {
                let mesh = mesh_name(oi, *kind, i);
                x.empty(
                    "geom",
                    &[("name", &name), ("type", "mesh"), ("mesh", &mesh)],
                );
            }
        }
    }
    x.close("body");
}
