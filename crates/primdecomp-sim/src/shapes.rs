//! Rapier shapes for the three kinds of collider the simulation compares (§4.1
//! "Simulation details"): our primitives — native cuboid, ball, capsule and
//! cylinder; prisms as [`PrismShape`] and frustums as [`FrustumShape`] (their corners'
//! hulls with an analytic point projection), since no engine has them —,
//! convex hulls (CoACD, V-HACD), and the input mesh itself as a triangle mesh.
//!
//! Every shape is placed in the simulation frame of [`Frame`]: world coordinates
//! minus the input's AABB centre, times a scale, in f32. Hull points are stored
//! relative to their own centroid and the centroid goes into the pose, so f32
//! keeps the detail of small parts far from the origin.

use super::frustum_shape::{FrustumShape, FRUSTUM_SEGMENTS};
use super::prism_shape::PrismShape;
use primdecomp::Mesh;
use primdecomp::{Frustum, Primitive};
use primdecomp_math::circle_frame;
use primdecomp_math::quat_from_axes;
use primdecomp_math::{add, cross, norm2, normalize, scale, sub, V3};
use rapier3d::geometry::SharedShape;
use rapier3d::math::{Pose, Rotation, Vector};

/// World → simulation coordinates: `(p − offset) · scale`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    pub offset: V3,
    pub scale: f64,
}

impl Frame {
    /// A world point in the simulation frame, still in f64.
    pub fn point(&self, p: V3) -> V3 {
        scale(sub(p, self.offset), self.scale)
    }
    /// A simulation-frame f64 point as Rapier's f32 vector.
    pub fn vector(p: V3) -> Vector {
        Vector::new(p[0] as f32, p[1] as f32, p[2] as f32)
    }
    /// A simulation-frame point back in world coordinates.
    pub fn to_world(&self, p: V3) -> V3 {
        add(scale(p, 1.0 / self.scale), self.offset)
    }
}

/// One static shape and where it sits.
pub type Placed = (SharedShape, Pose);

fn rotation(axes: &[V3; 3]) -> Rotation {
    let q = quat_from_axes(axes);
    Rotation::from_xyzw(q[0] as f32, q[1] as f32, q[2] as f32, q[3] as f32).normalize()
}

/// A shape whose axis is its local +y (Rapier's cylinder), placed between `p0` and
/// `p1` (simulation frame); returns the pose and the half-length.
fn y_axis_pose(p0: V3, p1: V3) -> (Pose, f32) {
    let d = sub(p1, p0);
    let len = norm2(d).sqrt();
    let mid = scale(add(p0, p1), 0.5);
    let rot = if len > 0.0 {
        Rotation::from_rotation_arc(Vector::Y, Frame::vector(scale(d, 1.0 / len)))
    } else {
        Rotation::IDENTITY
    };
    (
        Pose::from_parts(Frame::vector(mid), rot),
        (0.5 * len) as f32,
    )
}

/// Convex hull of simulation-frame points, relative to their centroid; `None` when
/// the points span no volume (Rapier cannot build the hull).
pub fn hull(points: &[V3]) -> Option<Placed> {
    if points.is_empty() {
        return None;
    }
    let c = scale(
        points.iter().fold([0.0; 3], |a, &p| add(a, p)),
        1.0 / points.len() as f64,
    );
    let local: Vec<Vector> = points.iter().map(|&p| Frame::vector(sub(p, c))).collect();
    let shape = SharedShape::convex_hull(&local)?;
    Some((shape, Pose::from_translation(Frame::vector(c))))
}

/// The largest magnitude a shape may reach in the simulation frame: Rapier holds
/// lengths in f32 and squares them (1e36 < f32's 3.4e38).
pub const MAX_LENGTH: f64 = 1e18;

/// How far a primitive reaches from the simulation frame's origin (the input's
/// centre, scaled to the scene), in the simulation's units; NaN if a number is not
/// finite.
pub fn reach(p: &Primitive, frame: &Frame) -> f64 {
    let (lo, hi) = p.aabb();
    lo.iter()
        .chain(&hi)
        .enumerate()
        .map(|(k, x)| ((x - frame.offset[k % 3]) * frame.scale).abs())
        .fold(0.0f64, |m, x| {
            if x.is_nan() || m.is_nan() {
                f64::NAN
            } else {
                m.max(x)
            }
        })
}

