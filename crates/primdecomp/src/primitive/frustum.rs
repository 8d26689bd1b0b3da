//! Frustum (§3.2 "Frustum", Alg. 2): a truncated cone on the best cylinder's axis.

use super::{aabb_union, disc_aabb};
use crate::math::{dot, norm2, normalize, sub, V3};

/// Frustum between cap centres `p0` (radius `r0`) and `p1` (radius `r1`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frustum {
    /// Centre of the cap of radius `r0`.
    pub p0: V3,
    /// Centre of the cap of radius `r1`.
    pub p1: V3,
    /// Radius at `p0`.
    pub r0: f64,
    /// Radius at `p1`.
    pub r1: f64,
}

impl Frustum {
    /// Support function: the largest `n·x` over the frustum (`n` a unit vector).
    pub fn support(&self, n: V3) -> f64 {
        super::disc_support(self.p0, self.p1, self.r0, self.r1, n)
    }
    /// §3.2: π·h/3·(r0² + r0·r1 + r1²).
    pub fn volume(&self) -> f64 {
        let h = norm2(sub(self.p1, self.p0)).sqrt();
        std::f64::consts::PI * h / 3.0 * (self.r0 * self.r0 + self.r0 * self.r1 + self.r1 * self.r1)
    }
    /// Whether `p` lies inside, allowing `tol` of slack (distance units).
    pub fn contains(&self, p: V3, tol: f64) -> bool {
        let axis = sub(self.p1, self.p0);
        let h = norm2(axis).sqrt();
        let Some(a) = normalize(axis) else {
            return norm2(sub(p, self.p0)).sqrt() <= tol;
        };
        let d = sub(p, self.p0);
        let t = dot(d, a);
        if t < -tol || t > h + tol {
            return false;
        }
        let s = (t / h).clamp(0.0, 1.0);
        let r = self.r0 + (self.r1 - self.r0) * s;
        (norm2(d) - t * t).max(0.0).sqrt() <= r + tol
    }
    /// Axis-aligned bounds (min, max), conservative.
    pub fn aabb(&self) -> (V3, V3) {
        let a = normalize(sub(self.p1, self.p0)).unwrap_or([0.0, 0.0, 1.0]);
        aabb_union(
            disc_aabb(self.p0, a, self.r0),
            disc_aabb(self.p1, a, self.r1),
        )
    }
}
