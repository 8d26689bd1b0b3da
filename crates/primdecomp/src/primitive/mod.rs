//! The six convex primitives of §3.2 (Fig. 3): storage as a closed enum, volume,
//! point containment (used by post-processing, §3.4), and the per-kind fits,
//! dispatched by `match` in [`fit`].

pub(crate) mod capsule;
pub(crate) mod cylinder;
pub(crate) mod fit;
pub(crate) mod frame;
pub(crate) mod frustum;
pub(crate) mod obb;
pub(crate) mod prism;
pub(crate) mod profile;
pub(crate) mod sphere;
pub(crate) mod world;

pub use capsule::Capsule;
pub use cylinder::Cylinder;
pub(crate) use fit::{fit_best, Cloud, FitScratch};
pub use frustum::Frustum;
pub use obb::Obb;
pub use prism::Prism;
pub use sphere::Sphere;

use crate::math::V3;

/// Primitive kinds, in the order used everywhere (weights, counts, JSON).
///
/// ```
/// use primdecomp::Kind;
///
/// assert_eq!(Kind::ALL.len(), 6);
/// assert_eq!(Kind::Box.name(), "box");
/// assert_eq!(Kind::Prism.bytes(), 44);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Kind {
    /// Oriented box ([`Obb`]).
    Box = 0,
    /// Ball ([`Sphere`]).
    Sphere = 1,
    /// Segment swept by a ball ([`Capsule`]).
    Capsule = 2,
    /// Capped cylinder ([`Cylinder`]).
    Cylinder = 3,
    /// Truncated cone ([`Frustum`]).
    Frustum = 4,
    /// Trapezoidal prism ([`Prism`]): isosceles, or skewed where the cut's nearest
    /// fit makes it so.
    Prism = 5,
}

impl Kind {
    /// Every kind, in index order.
    pub const ALL: [Kind; 6] = [
        Kind::Box,
        Kind::Sphere,
        Kind::Capsule,
        Kind::Cylinder,
        Kind::Frustum,
        Kind::Prism,
    ];
    /// Name used in JSON, OBJ object names and the CLI.
    pub fn name(self) -> &'static str {
        match self {
            Kind::Box => "box",
            Kind::Sphere => "sphere",
            Kind::Capsule => "capsule",
            Kind::Cylinder => "cylinder",
            Kind::Frustum => "frustum",
            Kind::Prism => "prism",
        }
    }
    /// The kind [`Kind::name`] names.
    pub fn from_name(s: &str) -> Option<Kind> {
        Kind::ALL.into_iter().find(|k| k.name() == s)
    }
    /// Minimum floats to store one (paper Table 2).
    pub fn floats(self) -> usize {
        match self {
            Kind::Box => 10,
            Kind::Sphere => 4,
            Kind::Capsule => 7,
            Kind::Cylinder => 7,
            Kind::Frustum => 8,
            Kind::Prism => 11,
        }
    }
    /// Bytes at 4 bytes per float (paper Table 2).
    pub fn bytes(self) -> usize {
        4 * self.floats()
    }
}

/// One fitted primitive. Coordinates are in whatever frame the points were in
/// (re-centred inside the engine, world in a [`crate::Decomposition`]).
///
/// ```
/// use primdecomp::{Kind, Primitive, Sphere};
///
/// let p = Primitive::Sphere(Sphere { center: [0.0; 3], radius: 1.0 });
/// assert_eq!(p.kind(), Kind::Sphere);
/// assert_eq!(p.bytes(), 16); // four 4-byte numbers, as the paper's Table 2 counts
/// assert!(p.contains([0.0, 0.0, 1.0], 1e-12));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Primitive {
    /// An oriented box.
    Box(Obb),
    /// A ball.
    Sphere(Sphere),
    /// A capsule.
    Capsule(Capsule),
    /// A capped cylinder.
    Cylinder(Cylinder),
    /// A truncated cone.
    Frustum(Frustum),
    /// A trapezoidal prism.
    Prism(Prism),
}