/// One primitive (world coordinates) as a Rapier shape in the simulation frame.
/// `None` only for a frustum or prism so flat that it has no volume.
pub fn primitive(p: &Primitive, frame: &Frame) -> Option<Placed> {
    let s = frame.scale;
    let placed = match *p {
        Primitive::Box(b) => {
            let h = b.half.map(|x| (x * s) as f32);
            let pose = Pose::from_parts(Frame::vector(frame.point(b.center)), rotation(&b.axes));
            (SharedShape::cuboid(h[0], h[1], h[2]), pose)
        }
        Primitive::Sphere(b) => (
            SharedShape::ball((b.radius * s) as f32),
            Pose::from_translation(Frame::vector(frame.point(b.center))),
        ),
        Primitive::Capsule(c) => {
            let (pose, half) = y_axis_pose(frame.point(c.p0), frame.point(c.p1));
            (SharedShape::capsule_y(half, (c.radius * s) as f32), pose)
        }
        Primitive::Cylinder(c) => {
            let (pose, half) = y_axis_pose(frame.point(c.p0), frame.point(c.p1));
            (SharedShape::cylinder(half, (c.radius * s) as f32), pose)
        }
        // A skewed prism (the cut's nearest fits) is its corners' hull: the analytic
        // projection assumes the isosceles section's symmetry.
        Primitive::Prism(q) if q.is_skewed() => {
            return hull(&q.corners().map(|c| frame.point(c)));
        }
        Primitive::Prism(q) => {
            let h = [q.hx, q.hy, q.hz_top, q.hz_bottom].map(|x| (x * s) as f32);
            let shape = PrismShape::new(h[0], h[1], h[2], h[3])?;
            let pose = Pose::from_parts(Frame::vector(frame.point(q.center)), rotation(&q.axes));
            (SharedShape::new(shape), pose)
        }
        Primitive::Frustum(f) => return frustum(&f, frame),
    };
    Some(placed)
}

/// A frustum as [`FrustumShape`]: the hull of the OBJ export's tessellation (same
/// vertex radii r / cos(π/k), same angles: the `stack` frame of the core's OBJ tessellation puts
/// vertex j at u cos t + v sin t, t = 2πj/k, which is angle −t in local (x, z) with
/// x = u, y = the axis, z = u × axis = −v).
fn frustum(f: &Frustum, frame: &Frame) -> Option<Placed> {
    let (p0, p1) = (frame.point(f.p0), frame.point(f.p1));
    let a = normalize(sub(p1, p0)).unwrap_or([0.0, 0.0, 1.0]);
    let (u, _) = circle_frame(a);
    let circ = frame.scale / (std::f64::consts::PI / FRUSTUM_SEGMENTS as f64).cos();
    let hy = 0.5 * norm2(sub(p1, p0)).sqrt();
    let shape = FrustumShape::new(hy as f32, (f.r0 * circ) as f32, (f.r1 * circ) as f32)?;
    let centre = scale(add(p0, p1), 0.5);
    let pose = Pose::from_parts(Frame::vector(centre), rotation(&[u, a, cross(u, a)]));
    Some((SharedShape::new(shape), pose))
}

/// The input mesh as one triangle mesh in the simulation frame: polygons
/// fan-triangulated, triangles with a repeated vertex or zero area dropped. `None`
/// when nothing is left.
pub fn trimesh(mesh: &Mesh, frame: &Frame) -> Option<Placed> {
    let s = frame.scale;
    let vertices: Vec<Vector> = (0..mesh.vertex_count() as u32)
        .map(|v| Frame::vector(scale(mesh.pos(v), s)))
        .collect();
    let mut triangles = Vec::with_capacity(mesh.face_count());
    for f in 0..mesh.face_count() {
        let face = mesh.face(f);
        for k in 1..face.len() - 1 {
            let t = [face[0], face[k], face[k + 1]];
            let (a, b, c) = (mesh.pos(t[0]), mesh.pos(t[1]), mesh.pos(t[2]));
            if t[0] != t[1]
                && t[1] != t[2]
                && t[0] != t[2]
                && norm2(cross(sub(b, a), sub(c, a))) > 0.0
            {
                triangles.push(t);
            }
        }
    }
    if triangles.is_empty() {
        return None;
    }
    let shape = SharedShape::trimesh(vertices, triangles).ok()?;
    // Mesh positions are already re-centred on the AABB centre (the frame's offset).
    Some((shape, Pose::IDENTITY))
}

