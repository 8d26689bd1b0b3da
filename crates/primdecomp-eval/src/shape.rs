//! The exact analytic surfaces of the six primitives, as area-weighted pieces to
//! sample (triangles, discs, spheres or hemispheres, cone and cylinder sides), and
//! the exact distance from a point to a primitive's surface.
//!
//! Boxes and prisms are their six planar faces (two triangles each; the prism's end
//! caps are trapezoids). Cylinders and frustums are a side and two discs; a capsule
//! is a cylinder side and two hemispheres. No tessellation: every sample lies on the
//! true surface, and the distance is to the true surface.

use primdecomp::{Obb, Primitive, Prism};
use primdecomp_math::{add, cross, dot, madd, norm, norm2, normalize, scale, sub, V3};
use std::f64::consts::PI;

/// A surface piece with a closed-form area and an area-uniform sampler.
#[derive(Clone, Copy, Debug)]
pub enum Piece {
    Tri([V3; 3]),
    /// Disc of radius `r` centred at `c` in the plane spanned by `u`, `v` (orthonormal).
    Disc {
        c: V3,
        u: V3,
        v: V3,
        r: f64,
    },
    /// Sphere of radius `r` at `c`; with `half = Some(a)`, only the half on the side
    /// of unit vector `a`.
    Sphere {
        c: V3,
        r: f64,
        half: Option<V3>,
    },
    /// Side of a frustum (cylinder when `r0 == r1`) from `p0` along unit `a` for `h`,
    /// with `u`, `v` completing an orthonormal frame.
    Side {
        p0: V3,
        a: V3,
        u: V3,
        v: V3,
        h: f64,
        r0: f64,
        r1: f64,
    },
}

impl Piece {
    pub fn area(&self) -> f64 {
        match *self {
            Piece::Tri([a, b, c]) => 0.5 * norm(cross(sub(b, a), sub(c, a))),
            Piece::Disc { r, .. } => PI * r * r,
            Piece::Sphere { r, half, .. } => {
                let full = 4.0 * PI * r * r;
                if half.is_some() {
                    0.5 * full
                } else {
                    full
                }
            }
            Piece::Side { h, r0, r1, .. } => PI * (r0 + r1) * (h * h + (r1 - r0).powi(2)).sqrt(),
        }
    }

    /// The point for uniforms `w` in [0, 1)³; area-uniform when `w` is uniform.
    pub fn point(&self, w: [f64; 3]) -> V3 {
        match *self {
            Piece::Tri([a, b, c]) => {
                // Square-root warp (Osada et al. 2002).
                let s = w[0].sqrt();
                let (x, y) = (1.0 - s, s * (1.0 - w[1]));
                add(a, add(scale(sub(b, a), 1.0 - x - y), scale(sub(c, a), y)))
            }
            Piece::Disc { c, u, v, r } => {
                let (rho, t) = (r * w[0].sqrt(), 2.0 * PI * w[1]);
                madd(madd(c, u, rho * t.cos()), v, rho * t.sin())
            }
            Piece::Sphere { c, r, half } => {
                // Archimedes: the axial coordinate of a uniform sphere point is uniform.
                let (axis, z) = match half {
                    Some(a) => (a, w[0]),
                    None => ([0.0, 0.0, 1.0], 2.0 * w[0] - 1.0),
                };
                let (u, v) = frame(axis);
                let (rho, t) = ((1.0 - z * z).max(0.0).sqrt(), 2.0 * PI * w[1]);
                let d = madd(madd(scale(axis, z), u, rho * t.cos()), v, rho * t.sin());
                madd(c, d, r)
            }
            Piece::Side {
                p0,
                a,
                u,
                v,
                h,
                r0,
                r1,
            } => {
                // Axial position with density ∝ radius: inverse CDF, in a form that
                // stays exact as r1 → r0.
                let den = r0 + (r0 * r0 + w[0] * (r1 * r1 - r0 * r0)).max(0.0).sqrt();
                let s = if den > 0.0 {
                    w[0] * (r0 + r1) / den
                } else {
                    w[0]
                };
                let r = r0 + (r1 - r0) * s;
                let t = 2.0 * PI * w[1];
                madd(madd(madd(p0, a, h * s), u, r * t.cos()), v, r * t.sin())
            }
        }
    }
}

