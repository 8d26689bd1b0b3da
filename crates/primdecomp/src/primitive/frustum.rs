//! Frustum (§3.2 "Frustum", Alg. 2): a truncated cone on the best cylinder's axis.

use super::{aabb_union, disc_aabb};
use crate::math::{dot, madd, norm2, normalize, sub, V3};

/// What [`Frustum::on_axis`] leaves unpadded of the error its slope adds, as a fraction
/// of the coordinates' magnitude: a few thousand ulps, far below every enclosure
/// tolerance (1e-9 of the diagonal in the engine), so that ordinary frustums, whose
/// slope adds a few ulps, are stored exactly as fitted.
const SLOPE_SLACK: f64 = 1e-12;

/// Frustum between cap centres `p0` (radius `r0`) and `p1` (radius `r1`).
///
/// ```
/// use primdecomp::{Frustum, Primitive};
///
/// let cone = Primitive::Frustum(Frustum { p0: [0.0; 3], p1: [0.0, 0.0, 1.0], r0: 1.0, r1: 0.5 });
/// assert!(cone.contains([0.9, 0.0, 0.0], 1e-12));
/// assert!(!cone.contains([0.9, 0.0, 1.0], 1e-12)); // the top is narrower
/// ```
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
    /// The frustum fitted around the axis from `c − a·h` (radius `r0`) to `c + a·h`
    /// (radius `r1`), `a` a unit vector, as it is stored: two rounded end points, with
    /// the radii grown where that rounding could cost enclosure through the slope.
    ///
    /// Each stored end lies within η = 4ε·m of the fitted one (m = |c|∞ + h + r̂, r̂ the
    /// larger radius; the bound also covers the fit's own rounding of the points'
    /// coordinates along the axes), so the stored axis of length L = 2h is tilted by up
    /// to δ = 4η/L: a point at distance ≤ r̂ from the axis gets an axial coordinate off by
    /// up to σ = r̂·δ + 3η, and the radius read there along the slope (r1 − r0)/L is off
    /// by up to |r1 − r0|·(σ + 2η)/(L − 2η). That is a few ulps for most frustums, as a
    /// cylinder's own rounding (not padded), but a short steep frustum amplifies it by
    /// its slope times r̂/L: a coplanar cloud seen along an axis tilted by 4e-4 rad gave
    /// L = 5.9e-7, radii 4.5e-3 and 6.3e-3 (slope 3,200), and the stored solid missed a
    /// fitted point by 6.6e-11 (the point's axial coordinate moved by 2e-14). Whatever
    /// that bound exceeds [`SLOPE_SLACK`]·m by is added to both radii, or, where a
    /// cylinder of radius r̂ is smaller (or the axis too short, L ≤ 40η, to carry a
    /// slope at all), both radii become r̂, which no tilt shortens.
    pub(crate) fn on_axis(c: V3, a: V3, h: f64, r0: f64, r1: f64) -> Frustum {
        let (r0, r1) = stored_radii(c, h, r0, r1);
        Frustum {
            p0: madd(c, a, -h),
            p1: madd(c, a, h),
            r0,
            r1,
        }
    }
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

