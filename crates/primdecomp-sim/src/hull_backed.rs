//! The part of a Rapier shape that [`PrismShape`](super::prism_shape::PrismShape) and
//! [`FrustumShape`](super::frustum_shape::FrustumShape) share: each holds the convex
//! hull the simulation has always used for its kind (a `hull` field) and answers
//! every query but point projection through it — support map, ray casts, CCD, mass,
//! AABB, feature ids — so the shape, its contacts' feature ids and its enclosure are
//! the hull's. The type supplies `fn project(&self, p: Vector, solid: bool) ->
//! PointProjection`, an exact analytic projection on that same hull: a ball's contact
//! is the projection of its centre, which parry otherwise finds by GJK over the
//! hull's vertices.

/// `PointQuery` (through the type's `project`, and `project_on_face`, which also
/// names the hull's feature when the closest point lies inside a face, the direction
/// being that face's normal: the id parry would find by scanning the hull), `RayCast`, `SupportMap`,
/// `PolygonalFeatureMap` and `Shape` for a type with a `hull: ConvexPolyhedron`.
macro_rules! hull_backed_shape {
    ($t:ty) => {
        impl rapier3d::parry::query::PointQuery for $t {
            fn project_local_point(
                &self,
                p: rapier3d::math::Vector,
                solid: bool,
            ) -> rapier3d::parry::query::PointProjection {
                self.project(p, solid)
            }

            /// As parry's convex polyhedron does: the feature is the hull's support
            /// feature towards the projection direction, stored per face when the
            /// closest point lies inside one (that direction is the face's normal).
            fn project_local_point_and_get_feature(
                &self,
                p: rapier3d::math::Vector,
            ) -> (
                rapier3d::parry::query::PointProjection,
                rapier3d::parry::shape::FeatureId,
            ) {
                let (proj, face) = self.project_on_face(p, false);
                if let Some(face) = face {
                    return (proj, face);
                }
                let d = p - proj.point;
                let dir = if proj.is_inside { -d } else { d };
                match dir.try_normalize() {
                    Some(dir) => (proj, self.hull.support_feature_id_toward(dir)),
                    None => (proj, rapier3d::parry::shape::FeatureId::Unknown),
                }
            }
        }

        impl rapier3d::parry::query::RayCast for $t {
            fn cast_local_ray_and_get_normal(
                &self,
                ray: &rapier3d::parry::query::Ray,
                max_time_of_impact: rapier3d::math::Real,
                solid: bool,
            ) -> Option<rapier3d::parry::query::RayIntersection> {
                self.hull
                    .cast_local_ray_and_get_normal(ray, max_time_of_impact, solid)
            }
        }

        impl rapier3d::parry::shape::SupportMap for $t {
            fn local_support_point(&self, dir: rapier3d::math::Vector) -> rapier3d::math::Vector {
                self.hull.local_support_point(dir)
            }
        }

        impl rapier3d::parry::shape::PolygonalFeatureMap for $t {
            fn local_support_feature(
                &self,
                dir: rapier3d::math::Vector,
                out: &mut rapier3d::parry::shape::PolygonalFeature,
            ) {
                self.hull.local_support_feature(dir, out)
            }
        }

        impl rapier3d::parry::shape::Shape for $t {
            fn compute_local_aabb(&self) -> rapier3d::parry::bounding_volume::Aabb {
                self.hull.local_aabb()
            }
            fn compute_local_bounding_sphere(
                &self,
            ) -> rapier3d::parry::bounding_volume::BoundingSphere {
                self.hull.local_bounding_sphere()
            }
            fn compute_aabb(
                &self,
                position: &rapier3d::math::Pose,
            ) -> rapier3d::parry::bounding_volume::Aabb {
                self.hull.aabb(position)
            }
            fn clone_dyn(&self) -> Box<dyn rapier3d::parry::shape::Shape> {
                Box::new(self.clone())
            }
            fn scale_dyn(
                &self,
                scale: rapier3d::math::Vector,
                subdivisions: u32,
            ) -> Option<Box<dyn rapier3d::parry::shape::Shape>> {
                self.hull.scale_dyn(scale, subdivisions)
            }
            fn mass_properties(
                &self,
                density: rapier3d::math::Real,
            ) -> rapier3d::parry::mass_properties::MassProperties {
                self.hull.mass_properties(density)
            }
            fn is_convex(&self) -> bool {
                true
            }
            fn shape_type(&self) -> rapier3d::parry::shape::ShapeType {
                rapier3d::parry::shape::ShapeType::Custom
            }
            fn as_typed_shape(&self) -> rapier3d::parry::shape::TypedShape<'_> {
                rapier3d::parry::shape::TypedShape::Custom(self)
            }
            fn ccd_thickness(&self) -> rapier3d::math::Real {
                self.hull.ccd_thickness()
            }
            fn ccd_angular_thickness(&self) -> rapier3d::math::Real {
                self.hull.ccd_angular_thickness()
            }
            fn as_support_map(&self) -> Option<&dyn rapier3d::parry::shape::SupportMap> {
                Some(self as &dyn rapier3d::parry::shape::SupportMap)
            }
            fn as_polygonal_feature_map(
                &self,
            ) -> Option<(
                &dyn rapier3d::parry::shape::PolygonalFeatureMap,
                rapier3d::math::Real,
            )> {
                Some((
                    self as &dyn rapier3d::parry::shape::PolygonalFeatureMap,
                    0.0,
                ))
            }
            fn feature_normal_at_point(
                &self,
                subshape: rapier3d::parry::shape::SubShapeId,
                feature: rapier3d::parry::shape::FeatureId,
                point: rapier3d::math::Vector,
            ) -> Option<rapier3d::math::Vector> {
                self.hull.feature_normal_at_point(subshape, feature, point)
            }
        }
    };
}