/// Two unit vectors completing unit `a` to an orthonormal frame.
pub fn frame(a: V3) -> (V3, V3) {
    let k = (0..3)
        .min_by(|&i, &j| a[i].abs().total_cmp(&a[j].abs()))
        .unwrap_or(0);
    let mut e = [0.0; 3];
    e[k] = 1.0;
    let u = normalize(cross(a, e)).unwrap_or([1.0, 0.0, 0.0]);
    (u, cross(a, u))
}

/// Corners of a box-like solid: index `4·ix + 2·iy + iz` for the signs (−, +) of
/// each local axis; the half-width along z is `hz[iy]` (a prism's trapezoid).
/// Corners of a box-like solid: `hz[i]` the half-width along z at y = ∓hy, about
/// `mid[i]` (a skewed prism's sides' midpoints; 0 for a box).
fn corners(center: V3, axes: &[V3; 3], hx: f64, hy: f64, hz: [f64; 2], mid: [f64; 2]) -> [V3; 8] {
    std::array::from_fn(|i| {
        let (sx, iy, sz) = (
            if i & 4 != 0 { 1.0 } else { -1.0 },
            (i >> 1) & 1,
            if i & 1 != 0 { 1.0 } else { -1.0 },
        );
        let sy = if iy == 1 { 1.0 } else { -1.0 };
        let p = madd(center, axes[0], sx * hx);
        let p = madd(p, axes[1], sy * hy);
        madd(p, axes[2], mid[iy] + sz * hz[iy])
    })
}

/// The six faces of a box-like solid as corner cycles.
const FACES: [[usize; 4]; 6] = [
    [0, 1, 3, 2],
    [4, 5, 7, 6],
    [0, 1, 5, 4],
    [2, 3, 7, 6],
    [0, 2, 6, 4],
    [1, 3, 7, 5],
];

/// The 12 triangles of a box-like solid's faces.
fn hexahedron(c: &[V3; 8]) -> [[V3; 3]; 12] {
    std::array::from_fn(|i| {
        let f = FACES[i / 2];
        if i % 2 == 0 {
            [c[f[0]], c[f[1]], c[f[2]]]
        } else {
            [c[f[0]], c[f[2]], c[f[3]]]
        }
    })
}

/// The 12 triangles of a box's surface.
pub fn box_triangles(b: &Obb) -> [[V3; 3]; 12] {
    hexahedron(&corners(
        b.center,
        &b.axes,
        b.half[0],
        b.half[1],
        [b.half[2]; 2],
        [0.0; 2],
    ))
}

fn prism_tris(p: &Prism) -> [[V3; 3]; 12] {
    hexahedron(&corners(
        p.center,
        &p.axes,
        p.hx,
        p.hy,
        [p.hz_bottom, p.hz_top],
        [-p.shift, p.shift],
    ))
}

/// Axis of a segment-based primitive: (unit axis, length), any unit axis when the
/// ends coincide.
fn axis(p0: V3, p1: V3) -> (V3, f64) {
    let d = sub(p1, p0);
    (normalize(d).unwrap_or([0.0, 0.0, 1.0]), norm(d))
}

/// Side and two caps of a frustum (a cylinder when `r0 == r1`).
fn frustum_pieces(p0: V3, p1: V3, r0: f64, r1: f64, out: &mut Vec<Piece>) {
    let (a, h) = axis(p0, p1);
    let (u, v) = frame(a);
    out.push(Piece::Side {
        p0,
        a,
        u,
        v,
        h,
        r0,
        r1,
    });
    out.push(Piece::Disc { c: p0, u, v, r: r0 });
    out.push(Piece::Disc { c: p1, u, v, r: r1 });
}

/// Appends the surface pieces of `prim` to `out`.
pub fn pieces(prim: &Primitive, out: &mut Vec<Piece>) {
    match prim {
        Primitive::Box(b) => out.extend(box_triangles(b).map(Piece::Tri)),
        Primitive::Prism(p) => out.extend(prism_tris(p).map(Piece::Tri)),
        Primitive::Sphere(s) => out.push(Piece::Sphere {
            c: s.center,
            r: s.radius,
            half: None,
        }),
        Primitive::Cylinder(c) => frustum_pieces(c.p0, c.p1, c.radius, c.radius, out),
        Primitive::Frustum(f) => frustum_pieces(f.p0, f.p1, f.r0, f.r1, out),
        Primitive::Capsule(c) => {
            let (a, h) = axis(c.p0, c.p1);
            let r = c.radius;
            if h == 0.0 {
                out.push(Piece::Sphere {
                    c: c.p0,
                    r,
                    half: None,
                });
                return;
            }
            let (u, v) = frame(a);
            out.push(Piece::Side {
                p0: c.p0,
                a,
                u,
                v,
                h,
                r0: r,
                r1: r,
            });
            out.push(Piece::Sphere {
                c: c.p0,
                r,
                half: Some(scale(a, -1.0)),
            });
            out.push(Piece::Sphere {
                c: c.p1,
                r,
                half: Some(a),
            });
        }
    }
}

