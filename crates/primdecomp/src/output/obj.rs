//! Wavefront OBJ output of a level's primitives: one named object per primitive
//! (`o box_0`, `o capsule_3`, …), each a closed, outward-wound, **conservative**
//! polyhedron, i.e. one that contains the exact primitive. Round shapes use
//! circumscribed polygons (vertex radius r / cos(π/k)) and, for spheres and capsule
//! caps, a UV sphere scaled by the exact factor that puts every face plane outside
//! the sphere.

use crate::math::{add, circle_frame, cross, dot, madd, normalize, scale, sub, V3};
use crate::output::result::Level;
use crate::primitive::Primitive;
use std::collections::HashMap;
use std::f64::consts::{PI, TAU};
use std::fmt::Write;

/// Segments around each circle when the caller has no preference.
pub(crate) const DEFAULT_DETAIL: usize = 16;

/// The most segments around a circle [`Primitive::tessellate`] makes (a larger `detail` is
/// taken as this): a sphere at 1024 segments already has about half a million
/// vertices, and a detail of millions would ask for more memory than any machine has.
pub(crate) const MAX_DETAIL: usize = 1024;

/// A closed convex polyhedron: vertices and polygons (0-based indices) wound
/// counter-clockwise seen from outside.
///
/// ```
/// use primdecomp::{Obb, Primitive};
///
/// let cube = Obb { center: [0.0; 3], axes: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]], half: [1.0; 3] };
/// let t = Primitive::Box(cube).tessellate(16);
/// assert_eq!((t.vertices.len(), t.faces.len()), (8, 6));
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Tess {
    /// Vertex positions.
    pub vertices: Vec<V3>,
    /// Convex polygons, each a list of indices into `vertices`.
    pub faces: Vec<Vec<u32>>,
}

impl Tess {
    /// Segments around each circle when the caller has no preference: 16.
    ///
    /// ```
    /// assert_eq!(primdecomp::Tess::DEFAULT_DETAIL, 16);
    /// ```
    pub const DEFAULT_DETAIL: usize = DEFAULT_DETAIL;

    /// The most segments around a circle [`Primitive::tessellate`] makes (a larger
    /// `detail` is taken as this): 1024. A sphere at 1024 segments already has about
    /// half a million vertices, and a detail of millions would ask for more memory than
    /// any machine has.
    ///
    /// ```
    /// use primdecomp::{Primitive, Sphere, Tess};
    ///
    /// let ball = Primitive::Sphere(Sphere { center: [0.0; 3], radius: 1.0 });
    /// assert_eq!(ball.tessellate(usize::MAX), ball.tessellate(Tess::MAX_DETAIL));
    /// ```
    pub const MAX_DETAIL: usize = MAX_DETAIL;
}

/// Quads of a hexahedron whose corner `i` sits at local signs (bit 0 → x, bit 1 → y,
/// bit 2 → z; bit set = +), wound outward for a right-handed frame.
const BOX_FACES: [[usize; 4]; 6] = [
    [0, 4, 6, 2], // −x
    [1, 3, 7, 5], // +x
    [0, 1, 5, 4], // −y
    [2, 6, 7, 3], // +y
    [0, 2, 3, 1], // −z
    [4, 5, 7, 6], // +z
];

impl Tess {
    fn push(&mut self, p: V3) -> u32 {
        self.vertices.push(p);
        (self.vertices.len() - 1) as u32
    }

    /// Welds bit-identical vertices and drops the degenerate polygons that zero
    /// sizes produce (a frustum apex, a flat prism side, a zero-length capsule).
    fn cleaned(self) -> Tess {
        let mut out = Tess::default();
        let mut seen: HashMap<[u64; 3], u32> = HashMap::new();
        let remap: Vec<u32> = self
            .vertices
            .iter()
            .map(|&p| {
                let p = p.map(|x| x + 0.0); // −0 → +0
                *seen
                    .entry(p.map(f64::to_bits))
                    .or_insert_with(|| out.push(p))
            })
            .collect();
        for f in &self.faces {
            let mut g: Vec<u32> = Vec::with_capacity(f.len());
            for &i in f {
                let i = remap[i as usize];
                if g.last() != Some(&i) {
                    g.push(i);
                }
            }
            while g.len() > 1 && g.first() == g.last() {
                g.pop();
            }
            if g.len() >= 3 {
                out.faces.push(g);
            }
        }
        out
    }
}

