//! What the engine exports share: the formats, the options (`--up`,
//! `--scale`), the conversion of a result into the format's frame, and the mapping of
//! each primitive kind to a native shape or to the conservative tessellation of
//! [`tessellate`].
//!
//! Conventions (docs/decisions/exports-engine-conventions.md):
//! - `--up` names the up axis of the result (the input's): `y` (default) or `z`.
//!   glTF and Godot are +Y up, MJCF and URDF +Z up (gravity along −z), so a result
//!   whose up differs is turned by ±90° about x; USD declares the result's own axis
//!   in `upAxis` and is not turned.
//! - `--scale S` multiplies every length (input units → metres); the formats take
//!   metres, and USD says `metersPerUnit = 1`.
//! - Every shape is grown by [`Frame::GROW_REL`] of its magnitude
//!   ([`Frame::conservative`]) before it is written, so rounding in the
//!   consumer cannot cut a face.

use super::names::Names;
use super::range;
use primdecomp::Body;
use primdecomp::Frame;
use primdecomp::Tess;
use primdecomp::Up;
use primdecomp::{Kind, Primitive};
use primdecomp_files::visible;
use primdecomp_math::{add, norm, normalize, scale, sub, V3};
use std::path::Path;

/// An export format.
///
/// ```
/// use primdecomp_export::Format;
///
/// assert_eq!(Format::from_path("robot.urdf".as_ref()), Some(Format::Urdf));
/// assert_eq!(Format::from_path("scene.xml".as_ref()), None); // MJCF or not: say so
/// assert_eq!(Format::from_name("usd"), Some(Format::Usda));
/// assert_eq!(Format::Mjcf.up(), Some(primdecomp::Up::Z));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// glTF 2.0 JSON (`.gltf`, buffers embedded as data URIs).
    Gltf,
    /// Binary glTF (`.glb`).
    Glb,
    /// MuJoCo MJCF (`.xml`, only with `--format mjcf`).
    Mjcf,
    /// URDF (`.urdf`), mesh files beside it.
    Urdf,
    /// USD text (`.usda`).
    Usda,
    /// Godot 4 text scene (`.tscn`).
    Tscn,
}

impl Format {
    /// Every format, in the order `--help` lists them.
    pub const ALL: [Format; 6] = [
        Format::Gltf,
        Format::Glb,
        Format::Mjcf,
        Format::Urdf,
        Format::Usda,
        Format::Tscn,
    ];

    /// The name `--format` takes.
    pub fn name(self) -> &'static str {
        match self {
            Format::Gltf => "gltf",
            Format::Glb => "glb",
            Format::Mjcf => "mjcf",
            Format::Urdf => "urdf",
            Format::Usda => "usda",
            Format::Tscn => "tscn",
        }
    }

    /// The format a `--format` name gives (`usd` is `usda`), case-insensitive.
    pub fn from_name(s: &str) -> Option<Format> {
        let s = s.to_ascii_lowercase();
        Format::ALL
            .into_iter()
            .find(|f| f.name() == s || (s == "usd" && *f == Format::Usda))
    }

    /// The format a path's extension names (`.xml` is ambiguous: give `--format`).
    pub fn from_path(p: &Path) -> Option<Format> {
        let ext = p.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "gltf" => Some(Format::Gltf),
            "glb" => Some(Format::Glb),
            "urdf" => Some(Format::Urdf),
            "usda" => Some(Format::Usda),
            "tscn" => Some(Format::Tscn),
            "mjcf" => Some(Format::Mjcf),
            _ => None,
        }
    }

    /// The format's own up axis (`None`: USD declares any).
    pub fn up(self) -> Option<Up> {
        match self {
            Format::Gltf | Format::Glb | Format::Tscn => Some(Up::Y),
            Format::Mjcf | Format::Urdf => Some(Up::Z),
            Format::Usda => None,
        }
    }

    /// The kinds the format writes natively; the others become convex hulls.
    pub fn native(self, opts: &ExportOptions) -> [bool; 6] {
        let mut n = [true, true, true, true, false, false];
        match self {
            // KHR_implicit_shapes' cylinder has two radii: a frustum is one.
            Format::Gltf | Format::Glb => n[Kind::Frustum as usize] = opts.physics == Physics::Khr,
            // URDF 1.0 has no capsule: an exact cylinder and two spheres.
            Format::Urdf => n[Kind::Capsule as usize] = true,
            _ => {}
        }
        n
    }
}

