//! URDF export: a root link, and one link per object joined to it by a
//! fixed joint at the object's frame (`xyz`, and `rpy` = fixed-axis roll, pitch,
//! yaw: R = Rz(yaw)·Ry(pitch)·Rx(roll)). Each primitive is a `<collision>`: `box`
//! with full sizes, `sphere`, `cylinder` along its local z with full length; a
//! capsule is an exact cylinder plus two spheres (URDF 1.0 has no capsule; with
//! `urdf_capsule` one `<capsule radius length>`, length between the cap centres, as
//! Gazebo reads it); frustums and prisms are `<mesh>` OBJ files (the conservative
//! tessellation) written beside the URDF, referred to by relative paths. URDF is
//! +Z up: `--up y` results are turned.

use super::engine::{prepare, quat_between, ExportOptions, Files, Format, Prepared, Shape};
use super::names::{file_name, ident, MAX_FILE_NAME};
use super::xml::{nums, Xml};
use primdecomp::Body;
use primdecomp::Tess;
use primdecomp_files::visible;
use primdecomp_math::axes_from_quat;
use std::fmt::Write;

/// Fixed-axis roll, pitch, yaw of a unit quaternion (scalar last), from its matrix;
/// at pitch ±90° yaw is 0 and roll takes the whole turn about x.
pub fn rpy(q: [f64; 4]) -> [f64; 3] {
    let a = axes_from_quat(q);
    // r(i, j): row i, column j; column j is a[j].
    let r = |i: usize, j: usize| a[j][i];
    let cp = r(0, 0).hypot(r(1, 0));
    let pitch = (-r(2, 0)).atan2(cp);
    if cp > 1e-12 {
        [r(2, 1).atan2(r(2, 2)), pitch, r(1, 0).atan2(r(0, 0))]
    } else {
        [(-r(1, 2)).atan2(r(1, 1)), pitch, 0.0]
    }
}

fn origin(x: &mut Xml, xyz: [f64; 3], q: [f64; 4]) {
    x.empty("origin", &[("xyz", &nums(&xyz)), ("rpy", &nums(&rpy(q)))]);
}

/// OBJ text of a hull.
fn obj(t: &Tess) -> String {
    let mut s = String::from("# primdecomp collider hull (conservative tessellation)\n");
    for v in &t.vertices {
        let _ = writeln!(s, "v {}", nums(v));
    }
    for f in &t.faces {
        let idx: Vec<String> = f.iter().map(|i| (i + 1).to_string()).collect();
        let _ = writeln!(s, "f {}", idx.join(" "));
    }
    s
}

/// The folder of the URDF's mesh files for an output of stem `stem`: `{stem}_meshes`,
/// the stem as an identifier and cut ([`file_name`]) so the name stays a valid file
/// name.
pub fn mesh_dir(stem: &str) -> String {
    format!(
        "{}_meshes",
        file_name(&ident(stem, false), MAX_FILE_NAME - "_meshes".len())
    )
}

/// The URDF and its mesh files (`{stem}_meshes/…obj`, relative to the URDF), or why it
/// cannot be written ([`prepare`]).
pub fn to_urdf(objects: &[Body], opts: &ExportOptions, stem: &str) -> Result<Files, String> {
    let prepared = prepare(objects, Format::Urdf, opts, false)?;
    let mut files = Files::default();
    let mut x = Xml::new();
    let robot = visible(&opts.model);
    x.open("robot", &[("name", &robot)]);
    x.comment(
        "primdecomp colliders: one link per object (docs/decisions/exports-engine-conventions.md)",
    );
    let base = root_link(&robot, &prepared);
    x.empty("link", &[("name", &base)]);
    let dir = mesh_dir(stem);
    for (oi, o) in prepared.iter().enumerate() {
        x.open("link", &[("name", &o.name)]);
        for (i, (kind, s)) in o.shapes.iter().enumerate() {
            // Unique across the robot: consumers key collision geometry by name.
            let name = format!("{}_{}_{i}", o.name, kind.name());
            // At most 64 bytes of the name: the index keeps files apart.
            let file = || {
                let stem = file_name(&ident(&o.name, false), 64);
                format!("{dir}/{oi}_{stem}_{}_{i}.obj", kind.name())
            };
            collisions(&mut x, &mut files, &name, s, file, opts.urdf_capsule);
        }
        x.close("link");
        joint(&mut x, &base, o);
    }
    x.close("robot");
    files.main = x.finish().into_bytes();
    Ok(files)
}

/// The identity rotation (scalar last).
const ID: [f64; 4] = [0.0, 0.0, 0.0, 1.0];

