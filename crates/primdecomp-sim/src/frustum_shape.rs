//! Our frustum (§3.2) as a Rapier shape with an exact, analytic point projection on
//! the hull the simulation has always used for it: the convex hull of two regular
//! [`FRUSTUM_SEGMENTS`]-gons circumscribing its end circles (vertex radius
//! r / cos(π/k), the OBJ export's conservative tessellation), so the shape still
//! contains the exact frustum. As a plain convex polyhedron of 32 vertices every
//! ball–frustum pair runs GJK (427 ns per touching pair against a cuboid's 66,
//! `cargo bench --bench sim_pairs`).
//!
//! The hull is symmetric under rotation by 2π/k about its axis (local y), and the
//! closest point of a convex set symmetric in a plane lies on the query point's side
//! of it, so the closest point to p lies in p's angular sector around the side face
//! whose outward normal is nearest p's direction. In that sector the solid is
//! u ≤ a(y), |y| ≤ hy (u: the coordinate along the face normal, a(y): the apothem,
//! linear in y); the boundary there is that side face (an isosceles trapezoid) and the
//! two caps (whose part in the sector is the edge u = a, |w| ≤ half-edge). Outside,
//! the closest point is the nearest of the three faces' closest points; inside, the
//! foot on the nearest of the three planes. Everything else is the hull
//! ([`hull_backed`](super::hull_backed)).

use super::hull_backed::hull_backed_shape;
use super::prism_shape::on_segment;
use rapier3d::math::{Real, Vector};
use rapier3d::parry::query::PointProjection;
use rapier3d::parry::shape::{ConvexPolyhedron, FeatureId};
use std::f32::consts::PI;

/// Segments around the frustum's circles in its convex hull: the OBJ export's
/// conservative tessellation (vertex radius r / cos(π/k)), so the hull contains the
/// exact frustum.
pub const FRUSTUM_SEGMENTS: usize = 16;

const K: usize = FRUSTUM_SEGMENTS;

/// A frustum's hull in its local frame: axis along y over [−hy, hy], k-gons with
/// vertices at angles 2πj/k in the (x, z) plane (angle atan2(z, x)) and vertex radius
/// `r[0]` at y = −hy, `r[1]` at y = +hy; simulation units.
#[derive(Clone, Debug)]
pub struct FrustumShape {
    hy: Real,
    /// Apothems (distance from the axis to a side face) at y = −hy and +hy.
    apo: [Real; 2],
    /// Half edge lengths of the k-gons at y = −hy and +hy.
    half: [Real; 2],
    /// Unit direction of a side face's slant in (u, y), bottom to top, and its length.
    slant: [Real; 2],
    slant_len: Real,
    /// (cos, sin) of the side faces' outward normal angles 2π(j + ½)/k.
    normals: [[Real; 2]; K],
    /// The convex hull of the two k-gons: everything but point projection.
    hull: ConvexPolyhedron,
    /// The hull's support feature towards each side face's normal, then −y and +y
    /// ([`hull_backed`](super::hull_backed)).
    face_ids: [FeatureId; K + 2],
}