/// The glTF physics extensions to write.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Physics {
    /// `KHR_implicit_shapes` + `KHR_physics_rigid_bodies` (Khronos).
    #[default]
    Khr,
    /// `OMI_physics_shape` + `OMI_physics_body` (Godot 4 imports these natively).
    Omi,
}

/// Options of every export.
#[derive(Clone, Debug, PartialEq)]
pub struct ExportOptions {
    /// The result's up axis.
    pub up: Up,
    /// Length multiplier (input units → metres); positive and finite.
    pub scale: f64,
    /// Segments around circles of the tessellated kinds (at least 3).
    pub detail: usize,
    /// glTF: which physics extensions.
    pub physics: Physics,
    /// glTF: also coloured preview meshes of the colliders.
    pub preview: bool,
    /// URDF: write capsules as `<capsule>` (not URDF 1.0) instead of a cylinder and
    /// two spheres.
    pub urdf_capsule: bool,
    /// The model's name (MJCF model, URDF robot, USD default prim, Godot root).
    pub model: String,
    /// glTF: the input mesh to include (result coordinates, polygons).
    pub input_mesh: Option<(Vec<V3>, Vec<Vec<u32>>)>,
}

impl Default for ExportOptions {
    fn default() -> Self {
        ExportOptions {
            up: Up::Y,
            scale: 1.0,
            detail: primdecomp::Tess::DEFAULT_DETAIL,
            physics: Physics::Khr,
            preview: false,
            urdf_capsule: false,
            model: "primdecomp".into(),
            input_mesh: None,
        }
    }
}

/// A shape as the writers see it, in its object's frame.
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    /// Centre, rotation (scalar-last quaternion) and half extents.
    Box {
        center: V3,
        rotation: [f64; 4],
        half: V3,
    },
    Sphere {
        center: V3,
        radius: f64,
    },
    /// Segment `p0`–`p1` (distinct) and radius.
    Capsule {
        p0: V3,
        p1: V3,
        radius: f64,
    },
    /// A solid of revolution from `p0` (radius `r0`) to `p1` (radius `r1`); a
    /// cylinder when the radii are equal. `p0 != p1`.
    Round {
        p0: V3,
        p1: V3,
        r0: f64,
        r1: f64,
    },
    /// A closed convex polyhedron (the conservative tessellation).
    Hull(Tess),
}

impl Shape {
    /// Centre of the segment or solid and its half length, unit axis.
    pub fn axis(p0: V3, p1: V3) -> (V3, V3, f64) {
        let c = scale(add(p0, p1), 0.5);
        let a = normalize(sub(p1, p0)).unwrap_or([0.0, 0.0, 1.0]);
        (c, a, 0.5 * norm(sub(p1, p0)))
    }
}

/// One object ready to write: a unique name, its frame in the format's coordinates
/// (up axis and scale applied) and its shapes with the kind each came from.
#[derive(Clone, Debug)]
pub struct Prepared {
    pub name: String,
    pub frame: Frame,
    pub shapes: Vec<(Kind, Shape)>,
}

/// The rotation turning the result's up axis into the format's (identity when they
/// agree): +90° about x takes +y to +z, −90° takes +z to +y.
pub fn up_rotation(from: Up, to: Option<Up>) -> [f64; 4] {
    let h = std::f64::consts::FRAC_1_SQRT_2;
    match (from, to) {
        (Up::Y, Some(Up::Z)) => [h, 0.0, 0.0, h],
        (Up::Z, Some(Up::Y)) => [-h, 0.0, 0.0, h],
        _ => [0.0, 0.0, 0.0, 1.0],
    }
}

/// The frame taking result coordinates to the format's: rotation and scale.
pub fn format_frame(format: Format, opts: &ExportOptions) -> Frame {
    Frame {
        translation: [0.0; 3],
        rotation: up_rotation(opts.up, format.up()),
        scale: opts.scale,
    }
}

