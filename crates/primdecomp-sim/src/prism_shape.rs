//! Our isosceles trapezoidal prism (§3.2) as a Rapier shape with an exact, analytic
//! point projection. Parry has no such shape, and as a plain convex polyhedron every
//! ball–prism pair of the narrow phase runs GJK over its corners (a ball's contact is
//! the projection of its centre on the other shape), 5–7× the cost of a ball–cuboid
//! pair (`cargo bench --bench sim_pairs`, docs/results/sim.md). The prism is the
//! product of the x-interval [−hx, hx] and a trapezoid in (y, z), so the closest point
//! of the solid to p = (x, q) is (clamp(x), closest point of the trapezoid to q): one
//! clamp and three segment projections, no iteration. Everything else (support map,
//! ray casts, CCD, mass, AABB, feature ids) is the same convex polyhedron as before,
//! held inside ([`hull_backed`](super::hull_backed)), so the shape, its contacts'
//! feature ids and its enclosure are unchanged.

use super::hull_backed::hull_backed_shape;
use rapier3d::math::{Real, Vector};
use rapier3d::parry::query::PointProjection;
use rapier3d::parry::shape::{ConvexPolyhedron, FeatureId};

/// A prism in its local frame (extruded along x over [−hx, hx]; half-width along z
/// `hz_bottom` at y = −hy and `hz_top` at y = +hy), simulation units.
#[derive(Clone, Debug)]
pub struct PrismShape {
    hx: Real,
    hy: Real,
    hz_top: Real,
    hz_bottom: Real,
    /// The convex hull of the 8 corners: everything but point projection.
    hull: ConvexPolyhedron,
    /// The hull's support feature towards each face normal: −x, +x, −y, +y, the
    /// slanted side at −z, at +z ([`hull_backed`](super::hull_backed)).
    face_ids: [FeatureId; 6],
}

