//! Oriented bounding box (§3.2 "Oriented Bounding Boxes"): the foundation of every
//! other fit, since its centre seeds them.

use super::fit::AxisBounds;
use crate::math::{dot, madd, sub, V3};

/// Box with orthonormal right-handed `axes` and `half` extents along them.
///
/// ```
/// use primdecomp::{Obb, Primitive};
///
/// let unit = Obb { center: [0.0; 3], axes: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]], half: [0.5; 3] };
/// assert_eq!(unit.volume(), 1.0);
/// assert!(Primitive::Box(unit).contains([0.5, 0.5, -0.5], 1e-12));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Obb {
    /// Centre.
    pub center: V3,
    /// Unit axes (rows), orthonormal and right-handed.
    pub axes: [V3; 3],
    /// Half-extents along the axes.
    pub half: V3,
}

impl Obb {
    /// §3.2: volume 8·Πh_i.
    pub fn volume(&self) -> f64 {
        8.0 * self.half[0] * self.half[1] * self.half[2]
    }
    /// Whether `p` lies inside, allowing `tol` of slack (distance units).
    pub fn contains(&self, p: V3, tol: f64) -> bool {
        let d = sub(p, self.center);
        (0..3).all(|k| dot(d, self.axes[k]).abs() <= self.half[k] + tol)
    }
    /// Support function: the largest `n·x` over the box (`n` a unit vector).
    pub fn support(&self, n: V3) -> f64 {
        dot(n, self.center)
            + (0..3)
                .map(|k| self.half[k] * dot(n, self.axes[k]).abs())
                .sum::<f64>()
    }
    /// Axis-aligned bounds (min, max), conservative.
    pub fn aabb(&self) -> (V3, V3) {
        let mut lo = self.center;
        let mut hi = self.center;
        for k in 0..3 {
            let e: f64 = (0..3).map(|j| (self.axes[j][k] * self.half[j]).abs()).sum();
            lo[k] -= e;
            hi[k] += e;
        }
        (lo, hi)
    }
    /// The box of a frame: centre of the projected bounds, half-extents clamped to `min_half`.
    pub(crate) fn from_frame(f: &AxisBounds, min_half: f64) -> Obb {
        let mut center = f.origin;
        let mut half = [0.0; 3];
        for k in 0..3 {
            center = madd(center, f.axes[k], 0.5 * (f.lo[k] + f.hi[k]));
            half[k] = (0.5 * (f.hi[k] - f.lo[k])).max(min_half);
        }
        Obb {
            center,
            axes: f.axes,
            half,
        }
    }
}
