//! Isosceles trapezoidal prism (§3.2 "Isosceles Trapezoidal Prisms", Alg. 3).
//!
//! Local frame: extruded along `axes[0]` (x) over [−hx, hx]; the y–z cross-section is
//! the trapezoid whose half-width along z is `hz_top` at y = +hy and `hz_bottom` at
//! y = −hy. `axes` is orthonormal and right-handed.

use crate::math::{dot, madd, sub, V3};

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Prism {
    pub center: V3,
    pub axes: [V3; 3],
    pub hx: f64,
    pub hy: f64,
    pub hz_top: f64,
    pub hz_bottom: f64,
}

impl Prism {
    /// §3.2: 4·hx·hy·(hzt + hzb).
    pub fn volume(&self) -> f64 {
        4.0 * self.hx * self.hy * (self.hz_top + self.hz_bottom)
    }
    /// Half-width along z at local height `y` (clamped to the prism's y range).
    pub fn half_width_at(&self, y: f64) -> f64 {
        let s = if self.hy > 0.0 {
            ((y + self.hy) / (2.0 * self.hy)).clamp(0.0, 1.0)
        } else {
            0.5
        };
        self.hz_bottom + (self.hz_top - self.hz_bottom) * s
    }
    pub fn contains(&self, p: V3, tol: f64) -> bool {
        let d = sub(p, self.center);
        let (x, y, z) = (
            dot(d, self.axes[0]),
            dot(d, self.axes[1]),
            dot(d, self.axes[2]),
        );
        if x.abs() > self.hx + tol || y.abs() > self.hy + tol {
            return false;
        }
        // Distance to a slanted side is its z-excess times cos of the side's tilt.
        let w = self.half_width_at(y);
        let slope = (self.hz_top - self.hz_bottom) / (2.0 * self.hy.max(f64::MIN_POSITIVE));
        z.abs() - w <= tol * (1.0 + slope * slope).sqrt()
    }
    /// The 8 corners (exact AABB source, and the OBJ tessellation).
    pub fn corners(&self) -> [V3; 8] {
        let mut out = [[0.0; 3]; 8];
        let mut i = 0;
        for sx in [-1.0, 1.0] {
            for (sy, hz) in [(-1.0, self.hz_bottom), (1.0, self.hz_top)] {
                for sz in [-1.0, 1.0] {
                    let p = madd(self.center, self.axes[0], sx * self.hx);
                    let p = madd(p, self.axes[1], sy * self.hy);
                    out[i] = madd(p, self.axes[2], sz * hz);
                    i += 1;
                }
            }
        }
        out
    }
    pub fn aabb(&self) -> (V3, V3) {
        crate::mesh::aabb_of(self.corners().into_iter())
    }
}