/// Unit axis from `p0` to `p1`, or +z when they coincide.
fn axis(p0: V3, p1: V3) -> V3 {
    normalize(sub(p1, p0)).unwrap_or([0.0, 0.0, 1.0])
}

/// A closed surface of `k`-gon rings `(centre, vertex radius)` stacked along unit
/// `a`, first ring lowest: end caps, and quads between consecutive rings. Rings of
/// radius 0 become poles (the cleaning turns their quads into triangles).
fn stack(rings: &[(V3, f64)], a: V3, k: usize) -> Tess {
    let (u, v) = circle_frame(a);
    let dirs: Vec<V3> = (0..k)
        .map(|j| {
            let t = TAU * j as f64 / k as f64;
            add(scale(u, t.cos()), scale(v, t.sin()))
        })
        .collect();
    let mut t = Tess::default();
    let ids: Vec<Vec<u32>> = rings
        .iter()
        .map(|&(c, r)| dirs.iter().map(|&d| t.push(madd(c, d, r))).collect())
        .collect();
    t.faces.push(ids[0].iter().rev().copied().collect());
    for w in ids.windows(2) {
        for j in 0..k {
            let j1 = (j + 1) % k;
            t.faces.push(vec![w[0][j], w[0][j1], w[1][j1], w[1][j]]);
        }
    }
    t.faces.push(ids[ids.len() - 1].clone());
    t.cleaned()
}

/// `(sin φ, cos φ)` of the `2h + 1` ring polar angles φ = π·i/(2h), exact at the
/// poles and the equator.
fn polar(h: usize) -> Vec<(f64, f64)> {
    (0..=2 * h)
        .map(|i| match i {
            0 => (0.0, 1.0),
            _ if i == h => (1.0, 0.0),
            _ if i == 2 * h => (0.0, -1.0),
            _ => {
                let phi = PI * i as f64 / (2 * h) as f64;
                (phi.sin(), phi.cos())
            }
        })
        .collect()
}

/// Factor that makes a unit UV sphere with `k` segments and the rings of
/// [`polar`]`(h)` circumscribe the unit sphere: 1 / (smallest face-plane distance).
/// In the meridian through a face's centre the face is the line through its edge
/// midpoints (c·sin φ, cos φ), c = cos(π/k); its distance to the origin is exact.
fn sphere_scale(h: usize, k: usize) -> f64 {
    let c = (PI / k as f64).cos();
    let rings = polar(h);
    let min_d = rings
        .windows(2)
        .map(|w| {
            let (ax, ay) = (c * w[0].0, w[0].1);
            let (bx, by) = (c * w[1].0, w[1].1);
            (ax * by - ay * bx).abs() / (ax - bx).hypot(ay - by)
        })
        .fold(f64::INFINITY, f64::min);
    1.0 / min_d
}

/// Rings of a conservative capsule (`p0 == p1` gives a sphere): the lower
/// hemisphere about `p0`, then the upper one about `p1`, sharing the equator ring.
/// A segment shorter than [`SPHERE_REL`] of the radius is a sphere about its middle,
/// grown by half its length: two equator rings a rounding error apart would leave a
/// band of slivers that mesh tools read as an open, non-convex surface.
fn capsule_rings(p0: V3, p1: V3, r: f64, h: usize, k: usize) -> (Vec<(V3, f64)>, V3) {
    let d = sub(p1, p0);
    let len = dot(d, d).sqrt();
    let (p0, p1, r) = match len > 0.0 && len <= SPHERE_REL * r {
        true => {
            let c = madd(p0, d, 0.5);
            (c, c, r + 0.5 * len)
        }
        false => (p0, p1, r),
    };
    let a = axis(p0, p1);
    let s = r * sphere_scale(h, k);
    let rings = polar(h);
    let lower = rings[h..]
        .iter()
        .rev()
        .map(|&(sn, cs)| (madd(p0, a, s * cs), s * sn));
    let upper = rings[..=h]
        .iter()
        .rev()
        .map(|&(sn, cs)| (madd(p1, a, s * cs), s * sn));
    (lower.chain(upper).collect(), a)
}

/// Segments shorter than this fraction of their capsule's radius are tessellated as
/// a sphere ([`capsule_rings`]).
const SPHERE_REL: f64 = 1e-9;

