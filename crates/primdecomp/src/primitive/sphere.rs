//! Sphere (§3.2 "Spheres"): centred on the OBB centre, radius the farthest point.

use crate::math::{norm2, sub, V3};

/// Ball of `radius` around `center`.
///
/// ```
/// use primdecomp::Sphere;
///
/// let ball = Sphere { center: [0.0, 0.0, 1.0], radius: 2.0 };
/// assert!(ball.contains([0.0, 2.0, 1.0], 0.0));
/// assert!(!ball.contains([0.0, 0.0, 3.5], 0.0));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sphere {
    /// Centre.
    pub center: V3,
    /// Radius.
    pub radius: f64,
}

impl Sphere {
    /// §3.2: 4/3·π·r³.
    pub fn volume(&self) -> f64 {
        4.0 / 3.0 * std::f64::consts::PI * self.radius.powi(3)
    }
    /// Whether `p` lies inside, allowing `tol` of slack (distance units).
    pub fn contains(&self, p: V3, tol: f64) -> bool {
        norm2(sub(p, self.center)).sqrt() <= self.radius + tol
    }
    /// Support function: the largest `n·x` over the ball (`n` a unit vector).
    pub fn support(&self, n: V3) -> f64 {
        crate::math::dot(n, self.center) + self.radius
    }
    /// Axis-aligned bounds (min, max), conservative.
    pub fn aabb(&self) -> (V3, V3) {
        let r = self.radius;
        let c = self.center;
        (
            [c[0] - r, c[1] - r, c[2] - r],
            [c[0] + r, c[1] + r, c[2] + r],
        )
    }
}
