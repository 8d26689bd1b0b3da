//! Moving a fitted primitive from the engine's re-centred frame to world coordinates
//! without losing enclosure (fuzz finding 3).
//!
//! Boxes, spheres, capsules and prisms move by a centre or two end points: rounding
//! moves every point of their surface by at most that rounding, an ulp or so of the
//! coordinates' magnitude, which the enclosure tolerance covers. Cylinders and
//! frustums are stored as two cap centres, so their axis is a difference of rounded
//! numbers: moving either end by η tilts the axis of length `L` by up to 2η/L, and a
//! rim point at radius `r` moves by about r·2η/L along it. That error has no bound:
//! a flat disc 1 across at 8.5e6 (ulp 1.9e-9) with a minimum extent of 1e-6 lost
//! 5e-4 of its rim, and one 5e-6 across (the fuzz case) got an axis one ulp long.
//! No minimum length removes it for every radius, so [`Primitive::to_world`] pushes
//! both ends out along the axis and grows the radii by just enough that the world
//! solid contains the fitted one whatever the rounding (bound below).
//!
//! The bound. Let the fitted solid have ends `P0`, `P1` (length `L`, unit axis `a`,
//! radii `r0`, `r1`, largest `r̂`), and the written one ends `Q0`, `Q1` (unit axis `b`,
//! length `L''`) within η of `A0 = P0 − a·e` and `A1 = P1 + a·e` (`M = L + 2e`), so
//! that `δ = |a − b| ≤ 4η/M`. A point `x = A0 + τ·a + w` of the fitted solid
//! (`τ ∈ [e, e + L]`, `w ⊥ a`, `|w| ≤ r(τ)`) has axial coordinate
//! `t = (x − Q0)·b ∈ [τ(1 − δ²/2) − r̂δ − η, τ + r̂δ + η]`, which lies in `[0, L'']`
//! (`L'' ≥ M − 2η`) when `e(1 − δ²/2) ≥ r̂δ + 3η`; and its distance from the new axis
//! is at most `|w| + τδ + η ≤ |w| + 5η`. So a cylinder needs `r + 5η`; a frustum either
//! `max(r0, r1) + 5η` at both ends, or its cone extended over `[0, M]` (`t` and `τ`
//! differ by at most `r̂δ + 1.2η`) plus the slope times that difference — whichever
//! is smaller. η covers the fit's rounding of the ends in the local frame, the
//! rounding of the extension and of the translation (each a few ε of the magnitudes),
//! and the extension's own tilt; requiring `M ≥ 40η` keeps `δ ≤ 0.1`. When the local
//! ends themselves are too close to carry an axis (tilt bound over 1%), the result is
//! a cylinder around the ball that holds the whole solid.

use super::{Cylinder, Frustum, Primitive};
use crate::math::{add, madd, norm, normalize, scale, sub, V3};

/// Largest tolerated tilt of the stored local axis (as a fraction of a radian) before
/// the axis is treated as lost.
const MAX_LOCAL_TILT: f64 = 0.01;

/// The two ends and radii of a solid of revolution (a cylinder has `r0 == r1`).
#[derive(Clone, Copy, Debug)]
struct Round {
    p0: V3,
    p1: V3,
    r0: f64,
    r1: f64,
}

impl Primitive {
    /// The primitive in world coordinates, `offset` being the re-centring offset:
    /// moved by `offset`, and for cylinders and frustums grown so that rounding cannot
    /// tilt the axis out of the fitted solid (see the module doc).
    pub(crate) fn to_world(self, offset: V3) -> Primitive {
        let round = match self {
            Primitive::Cylinder(c) => world_round(c.p0, c.p1, c.radius, c.radius, offset),
            Primitive::Frustum(f) => world_round(f.p0, f.p1, f.r0, f.r1, offset),
            _ => return self.translated(offset),
        };
        // The pads are ~1e-13 of the coordinates' magnitude: `decompose` refuses
        // coordinates beyond `mesh::MAX_POSITION` (1e70), so they never overflow there;
        // a direct caller with coordinates near f64::MAX gets the plain translation.
        let Some(r) = round.filter(Round::is_finite) else {
            return self.translated(offset);
        };
        match self {
            Primitive::Cylinder(_) => Primitive::Cylinder(Cylinder {
                p0: r.p0,
                p1: r.p1,
                radius: r.r0.max(r.r1),
            }),
            _ => Primitive::Frustum(Frustum {
                p0: r.p0,
                p1: r.p1,
                r0: r.r0,
                r1: r.r1,
            }),
        }
    }
}

impl Round {
    fn is_finite(&self) -> bool {
        [self.r0, self.r1]
            .iter()
            .chain(&self.p0)
            .chain(&self.p1)
            .all(|v| v.is_finite())
    }
}