pub(super) use hull_backed_shape;

/// Test check shared by the hull-backed shapes: on 20,000 random points in the box of
/// half-size `ext`, the shape's exact projection (`project`) agrees with parry's GJK
/// projection on its `hull` (inside/outside away from the surface; never farther,
/// within GJK's tolerance; on the hull's surface), and the points fall both inside
/// and outside.
#[cfg(test)]
pub(super) fn check_projection_against_hull(
    project: impl Fn(rapier3d::math::Vector, bool) -> rapier3d::parry::query::PointProjection,
    hull: &rapier3d::parry::shape::ConvexPolyhedron,
    ext: rapier3d::math::Vector,
    rng: &mut rand_chacha::ChaCha8Rng,
) {
    use rapier3d::parry::query::PointQuery;
    let (mut inside, mut outside) = (0, 0);
    for _ in 0..20_000 {
        let p = random_point(rng, ext);
        let surface = (hull.project_local_point(p, false).point - p).length();
        for solid in [false, true] {
            let a = project(p, solid);
            let b = hull.project_local_point(p, solid);
            let (da, db) = ((a.point - p).length(), (b.point - p).length());
            // Within round-off of the surface either side is right.
            if surface > 1e-4 {
                assert_eq!(a.is_inside, b.is_inside, "{p:?} solid {solid}");
            }
            // GJK stops within a relative tolerance; ours is never farther.
            assert!(
                da <= db + 1e-4 && db - da < 1e-3 * db.max(0.1),
                "{p:?} solid {solid}: distance {da} vs hull {db}"
            );
            // The point may differ where faces tie or GJK stopped early on a face,
            // but it lies on the hull's surface (or is p, when solid).
            let on = (hull.project_local_point(a.point, false).point - a.point).length();
            assert!(
                on < 1e-4 || (solid && a.point == p),
                "{p:?} solid {solid}: {:?} is {on} off the surface",
                a.point
            );
        }
        if hull.contains_local_point(p) {
            inside += 1;
        } else {
            outside += 1;
        }
    }
    assert!(inside > 50 && outside > 1000, "{inside} in, {outside} out");
}

/// Test check shared by the hull-backed shapes: on 20,000 random points in the box of
/// half-size `ext`, where the closest point lies inside a face (`project_on_face`
/// names one), that id is the one parry finds by scanning the hull towards the
/// projection direction; over 5,000 of the points land there.
#[cfg(test)]
pub(super) fn check_face_ids_against_hull(
    project_on_face: impl Fn(
        rapier3d::math::Vector,
    ) -> (
        rapier3d::parry::query::PointProjection,
        Option<rapier3d::parry::shape::FeatureId>,
    ),
    hull: &rapier3d::parry::shape::ConvexPolyhedron,
    ext: rapier3d::math::Vector,
    rng: &mut rand_chacha::ChaCha8Rng,
) {
    let mut faces = 0;
    for _ in 0..20_000 {
        let p = random_point(rng, ext);
        let (proj, face) = project_on_face(p);
        let d = p - proj.point;
        let dir = if proj.is_inside { -d } else { d };
        if let (Some(face), Some(dir)) = (face, dir.try_normalize()) {
            assert_eq!(face, hull.support_feature_id_toward(dir), "{p:?}");
            faces += 1;
        }
    }
    assert!(faces > 5_000, "{faces} face projections");
}

/// A uniform random point in the box of half-size `ext` about the origin.
#[cfg(test)]
fn random_point(
    rng: &mut rand_chacha::ChaCha8Rng,
    ext: rapier3d::math::Vector,
) -> rapier3d::math::Vector {
    use rand::Rng;
    rapier3d::math::Vector::new(
        rng.gen_range(-1.0..1.0),
        rng.gen_range(-1.0..1.0),
        rng.gen_range(-1.0..1.0),
    ) * ext
}
