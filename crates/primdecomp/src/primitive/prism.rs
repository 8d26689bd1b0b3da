//! Trapezoidal prism (§3.2 "Isosceles Trapezoidal Prisms", Alg. 3).
//!
//! Local frame: extruded along `axes[0]` (x) over [−hx, hx]; the y–z cross-section is
//! the trapezoid whose half-width along z is `hz_top` at y = +hy and `hz_bottom` at
//! y = −hy, its parallel sides' midpoints at z = `shift` (top) and −`shift` (bottom).
//! `shift` = 0 is the paper's isosceles prism, which every fit by volume makes; a
//! skewed one holds a scalene triangle exactly, and only the cut's nearest fits make
//! it (docs/decisions/0045-skewed-prisms-where-the-cut-cannot-split.md). `axes` is
//! orthonormal and right-handed.

use super::profile::{fit_profile_sorted, Objective, ProfileScratch};
use crate::math::{dot, madd, sub, V3};

/// Trapezoidal prism: a trapezoid in the local y–z plane extruded along x (see the
/// module documentation for the frame).
///
/// ```
/// use primdecomp::{Primitive, Prism};
///
/// // A wedge: 2 × 2 at the bottom, 2 × 1 at the top.
/// let axes = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
/// let wedge = Prism { center: [0.0; 3], axes, hx: 1.0, hy: 1.0, hz_top: 0.5, hz_bottom: 1.0, shift: 0.0 };
/// assert!(Primitive::Prism(wedge).contains([0.0, -1.0, -1.0], 1e-12));
/// assert!(!Primitive::Prism(wedge).contains([0.0, 1.0, 1.0], 1e-12));
/// ```
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
    /// z of the top side's midpoint (the bottom side's is −`shift`): 0 for the
    /// paper's isosceles trapezoid.
    pub shift: f64,
}

impl Prism {
    /// §3.2: 4·hx·hy·(hzt + hzb).
    pub fn volume(&self) -> f64 {
        4.0 * self.hx * self.hy * (self.hz_top + self.hz_bottom)
    }
    /// The cross-section's (middle, half-width) along z at local height `y` (clamped
    /// to the prism's y range).
    pub(crate) fn section_at(&self, y: f64) -> (f64, f64) {
        let s = if self.hy > 0.0 {
            ((y + self.hy) / (2.0 * self.hy)).clamp(0.0, 1.0)
        } else {
            0.5
        };
        (
            self.shift * (2.0 * s - 1.0),
            self.hz_bottom + (self.hz_top - self.hz_bottom) * s,
        )
    }
    /// Whether the trapezoid is skewed (not the paper's isosceles one): it takes one
    /// float more to store.
    pub fn is_skewed(&self) -> bool {
        self.shift != 0.0
    }
    /// The z range of the cross-section over all heights: (least, greatest).
    pub(crate) fn z_range(&self) -> (f64, f64) {
        let (t, b) = (self.shift, -self.shift);
        (
            (t - self.hz_top).min(b - self.hz_bottom),
            (t + self.hz_top).max(b + self.hz_bottom),
        )
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
        // beyond its ends are near the line, so the z range of the ends caps z too.
        let (mid, w) = self.section_at(y);
        let two_hy = 2.0 * self.hy.max(f64::MIN_POSITIVE);
        let widen = (self.hz_top - self.hz_bottom) / two_hy;
        let lean = 2.0 * self.shift / two_hy;
        let slack = |slope: f64| {
            if tol > 0.0 {
                tol * (1.0 + slope * slope).sqrt()
            } else {
                0.0
            }
        };
        let (lo, hi) = self.z_range();
        let off = z - mid;
        off - w <= slack(lean + widen)
            && -off - w <= slack(lean - widen)
            && z <= hi + tol
            && z >= lo - tol
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
                    out[i] = madd(p, self.axes[2], sy * self.shift + sz * hz);
                    i += 1;
                }
            }
        }
        out
    }
    /// The prism with every side pushed out by `m` (perpendicular), or the box of its
    /// z range pushed out where that holds less (a steep side pushed out reaches
    /// far along z at the ends).
    pub(crate) fn grown(&self, m: f64) -> Prism {
        let (lo, hi) = self.z_range();
        let wide = 0.5 * (hi - lo) + m;
        let mut out = Prism {
            center: madd(self.center, self.axes[2], 0.5 * (hi + lo)),
            hx: self.hx + m,
            hy: self.hy + m,
            hz_top: wide,
            hz_bottom: wide,
            shift: 0.0,
            ..*self
        };
        if self.hy > 0.0 {
            // Side lines z = mid(y) ± w(y): slopes lean ± widen, each pushed out by
            // m·√(1 + slope²) and extended by m at both ends.
            let widen = (self.hz_top - self.hz_bottom) / (2.0 * self.hy);
            let lean = self.shift / self.hy;
            let push = |slope: f64| m * (1.0 + slope * slope).sqrt();
            let (right, left) = (push(lean + widen), push(lean - widen));
            let grow = 0.5 * (right + left);
            let (t, b) = (
                self.hz_top + widen * m + grow,
                self.hz_bottom - widen * m + grow,
            );
            if t + b <= 2.0 * wide {
                out = Prism {
                    center: madd(self.center, self.axes[2], 0.5 * (right - left)),
                    hz_top: t,
                    hz_bottom: b,
                    shift: self.shift + lean * m,
                    ..out
                };
            }
        }
        out
    }
    /// Axis-aligned bounds (min, max), conservative.
    pub fn aabb(&self) -> (V3, V3) {
        crate::math::aabb_of(self.corners().into_iter())
    }
}