/// Box-like hexahedron from corners in [`BOX_FACES`] order; wound outward when
/// `right_handed`, reversed otherwise.
fn hexahedron(corners: [V3; 8], right_handed: bool) -> Tess {
    let faces = BOX_FACES
        .iter()
        .map(|f| {
            let mut g: Vec<u32> = f.iter().map(|&i| i as u32).collect();
            if !right_handed {
                g.reverse();
            }
            g
        })
        .collect();
    Tess {
        vertices: corners.to_vec(),
        faces,
    }
    .cleaned()
}

fn right_handed(axes: &[V3; 3]) -> bool {
    dot(cross(axes[0], axes[1]), axes[2]) >= 0.0
}

impl Primitive {
    /// A conservative closed tessellation with `detail` segments around circles (at
    /// least 3, at most [`Tess::MAX_DETAIL`]; latitude bands per hemisphere:
    /// `max(1, detail / 4)`): the polyhedron contains the primitive, so the enclosure
    /// guarantee holds for the mesh too.
    ///
    /// ```
    /// use primdecomp::{Primitive, Sphere, Tess};
    ///
    /// let ball = Primitive::Sphere(Sphere { center: [0.0, 0.0, 0.0], radius: 1.0 });
    /// let mesh = ball.tessellate(Tess::DEFAULT_DETAIL);
    /// // Every face's plane lies outside the sphere: the tessellation encloses it.
    /// assert!(mesh.vertices.iter().all(|v| v.iter().map(|x| x * x).sum::<f64>() >= 1.0 - 1e-12));
    /// assert!(mesh.faces.len() > 8);
    /// ```
    pub fn tessellate(&self, detail: usize) -> Tess {
        tessellate(self, detail)
    }
}

/// [`Primitive::tessellate`].
pub(crate) fn tessellate(p: &Primitive, detail: usize) -> Tess {
    let k = detail.clamp(3, MAX_DETAIL);
    let h = (k / 4).max(1);
    let circ = 1.0 / (PI / k as f64).cos();
    match *p {
        Primitive::Box(b) => {
            let corners = std::array::from_fn(|i| {
                (0..3).fold(b.center, |c, d| {
                    let sign = if i >> d & 1 == 1 { 1.0 } else { -1.0 };
                    madd(c, b.axes[d], sign * b.half[d])
                })
            });
            hexahedron(corners, right_handed(&b.axes))
        }
        Primitive::Prism(q) => {
            // `Prism::corners` puts x in bit 2 and z in bit 0: swap them.
            let c = q.corners();
            let corners = std::array::from_fn(|i| c[(i & 1) << 2 | (i & 2) | (i >> 2 & 1)]);
            hexahedron(corners, right_handed(&q.axes))
        }
        Primitive::Sphere(s) => {
            let (rings, a) = capsule_rings(s.center, s.center, s.radius, h, k);
            stack(&rings, a, k)
        }
        Primitive::Capsule(c) => {
            let (rings, a) = capsule_rings(c.p0, c.p1, c.radius, h, k);
            stack(&rings, a, k)
        }
        Primitive::Cylinder(c) => stack(
            &[(c.p0, c.radius * circ), (c.p1, c.radius * circ)],
            axis(c.p0, c.p1),
            k,
        ),
        Primitive::Frustum(f) => stack(
            &[(f.p0, f.r0 * circ), (f.p1, f.r1 * circ)],
            axis(f.p0, f.p1),
            k,
        ),
    }
}

impl Level {
    /// The level as OBJ text, each primitive tessellated conservatively
    /// ([`Primitive::tessellate`] with `detail`): a header comment, then per primitive
    /// `o {kind}_{index}`, its `v` lines and its `f` lines (1-based, global across
    /// objects).
    ///
    /// ```
    /// use primdecomp::{decompose, Goal, Mesh, Params, Tess};
    ///
    /// let corners = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    /// let tetrahedron = Mesh::from_triangles(&corners, &[[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])?;
    /// let result = decompose(&tetrahedron, &Params { goal: Goal::counts([1]), ..Params::default() })?;
    /// let obj = result.levels[0].to_obj(Tess::DEFAULT_DETAIL);
    /// assert!(obj.starts_with("# primdecomp: 1 primitives"));
    /// assert_eq!(obj.lines().filter(|l| l.starts_with("o ")).count(), 1);
    /// # Ok::<(), primdecomp::Error>(())
    /// ```
    pub fn to_obj(&self, detail: usize) -> String {
        to_obj(self, detail)
    }
}