/// The radii [`Frustum::on_axis`] stores (see there for the bound).
fn stored_radii(c: V3, h: f64, r0: f64, r1: f64) -> (f64, f64) {
    let eps = f64::EPSILON;
    let big = r0.max(r1);
    let m = c[0].abs().max(c[1].abs()).max(c[2].abs()) + h + big;
    if r0 == r1 || !m.is_finite() {
        return (r0, r1); // no slope to amplify anything (or nothing to bound)
    }
    let eta = 4.0 * eps * m;
    let len = 2.0 * h;
    if len.is_nan() || len <= 40.0 * eta {
        return (big, big);
    }
    let delta = 4.0 * eta / len + 4.0 * eps;
    let sigma = big * delta + 3.0 * eta;
    let err = (r1 - r0).abs() * (sigma + 2.0 * eta) / (len - 2.0 * eta);
    let pad = err - SLOPE_SLACK * m;
    if pad <= 0.0 {
        return (r0, r1);
    }
    let (s0, s1) = (r0 + pad, r1 + pad);
    // Same length, so the volumes compare as r0² + r0·r1 + r1².
    if s0 * s0 + s0 * s1 + s1 * s1 < 3.0 * big * big {
        (s0, s1)
    } else {
        (big, big)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::{cross, norm};

    fn max_abs(v: V3) -> f64 {
        v[0].abs().max(v[1].abs()).max(v[2].abs())
    }

    /// Seeded uniform numbers in [0, 1) (a 64-bit LCG's top 53 bits).
    fn uniform(mut seed: u64) -> impl FnMut() -> f64 {
        move || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// How far `x` is outside `f` radially (the rejection's norm, not `contains`'s
    /// √(|d|² − t²)), and how far beyond its ends along the stored axis.
    fn misses(f: &Frustum, x: V3) -> (f64, f64) {
        let axis = sub(f.p1, f.p0);
        let len = norm(axis);
        let b = normalize(axis).unwrap();
        let d = sub(x, f.p0);
        let t = dot(d, b);
        let r = f.r0 + (f.r1 - f.r0) * (t / len).clamp(0.0, 1.0);
        (norm(madd(d, b, -t)) - r, (-t).max(t - len))
    }

    /// Points of the surface of the frustum of centre `c`, unit axis `a`, half-height
    /// `h` and end radii `r0`, `r1`: 16 around it at five heights, its rims among them.
    fn surface_points(c: V3, a: V3, h: f64, (r0, r1): (f64, f64)) -> Vec<V3> {
        let u = normalize(cross(a, [a[1], a[2], -a[0]])).unwrap();
        let v = cross(a, u);
        let mut points = Vec::with_capacity(5 * 16);
        for i in 0..5 {
            let s = i as f64 / 4.0;
            let r = r0 + (r1 - r0) * s;
            let centre = madd(c, a, (2.0 * s - 1.0) * h);
            for j in 0..16 {
                let th = j as f64 / 16.0 * std::f64::consts::TAU;
                points.push(madd(madd(centre, u, r * th.cos()), v, r * th.sin()));
            }
        }
        points
    }

    /// Frustums from long to 1e5 times shorter than their radius, with any taper, at
    /// offsets up to 5 times their size: every point of the fitted solid's surface (rims
    /// and side at five heights) lies within the slack of the stored solid radially, and
    /// within the tilt's axial bound of its ends. Stored with their fitted radii, the
    /// short steep ones missed by far more than the slack; frustums whose slope adds
    /// less than the slack are stored exactly as fitted.
    #[test]
    fn stored_frustum_holds_the_fitted_one() {
        let mut rnd = uniform(2024);
        let (mut padded, mut plain_missed, mut worst_plain, mut worst_grown) =
            (0, 0, 0.0f64, 0.0f64);
        for trial in 0..3000 {
            let size = 10f64.powf(6.0 * rnd() - 3.0);
            let c: V3 = [0; 3].map(|_| (10.0 * rnd() - 5.0) * size);
            let a = normalize([rnd() - 0.5, rnd() - 0.5, rnd() - 0.5]).unwrap();
            let big = size * (0.1 + 0.9 * rnd());
            let small = if trial % 5 == 0 { 0.0 } else { big * rnd() };
            let (r0, r1) = if trial % 2 == 0 {
                (small, big)
            } else {
                (big, small)
            };
            let h = 0.5 * big * 10f64.powf(6.0 * rnd() - 5.0);
            let f = Frustum::on_axis(c, a, h, r0, r1);
            let plain = Frustum {
                p0: madd(c, a, -h),
                p1: madd(c, a, h),
                r0,
                r1,
            };
            assert_eq!((f.p0, f.p1), (plain.p0, plain.p1));
            if (f.r0, f.r1) != (r0, r1) {
                padded += 1;
                // Down to the failing case's length (1e-4 of the radius) and out to 10
                // radii from the origin the pad is a few parts in 1e6; it grows as
                // (r̂/L)² and with the magnitude.
                let grown = (f.r0 - r0).max(f.r1 - r1) / big;
                worst_grown = worst_grown.max(grown);
                let near = h >= 0.5e-4 * big && max_abs(c) <= 10.0 * big;
                let limit = if near { 1e-5 } else { 1e-2 };
                assert!(grown <= limit, "trial {trial}: grew {grown} of {big}");
            }
            let m = max_abs(c) + h + big;
            let eps = f64::EPSILON;
            let radial_tol = SLOPE_SLACK * m + 64.0 * eps * m;
            let axial_tol = big * (64.0 * eps * m / (2.0 * h) + 4.0 * eps) + 64.0 * eps * m;
            for x in surface_points(c, a, h, (r0, r1)) {
                let (radial, axial) = misses(&f, x);
                assert!(
                    radial <= radial_tol && axial <= axial_tol,
                    "trial {trial}: {f:?} misses {x:?} by {radial} radially, {axial} axially"
                );
                let (radial, _) = misses(&plain, x);
                if radial > radial_tol {
                    plain_missed += 1;
                    worst_plain = worst_plain.max(radial / m);
                }
            }
        }
        eprintln!(
            "padded {padded} of 3000 (radius grown by up to {worst_grown:e}); the plain \
             ends missed {plain_missed} points, by up to {worst_plain:e} of m"
        );
        assert!(padded > 100 && padded < 2900, "padded {padded}");
        assert!(
            plain_missed > 0,
            "the test no longer reaches the steep frustums"
        );
    }
}
