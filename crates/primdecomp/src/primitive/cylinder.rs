//! Capped cylinder (§3.2 "Capped Cylinders"): one per eigen-axis, through the OBB
//! centre; radius the farthest radial distance, height the axial extent.

use super::{aabb_union, disc_aabb};
use crate::math::{dot, norm2, normalize, sub, V3};

/// Cylinder between cap centres `p0` and `p1`.
///
/// ```
/// use primdecomp::{Cylinder, Primitive};
///
/// let can = Primitive::Cylinder(Cylinder { p0: [0.0; 3], p1: [0.0, 0.0, 1.0], radius: 1.0 });
/// assert!(can.contains([1.0, 0.0, 1.0], 1e-12)); // on the top rim
/// assert!(!can.contains([0.0, 0.0, 1.1], 1e-12)); // flat caps
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cylinder {
    /// Centre of one cap.
    pub p0: V3,
    /// Centre of the other cap.
    pub p1: V3,
    /// Radius.
    pub radius: f64,
}

impl Cylinder {
    /// Support function: the largest `n·x` over the cylinder (`n` a unit vector).
    pub fn support(&self, n: V3) -> f64 {
        super::disc_support(self.p0, self.p1, self.radius, self.radius, n)
    }
    /// §3.2: π·r²·h.
    pub fn volume(&self) -> f64 {
        std::f64::consts::PI * self.radius * self.radius * norm2(sub(self.p1, self.p0)).sqrt()
    }
    /// Whether `p` lies inside, allowing `tol` of slack (distance units).
    pub fn contains(&self, p: V3, tol: f64) -> bool {
        let axis = sub(self.p1, self.p0);
        let len = norm2(axis).sqrt();
        let Some(a) = normalize(axis) else {
            return norm2(sub(p, self.p0)).sqrt() <= tol && self.radius >= 0.0;
        };
        let d = sub(p, self.p0);
        let t = dot(d, a);
        if t < -tol || t > len + tol {
            return false;
        }
        (norm2(d) - t * t).max(0.0).sqrt() <= self.radius + tol
    }
    /// Axis-aligned bounds (min, max), conservative.
    pub fn aabb(&self) -> (V3, V3) {
        let a = normalize(sub(self.p1, self.p0)).unwrap_or([0.0, 0.0, 1.0]);
        aabb_union(
            disc_aabb(self.p0, a, self.radius),
            disc_aabb(self.p1, a, self.radius),
        )
    }
}