impl ExportOptions {
    /// Refuses a scale that is not positive and finite, and fewer than 3 segments.
    ///
    /// ```
    /// let mut opts = primdecomp_export::ExportOptions::default();
    /// assert!(opts.validate().is_ok());
    /// opts.scale = 0.0;
    /// assert!(opts.validate().is_err());
    /// ```
    pub fn validate(&self) -> Result<(), primdecomp::Error> {
        check_options(self).map_err(primdecomp::Error::InvalidParams)
    }
}

/// The options' problem in one sentence, if any.
pub(crate) fn check_options(opts: &ExportOptions) -> Result<(), String> {
    if !(opts.scale.is_finite() && opts.scale > 0.0) {
        return Err(format!(
            "--scale must be positive and finite, got {}",
            opts.scale
        ));
    }
    if !(3..=primdecomp::Tess::MAX_DETAIL).contains(&opts.detail) {
        return Err(format!(
            "--export-detail must be from 3 to {}, got {}",
            primdecomp::Tess::MAX_DETAIL,
            opts.detail
        ));
    }
    Ok(())
}

/// The most primitives one export writes: engines load colliders shape by shape, and
/// the glTF writer holds about 6.5 KB per primitive (20 KB with `preview`; measured
/// with 100,000 spheres: 657 MB and 1.98 GB peak), so 65,536 stay within about 1.3 GB.
pub const MAX_PRIMITIVES: usize = 65_536;

/// The most vertices of tessellated shapes (hulls, and previews) one export writes:
/// 2²⁴, some hundreds of MB of geometry.
pub const MAX_VERTICES: usize = 1 << 24;

/// Vertices the export's tessellated shapes will have: the kinds written as hulls
/// (every kind with a preview), counted once per kind at `detail`.
fn tessellated_vertices(
    objects: &[Body],
    native: [bool; 6],
    preview: bool,
    detail: usize,
) -> usize {
    let mut per_kind = [None; 6];
    objects
        .iter()
        .flat_map(|o| &o.primitives)
        .filter(|p| preview || !native[p.kind() as usize])
        .map(|p| {
            *per_kind[p.kind() as usize].get_or_insert_with(|| p.tessellate(detail).vertices.len())
        })
        .fold(0usize, usize::saturating_add)
}

/// The objects of a result in the format's frame. With `keep_scale` an object's
/// frame keeps its own scale (glTF nodes) and `--scale` is baked into the shapes,
/// otherwise every scale is baked into the shapes and the frame is rigid (scale 1). Names are made visible ([`visible`]: control
/// characters escaped), non-empty (`object`, then `name_2`, …) and unique, clear of
/// the format's reserved names (MuJoCo's `world`), before the writer escapes them for
/// its syntax. Refuses (one sentence naming the object and primitive) a shape whose
/// numbers the format's readers could not load ([`super::range`]).
pub fn prepare(
    objects: &[Body],
    format: Format,
    opts: &ExportOptions,
    keep_scale: bool,
) -> Result<Vec<Prepared>, String> {
    let native = format.native(opts);
    check_size(objects, format, opts, native)?;
    let to_format = format_frame(format, opts);
    let reserved: &[&str] = match format {
        Format::Mjcf => &["world"],
        _ => &[],
    };
    let mut names = Names::with_reserved(reserved);
    let mut out = Vec::with_capacity(objects.len());
    for (i, o) in objects.iter().enumerate() {
        let (frame, inner) = frames(o, &to_format, opts, keep_scale);
        // The consumer adds the frame's translation: its rounding counts too,
        // relative to the local units.
        let offset = norm(frame.translation) / frame.scale;
        let object = |j: usize, kind: Kind| match (objects.len(), o.name.is_empty()) {
            (1, true) => format!("primitive {j} ({})", kind.name()),
            _ => format!("object {i} ({:?}), primitive {j} ({})", o.name, kind.name()),
        };
        let this = match (objects.len(), o.name.is_empty()) {
            (1, true) => "the result".to_string(),
            _ => format!("object {i} ({:?})", o.name),
        };
        range::check_frame(&frame, keep_scale, &this)?;
        let mut shapes = Vec::with_capacity(o.primitives.len());
        for (j, p) in o.primitives.iter().enumerate() {
            let q = inner.conservative(p, offset);
            let what = object(j, p.kind());
            range::check_shape(&q, &frame, keep_scale, &what)?;
            let s = shape(&q, native, opts.detail);
            if let (Format::Mjcf, Shape::Hull(t)) = (format, &s) {
                range::check_mjcf(t, &what)?;
            }
            shapes.push((p.kind(), s));
        }
        let base = match (o.name.is_empty(), objects.len()) {
            (true, 1) => visible(&opts.model),
            (true, _) => format!("object{i}"),
            (false, _) => visible(&o.name),
        };
        out.push(Prepared {
            name: names.unique(base),
            frame,
            shapes,
        });
    }
    if let Some((points, _)) = &opts.input_mesh {
        range::check_points(points, &to_format)?;
    }
    Ok(out)
}