/// A skewed section ([`skewed_section`]) in its frame: the z of its middle at y = 0,
/// the top side's midpoint relative to that (the bottom's is −`shift`), and the two
/// half-widths.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Section {
    pub middle: f64,
    pub shift: f64,
    pub top: f64,
    pub bottom: f64,
}

/// §3.2's trapezoid (Alg. 3) without the mirror: over the points `(uy[i], uz[i])`
/// (`order` sorting them by y, |y| ≤ `hy`), the least-area trapezoid with parallel
/// sides at y = ±`hy`. The area is `2·hy` times the width at y = 0, which splits into
/// what each slanted side adds, so each is the profile fit's least `Sum` line on its
/// own side (above z − min z, and above max z − z). `None` where the two lines cross
/// inside (points only in the middle of a padded `hy`).
pub(crate) fn skewed_section(
    uy: &[f64],
    uz: &[f64],
    order: &[u32],
    hy: f64,
    sc: &mut ProfileScratch,
) -> Option<Section> {
    let (lo, hi) = uz
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &z| {
            (a.min(z), b.max(z))
        });
    if !(hy > 0.0 && lo <= hi) {
        return None;
    }
    let t = |i: usize| ((uy[i] + hy) / (2.0 * hy)).clamp(0.0, 1.0);
    let (b_up, t_up) = fit_profile_sorted(order, |i| (t(i), uz[i] - lo), Objective::Sum, sc);
    let (b_dn, t_dn) = fit_profile_sorted(order, |i| (t(i), hi - uz[i]), Objective::Sum, sc);
    // Each end's z range: [hi − down, lo + up]; a side of no width (a triangle's
    // apex) may come out an ulp negative.
    let (bottom, top) = ([hi - b_dn, lo + b_up], [hi - t_dn, lo + t_up]);
    // The sums here round by an ulp of the ends' magnitudes: widen by a few.
    let big = [bottom[0], bottom[1], top[0], top[1]].map(f64::abs);
    let pad = 8.0 * f64::EPSILON * big.into_iter().fold(0.0, f64::max);
    if !(bottom[1] - bottom[0] >= -pad && top[1] - top[0] >= -pad) {
        return None;
    }
    let (mb, mt) = (0.5 * (bottom[0] + bottom[1]), 0.5 * (top[0] + top[1]));
    let half = |[a, b]: [f64; 2]| 0.5 * (b - a).max(0.0) + pad;
    Some(Section {
        middle: 0.5 * (mb + mt),
        shift: 0.5 * (mt - mb),
        top: half(top),
        bottom: half(bottom),
    })
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
            shift: 0.0,
        };
        assert!(!p.contains([0.0, 0.0, 100.0], 0.1));
        assert!(!p.contains([0.0, 1e-3, 10.2], 0.1));
        assert!(p.contains([0.0, 1e-3, 10.05], 0.1));
        assert!(p.contains([0.5, 0.0, 5.4], 1e-9));
    }

    /// A prism in the world frame around the section, extruded `hx` along x.
    fn around(sec: Section, hx: f64, hy: f64) -> Prism {
        Prism {
            center: [0.0, 0.0, sec.middle],
            axes: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            hx,
            hy,
            hz_top: sec.top,
            hz_bottom: sec.bottom,
            shift: sec.shift,
        }
    }

    fn section_of(pts: &[(f64, f64)], hy: f64) -> Option<Section> {
        let (uy, uz): (Vec<f64>, Vec<f64>) = pts.iter().copied().unzip();
        let mut order: Vec<u32> = (0..pts.len() as u32).collect();
        order.sort_by(|&a, &b| uy[a as usize].total_cmp(&uy[b as usize]));
        skewed_section(&uy, &uz, &order, hy, &mut ProfileScratch::default())
    }

    /// A scalene triangle is its own skewed section (area 3, as the triangle's), where
    /// the isosceles one must mirror the apex's offset: the prism holds the
    /// triangle's corners and not the mirrored corner the isosceles one stands out to.
    #[test]
    fn a_scalene_triangle_is_its_own_skewed_section() {
        let tri = [(-1.0, 0.0), (-1.0, 3.0), (1.0, 0.4)];
        let sec = section_of(&tri, 1.0).unwrap();
        assert!(
            sec.top.abs() < 1e-12 && (sec.bottom - 1.5).abs() < 1e-12,
            "{sec:?}"
        );
        let p = around(sec, 0.1, 1.0);
        assert!((p.volume() - 0.2 * 3.0).abs() < 1e-12);
        for (y, z) in tri {
            assert!(p.contains([0.05, y, z], 1e-12), "{y} {z}");
        }
        // The isosceles trapezoid about the apex's line would reach z = 0.4 − 1.5.
        assert!(!p.contains([0.0, -1.0, -0.5], 1e-3));
        assert!(!p.contains([0.0, 0.0, 2.0], 1e-3));
    }

    /// Random clouds: the skewed section holds every point and is never larger than
    /// the isosceles one (the paper's, centred on the points' z range).
    #[test]
    fn skewed_sections_hold_their_points_and_beat_the_mirror() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(45);
        for case in 0..500 {
            let n = rng.gen_range(1..30);
            let lean = rng.gen_range(-3.0..3.0);
            let mut pts: Vec<(f64, f64)> = (0..n)
                .map(|_| {
                    let y: f64 = rng.gen_range(-1.0..1.0);
                    (y, lean * y + rng.gen_range(-0.5..0.5))
                })
                .collect();
            // Centred on their y range, as the fit's frame centres them.
            let (ylo, yhi) = pts
                .iter()
                .fold((f64::MAX, f64::MIN), |(a, b), p| (a.min(p.0), b.max(p.0)));
            pts.iter_mut().for_each(|p| p.0 -= 0.5 * (ylo + yhi));
            let hy = 0.5 * (yhi - ylo);
            let Some(sec) = section_of(&pts, hy) else {
                assert!(hy == 0.0, "case {case}: no section for {pts:?}");
                continue;
            };
            let p = around(sec, 1.0, hy);
            for &(y, z) in &pts {
                assert!(
                    p.contains([0.0, y, z], 1e-12),
                    "case {case}: {y} {z} {sec:?}"
                );
            }
            let (lo, hi) = pts
                .iter()
                .fold((f64::MAX, f64::MIN), |(a, b), p| (a.min(p.1), b.max(p.1)));
            let mid = 0.5 * (lo + hi);
            let mut order: Vec<u32> = (0..n as u32).collect();
            order.sort_by(|&a, &b| pts[a as usize].0.total_cmp(&pts[b as usize].0));
            let t = |i: usize| (pts[i].0 + hy) / (2.0 * hy);
            let (b, a) = fit_profile_sorted(
                &order,
                |i| (t(i), (pts[i].1 - mid).abs()),
                Objective::Sum,
                &mut ProfileScratch::default(),
            );
            assert!(sec.top + sec.bottom <= a + b + 1e-9, "case {case}");
        }
    }

    /// `grown(m)` holds every point within `m` of the prism: the corners pushed out
    /// by `m` along 200 directions, for skewed, isosceles and steep sections.
    #[test]
    fn grown_prisms_hold_the_margin() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        for (hy, top, bottom, shift) in [
            (0.5, 0.1, 0.9, 0.0),
            (0.5, 0.1, 0.9, 0.7),
            (0.01, 3.0, 0.2, -1.5),
            (1.0, 0.0, 1.5, 0.4),
        ] {
            let p = Prism {
                center: [1.0, 2.0, 3.0],
                axes: [[0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]],
                hx: 0.3,
                hy,
                hz_top: top,
                hz_bottom: bottom,
                shift,
            };
            let m = 0.05;
            let g = p.grown(m);
            for c in p.corners() {
                for _ in 0..200 {
                    let d: [f64; 3] = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
                    let l = dot(d, d).sqrt();
                    let q = madd(c, d, m / l);
                    assert!(g.contains(q, 1e-12), "{p:?} {q:?}");
                }
            }
            assert!(g.volume() < p.grown(2.0 * m).volume());
        }
    }
}