/// Closest point to `q` on the segment `a`–`b` (2-D), its squared distance and its
/// parameter t ∈ [0, 1] along the segment.
pub(super) fn on_segment(q: [Real; 2], a: [Real; 2], b: [Real; 2]) -> ([Real; 2], Real, Real) {
    let ab = [b[0] - a[0], b[1] - a[1]];
    let l2 = ab[0] * ab[0] + ab[1] * ab[1];
    let t = if l2 > 0.0 {
        (((q[0] - a[0]) * ab[0] + (q[1] - a[1]) * ab[1]) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let c = [a[0] + t * ab[0], a[1] + t * ab[1]];
    let d = [q[0] - c[0], q[1] - c[1]];
    (c, d[0] * d[0] + d[1] * d[1], t)
}

impl PrismShape {
    /// `None` when the prism spans no volume (the hull cannot be built).
    pub fn new(hx: Real, hy: Real, hz_top: Real, hz_bottom: Real) -> Option<PrismShape> {
        let mut corners = Vec::with_capacity(8);
        for sx in [-1.0, 1.0] {
            for (sy, hz) in [(-1.0, hz_bottom), (1.0, hz_top)] {
                for sz in [-1.0, 1.0] {
                    corners.push(Vector::new(sx * hx, sy * hy, sz * hz));
                }
            }
        }
        let hull = ConvexPolyhedron::from_convex_hull(&corners)?;
        // The slanted side's outward normal in (y, z ≥ 0).
        let (ny, nz) = (hz_bottom - hz_top, 2.0 * hy);
        let normals = [
            Vector::NEG_X,
            Vector::X,
            Vector::NEG_Y,
            Vector::Y,
            Vector::new(0.0, ny, -nz),
            Vector::new(0.0, ny, nz),
        ];
        let face_ids = normals.map(|n| hull.support_feature_id_toward(n.normalize()));
        Some(PrismShape {
            hx,
            hy,
            hz_top,
            hz_bottom,
            hull,
            face_ids,
        })
    }

    /// Whether (y, |z|) lies in the trapezoid (closed).
    fn in_section(&self, y: Real, z: Real) -> bool {
        if y.abs() > self.hy {
            return false;
        }
        let s = if self.hy > 0.0 {
            (y + self.hy) / (2.0 * self.hy)
        } else {
            0.5
        };
        z <= self.hz_bottom + (self.hz_top - self.hz_bottom) * s
    }

    /// Closest point to (y, z ≥ 0) on the trapezoid's boundary (its z ≥ 0 half, which
    /// holds the closest point by symmetry), the squared distance, and the face (2:
    /// −y, 3: +y, 5: the slanted side) when the point is inside one, not on a corner
    /// (a wedge's zero-width end is an edge, not a face).
    fn section_boundary(&self, y: Real, z: Real) -> ([Real; 2], Real, Option<usize>) {
        let (hy, zt, zb) = (self.hy, self.hz_top, self.hz_bottom);
        let q = [y, z];
        let (c, d2, t) = on_segment(q, [-hy, 0.0], [-hy, zb]);
        let mut best = (c, d2, (t < 1.0 && zb > 0.0).then_some(2));
        let (c, d2, t) = on_segment(q, [hy, 0.0], [hy, zt]);
        if d2 < best.1 {
            best = (c, d2, (t < 1.0 && zt > 0.0).then_some(3));
        }
        let (c, d2, t) = on_segment(q, [-hy, zb], [hy, zt]);
        if d2 < best.1 {
            best = (c, d2, (t > 0.0 && t < 1.0).then_some(5));
        }
        best
    }

    /// Exact closest point of the hull to `p` (see the module doc).
    fn project(&self, p: Vector, solid: bool) -> PointProjection {
        self.project_on_face(p, solid).0
    }

    /// [`project`](Self::project), and the hull's feature id when the closest point lies
    /// inside a face (the projection direction is then that face's normal, and the
    /// hull's support feature towards it is the id stored for it); `None` on an edge
    /// or corner.
    fn project_on_face(&self, p: Vector, solid: bool) -> (PointProjection, Option<FeatureId>) {
        let (x, y, za) = (p.x, p.y, p.z.abs());
        let sz = if p.z < 0.0 { -1.0 } else { 1.0 };
        // −z side: the +z face index minus one.
        let side =
            |f: Option<usize>| f.map(|f| self.face_ids[if f == 5 && sz < 0.0 { 4 } else { f }]);
        let inside_x = x.abs() <= self.hx;
        if !self.in_section(y, za) {
            let (c, _, f) = self.section_boundary(y, za);
            let cx = x.clamp(-self.hx, self.hx);
            let f = if inside_x { side(f) } else { None };
            return (
                PointProjection::new(false, Vector::new(cx, c[0], sz * c[1])),
                f,
            );
        }
        let (xf, fx) = if x < 0.0 { (-self.hx, 0) } else { (self.hx, 1) };
        if !inside_x {
            let proj = PointProjection::new(false, Vector::new(xf, y, p.z));
            return (proj, Some(self.face_ids[fx]));
        }
        if solid {
            return (PointProjection::new(true, p), None);
        }
        // Inside: the nearer of the x faces and the section's boundary.
        let (c, d2, f) = self.section_boundary(y, za);
        let dx = self.hx - x.abs();
        if dx * dx <= d2 {
            let proj = PointProjection::new(true, Vector::new(xf, y, p.z));
            (proj, Some(self.face_ids[fx]))
        } else {
            (
                PointProjection::new(true, Vector::new(x, c[0], sz * c[1])),
                side(f),
            )
        }
    }
}

hull_backed_shape!(PrismShape);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hull_backed::{check_face_ids_against_hull, check_projection_against_hull};
    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;
    use rapier3d::parry::query::PointQuery;

    /// The analytic projection agrees with parry's GJK projection on the same corners'
    /// hull (same side, same distance to GJK's tolerance, a point on the surface), inside and
    /// outside, for a trapezoid, a wedge (top
    /// width 0) and a box-like prism: the shape the balls meet has not changed.
    #[test]
    fn projection_matches_the_hulls() {
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        for (hx, hy, zt, zb) in [
            (1.0, 0.5, 0.2, 0.8),
            (0.3, 1.2, 0.0, 0.9),
            (0.7, 0.7, 0.7, 0.7),
            (0.002, 0.35, 0.002, 0.7),
        ] {
            let s = PrismShape::new(hx, hy, zt, zb).unwrap();
            // Around the prism, each axis over 1.6× its half-extent.
            let ext = Vector::new(hx, hy, zt.max(zb)) * 1.6;
            let project = |p, solid| s.project_local_point(p, solid);
            check_projection_against_hull(project, &s.hull, ext, &mut rng);
        }
    }

    /// Where the closest point lies inside a face, the stored feature id is the one
    /// parry finds by scanning the hull towards the projection direction (what
    /// `project_local_point_and_get_feature` returned before the ids were stored),
    /// and that case is common (over 5,000 of 20,000 points around the shape).
    #[test]
    fn face_ids_match_the_hulls() {
        let mut rng = ChaCha8Rng::seed_from_u64(9);
        for (hx, hy, zt, zb) in [
            (1.0, 0.5, 0.2, 0.8),
            (0.3, 1.2, 0.0, 0.9),
            (0.7, 0.7, 0.7, 0.7),
        ] {
            let s = PrismShape::new(hx, hy, zt, zb).unwrap();
            let ext = Vector::new(hx, hy, zt.max(zb)) * 1.6;
            let on_face = |p| s.project_on_face(p, false);
            check_face_ids_against_hull(on_face, &s.hull, ext, &mut rng);
        }
    }

    #[test]
    fn flat_prism_has_no_shape() {
        assert!(PrismShape::new(1.0, 0.0, 0.0, 0.0).is_none());
    }
}