impl Primitive {
    /// Its kind.
    pub fn kind(&self) -> Kind {
        match self {
            Primitive::Box(_) => Kind::Box,
            Primitive::Sphere(_) => Kind::Sphere,
            Primitive::Capsule(_) => Kind::Capsule,
            Primitive::Cylinder(_) => Kind::Cylinder,
            Primitive::Frustum(_) => Kind::Frustum,
            Primitive::Prism(_) => Kind::Prism,
        }
    }
    /// Bytes to store it at 4 bytes per float: its kind's ([`Kind::bytes`]), and 4
    /// more for a skewed prism's shift ([`Prism::is_skewed`]).
    ///
    /// ```
    /// use primdecomp::{Kind, Primitive, Sphere};
    /// let ball = Primitive::Sphere(Sphere { center: [0.0; 3], radius: 1.0 });
    /// assert_eq!(ball.bytes(), Kind::Sphere.bytes());
    /// ```
    pub fn bytes(&self) -> usize {
        let skewed = matches!(self, Primitive::Prism(p) if p.is_skewed());
        self.kind().bytes() + if skewed { 4 } else { 0 }
    }
    /// Its volume (§3.2's formulas).
    pub fn volume(&self) -> f64 {
        match self {
            Primitive::Box(p) => p.volume(),
            Primitive::Sphere(p) => p.volume(),
            Primitive::Capsule(p) => p.volume(),
            Primitive::Cylinder(p) => p.volume(),
            Primitive::Frustum(p) => p.volume(),
            Primitive::Prism(p) => p.volume(),
        }
    }
    /// Support function `h(n)`: the largest `n·x` over the primitive, `n` a unit
    /// vector (how far it reaches in direction `n`).
    pub fn support(&self, n: V3) -> f64 {
        match self {
            Primitive::Box(s) => s.support(n),
            Primitive::Sphere(s) => s.support(n),
            Primitive::Capsule(s) => s.support(n),
            Primitive::Cylinder(s) => s.support(n),
            Primitive::Frustum(s) => s.support(n),
            Primitive::Prism(s) => s.support(n),
        }
    }
    /// The unit axis along which this primitive is a plate at most `2·floor` thick with
    /// the same cross-section all through (a box's thinnest axis, a prism's extrusion
    /// axis, a cylinder's axis), for `merge::Fitter`'s flush plates
    /// (docs/decisions/0026); `None` for any other shape.
    pub(crate) fn plate_axis(&self, floor: f64) -> Option<V3> {
        let thin = |h: f64| h <= floor * (1.0 + 1e-9);
        match self {
            Primitive::Box(s) => {
                let k = (0..3).min_by(|&a, &b| s.half[a].total_cmp(&s.half[b]))?;
                thin(s.half[k]).then_some(s.axes[k])
            }
            Primitive::Prism(s) => thin(s.hx).then_some(s.axes[0]),
            Primitive::Cylinder(s) => {
                let d = crate::math::sub(s.p1, s.p0);
                let len = crate::math::norm(d);
                (len > 0.0 && thin(0.5 * len)).then(|| d.map(|x| x / len))
            }
            Primitive::Sphere(_) | Primitive::Capsule(_) | Primitive::Frustum(_) => None,
        }
    }
    /// Whether `p` lies inside, allowing `tol` of slack (absolute distance units).
    pub fn contains(&self, p: V3, tol: f64) -> bool {
        match self {
            Primitive::Box(s) => s.contains(p, tol),
            Primitive::Sphere(s) => s.contains(p, tol),
            Primitive::Capsule(s) => s.contains(p, tol),
            Primitive::Cylinder(s) => s.contains(p, tol),
            Primitive::Frustum(s) => s.contains(p, tol),
            Primitive::Prism(s) => s.contains(p, tol),
        }
    }
    /// The same primitive moved by `d`, each stored point plus `d` (rounded once: a
    /// primitive that must keep enclosing points moved with it exactly is moved by the
    /// library itself, which pads for round-off).
    pub fn translated(&self, d: V3) -> Primitive {
        use crate::math::add;
        match *self {
            Primitive::Box(mut s) => {
                s.center = add(s.center, d);
                Primitive::Box(s)
            }
            Primitive::Sphere(mut s) => {
                s.center = add(s.center, d);
                Primitive::Sphere(s)
            }
            Primitive::Capsule(mut s) => {
                (s.p0, s.p1) = (add(s.p0, d), add(s.p1, d));
                Primitive::Capsule(s)
            }
            Primitive::Cylinder(mut s) => {
                (s.p0, s.p1) = (add(s.p0, d), add(s.p1, d));
                Primitive::Cylinder(s)
            }
            Primitive::Frustum(mut s) => {
                (s.p0, s.p1) = (add(s.p0, d), add(s.p1, d));
                Primitive::Frustum(s)
            }
            Primitive::Prism(mut s) => {
                s.center = add(s.center, d);
                Primitive::Prism(s)
            }
        }
    }
    /// Axis-aligned bounds (min, max), conservative.
    pub fn aabb(&self) -> (V3, V3) {
        match self {
            Primitive::Box(s) => s.aabb(),
            Primitive::Sphere(s) => s.aabb(),
            Primitive::Capsule(s) => s.aabb(),
            Primitive::Cylinder(s) => s.aabb(),
            Primitive::Frustum(s) => s.aabb(),
            Primitive::Prism(s) => s.aabb(),
        }
    }
}

