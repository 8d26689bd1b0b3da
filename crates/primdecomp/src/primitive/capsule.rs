//! Capsule (§3.2 "Capsules"): a segment swept by a ball, one per eigen-axis.

use crate::math::{dot, norm2, sub, V3};

/// Capsule: segment `p0`–`p1` swept by a ball of `radius`.
///
/// ```
/// use primdecomp::{Capsule, Kind, Primitive};
///
/// let rod = Primitive::Capsule(Capsule { p0: [0.0; 3], p1: [0.0, 0.0, 2.0], radius: 0.5 });
/// assert_eq!(rod.kind(), Kind::Capsule);
/// assert!(rod.contains([0.0, 0.0, 2.5], 1e-12)); // the cap's tip
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Capsule {
    /// One end of the segment.
    pub p0: V3,
    /// The other end.
    pub p1: V3,
    /// Radius of the ball swept along it.
    pub radius: f64,
}

impl Capsule {
    /// Support function: the largest `n·x` over the capsule (`n` a unit vector).
    pub fn support(&self, n: V3) -> f64 {
        dot(n, self.p0).max(dot(n, self.p1)) + self.radius
    }
    /// π·r²·L + 4/3·π·r³.
    pub fn volume(&self) -> f64 {
        let r = self.radius;
        let l = norm2(sub(self.p1, self.p0)).sqrt();
        std::f64::consts::PI * r * r * (l + 4.0 / 3.0 * r)
    }
    /// Whether `p` lies inside, allowing `tol` of slack (distance units).
    pub fn contains(&self, p: V3, tol: f64) -> bool {
        let ab = sub(self.p1, self.p0);
        let l2 = norm2(ab);
        let d = sub(p, self.p0);
        let t = if l2 > 0.0 {
            (dot(d, ab) / l2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let q = [d[0] - ab[0] * t, d[1] - ab[1] * t, d[2] - ab[2] * t];
        norm2(q).sqrt() <= self.radius + tol
    }
    /// Axis-aligned bounds (min, max), conservative.
    pub fn aabb(&self) -> (V3, V3) {
        let r = self.radius;
        let mut lo = [0.0; 3];
        let mut hi = [0.0; 3];
        for k in 0..3 {
            lo[k] = self.p0[k].min(self.p1[k]) - r;
            hi[k] = self.p0[k].max(self.p1[k]) + r;
        }
        (lo, hi)
    }
}