/// [`Level::to_obj`].
pub(crate) fn to_obj(level: &Level, detail: usize) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "# primdecomp: {} primitives (target {}), conservative tessellation, {} segments",
        level.primitives.len(),
        level.target,
        detail.max(3)
    );
    let mut base = 1usize;
    for (i, p) in level.primitives.iter().enumerate() {
        let t = tessellate(p, detail);
        let _ = writeln!(out, "o {}_{}", p.kind().name(), i);
        for v in &t.vertices {
            debug_assert!(
                v.iter().all(|x| x.is_finite()),
                "non-finite vertex in {p:?}"
            );
            let _ = writeln!(out, "v {} {} {}", v[0] + 0.0, v[1] + 0.0, v[2] + 0.0);
        }
        for f in &t.faces {
            out.push('f');
            for &ix in f {
                let _ = write!(out, " {}", base + ix as usize);
            }
            out.push('\n');
        }
        base += t.vertices.len();
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::quat::axes_from_quat;
    use crate::math::{norm, norm2};
    use crate::primitive::{Capsule, Cylinder, Frustum, Kind, Obb, Prism, Sphere};
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// One parsed `o` object: name and polygons as world positions.
    struct Object {
        name: String,
        faces: Vec<Vec<V3>>,
        edges: Vec<(usize, usize)>,
    }

    /// Parses our own OBJ output, checking index ranges on the way.
    fn parse(text: &str) -> Vec<Object> {
        let mut verts: Vec<V3> = Vec::new();
        let mut objs: Vec<Object> = Vec::new();
        for line in text.lines() {
            let mut it = line.split_whitespace();
            match it.next() {
                Some("o") => objs.push(Object {
                    name: it.next().unwrap().to_string(),
                    faces: vec![],
                    edges: vec![],
                }),
                Some("v") => {
                    verts.push(std::array::from_fn(|_| it.next().unwrap().parse().unwrap()))
                }
                Some("f") => {
                    let idx: Vec<usize> = it.map(|s| s.parse::<usize>().unwrap()).collect();
                    assert!(idx.iter().all(|&i| i >= 1 && i <= verts.len()), "{line}");
                    let o = objs.last_mut().unwrap();
                    for j in 0..idx.len() {
                        o.edges.push((idx[j], idx[(j + 1) % idx.len()]));
                    }
                    o.faces.push(idx.iter().map(|&i| verts[i - 1]).collect());
                }
                _ => assert!(line.starts_with('#'), "{line}"),
            }
        }
        objs
    }

    /// Newell normal (unnormalized) of a polygon.
    fn newell(f: &[V3]) -> V3 {
        let mut n = [0.0; 3];
        for (i, a) in f.iter().enumerate() {
            let b = f[(i + 1) % f.len()];
            n = add(n, cross(*a, b));
        }
        n
    }

    /// Checks closedness, planarity, convexity and outward winding of one object
    /// and that every point of `surface` lies inside it; returns its volume.
    fn check_object(o: &Object, surface: &[V3], tol: f64) -> f64 {
        let mut directed = o.edges.clone();
        directed.sort_unstable();
        assert!(
            directed.windows(2).all(|w| w[0] != w[1]),
            "{}: repeated edge",
            o.name
        );
        for &(a, b) in &o.edges {
            assert!(
                directed.binary_search(&(b, a)).is_ok(),
                "{}: open edge",
                o.name
            );
        }
        let all: Vec<V3> = o.faces.iter().flatten().copied().collect();
        let mut volume = 0.0;
        for f in &o.faces {
            let n = newell(f);
            volume += dot(f[0], n) / 6.0;
            let Some(n) = normalize(n) else { continue };
            for v in all.iter().chain(surface) {
                let d = dot(n, sub(*v, f[0]));
                assert!(d <= tol, "{}: point {v:?} outside a face by {d}", o.name);
            }
            for v in f {
                assert!(
                    dot(n, sub(*v, f[0])).abs() <= tol,
                    "{}: non-planar face",
                    o.name
                );
            }
        }
        volume
    }

    fn unit(rng: &mut ChaCha8Rng) -> V3 {
        loop {
            let v: V3 = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
            if (1e-3..=1.0).contains(&norm(v)) {
                return normalize(v).unwrap();
            }
        }
    }

    fn rot(rng: &mut ChaCha8Rng) -> [V3; 3] {
        axes_from_quat(std::array::from_fn(|_| rng.gen_range(-1.0..1.0)))
    }

    /// Point on a circle of radius `r` about `c` in the plane normal to `a`.
    fn on_circle(c: V3, a: V3, r: f64, t: f64) -> V3 {
        let (u, v) = circle_frame(a);
        madd(madd(c, u, r * t.cos()), v, r * t.sin())
    }

    /// A random instance of `kind` (sometimes with degenerate sizes) and points on
    /// its exact surface.
    fn instance(kind: Kind, rng: &mut ChaCha8Rng) -> (Primitive, Vec<V3>) {
        let c: V3 = std::array::from_fn(|_| rng.gen_range(-100.0..100.0));
        let mut size = || {
            if rng.gen_bool(0.1) {
                0.0
            } else {
                rng.gen_range(0.01..5.0)
            }
        };
        let (s1, s2, s3, s4) = (size(), size(), size(), size());
        let p1 = madd(c, unit(rng), s1);
        let mut pts = Vec::new();
        let prim = match kind {
            Kind::Box => Primitive::Box(Obb {
                center: c,
                axes: rot(rng),
                half: [s2, s3, s4],
            }),
            Kind::Sphere => Primitive::Sphere(Sphere {
                center: c,
                radius: s2,
            }),
            Kind::Capsule => Primitive::Capsule(Capsule {
                p0: c,
                p1,
                radius: s2,
            }),
            Kind::Cylinder => Primitive::Cylinder(Cylinder {
                p0: c,
                p1,
                radius: s2,
            }),
            Kind::Frustum => Primitive::Frustum(Frustum {
                p0: c,
                p1,
                r0: s2,
                r1: s3,
            }),
            Kind::Prism => {
                let (hx, hy) = (s1.max(0.01), s4.max(0.01));
                Primitive::Prism(Prism {
                    center: c,
                    axes: rot(rng),
                    hx,
                    hy,
                    hz_top: s2,
                    hz_bottom: s3,
                    shift: 0.5 * (s3 - s2),
                })
            }
        };
        for _ in 0..300 {
            pts.push(surface_point(&prim, rng));
        }
        (prim, pts)
    }

    fn surface_point(prim: &Primitive, rng: &mut ChaCha8Rng) -> V3 {
        let t = rng.gen_range(0.0..TAU);
        let f: f64 = rng.gen_range(0.0..1.0);
        let side = rng.gen_bool(0.5);
        match *prim {
            Primitive::Box(b) => {
                let (k, s) = (rng.gen_range(0..3), if side { 1.0 } else { -1.0 });
                (0..3).fold(b.center, |p, d| {
                    let x = if d == k {
                        s * b.half[d]
                    } else {
                        rng.gen_range(-1.0..=1.0) * b.half[d]
                    };
                    madd(p, b.axes[d], x)
                })
            }
            Primitive::Sphere(s) => madd(s.center, unit(rng), s.radius),
            Primitive::Capsule(c) => {
                let a = axis(c.p0, c.p1);
                if rng.gen_bool(0.4) {
                    on_circle(add(c.p0, scale(sub(c.p1, c.p0), f)), a, c.radius, t)
                } else {
                    let d = unit(rng);
                    madd(if dot(d, a) < 0.0 { c.p0 } else { c.p1 }, d, c.radius)
                }
            }
            Primitive::Cylinder(c) => frustum_point(c.p0, c.p1, c.radius, c.radius, rng),
            Primitive::Frustum(q) => frustum_point(q.p0, q.p1, q.r0, q.r1, rng),
            Primitive::Prism(q) => {
                let (x, y) = (rng.gen_range(-q.hx..=q.hx), rng.gen_range(-q.hy..=q.hy));
                let (x, y, z) = match rng.gen_range(0..3) {
                    0 => (if side { q.hx } else { -q.hx }, y, f * 2.0 - 1.0),
                    1 => (x, if side { q.hy } else { -q.hy }, f * 2.0 - 1.0),
                    _ => (x, y, if side { 1.0 } else { -1.0 }),
                };
                let (mid, w) = q.section_at(y);
                let z = mid + z * w;
                madd(
                    madd(madd(q.center, q.axes[0], x), q.axes[1], y),
                    q.axes[2],
                    z,
                )
            }
        }
    }

    /// Side (including rims) or cap point of a frustum.
    fn frustum_point(p0: V3, p1: V3, r0: f64, r1: f64, rng: &mut ChaCha8Rng) -> V3 {
        let a = axis(p0, p1);
        let t = rng.gen_range(0.0..TAU);
        let f: f64 = rng.gen_range(0.0..=1.0);
        match rng.gen_range(0..4) {
            0 | 1 => on_circle(add(p0, scale(sub(p1, p0), f)), a, r0 + (r1 - r0) * f, t),
            2 => on_circle(p0, a, r0 * f.sqrt(), t),
            _ => on_circle(p1, a, r1 * f.sqrt(), t),
        }
    }

    #[test]
    fn tessellations_are_closed_convex_and_conservative() {
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        for kind in Kind::ALL {
            for detail in [0, 3, 4, 5, 7, 16, 33] {
                for _ in 0..20 {
                    let (prim, pts) = instance(kind, &mut rng);
                    let level = Level {
                        target: 1,
                        primitives: vec![prim],
                        faces: vec![1],
                        ..Default::default()
                    };
                    let objs = parse(&to_obj(&level, detail));
                    assert_eq!(objs.len(), 1);
                    assert_eq!(objs[0].name, format!("{}_0", kind.name()));
                    let (lo, hi) = prim.aabb();
                    let tol = 1e-9 * (norm(lo).max(norm(hi)) + norm(sub(hi, lo)));
                    let vol = check_object(&objs[0], &pts, tol);
                    let exact = prim.volume();
                    let slack = tol * norm2(sub(hi, lo));
                    assert!(
                        vol + slack >= exact * (1.0 - 1e-9),
                        "{prim:?}: {vol} < {exact}"
                    );
                    if detail == 16 && exact > 0.0 {
                        assert!(vol <= exact * 1.35, "{prim:?}: {vol} loose vs {exact}");
                    }
                }
            }
        }
    }

    #[test]
    fn objects_are_numbered_and_indexed_globally() {
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        let primitives: Vec<Primitive> =
            Kind::ALL.iter().map(|&k| instance(k, &mut rng).0).collect();
        let level = Level {
            target: 6,
            faces: vec![1; 6],
            primitives,
            ..Default::default()
        };
        let text = to_obj(&level, DEFAULT_DETAIL);
        let names: Vec<String> = parse(&text).into_iter().map(|o| o.name).collect();
        let want: Vec<String> = Kind::ALL
            .iter()
            .enumerate()
            .map(|(i, k)| format!("{}_{i}", k.name()))
            .collect();
        assert_eq!(names, want);
        assert_eq!(text, to_obj(&level, DEFAULT_DETAIL));
        assert!(!text.contains("NaN") && !text.contains("inf") && !text.contains(" -0 "));
    }

    #[test]
    fn expected_face_counts() {
        let z = [0.0; 3];
        let axes = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let count = |p: Primitive| tessellate(&p, 16).faces.len();
        assert_eq!(
            count(Primitive::Box(Obb {
                center: z,
                axes,
                half: [1.0; 3]
            })),
            6
        );
        let cyl = Primitive::Cylinder(Cylinder {
            p0: z,
            p1: [0.0, 0.0, 1.0],
            radius: 1.0,
        });
        assert_eq!(count(cyl), 18);
        let cone = Primitive::Frustum(Frustum {
            p0: z,
            p1: [0.0, 0.0, 1.0],
            r0: 1.0,
            r1: 0.0,
        });
        assert_eq!(count(cone), 17);
        assert_eq!(
            count(Primitive::Sphere(Sphere {
                center: z,
                radius: 1.0
            })),
            16 * 8
        );
        let cap = Primitive::Capsule(Capsule {
            p0: z,
            p1: [0.0, 0.0, 1.0],
            radius: 1.0,
        });
        assert_eq!(count(cap), 16 * 9);
        // A segment a rounding error long is a sphere: no band of slivers.
        let dot_cap = Primitive::Capsule(Capsule {
            p0: [2.0, 0.5, 0.5],
            p1: [2.0, 0.5, 0.5 + 1e-15],
            radius: 0.5,
        });
        assert_eq!(count(dot_cap), 16 * 8);
        let wedge = Prism {
            center: z,
            axes,
            hx: 1.0,
            hy: 1.0,
            hz_top: 0.0,
            hz_bottom: 1.0,
            shift: 0.0,
        };
        assert_eq!(count(Primitive::Prism(wedge)), 5);
    }

    #[test]
    fn sphere_scale_is_tight() {
        // A circumscribed octahedron (k = 4, one band per hemisphere) needs √3.
        assert!((sphere_scale(1, 4) - 3f64.sqrt()).abs() < 1e-12);
        let s = sphere_scale(4, 16);
        assert!(s > 1.0 && s < 1.04, "{s}");
    }
}
