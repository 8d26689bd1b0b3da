//! USD text (`.usda`) export with UsdPhysics colliders: the stage's
//! `upAxis` is the result's own (`--up`; nothing is turned) and `metersPerUnit = 1`
//! (`--scale` converts to metres). One `Xform` per object (translate, orient),
//! holding per primitive a `Cube` (size 2, scaled by the half extents), `Sphere`,
//! `Capsule` (`height` between the cap centres, as USD defines it) or `Cylinder`
//! (full `height`), all along local Z, each with `PhysicsCollisionAPI`; frustums
//! and prisms are `Mesh`es of the conservative tessellation with
//! `PhysicsMeshCollisionAPI` and `physics:approximation = "convexHull"`. Prim
//! names are identifiers (other characters become `_`, made unique); the original
//! name is kept in a `primdecomp:name` string, escaped.

use super::engine::{prepare, quat_between, ExportOptions, Format, Shape};
use super::names::{ident, quote, Names};
use primdecomp::Body;
use primdecomp_files::visible;
use primdecomp_math::V3;
use std::fmt::Write;

fn tuple(v: &[f64]) -> String {
    let s: Vec<String> = v.iter().map(|&x| super::engine::num(x)).collect();
    format!("({})", s.join(", "))
}

/// translate + orient (+ scale) ops at indentation `ind`.
fn xform(out: &mut String, ind: &str, t: V3, q: [f64; 4], scale: Option<V3>) {
    let [x, y, z, w] = q;
    let _ = writeln!(out, "{ind}double3 xformOp:translate = {}", tuple(&t));
    let _ = writeln!(out, "{ind}quatd xformOp:orient = {}", tuple(&[w, x, y, z]));
    let mut ops = vec!["\"xformOp:translate\"", "\"xformOp:orient\""];
    if let Some(s) = scale {
        let _ = writeln!(out, "{ind}double3 xformOp:scale = {}", tuple(&s));
        ops.push("\"xformOp:scale\"");
    }
    let _ = writeln!(
        out,
        "{ind}uniform token[] xformOpOrder = [{}]",
        ops.join(", ")
    );
}

/// The `.usda` text, or why it cannot be written ([`prepare`]).
pub fn to_usda(objects: &[Body], opts: &ExportOptions) -> Result<String, String> {
    let prepared = prepare(objects, Format::Usda, opts, false)?;
    let root = ident(&visible(&opts.model), true);
    let mut out = String::new();
    let _ = writeln!(out, "#usda 1.0");
    let _ = writeln!(out, "(");
    let _ = writeln!(out, "    defaultPrim = {}", quote(&root));
    let _ = writeln!(
        out,
        "    doc = \"primdecomp colliders (docs/decisions/exports-engine-conventions.md)\""
    );
    let _ = writeln!(out, "    metersPerUnit = 1");
    let _ = writeln!(out, "    upAxis = \"{}\"", opts.up.name());
    let _ = writeln!(out, ")");
    let _ = writeln!(out);
    let _ = writeln!(out, "def Xform {}", quote(&root));
    let _ = writeln!(out, "{{");
    let mut used = Names::default();
    for o in &prepared {
        let name = used.unique(ident(&o.name, true));
        let _ = writeln!(out, "    def Xform {}", quote(&name));
        let _ = writeln!(out, "    {{");
        let _ = writeln!(
            out,
            "        custom string primdecomp:name = {}",
            quote(&o.name)
        );
        xform(
            &mut out,
            "        ",
            o.frame.translation,
            o.frame.rotation,
            None,
        );
        for (i, (kind, s)) in o.shapes.iter().enumerate() {
            collider(&mut out, &format!("{}_{i}", kind.name()), s);
        }
        let _ = writeln!(out, "    }}");
    }
    let _ = writeln!(out, "}}");
    Ok(out)
}

/// The collider prim `prim` of shape `s`, with its physics API schemas.
fn collider(out: &mut String, prim: &str, s: &Shape) {
    let (ty, api) = match s {
        Shape::Box { .. } => ("Cube", "\"PhysicsCollisionAPI\""),
        Shape::Sphere { .. } => ("Sphere", "\"PhysicsCollisionAPI\""),
        Shape::Capsule { .. } => ("Capsule", "\"PhysicsCollisionAPI\""),
        Shape::Round { .. } => ("Cylinder", "\"PhysicsCollisionAPI\""),
        Shape::Hull(_) => (
            "Mesh",
            "\"PhysicsCollisionAPI\", \"PhysicsMeshCollisionAPI\"",
        ),
    };
    let _ = writeln!(out);
    let _ = writeln!(out, "        def {ty} {} (", quote(prim));
    let _ = writeln!(out, "            prepend apiSchemas = [{api}]");
    let _ = writeln!(out, "        )");
    let _ = writeln!(out, "        {{");
    shape_attributes(out, "            ", s);
    let _ = writeln!(out, "        }}");
}

/// Shape `s`'s attributes and transform at indentation `ind`.
fn shape_attributes(out: &mut String, ind: &str, s: &Shape) {
    let z = [0.0, 0.0, 1.0];
    let id = [0.0, 0.0, 0.0, 1.0];
    match s {
        Shape::Box {
            center,
            rotation,
            half,
        } => {
            let _ = writeln!(out, "{ind}double size = 2");
            xform(out, ind, *center, *rotation, Some(*half));
        }
        Shape::Sphere { center, radius } => {
            let _ = writeln!(out, "{ind}double radius = {}", super::engine::num(*radius));
            xform(out, ind, *center, id, None);
        }
        Shape::Capsule { p0, p1, radius } => {
            let (c, a, h) = Shape::axis(*p0, *p1);
            let _ = writeln!(out, "{ind}uniform token axis = \"Z\"");
            let _ = writeln!(out, "{ind}double height = {}", super::engine::num(2.0 * h));
            let _ = writeln!(out, "{ind}double radius = {}", super::engine::num(*radius));
            xform(out, ind, c, quat_between(z, a), None);
        }
        Shape::Round { p0, p1, r0, r1 } => {
            let (c, a, h) = Shape::axis(*p0, *p1);
            let _ = writeln!(out, "{ind}uniform token axis = \"Z\"");
            let _ = writeln!(out, "{ind}double height = {}", super::engine::num(2.0 * h));
            let r = super::engine::num(r0.max(*r1));
            let _ = writeln!(out, "{ind}double radius = {r}");
            xform(out, ind, c, quat_between(z, a), None);
        }
        Shape::Hull(t) => {
            let pts: Vec<String> = t.vertices.iter().map(|v| tuple(v)).collect();
            let counts: Vec<String> = t.faces.iter().map(|f| f.len().to_string()).collect();
            let idx: Vec<String> = t.faces.iter().flatten().map(|i| i.to_string()).collect();
            let _ = writeln!(
                out,
                "{ind}uniform token physics:approximation = \"convexHull\""
            );
            let _ = writeln!(out, "{ind}uniform token subdivisionScheme = \"none\"");
            let _ = writeln!(out, "{ind}point3f[] points = [{}]", pts.join(", "));
            let _ = writeln!(out, "{ind}int[] faceVertexCounts = [{}]", counts.join(", "));
            let _ = writeln!(out, "{ind}int[] faceVertexIndices = [{}]", idx.join(", "));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strings_are_escaped() {
        assert_eq!(quote("a\"b\\c\nd<e>"), "\"a\\\"b\\\\c\\\\u{a}d<e>\"");
    }
}
