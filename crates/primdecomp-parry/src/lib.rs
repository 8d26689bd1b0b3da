//! primdecomp's primitives as [parry3d](https://parry.rs) shapes, for Rust engines:
//! Rapier takes the compound as a collider's shape, and Bevy through bevy_rapier3d
//! (`Collider::from(shape)`).
//!
//! ```
//! use primdecomp::{Goal, Params, decompose, demo_scene};
//! use primdecomp_parry::compound;
//!
//! let result = decompose(&demo_scene(), &Params { goal: Goal::counts([40]), ..Params::default() })?;
//! let colliders = compound(&result.levels[0].primitives)?;
//! // One shape holding every primitive, relative to `colliders.origin`: place the
//! // collider (or the body it is attached to) there.
//! assert_eq!(colliders.shape.as_compound().unwrap().shapes().len(), result.levels[0].primitives.len());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! Boxes, spheres, capsules and cylinders become parry's own shapes; frustums and
//! prisms, which parry lacks, the convex hull of their conservative tessellation
//! ([`primdecomp::Primitive::tessellate`], which contains the exact primitive). parry works in
//! `f32`: each shape is placed relative to an origin near the primitives (so that
//! `f32` keeps their detail) and grown by 2⁻¹⁸ of its size plus its distance from that
//! origin, the margin the engine exports use (docs/decisions/exports-engine-conventions.md),
//! so that rounding to `f32` cannot cut an input face: every input face stays inside
//! the compound.

use parry3d::math::{Pose, Rotation, Vector};
use parry3d::shape::SharedShape;
use primdecomp::{Kind, Primitive};
use primdecomp_math::{add, norm, quat_from_axes, scale, sub, V3};

/// How much each shape grows, relative to its size plus its distance from the origin.
pub const GROW_REL: f64 = 1.0 / 262_144.0;

/// Segments around the circles of a frustum's hull.
const FRUSTUM_DETAIL: usize = primdecomp::Tess::DEFAULT_DETAIL;

/// A primitive parry cannot hold (a hull with no volume). The library's own output
/// never has one: every primitive is at least its minimum extent thick.
#[derive(Debug, thiserror::Error)]
#[error("primitive {index} ({kind}) spans no volume: parry cannot build its convex hull")]
pub struct ShapeError {
    /// Its index in the slice given.
    pub index: usize,
    /// Its kind's name.
    pub kind: &'static str,
}

/// Primitives as one compound shape, relative to `origin`.
#[derive(Clone)]
pub struct Colliders {
    /// A [`parry3d::shape::Compound`] with one part per primitive, in the order given.
    pub shape: SharedShape,
    /// Where the shape's frame sits in the primitives' coordinates (the centre of
    /// their bounding box): a collider with this shape belongs at this translation.
    pub origin: V3,
}

impl Colliders {
    /// The pose that puts the shape back where the primitives are (the translation
    /// to [`Colliders::origin`], in `f32`).
    pub fn pose(&self) -> Pose {
        Pose::from_translation(vector(self.origin))
    }
}

/// Every primitive as a part of one compound shape (see the crate's example).
///
/// # Errors
/// [`ShapeError`] for a frustum or prism with no volume.
pub fn compound(primitives: &[Primitive]) -> Result<Colliders, ShapeError> {
    let origin = centre(primitives);
    let parts = shapes(primitives, origin)?;
    Ok(Colliders {
        shape: SharedShape::compound(parts),
        origin,
    })
}

/// Every primitive as its own shape and pose relative to `origin` (for one collider
/// per primitive).
///
/// # Errors
/// [`ShapeError`] for a frustum or prism with no volume.
pub fn shapes(
    primitives: &[Primitive],
    origin: V3,
) -> Result<Vec<(Pose, SharedShape)>, ShapeError> {
    primitives
        .iter()
        .enumerate()
        .map(|(index, p)| {
            shape(p, origin).ok_or(ShapeError {
                index,
                kind: p.kind().name(),
            })
        })
        .collect()
}