impl FrustumShape {
    /// `None` when the frustum spans no volume (the hull cannot be built).
    pub fn new(hy: Real, r_bottom: Real, r_top: Real) -> Option<FrustumShape> {
        // Parry builds a flat "hull" of coplanar points; the old hull path gave none.
        if !(hy > 0.0 && r_bottom.max(r_top) > 0.0) {
            return None;
        }
        let mut corners = Vec::with_capacity(2 * K);
        for (y, r) in [(-hy, r_bottom), (hy, r_top)] {
            if r == 0.0 {
                corners.push(Vector::new(0.0, y, 0.0));
                continue;
            }
            for j in 0..K {
                let t = 2.0 * PI * j as Real / K as Real;
                corners.push(Vector::new(r * t.cos(), y, r * t.sin()));
            }
        }
        let hull = ConvexPolyhedron::from_convex_hull(&corners)?;
        let (c, s) = ((PI / K as Real).cos(), (PI / K as Real).sin());
        let apo = [r_bottom * c, r_top * c];
        let d = [apo[1] - apo[0], 2.0 * hy];
        let slant_len = (d[0] * d[0] + d[1] * d[1]).sqrt();
        let normals: [[Real; 2]; K] = std::array::from_fn(|j| {
            let t = 2.0 * PI * (j as Real + 0.5) / K as Real;
            [t.cos(), t.sin()]
        });
        // A side face's outward normal: (d_y · horizontal normal, −d_u) / |d|.
        let face_ids = std::array::from_fn(|j| match j {
            _ if j < K => {
                let n = Vector::new(d[1] * normals[j][0], -d[0], d[1] * normals[j][1]);
                hull.support_feature_id_toward(n.normalize())
            }
            _ if j == K => hull.support_feature_id_toward(Vector::NEG_Y),
            _ => hull.support_feature_id_toward(Vector::Y),
        });
        Some(FrustumShape {
            hy,
            apo,
            half: [r_bottom * s, r_top * s],
            slant: [d[0] / slant_len, d[1] / slant_len],
            slant_len,
            normals,
            hull,
            face_ids,
        })
    }

    /// The side face whose outward normal is nearest the direction of (x, z): its
    /// index and horizontal normal.
    fn sector(&self, x: Real, z: Real) -> (usize, [Real; 2]) {
        let (mut best, mut best_u) = (0, x * self.normals[0][0] + z * self.normals[0][1]);
        for (j, n) in self.normals.iter().enumerate().skip(1) {
            let u = x * n[0] + z * n[1];
            if u > best_u {
                (best, best_u) = (j, u);
            }
        }
        (best, self.normals[best])
    }

    /// Closest point to (t, w) of the side face as a trapezoid in its own plane: t
    /// along the slant from the bottom edge, w along the edge; squared distance.
    fn side_face(&self, t: Real, w: Real) -> ([Real; 2], Real) {
        let (l, [h0, h1]) = (self.slant_len, self.half);
        let wa = w.abs();
        if (0.0..=l).contains(&t) && wa <= h0 + (h1 - h0) * t / l {
            return ([t, w], 0.0);
        }
        let q = [t, wa];
        let mut best = on_segment(q, [0.0, 0.0], [0.0, h0]);
        for (a, b) in [([l, 0.0], [l, h1]), ([0.0, h0], [l, h1])] {
            let c = on_segment(q, a, b);
            if c.1 < best.1 {
                best = c;
            }
        }
        (
            [best.0[0], if w < 0.0 { -best.0[1] } else { best.0[1] }],
            best.1,
        )
    }

    /// Exact closest point of the hull to `p` (see the module doc).
    fn project(&self, p: Vector, solid: bool) -> PointProjection {
        self.project_on_face(p, solid).0
    }

    /// [`project`](Self::project), worked in the sector's coordinates (u, y, w) and
    /// rotated back, and the hull's feature id when the closest point lies inside a
    /// face (the projection direction is then that face's normal); `None` on an edge
    /// or corner.
    fn project_on_face(&self, p: Vector, solid: bool) -> (PointProjection, Option<FeatureId>) {
        let (j, n) = self.sector(p.x, p.z);
        let (u, y, w) = (p.x * n[0] + p.z * n[1], p.y, p.z * n[0] - p.x * n[1]);
        let back =
            |u: Real, y: Real, w: Real| Vector::new(u * n[0] - w * n[1], y, u * n[1] + w * n[0]);
        let (hy, [a0, a1], [h0, h1], [eu, ey]) = (self.hy, self.apo, self.half, self.slant);
        // Signed distance to the side plane (outward normal (ey, −eu) in (u, y)).
        let sd = (u - a0) * ey - (y + hy) * eu;
        let inside = sd <= 0.0 && y.abs() <= hy;
        if inside && solid {
            return (PointProjection::new(true, p), None);
        }
        if inside {
            let (dt, db) = (hy - y, y + hy);
            let (q, f) = if -sd <= dt.min(db) {
                (back(u - sd * ey, y + sd * eu, w), j)
            } else if dt <= db {
                (back(u, hy, w), K + 1)
            } else {
                (back(u, -hy, w), K)
            };
            return (PointProjection::new(true, q), Some(self.face_ids[f]));
        }
        // Outside: the nearest of the side face and the two caps.
        let t = (u - a0) * eu + (y + hy) * ey;
        let (c, d2) = self.side_face(t, w);
        let side = [a0 + c[0] * eu, -hy + c[0] * ey, c[1]];
        let mut best = (sd * sd + d2, side, (d2 == 0.0).then_some(j));
        for (cy, a, h, f) in [(-hy, a0, h0, K), (hy, a1, h1, K + 1)] {
            let q = [u.min(a), cy, w.clamp(-h, h)];
            let d = [u - q[0], y - q[1], w - q[2]];
            let d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            if d2 < best.0 {
                best = (d2, q, (u < a && a > 0.0).then_some(f));
            }
        }
        let q = best.1;
        let proj = PointProjection::new(false, back(q[0], q[1], q[2]));
        (proj, best.2.map(|f| self.face_ids[f]))
    }
}