#[cfg(test)]
mod tests {
    use super::*;
    use primdecomp::{Capsule, Cylinder, Obb, Prism, Sphere};
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// Random primitives of every kind, at an offset from the origin.
    fn samples(rng: &mut ChaCha8Rng) -> Vec<Primitive> {
        let mut v = || -> V3 { std::array::from_fn(|_| 100.0 + rng.gen_range(-2.0..2.0)) };
        let (a, b, c, d, e, f, g) = (v(), v(), v(), v(), v(), v(), v());
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        vec![
            Primitive::Box(Obb {
                center: a,
                axes: primdecomp_testkit::random_axes(&mut rng),
                half: [0.5, 1.25, 0.2],
            }),
            Primitive::Sphere(Sphere {
                center: b,
                radius: 0.7,
            }),
            Primitive::Capsule(Capsule {
                p0: c,
                p1: d,
                radius: 0.3,
            }),
            Primitive::Cylinder(Cylinder {
                p0: e,
                p1: f,
                radius: 0.6,
            }),
            Primitive::Frustum(Frustum {
                p0: f,
                p1: g,
                r0: 0.8,
                r1: 0.2,
            }),
            Primitive::Prism(Prism {
                center: g,
                axes: primdecomp_testkit::random_axes(&mut rng),
                hx: 1.0,
                hy: 0.5,
                hz_top: 0.1,
                hz_bottom: 0.75,
                shift: 0.0,
            }),
        ]
    }

    /// Each Rapier shape agrees with `Primitive::contains` on random points away
    /// from the surface: a wrong axis convention (Rapier's cylinder and capsule run
    /// along local y, quaternions are scalar-last) would put thousands of points on
    /// the wrong side. Frustums are conservative hulls, so only "inside the exact
    /// frustum ⇒ inside the hull" and "outside the circumscribed margin ⇒ outside"
    /// are required of them.
    #[test]
    fn shapes_agree_with_primitive_containment() {
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        let frame = Frame {
            offset: [100.0; 3],
            scale: 2.5,
        };
        for (i, p) in samples(&mut rng).iter().enumerate() {
            let (shape, pose) = primitive(p, &frame).expect("solid primitive");
            let (lo, hi) = p.aabb();
            // Frustum hull: circumscribed 16-gon reaches r / cos(π/16) ≈ 1.02 r.
            let outer = if matches!(p, Primitive::Frustum(_)) {
                0.05
            } else {
                0.02
            };
            let (mut inside, mut outside) = (0, 0);
            for _ in 0..20_000 {
                let q: V3 = std::array::from_fn(|k| rng.gen_range(lo[k] - 0.5..hi[k] + 0.5));
                let pt = Frame::vector(frame.point(q));
                let hit = shape.contains_point(&pose, pt);
                if p.contains(q, -0.02) {
                    assert!(
                        hit,
                        "primitive {i} ({:?}): {q:?} inside, Rapier says outside",
                        p.kind()
                    );
                    inside += 1;
                } else if !p.contains(q, outer) {
                    assert!(
                        !hit,
                        "primitive {i} ({:?}): {q:?} outside, Rapier says inside",
                        p.kind()
                    );
                    outside += 1;
                }
            }
            assert!(
                inside > 500 && outside > 500,
                "primitive {i}: {inside} in, {outside} out"
            );
        }
    }

    /// The reference mesh keeps its position: a unit cube's trimesh, scaled by 2,
    /// spans [−1, 1]³ around the AABB centre.
    #[test]
    fn trimesh_is_recentred_and_scaled() {
        let mesh = crate::cuboid_mesh([10.0, 0.0, 0.0], [11.0, 1.0, 1.0]);
        let frame = Frame {
            offset: mesh.centre(),
            scale: 2.0,
        };
        let (shape, pose) = trimesh(&mesh, &frame).expect("a closed cube");
        let aabb = shape.compute_aabb(&pose);
        assert_eq!(aabb.mins, Vector::splat(-1.0));
        assert_eq!(aabb.maxs, Vector::splat(1.0));
        assert!(hull(&[]).is_none());
    }
}