/// One primitive as a parry shape and its pose relative to `origin`, grown by
/// [`GROW_REL`] of its size plus its distance from `origin`; `None` for a hull with
/// no volume.
pub fn shape(p: &Primitive, origin: V3) -> Option<(Pose, SharedShape)> {
    let (lo, hi) = bounds(p);
    let centre = scale(add(lo, hi), 0.5);
    let margin = GROW_REL * (norm(sub(hi, lo)) + norm(sub(centre, origin)));
    let grow = |x: f64| (x + margin) as f32;
    Some(match *p {
        Primitive::Box(b) => (
            Pose::from_parts(vector(sub(b.center, origin)), rotation(&b.axes)),
            SharedShape::cuboid(grow(b.half[0]), grow(b.half[1]), grow(b.half[2])),
        ),
        Primitive::Sphere(s) => (
            Pose::from_translation(vector(sub(s.center, origin))),
            SharedShape::ball(grow(s.radius)),
        ),
        Primitive::Capsule(c) => (
            Pose::IDENTITY,
            SharedShape::capsule(
                vector(sub(c.p0, origin)),
                vector(sub(c.p1, origin)),
                grow(c.radius),
            ),
        ),
        Primitive::Cylinder(c) => {
            let d = sub(c.p1, c.p0);
            let len = norm(d);
            let up = if len > 0.0 {
                Rotation::from_rotation_arc(Vector::Y, vector(scale(d, 1.0 / len)).normalize())
            } else {
                Rotation::IDENTITY
            };
            let mid = scale(add(c.p0, c.p1), 0.5);
            (
                Pose::from_parts(vector(sub(mid, origin)), up),
                SharedShape::cylinder(grow(0.5 * len), grow(c.radius)),
            )
        }
        Primitive::Frustum(_) | Primitive::Prism(_) => hull(p, centre, origin, margin)?,
    })
}

/// A frustum or prism as the hull of its conservative tessellation, each vertex
/// pushed `margin` further from the centre (the hull of the pushed vertices holds the
/// hull of the others), relative to the centre.
fn hull(p: &Primitive, centre: V3, origin: V3, margin: f64) -> Option<(Pose, SharedShape)> {
    let detail = if p.kind() == Kind::Frustum {
        FRUSTUM_DETAIL
    } else {
        3
    };
    let points: Vec<Vector> = p
        .tessellate(detail)
        .vertices
        .iter()
        .map(|&v| {
            let r = sub(v, centre);
            let n = norm(r);
            vector(if n > 0.0 {
                scale(r, 1.0 + margin / n)
            } else {
                r
            })
        })
        .collect();
    let shape = SharedShape::convex_hull(&points)?;
    Some((Pose::from_translation(vector(sub(centre, origin))), shape))
}

/// The axis-aligned box around a primitive.
fn bounds(p: &Primitive) -> (V3, V3) {
    let axis = |k: usize| {
        let mut n = [0.0; 3];
        n[k] = 1.0;
        n
    };
    let hi = [0, 1, 2].map(|k| p.support(axis(k)));
    let lo = [0, 1, 2].map(|k| -p.support(scale(axis(k), -1.0)));
    (lo, hi)
}

/// The centre of the primitives' bounding box (the origin at 0 when there are none).
fn centre(primitives: &[Primitive]) -> V3 {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in primitives {
        let (a, b) = bounds(p);
        for k in 0..3 {
            lo[k] = lo[k].min(a[k]);
            hi[k] = hi[k].max(b[k]);
        }
    }
    if primitives.is_empty() {
        return [0.0; 3];
    }
    scale(add(lo, hi), 0.5)
}

fn vector(v: V3) -> Vector {
    Vector::new(v[0] as f32, v[1] as f32, v[2] as f32)
}

fn rotation(axes: &[V3; 3]) -> Rotation {
    let q = quat_from_axes(axes);
    Rotation::from_xyzw(q[0] as f32, q[1] as f32, q[2] as f32, q[3] as f32).normalize()
}