/// Refuses a result of no primitive, or of more primitives or tessellated vertices
/// than an export writes.
fn check_size(
    objects: &[Body],
    format: Format,
    opts: &ExportOptions,
    native: [bool; 6],
) -> Result<(), String> {
    let total: usize = objects.iter().map(|o| o.primitives.len()).sum();
    if total == 0 {
        // glTF has no valid scene without nodes, and a collider file without a
        // collider is a mistake upstream.
        return Err("the result holds no primitive: there is nothing to export".into());
    }
    if total > MAX_PRIMITIVES {
        return Err(format!(
            "the result holds {total} primitives, and an export takes at most \
             {MAX_PRIMITIVES}; export a coarser level (a smaller -n)"
        ));
    }
    // Previews are glTF's alone.
    let preview = opts.preview && matches!(format, Format::Gltf | Format::Glb);
    let vertices = tessellated_vertices(objects, native, preview, opts.detail);
    if vertices > MAX_VERTICES {
        return Err(format!(
            "its hulls{} would hold {vertices} vertices at {} segments around circles, more \
             than the {MAX_VERTICES} an export writes; lower --export-detail",
            if preview { " and previews" } else { "" },
            opts.detail
        ));
    }
    Ok(())
}

/// Object `o`'s frame in the format's (`to_format`) and the frame its shapes are
/// taken through: with `keep_scale` the object's own scale stays on its frame and
/// `--scale` goes into the shapes (so a result beyond 32-bit range can be scaled into
/// it), otherwise the frame is rigid and every scale goes into the shapes.
fn frames(o: &Body, to_format: &Frame, opts: &ExportOptions, keep_scale: bool) -> (Frame, Frame) {
    let full = o.frame.then(to_format);
    if keep_scale {
        let node = Frame {
            scale: o.frame.scale,
            ..full
        };
        let inner = Frame {
            scale: opts.scale,
            ..Frame::IDENTITY
        };
        (node, inner)
    } else {
        let rigid = Frame { scale: 1.0, ..full };
        let inner = Frame {
            scale: full.scale,
            ..Frame::IDENTITY
        };
        (rigid, inner)
    }
}

/// The writer's shape of an (already grown) primitive: native where `native` says
/// so, else its conservative tessellation with `detail` segments.
pub fn shape(p: &Primitive, native: [bool; 6], detail: usize) -> Shape {
    if !native[p.kind() as usize] {
        return Shape::Hull(p.tessellate(detail));
    }
    match *p {
        Primitive::Box(b) => Shape::Box {
            center: b.center,
            rotation: primdecomp_math::quat_from_axes(&right_handed(b.axes)),
            half: b.half,
        },
        Primitive::Sphere(s) => Shape::Sphere {
            center: s.center,
            radius: s.radius,
        },
        // A capsule whose segment is shorter than MIN_AXIS_REL of its radius (its half
        // length may round to 0, which MuJoCo and URDF refuse): the sphere around it.
        Primitive::Capsule(c) if norm(sub(c.p1, c.p0)) <= Frame::MIN_AXIS_REL * c.radius => {
            let (center, _, h) = Shape::axis(c.p0, c.p1);
            Shape::Sphere {
                center,
                radius: c.radius + h,
            }
        }
        Primitive::Capsule(c) => Shape::Capsule {
            p0: c.p0,
            p1: c.p1,
            radius: c.radius,
        },
        // Grown solids of revolution have distinct ends (frame::grow).
        Primitive::Cylinder(c) => Shape::Round {
            p0: c.p0,
            p1: c.p1,
            r0: c.radius,
            r1: c.radius,
        },
        Primitive::Frustum(f) => Shape::Round {
            p0: f.p0,
            p1: f.p1,
            r0: f.r0,
            r1: f.r1,
        },
        Primitive::Prism(_) => Shape::Hull(p.tessellate(detail)),
    }
}

