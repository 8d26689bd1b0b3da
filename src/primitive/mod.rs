//! The six convex primitives of §3.2 (Fig. 3): storage as a closed enum, volume,
//! point containment (used by post-processing, §3.4), and the per-kind fits,
//! dispatched by `match` in [`fit`].

pub mod capsule;
pub mod cylinder;
pub mod fit;
pub mod frame;
pub mod frustum;
pub mod obb;
pub mod prism;
pub mod profile;
pub mod sphere;
pub mod world;

pub use capsule::Capsule;
pub use cylinder::Cylinder;
pub use fit::{fit_best, Cloud, FitScratch};
pub use frustum::Frustum;
pub use obb::Obb;
pub use prism::Prism;
pub use sphere::Sphere;

use crate::math::V3;

/// Primitive kinds, in the order used everywhere (weights, counts, JSON).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Kind {
    Box = 0,
    Sphere = 1,
    Capsule = 2,
    Cylinder = 3,
    Frustum = 4,
    Prism = 5,
}

impl Kind {
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
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Primitive {
    Box(Obb),
    Sphere(Sphere),
    Capsule(Capsule),
    Cylinder(Cylinder),
    Frustum(Frustum),
    Prism(Prism),
}

impl Primitive {
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
    /// The same primitive moved by `d` (exactly as stored; to move a fitted primitive
    /// to world coordinates use [`Primitive::to_world`], which keeps it enclosing).
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

pub(crate) fn aabb_union(a: (V3, V3), b: (V3, V3)) -> (V3, V3) {
    let mut lo = a.0;
    let mut hi = a.1;
    for k in 0..3 {
        lo[k] = lo[k].min(b.0[k]);
        hi[k] = hi[k].max(b.1[k]);
    }
    (lo, hi)
}