fn max_abs(v: V3) -> f64 {
    v[0].abs().max(v[1].abs()).max(v[2].abs())
}

/// The world solid of revolution around local ends `p0`, `p1` with radii `r0`, `r1`.
fn world_round(p0: V3, p1: V3, r0: f64, r1: f64, d: V3) -> Option<Round> {
    let eps = f64::EPSILON;
    let len = norm(sub(p1, p0));
    // The radius is not rounded with the ends, but counting it keeps r/η and L/η below
    // 1/(16ε), so the quadratic in `extension` cannot overflow.
    let m_local = max_abs(p0).max(max_abs(p1)) + len + r0.max(r1);
    let m_off = max_abs(d);
    // Tilt of the stored local axis: both ends within 4ε·m_local of the fitted ones.
    let tilt = 4.0 * (4.0 * eps * m_local) / len + 4.0 * eps;
    let axis = normalize(sub(p1, p0));
    let (Some(a), true) = (axis, tilt <= MAX_LOCAL_TILT) else {
        return Some(around_ball(p0, p1, r0.max(r1), m_local, d));
    };
    // η = eta0 + c1·e, with twice the ε-multiples the roundings need.
    let eta0 = 16.0 * eps * (m_local + m_off);
    let c1 = 8.0 * eps + tilt;
    let e = extension(len, r0.max(r1), eta0, c1);
    let eta = eta0 + c1 * e;
    let (q0, q1) = (add(madd(p0, a, -e), d), add(madd(p1, a, e), d));
    let m = len + 2.0 * e;
    // Axial mismatch between the two solids, then the two enclosing profiles.
    let shift = r0.max(r1) * 4.0 * eta / m + 1.2 * eta;
    let cyl = r0.max(r1) + 5.0 * eta;
    let k = if len > 0.0 { (r1 - r0) / len } else { 0.0 };
    let (g0, g1) = ((r0 - k * e).max(0.0), (r1 + k * e).max(0.0));
    let pad = 5.0 * eta + (g1 - g0).abs() * (shift + 2.0 * eta) / (0.95 * m);
    let (s0, s1) = (g0 + pad, g1 + pad);
    // Same length, so the volumes compare as r0² + r0·r1 + r1².
    let (r0, r1) = if s0 * s0 + s0 * s1 + s1 * s1 < 3.0 * cyl * cyl {
        (s0, s1)
    } else {
        (cyl, cyl)
    };
    Some(Round {
        p0: q0,
        p1: q1,
        r0,
        r1,
    })
}

/// The smallest `e` (up to the simplifications in the comments) with
/// `e(1 − δ²/2) ≥ r̂δ + 3η` and `L + 2e ≥ 40η`, where `η = eta0 + c1·e` and
/// `δ = 4η/(L + 2e)`; requires `c1 ≤ 0.01` and `eta0 > 0`.
fn extension(len: f64, r: f64, eta0: f64, c1: f64) -> f64 {
    // With δ ≤ 0.1, 1 − δ²/2 ≥ 0.995; 4r̂·c1·e/(L + 2e) ≤ 2r̂·c1. So it suffices that
    // s·e ≥ 4r̂·eta0/(L + 2e) + k, with s = 0.995 − 3c1 and k = 3·eta0 + 2r̂·c1:
    // a quadratic in e whose positive root is the bound.
    // Solved in units of eta0 (≥ 16ε·(L + r̂)), so that no square overflows.
    let (len, r) = (len / eta0, r / eta0);
    let s = 0.995 - 3.0 * c1;
    let k = 3.0 + 2.0 * r * c1;
    let (qa, qb, qc) = (2.0 * s, s * len - 2.0 * k, 4.0 * r + k * len);
    let root = (-qb + (qb * qb + 4.0 * qa * qc).sqrt()) / (2.0 * qa);
    // L + 2e ≥ 40(eta0 + c1·e).
    let long = (40.0 - len) / (2.0 - 40.0 * c1);
    eta0 * root.max(long).max(0.0)
}

