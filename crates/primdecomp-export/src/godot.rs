//! Godot 4 text scene (`.tscn`, format 3) export: a `Node3D` root with
//! one `StaticBody3D` per object (its transform; the original name in
//! `metadata/primdecomp_name`), whose children are `CollisionShape3D`s with
//! `BoxShape3D` (full `size`), `SphereShape3D`, `CapsuleShape3D` (`height` includes
//! the caps), `CylinderShape3D` (full `height`; capsules and cylinders along local
//! +Y) and `ConvexPolygonShape3D` (the conservative tessellation's vertices, of
//! which Godot takes the hull) for frustums and prisms. Godot is +Y up: `--up z`
//! results are turned. `Transform3D(…)` lists the basis by rows, then the origin,
//! as Godot writes it. Node names lose the characters Godot forbids; strings are
//! escaped.

use super::engine::{num, prepare, quat_between, ExportOptions, Format, Shape};
use super::names::{ident, quote, Names};
use primdecomp::Body;
use primdecomp_files::visible;
use primdecomp_math::axes_from_quat;
use primdecomp_math::V3;
use std::fmt::Write;

/// `Transform3D(…)` of rotation `q` (scalar last) and origin `t`.
pub fn transform(q: [f64; 4], t: V3) -> String {
    let a = axes_from_quat(q);
    // Row i, column j; column j is axis a[j].
    let mut v = Vec::with_capacity(12);
    for i in 0..3 {
        for aj in &a {
            v.push(num(aj[i]));
        }
    }
    v.extend(t.iter().map(|&x| num(x)));
    format!("Transform3D({})", v.join(", "))
}

fn vec3(v: V3) -> String {
    format!("Vector3({}, {}, {})", num(v[0]), num(v[1]), num(v[2]))
}

/// The `.tscn` text, or why it cannot be written ([`prepare`]).
pub fn to_tscn(objects: &[Body], opts: &ExportOptions) -> Result<String, String> {
    let prepared = prepare(objects, Format::Tscn, opts, false)?;
    // Sub-resources first (one per shape), then the nodes.
    let mut res = String::new();
    let mut nodes = String::new();
    let root = ident(&visible(&opts.model), false);
    let _ = writeln!(nodes, "[node name={} type=\"Node3D\"]", quote(&root));
    let mut count = 0usize;
    let mut used = Names::default();
    for o in &prepared {
        let name = used.unique(ident(&o.name, false));
        let _ = writeln!(nodes);
        let _ = writeln!(
            nodes,
            "[node name={} type=\"StaticBody3D\" parent=\".\"]",
            quote(&name)
        );
        let _ = writeln!(
            nodes,
            "transform = {}",
            transform(o.frame.rotation, o.frame.translation)
        );
        let _ = writeln!(nodes, "metadata/primdecomp_name = {}", quote(&o.name));
        for (i, (kind, s)) in o.shapes.iter().enumerate() {
            let (ty, body, q, c) = resource(s);
            count += 1;
            let rid = format!("{ty}_{count}");
            let _ = writeln!(res, "[sub_resource type=\"{ty}\" id=\"{rid}\"]");
            let _ = writeln!(res, "{body}");
            let _ = writeln!(res);
            let _ = writeln!(nodes);
            let _ = writeln!(
                nodes,
                "[node name=\"{}_{i}\" type=\"CollisionShape3D\" parent={}]",
                kind.name(),
                quote(&name)
            );
            let _ = writeln!(nodes, "transform = {}", transform(q, c));
            let _ = writeln!(nodes, "shape = SubResource(\"{rid}\")");
        }
    }
    let mut out = format!("[gd_scene load_steps={} format=3]\n\n", count + 1);
    out.push_str(&res);
    out.push_str(&nodes);
    Ok(out)
}

/// Shape `s`'s sub-resource: its type, its properties, and the rotation and origin of
/// the collision shape node using it (capsules and cylinders along local +Y).
fn resource(s: &Shape) -> (&'static str, String, [f64; 4], V3) {
    let y = [0.0, 1.0, 0.0];
    let id = [0.0, 0.0, 0.0, 1.0];
    match s {
        Shape::Box {
            center,
            rotation,
            half,
        } => (
            "BoxShape3D",
            format!("size = {}", vec3(half.map(|h| 2.0 * h))),
            *rotation,
            *center,
        ),
        Shape::Sphere { center, radius } => (
            "SphereShape3D",
            format!("radius = {}", num(*radius)),
            id,
            *center,
        ),
        Shape::Capsule { p0, p1, radius } => {
            let (c, a, h) = Shape::axis(*p0, *p1);
            (
                "CapsuleShape3D",
                format!(
                    "radius = {}\nheight = {}",
                    num(*radius),
                    num(2.0 * h + 2.0 * radius)
                ),
                quat_between(y, a),
                c,
            )
        }
        Shape::Round { p0, p1, r0, r1 } => {
            let (c, a, h) = Shape::axis(*p0, *p1);
            (
                "CylinderShape3D",
                format!("height = {}\nradius = {}", num(2.0 * h), num(r0.max(*r1))),
                quat_between(y, a),
                c,
            )
        }
        Shape::Hull(t) => {
            let pts: Vec<String> = t.vertices.iter().flatten().map(|&x| num(x)).collect();
            (
                "ConvexPolygonShape3D",
                format!("points = PackedVector3Array({})", pts.join(", ")),
                id,
                [0.0; 3],
            )
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn transform_lists_rows_then_origin() {
        // +90° about z: x → y. Column 0 (the image of x) is (0, 1, 0), so row 1
        // starts with 1.
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let t = transform([0.0, 0.0, h, h], [1.0, 2.0, 3.0]);
        let v: Vec<f64> = t["Transform3D(".len()..t.len() - 1]
            .split(", ")
            .map(|x| x.parse().unwrap())
            .collect();
        assert!(v[3] > 0.999 && v[1] < -0.999, "{t}");
        assert_eq!(&v[9..], &[1.0, 2.0, 3.0]);
        assert_eq!(quote("a\"b"), "\"a\\\"b\"");
    }
}