hull_backed_shape!(FrustumShape);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hull_backed::{check_face_ids_against_hull, check_projection_against_hull};
    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;
    use rapier3d::parry::query::PointQuery;

    /// The analytic projection agrees with parry's GJK projection on the same hull
    /// (same side, same distance to GJK's tolerance, a point on the hull's surface),
    /// inside and outside, for a frustum narrowing upwards, one widening, a cone (top
    /// radius 0), a cylinder-like one and a flat disc-like one: the shape the balls
    /// meet is the hull.
    #[test]
    fn projection_matches_the_hulls() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        for (hy, r0, r1) in [
            (1.0, 1.0, 0.7),
            (0.4, 0.3, 1.1),
            (0.8, 0.9, 0.0),
            (1.5, 0.5, 0.5),
            (0.01, 1.0, 0.99),
        ] {
            let s = FrustumShape::new(hy, r0, r1).unwrap();
            let r: Real = r0.max(r1);
            let ext = Vector::new(r, hy, r) * 1.6;
            let project = |p, solid| s.project_local_point(p, solid);
            check_projection_against_hull(project, &s.hull, ext, &mut rng);
        }
    }

    /// The hull reaches the circumscribed radius r / cos(π/k) at its vertices and the
    /// exact radius r at its faces' midpoints, never less: it encloses the frustum.
    #[test]
    fn hull_circumscribes_the_circles() {
        let (r0, r1) = (1.0 / (PI / K as Real).cos(), 0.5 / (PI / K as Real).cos());
        let s = FrustumShape::new(1.0, r0, r1).unwrap();
        for j in 0..64 {
            let t = 2.0 * PI * j as Real / 64.0;
            for (y, r) in [(-1.0, 1.0), (1.0, 0.5), (0.0, 0.75)] {
                let p = Vector::new(r * t.cos(), y * 0.999, r * t.sin()) * 0.999;
                assert!(s.contains_local_point(p), "{p:?}");
            }
        }
    }

    /// Where the closest point lies inside a face, the stored feature id is the one
    /// parry finds by scanning the hull towards the projection direction (what
    /// `project_local_point_and_get_feature` returned before the ids were stored),
    /// and that case is common (over 5,000 of 20,000 points around the shape).
    #[test]
    fn face_ids_match_the_hulls() {
        let mut rng = ChaCha8Rng::seed_from_u64(9);
        for (hy, r0, r1) in [(1.0, 1.0, 0.7), (0.4, 0.3, 1.1), (0.8, 0.9, 0.0)] {
            let s = FrustumShape::new(hy, r0, r1).unwrap();
            let ext = Vector::new(r0.max(r1), hy, r0.max(r1)) * 1.6;
            let on_face = |p| s.project_on_face(p, false);
            check_face_ids_against_hull(on_face, &s.hull, ext, &mut rng);
        }
    }

    #[test]
    fn flat_frustum_has_no_shape() {
        assert!(FrustumShape::new(0.0, 1.0, 1.0).is_none());
        assert!(FrustumShape::new(1.0, 0.0, 0.0).is_none());
    }
}