/// Squared distance in the plane from `(x, y)` to the segment `a`–`b`.
fn seg2_dist2(x: f64, y: f64, a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let l2 = dx * dx + dy * dy;
    let t = if l2 > 0.0 {
        (((x - a[0]) * dx + (y - a[1]) * dy) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let (ex, ey) = (x - a[0] - t * dx, y - a[1] - t * dy);
    ex * ex + ey * ey
}

/// Squared distance from `p` to the surface (not the solid) of `prim`, exact.
pub fn surface_dist2(prim: &Primitive, p: V3) -> f64 {
    use primdecomp_math::bvh::{point_segment_dist2, point_tri_dist2};
    let tris = |t: [[V3; 3]; 12]| {
        t.iter()
            .map(|t| point_tri_dist2(p, t))
            .fold(f64::INFINITY, f64::min)
    };
    match prim {
        Primitive::Box(b) => tris(box_triangles(b)),
        Primitive::Prism(q) => tris(prism_tris(q)),
        Primitive::Sphere(s) => (norm(sub(p, s.center)) - s.radius).powi(2),
        Primitive::Capsule(c) => (point_segment_dist2(p, c.p0, c.p1).sqrt() - c.radius).powi(2),
        Primitive::Cylinder(c) => revolved_dist2(p, c.p0, c.p1, c.radius, c.radius),
        Primitive::Frustum(f) => revolved_dist2(p, f.p0, f.p1, f.r0, f.r1),
    }
}

/// A surface of revolution's distance is the distance, in the half-plane through the
/// axis and `p`, to its profile: cap (0,0)–(0,r0), side (0,r0)–(h,r1), cap (h,r1)–(h,0).
fn revolved_dist2(p: V3, p0: V3, p1: V3, r0: f64, r1: f64) -> f64 {
    let (a, h) = axis(p0, p1);
    let d = sub(p, p0);
    let t = dot(d, a);
    let rho = (norm2(d) - t * t).max(0.0).sqrt();
    let prof = [[0.0, 0.0], [0.0, r0], [h, r1], [h, 0.0]];
    (0..3)
        .map(|i| seg2_dist2(t, rho, prof[i], prof[i + 1]))
        .fold(f64::INFINITY, f64::min)
}

#[cfg(test)]
mod tests {
    use super::*;
    use primdecomp::{Capsule, Cylinder, Frustum, Sphere};
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    pub(crate) fn all_kinds() -> Vec<Primitive> {
        let axes = primdecomp_math::axes_from_quat([0.3, -0.2, 0.5, 0.8]);
        vec![
            Primitive::Box(Obb {
                center: [1.0, 2.0, 3.0],
                axes,
                half: [0.5, 1.0, 0.25],
            }),
            Primitive::Sphere(Sphere {
                center: [0.0, 1.0, 0.0],
                radius: 0.7,
            }),
            Primitive::Capsule(Capsule {
                p0: [0.0, 0.0, 0.0],
                p1: [1.0, 1.0, 0.5],
                radius: 0.3,
            }),
            Primitive::Cylinder(Cylinder {
                p0: [0.0, 0.0, 1.0],
                p1: [0.0, 2.0, 1.0],
                radius: 0.4,
            }),
            Primitive::Frustum(Frustum {
                p0: [1.0, 0.0, 0.0],
                p1: [1.0, 0.0, 1.5],
                r0: 0.8,
                r1: 0.2,
            }),
            Primitive::Prism(Prism {
                center: [0.0, 0.0, -1.0],
                axes,
                hx: 1.0,
                hy: 0.5,
                hz_top: 0.1,
                hz_bottom: 0.6,
                shift: 0.0,
            }),
            // Skewed: a scalene section, its top side's midpoint 0.7 along z.
            Primitive::Prism(Prism {
                center: [0.5, 1.0, -1.0],
                axes,
                hx: 0.2,
                hy: 0.5,
                hz_top: 0.1,
                hz_bottom: 0.6,
                shift: 0.7,
            }),
        ]
    }

    /// Closed-form surface areas.
    fn area(p: &Primitive) -> f64 {
        match *p {
            Primitive::Box(b) => {
                let [x, y, z] = b.half;
                8.0 * (x * y + y * z + z * x)
            }
            Primitive::Sphere(s) => 4.0 * PI * s.radius * s.radius,
            Primitive::Capsule(c) => {
                let r = c.radius;
                2.0 * PI * r * norm(sub(c.p1, c.p0)) + 4.0 * PI * r * r
            }
            Primitive::Cylinder(c) => {
                let r = c.radius;
                2.0 * PI * r * norm(sub(c.p1, c.p0)) + 2.0 * PI * r * r
            }
            Primitive::Frustum(f) => {
                let h = norm(sub(f.p1, f.p0));
                PI * (f.r0 + f.r1) * (h * h + (f.r0 - f.r1).powi(2)).sqrt()
                    + PI * (f.r0 * f.r0 + f.r1 * f.r1)
            }
            Primitive::Prism(q) => {
                let side = |dz: f64| ((2.0 * q.hy).powi(2) + dz.powi(2)).sqrt();
                let (l, r) = (
                    side(q.shift - q.hz_top + q.shift + q.hz_bottom),
                    side(q.shift + q.hz_top + q.shift - q.hz_bottom),
                );
                4.0 * q.hy * (q.hz_top + q.hz_bottom)
                    + 2.0 * q.hx * (2.0 * q.hz_top + 2.0 * q.hz_bottom + l + r)
            }
        }
    }

    #[test]
    fn piece_areas_match_closed_forms() {
        for p in all_kinds() {
            let mut v = Vec::new();
            pieces(&p, &mut v);
            let sum: f64 = v.iter().map(Piece::area).sum();
            assert!(
                (sum - area(&p)).abs() < 1e-12 * area(&p),
                "{p:?}: {sum} vs {}",
                area(&p)
            );
        }
    }

    #[test]
    fn samples_lie_on_the_surface() {
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        for p in all_kinds() {
            let mut v = Vec::new();
            pieces(&p, &mut v);
            for piece in &v {
                for _ in 0..200 {
                    let q = piece.point([rng.gen(), rng.gen(), rng.gen()]);
                    assert!(surface_dist2(&p, q).sqrt() < 1e-12, "{p:?} {piece:?} {q:?}");
                    assert!(p.contains(q, 1e-12), "{p:?} {q:?}");
                }
            }
        }
    }

    #[test]
    fn surface_distance_of_inside_and_outside_points() {
        let s = Primitive::Sphere(Sphere {
            center: [0.0; 3],
            radius: 1.0,
        });
        assert!((surface_dist2(&s, [0.25, 0.0, 0.0]).sqrt() - 0.75).abs() < 1e-15);
        let c = Primitive::Cylinder(Cylinder {
            p0: [0.0; 3],
            p1: [0.0, 0.0, 4.0],
            radius: 1.0,
        });
        // Inside, nearer the side (0.5) than a cap (1.0); outside, beyond the rim.
        assert!((surface_dist2(&c, [0.5, 0.0, 1.0]).sqrt() - 0.5).abs() < 1e-15);
        assert!((surface_dist2(&c, [4.0, 0.0, 8.0]) - 25.0).abs() < 1e-12);
        let f = Primitive::Frustum(Frustum {
            p0: [0.0; 3],
            p1: [0.0, 0.0, 1.0],
            r0: 1.0,
            r1: 0.0,
        });
        // Apex of a 45° cone: the side is at distance sin 45° · 0.5 from (0,0,0.5).
        let d = surface_dist2(&f, [0.0, 0.0, 0.5]).sqrt();
        assert!(
            (d - 0.5 * std::f64::consts::FRAC_1_SQRT_2).abs() < 1e-15,
            "{d}"
        );
    }

    #[test]
    fn side_sampling_is_area_uniform_along_the_axis() {
        // On a cone side from r0 = 1 to r1 = 0, the fraction of area below s is
        // 1 − (1 − s)²: a quarter of it lies in the top half.
        let side = Piece::Side {
            p0: [0.0; 3],
            a: [0.0, 0.0, 1.0],
            u: [1.0, 0.0, 0.0],
            v: [0.0, 1.0, 0.0],
            h: 1.0,
            r0: 1.0,
            r1: 0.0,
        };
        let mut rng = ChaCha8Rng::seed_from_u64(2);
        let n = 200_000;
        let top = (0..n)
            .filter(|_| side.point([rng.gen(), rng.gen(), 0.0])[2] > 0.5)
            .count();
        let frac = top as f64 / n as f64;
        assert!((frac - 0.25).abs() < 0.005, "{frac}");
    }
}