/// Conservative AABB of a disc of radius `r` centred at `c` with unit normal `a`.
pub(crate) fn disc_aabb(c: V3, a: V3, r: f64) -> (V3, V3) {
    let mut lo = c;
    let mut hi = c;
    for k in 0..3 {
        let e = r * (1.0 - a[k] * a[k]).max(0.0).sqrt();
        lo[k] -= e;
        hi[k] += e;
    }
    (lo, hi)
}

/// Support function of the convex hull of two parallel discs: centres `p0` and `p1` on
/// their common axis, radii `r0` and `r1` (a cylinder or frustum); `n` a unit vector.
/// A disc of radius r about axis a reaches r·√(1 − (a·n)²) past its centre along n.
pub(crate) fn disc_support(p0: V3, p1: V3, r0: f64, r1: f64, n: V3) -> f64 {
    let a = crate::math::normalize(crate::math::sub(p1, p0)).unwrap_or([0.0, 0.0, 1.0]);
    let s = (1.0 - crate::math::dot(a, n).powi(2)).max(0.0).sqrt();
    (crate::math::dot(n, p0) + r0 * s).max(crate::math::dot(n, p1) + r1 * s)
}

pub(crate) fn aabb_union(a: (V3, V3), b: (V3, V3)) -> (V3, V3) {
    let mut lo = a.0;
    let mut hi = a.1;
    for k in 0..3 {
        lo[k] = lo[k].min(b.0[k]);
        hi[k] = hi[k].max(b.1[k]);
    }
    (lo, hi)
}

#[cfg(test)]
mod support_tests {
    use super::*;
    use crate::math::{cross, dot, normalize};

    /// Deterministic uniform numbers in [0, 1) (xorshift64*).
    struct Rng(u64);
    impl Rng {
        fn next(&mut self) -> f64 {
            self.0 ^= self.0 >> 12;
            self.0 ^= self.0 << 25;
            self.0 ^= self.0 >> 27;
            (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
        }
        fn unit(&mut self) -> V3 {
            loop {
                let v = [
                    2.0 * self.next() - 1.0,
                    2.0 * self.next() - 1.0,
                    2.0 * self.next() - 1.0,
                ];
                if let Some(u) = normalize(v).filter(|_| dot(v, v) <= 1.0) {
                    return u;
                }
            }
        }
    }

    fn frame(r: &mut Rng) -> [V3; 3] {
        let a = r.unit();
        let b = normalize(cross(a, r.unit())).unwrap();
        [a, b, cross(a, b)]
    }

    fn samples(r: &mut Rng) -> Vec<Primitive> {
        let f = frame(r);
        let (p0, p1) = ([0.1, -0.2, 0.3], [0.9, 0.4, -0.5]);
        vec![
            Primitive::Box(Obb {
                center: p0,
                axes: f,
                half: [0.7, 0.2, 0.4],
            }),
            Primitive::Sphere(Sphere {
                center: p1,
                radius: 0.6,
            }),
            Primitive::Capsule(Capsule {
                p0,
                p1,
                radius: 0.3,
            }),
            Primitive::Cylinder(Cylinder {
                p0,
                p1,
                radius: 0.5,
            }),
            Primitive::Frustum(Frustum {
                p0,
                p1,
                r0: 0.8,
                r1: 0.1,
            }),
            Primitive::Prism(Prism {
                center: p0,
                axes: f,
                hx: 0.5,
                hy: 0.3,
                hz_top: 0.1,
                hz_bottom: 0.9,
                shift: 0.0,
            }),
        ]
    }

    /// The support function bounds every contained point and is reached by them: the
    /// largest `n·x` over 200,000 points drawn in the AABB and kept by `contains` lies
    /// within 8% of the primitive's size below it (sharp edges are rarely sampled), never above.
    #[test]
    fn support_bounds_and_meets_contained_points() {
        let mut r = Rng(0x9E37_79B9_7F4A_7C15);
        for p in samples(&mut r) {
            let (lo, hi) = p.aabb();
            let size = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
            let pts: Vec<V3> = (0..200_000)
                .map(|_| std::array::from_fn(|k| lo[k] + (hi[k] - lo[k]) * r.next()))
                .filter(|&x| p.contains(x, 0.0))
                .collect();
            assert!(pts.len() > 1000, "{p:?}: too few samples inside");
            for _ in 0..50 {
                let n = r.unit();
                let h = p.support(n);
                let best = pts
                    .iter()
                    .map(|&x| dot(n, x))
                    .fold(f64::NEG_INFINITY, f64::max);
                assert!(
                    best <= h + 1e-12,
                    "{p:?}: a point beyond the support along {n:?}"
                );
                assert!(
                    best >= h - 0.08 * size,
                    "{p:?}: support {h} far beyond the points ({best})"
                );
            }
        }
    }
}