/// Box axes made right-handed (a box is symmetric: flipping the third axis changes
/// nothing), so they form a rotation.
fn right_handed(a: [V3; 3]) -> [V3; 3] {
    if primdecomp_math::dot(primdecomp_math::cross(a[0], a[1]), a[2]) >= 0.0 {
        a
    } else {
        [a[0], a[1], scale(a[2], -1.0)]
    }
}

/// A unit quaternion (scalar last) turning the local axis `local` (unit) onto the
/// unit vector `a`: the shortest arc, or a half turn about an axis perpendicular to
/// `local` when `a` is opposite.
pub fn quat_between(local: V3, a: V3) -> [f64; 4] {
    let d = primdecomp_math::dot(local, a);
    if d < -1.0 + 1e-12 {
        let (u, _) = primdecomp_math::circle_frame(local);
        return [u[0], u[1], u[2], 0.0];
    }
    let c = primdecomp_math::cross(local, a);
    let q = [c[0], c[1], c[2], 1.0 + d];
    let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
    q.map(|x| x / n)
}

/// Shortest text that reads back as the same f64 (Rust's `{:?}`: `1.0`, `0.25`,
/// `1e-20`), never `-0.0`.
pub fn num(x: f64) -> String {
    let x = x + 0.0;
    format!("{x:?}")
}

/// Files an export writes: the main file's bytes, and files beside it (relative
/// path, bytes), e.g. URDF meshes.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Files {
    /// The bytes of the file the caller named.
    pub main: Vec<u8>,
    /// Files beside it: a path relative to the main file's folder, and the bytes.
    pub beside: Vec<(String, Vec<u8>)>,
}

/// `R(q) · v`, for the tests of the writers.
#[cfg(test)]
pub(crate) fn rotate(q: [f64; 4], v: V3) -> V3 {
    Frame {
        rotation: q,
        ..Frame::IDENTITY
    }
    .vector(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn up_rotations_turn_the_right_way() {
        let y_to_z = up_rotation(Up::Y, Some(Up::Z));
        let v = rotate(y_to_z, [0.0, 1.0, 0.0]);
        assert!((v[2] - 1.0).abs() < 1e-15 && v[1].abs() < 1e-15);
        let z_to_y = up_rotation(Up::Z, Some(Up::Y));
        let v = rotate(z_to_y, [0.0, 0.0, 1.0]);
        assert!((v[1] - 1.0).abs() < 1e-15 && v[2].abs() < 1e-15);
        assert_eq!(up_rotation(Up::Z, None), [0.0, 0.0, 0.0, 1.0]);
    }

    #[test]
    fn quat_between_maps_the_axis() {
        for a in [
            [0.0, 1.0, 0.0],
            [0.0, -1.0, 0.0],
            [0.6, 0.0, 0.8],
            [0.0, 0.0, -1.0],
        ] {
            for local in [[0.0, 1.0, 0.0], [0.0, 0.0, 1.0]] {
                let q = quat_between(local, a);
                let v = rotate(q, local);
                assert!(
                    (0..3).all(|i| (v[i] - a[i]).abs() < 1e-12),
                    "{local:?} → {a:?}: {v:?}"
                );
            }
        }
    }

    #[test]
    fn numbers_are_short() {
        assert_eq!(num(-0.0), "0.0");
        assert_eq!(num(0.1), "0.1");
        assert_eq!(num(1e-20), "1e-20");
    }
}
