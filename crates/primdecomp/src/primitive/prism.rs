//! Isosceles trapezoidal prism (§3.2 "Isosceles Trapezoidal Prisms", Alg. 3).
//!
//! Local frame: extruded along `axes[0]` (x) over [−hx, hx]; the y–z cross-section is
//! the trapezoid whose half-width along z is `hz_top` at y = +hy and `hz_bottom` at
//! y = −hy. `axes` is orthonormal and right-handed.

use crate::math::{dot, madd, sub, V3};

/// Isosceles trapezoidal prism: a trapezoid in the local y–z plane extruded along x
/// (see the module documentation for the frame).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Prism {
    /// Centre.
    pub center: V3,
    /// Unit axes (rows): extrusion (x), height (y), width (z); orthonormal, right-handed.
    pub axes: [V3; 3],
    /// Half-length of the extrusion.
    pub hx: f64,
    /// Half-height of the trapezoid.
    pub hy: f64,
    /// Half-width of the trapezoid at y = +hy.
    pub hz_top: f64,
    /// Half-width of the trapezoid at y = −hy.
    pub hz_bottom: f64,
}

impl Prism {
    /// §3.2: 4·hx·hy·(hzt + hzb).
    pub fn volume(&self) -> f64 {
        4.0 * self.hx * self.hy * (self.hz_top + self.hz_bottom)
    }
    /// Half-width along z at local height `y` (clamped to the prism's y range).
    pub(crate) fn half_width_at(&self, y: f64) -> f64 {
        let s = if self.hy > 0.0 {
            ((y + self.hy) / (2.0 * self.hy)).clamp(0.0, 1.0)
        } else {
            0.5
        };
        self.hz_bottom + (self.hz_top - self.hz_bottom) * s
    }
    /// Whether `p` lies inside, allowing `tol` of slack (distance units).
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
        // Distance to a slanted side is its z-excess times cos of the side's tilt. That
        // is the distance to the side's whole line: where the side lies nearly along z
        // (a thin prism whose widths differ, slope 1.6e13 in fuzz run 13) points far
        // beyond its ends are near the line, so the wider end's width caps |z| too.
        let w = self.half_width_at(y);
        let slope = (self.hz_top - self.hz_bottom) / (2.0 * self.hy.max(f64::MIN_POSITIVE));
        z.abs() - w <= tol * (1.0 + slope * slope).sqrt()
            && z.abs() <= self.hz_top.max(self.hz_bottom) + tol
    }
    /// Support function: the largest `n·x` over the prism (`n` a unit vector).
    pub fn support(&self, n: V3) -> f64 {
        self.corners()
            .into_iter()
            .map(|c| crate::math::dot(n, c))
            .fold(f64::NEG_INFINITY, f64::max)
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
    /// Axis-aligned bounds (min, max), conservative.
    pub fn aabb(&self) -> (V3, V3) {
        crate::mesh::aabb_of(self.corners().into_iter())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Fuzz run 13: a prism 1e-3 thick whose widths are 1 and 10 has slanted sides
    /// nearly along z (slope 4,500). A point at z = 100, inside the thickness, lies
    /// within 0.1 of a side's *line* but 90 beyond the prism: it must not be contained,
    /// while points on the wide end and just inside its corner are.
    #[test]
    fn thin_prism_does_not_contain_points_beyond_its_wide_end() {
        let p = Prism {
            center: [0.0; 3],
            axes: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            hx: 1.0,
            hy: 1e-3,
            hz_top: 10.0,
            hz_bottom: 1.0,
        };
        assert!(!p.contains([0.0, 0.0, 100.0], 0.1));
        assert!(!p.contains([0.0, 1e-3, 10.2], 0.1));
        assert!(p.contains([0.0, 1e-3, 10.05], 0.1));
        assert!(p.contains([0.5, 0.0, 5.4], 1e-9));
    }
}