/// A cylinder holding the ball around the ends' midpoint that contains the whole
/// solid, for ends too close to define an axis; its direction is the stored one (or
/// z), which no longer matters.
fn around_ball(p0: V3, p1: V3, r: f64, m_local: f64, d: V3) -> Round {
    let eps = f64::EPSILON;
    let mid = scale(add(p0, p1), 0.5);
    let len = norm(sub(p1, p0));
    let a = normalize(sub(p1, p0)).unwrap_or([0.0, 0.0, 1.0]);
    // The fitted ends lie within 4ε·m_local of the stored ones.
    let rho = 0.5 * len + r + 8.0 * eps * m_local;
    let eta = 8.0 * eps * (max_abs(mid) + max_abs(d) + rho);
    let half = (rho + 2.0 * eta).max(20.0 * eta);
    let radius = rho + 2.0 * eta;
    Round {
        p0: add(madd(mid, a, -half), d),
        p1: add(madd(mid, a, half), d),
        r0: radius,
        r1: radius,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::{cross, dot};

    /// Rim points of a solid of revolution: `n` around each end circle.
    fn rim(p0: V3, p1: V3, r0: f64, r1: f64, n: usize) -> Vec<V3> {
        let a = normalize(sub(p1, p0)).unwrap();
        let t = if a[0].abs() < 0.9 {
            [1.0, 0.0, 0.0]
        } else {
            [0.0, 1.0, 0.0]
        };
        let u = normalize(cross(a, t)).unwrap();
        let v = cross(a, u);
        let mut out = Vec::new();
        for (c, r) in [(p0, r0), (p1, r1)] {
            for i in 0..n {
                let th = i as f64 / n as f64 * std::f64::consts::TAU;
                out.push(madd(madd(c, u, r * th.cos()), v, r * th.sin()));
            }
        }
        out
    }

    /// Whether `x` is within `tol` of the frustum, with the radial distance taken as the
    /// norm of the rejection (`Frustum::contains` uses √(|d|² − t²), which cancels to
    /// about 1e-8·|d| near the axis).
    fn inside(f: &Frustum, x: V3, tol: f64) -> bool {
        let len = norm(sub(f.p1, f.p0));
        let a = normalize(sub(f.p1, f.p0)).unwrap();
        let d = sub(x, f.p0);
        let t = dot(d, a);
        let r = f.r0 + (f.r1 - f.r0) * (t / len).clamp(0.0, 1.0);
        (-tol..=len + tol).contains(&t) && norm(madd(d, a, -t)) <= r + tol
    }

    /// Flat and ordinary cylinders and frustums at offsets up to 1e9: every rim point
    /// of the fitted solid, moved to world coordinates, lies in the world solid to
    /// within a few ulps of the offset (where plain translation missed by far more).
    #[test]
    fn world_solid_contains_the_fitted_one() {
        let dir = normalize([0.3, -0.7, 0.64]).unwrap();
        for off in [0.0, 1.0, 8.5e6, 1e9] {
            let d = [off, -0.5 * off, 0.25 * off];
            for (h, r0, r1) in [
                (1e-9, 0.5, 0.5),
                (1e-6, 0.5, 0.2),
                (0.3, 0.1, 0.4),
                (2.0, 0.7, 0.0),
            ] {
                let c = [0.3, 0.2, -0.1];
                let (p0, p1) = (madd(c, dir, -h), madd(c, dir, h));
                let Primitive::Frustum(f) =
                    Primitive::Frustum(Frustum { p0, p1, r0, r1 }).to_world(d)
                else {
                    panic!("kind changed")
                };
                let tol = 8.0 * f64::EPSILON * (off + 1.0);
                for p in rim(p0, p1, r0, r1, 64) {
                    let w = add(p, d);
                    assert!(inside(&f, w, tol), "off {off} h {h}: {f:?} misses {w:?}");
                }
                let grown = norm(sub(f.p1, f.p0)) - 2.0 * h;
                assert!(
                    (0.0..1e-2).contains(&grown),
                    "off {off} h {h}: grew {grown}"
                );
                assert!(dot(sub(f.p1, f.p0), dir) > 0.0);
            }
        }
    }

    /// An ordinary cylinder near the origin changes by ulps only.
    #[test]
    fn ordinary_cylinders_barely_change() {
        let c = Cylinder {
            p0: [0.1, 0.2, -0.3],
            p1: [0.4, 0.9, 0.5],
            radius: 0.25,
        };
        let Primitive::Cylinder(w) = Primitive::Cylinder(c).to_world([2.0, -1.0, 0.5]) else {
            panic!("kind changed")
        };
        for k in 0..3 {
            assert!((w.p0[k] - (c.p0[k] + [2.0, -1.0, 0.5][k])).abs() < 1e-13);
        }
        assert!(w.radius >= c.radius && w.radius - c.radius < 1e-13);
    }

    /// Ends closer than the rounding of their own magnitude: the result holds the ball
    /// around them whatever the true axis was.
    #[test]
    fn lost_axis_gives_the_enclosing_ball() {
        let p = [50.0, 0.0, 0.0];
        let f = Frustum {
            p0: p,
            p1: p,
            r0: 0.5,
            r1: 0.3,
        };
        let w = Primitive::Frustum(f).to_world([0.0; 3]);
        for dir in [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.6, 0.8]] {
            assert!(w.contains(madd(p, dir, 0.5), 1e-12), "{w:?} misses {dir:?}");
        }
    }
}