/// The root link's name: `{robot}_root`, lengthened until no object's link has it.
fn root_link(robot: &str, prepared: &[Prepared]) -> String {
    let links: std::collections::HashSet<&str> = prepared.iter().map(|o| o.name.as_str()).collect();
    let mut base = format!("{robot}_root");
    while links.contains(base.as_str()) {
        base.push('_');
    }
    base
}

/// The fixed joint placing object `o`'s link on the root link `base`.
fn joint(x: &mut Xml, base: &str, o: &Prepared) {
    x.open(
        "joint",
        &[("name", &format!("{}_joint", o.name)), ("type", "fixed")],
    );
    x.empty("parent", &[("link", base)]);
    x.empty("child", &[("link", &o.name)]);
    origin(x, o.frame.translation, o.frame.rotation);
    x.close("joint");
}

/// One `<collision>` named `name` at `xyz` turned by `q`, of geometry `tag` with `attrs`.
fn collision(
    x: &mut Xml,
    name: &str,
    xyz: [f64; 3],
    q: [f64; 4],
    tag: &str,
    attrs: &[(&str, &str)],
) {
    x.open("collision", &[("name", name)]);
    origin(x, xyz, q);
    x.open("geometry", &[]);
    x.empty(tag, attrs);
    x.close("geometry");
    x.close("collision");
}

/// The collisions of a shape: a box, a sphere, a capsule (one `<capsule>` with
/// `urdf_capsule`, else a cylinder and two spheres), a cylinder, or a hull's mesh
/// written to the mesh file `file` names.
fn collisions(
    x: &mut Xml,
    files: &mut Files,
    name: &str,
    s: &Shape,
    file: impl FnOnce() -> String,
    urdf_capsule: bool,
) {
    let z = [0.0, 0.0, 1.0];
    match s {
        Shape::Box {
            center,
            rotation,
            half,
        } => {
            let size = nums(&half.map(|h| 2.0 * h));
            collision(x, name, *center, *rotation, "box", &[("size", &size)]);
        }
        Shape::Sphere { center, radius } => {
            collision(
                x,
                name,
                *center,
                ID,
                "sphere",
                &[("radius", &nums(&[*radius]))],
            );
        }
        Shape::Capsule { p0, p1, radius } => {
            let (c, a, h) = Shape::axis(*p0, *p1);
            let q = quat_between(z, a);
            let r = nums(&[*radius]);
            let len = nums(&[2.0 * h]);
            let attrs = [("radius", r.as_str()), ("length", len.as_str())];
            if urdf_capsule {
                collision(x, name, c, q, "capsule", &attrs);
            } else {
                collision(x, name, c, q, "cylinder", &attrs);
                for (e, p) in [("cap0", p0), ("cap1", p1)] {
                    let n = format!("{name}_{e}");
                    collision(x, &n, *p, ID, "sphere", &[("radius", &r)]);
                }
            }
        }
        Shape::Round { p0, p1, r0, r1 } => {
            let (c, a, h) = Shape::axis(*p0, *p1);
            let q = quat_between(z, a);
            let (r, len) = (nums(&[r0.max(*r1)]), nums(&[2.0 * h]));
            let attrs = [("radius", r.as_str()), ("length", len.as_str())];
            collision(x, name, c, q, "cylinder", &attrs);
        }
        Shape::Hull(t) => {
            let file = file();
            files.beside.push((file.clone(), obj(t).into_bytes()));
            collision(x, name, [0.0; 3], ID, "mesh", &[("filename", &file)]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::rotate;

    /// R = Rz(yaw)·Ry(pitch)·Rx(roll) applied to v.
    fn from_rpy([r, p, y]: [f64; 3], v: [f64; 3]) -> [f64; 3] {
        let (sr, cr, sp, cp, sy, cy) = (r.sin(), r.cos(), p.sin(), p.cos(), y.sin(), y.cos());
        let v = [v[0], cr * v[1] - sr * v[2], sr * v[1] + cr * v[2]];
        let v = [cp * v[0] + sp * v[2], v[1], -sp * v[0] + cp * v[2]];
        [cy * v[0] - sy * v[1], sy * v[0] + cy * v[1], v[2]]
    }

    #[test]
    fn rpy_reproduces_the_rotation() {
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let qs = [
            [0.1, 0.7, -0.2, 0.6],
            [h, 0.0, 0.0, h],
            [0.0, h, 0.0, h],  // pitch +90°
            [0.0, -h, 0.0, h], // pitch −90°
            [0.3, 0.5, 0.1, -0.2],
        ];
        for q in qs {
            let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
            let q = q.map(|x| x / n);
            let angles = rpy(q);
            for v in [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]] {
                let a = rotate(q, v);
                let b = from_rpy(angles, v);
                assert!(
                    (0..3).all(|i| (a[i] - b[i]).abs() < 1e-12),
                    "{q:?}: {a:?} vs {b:?}"
                );
            }
        }
    }
}
