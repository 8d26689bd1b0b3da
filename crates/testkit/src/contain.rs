//! Independent containment oracle for the enclosure guarantee ("every input
//! face lies inside at least one output primitive").
//!
//! Written only from the JSON description of the primitives, sharing no code
//! with the library's fitting code:
//!
//! * world → local frame by the *conjugate* quaternion sandwich `q* (0,v) q`
//!   (explicit Hamilton products, no rotation matrix);
//! * cylinders and frusta are solids of revolution, tested in the
//!   (axial, radial) half-plane against the linearly interpolated radius;
//! * the prism's trapezoid is tested against the four half-planes bounded by
//!   explicit lines through consecutive corners.
//!
//! Tolerance semantics: `shape_contains(s, p, tol)` is true iff the Euclidean
//! distance from `p` to the (closed, convex) shape is `≤ tol`.  Exact distances
//! are used for the outside case (clamping for boxes, segment distance for
//! capsules, 2-D convex-polygon distance for the revolved and prism profiles).
//!
//! Degenerate input: a cylinder/frustum with `p0 == p1` has no axis; it is
//! treated as the single point `p0` (the intersection of all discs it could
//! be).  Malformed JSON (missing fields, non-finite numbers, negative radii or
//! half-extents, a quaternion whose norm is off by more than 1e−4, an unknown
//! kind) panics with a message naming the problem; near-unit quaternions are
//! normalised.
#![allow(dead_code)]

use rayon::prelude::*;
use serde_json::Value;

type P3 = [f64; 3];
type P2 = [f64; 2];

/// Quaternion `(x, y, z, w)`, scalar last.
type Quat = [f64; 4];

/// A parsed primitive: exact geometry plus a conservative world AABB.
#[derive(Clone, Debug)]
pub struct Shape {
    geom: Geom,
    lo: P3,
    hi: P3,
}

#[derive(Clone, Debug)]
enum Geom {
    Ball {
        c: P3,
        r: f64,
    },
    /// Ball of radius `r` swept along segment `a`–`b` (capsule).
    Sweep {
        a: P3,
        b: P3,
        r: f64,
    },
    /// Solid of revolution about `a + t·axis`, `t ∈ [0, len]`, radius
    /// `r0 + (r1 − r0)·t/len` (cylinder: `r0 == r1`).  `len == 0` → the point `a`.
    Revolved {
        a: P3,
        axis: P3,
        len: f64,
        r0: f64,
        r1: f64,
    },
    /// Oriented box: local `|x_i| ≤ h_i`.
    Cuboid {
        c: P3,
        q: Quat,
        h: P3,
    },
    /// Local `|x| ≤ hx` × trapezoid in (y, z) given by its corners, CCW.
    Prism {
        c: P3,
        q: Quat,
        hx: f64,
        corners: [P2; 4],
    },
}

impl Shape {
    /// Conservative world-space bounding box `(lo, hi)`.
    pub fn aabb(&self) -> (P3, P3) {
        (self.lo, self.hi)
    }
}

// ---------------------------------------------------------------- vectors --

fn sub(a: P3, b: P3) -> P3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn add(a: P3, b: P3) -> P3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
fn mul(a: P3, s: f64) -> P3 {
    [a[0] * s, a[1] * s, a[2] * s]
}
fn dot(a: P3, b: P3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn len3(a: P3) -> f64 {
    dot(a, a).sqrt()
}

/// Hamilton product of `(x, y, z, w)` quaternions.
fn qmul(p: Quat, q: Quat) -> Quat {
    let [px, py, pz, pw] = p;
    let [qx, qy, qz, qw] = q;
    [
        pw * qx + qw * px + (py * qz - pz * qy),
        pw * qy + qw * py + (pz * qx - px * qz),
        pw * qz + qw * pz + (px * qy - py * qx),
        pw * qw - (px * qx + py * qy + pz * qz),
    ]
}

fn conj(q: Quat) -> Quat {
    [-q[0], -q[1], -q[2], q[3]]
}

/// World direction → local: `q* (v, 0) q`.
fn to_local(q: Quat, v: P3) -> P3 {
    let r = qmul(qmul(conj(q), [v[0], v[1], v[2], 0.0]), q);
    [r[0], r[1], r[2]]
}

/// Local direction → world: `q (v, 0) q*`.
fn to_world(q: Quat, v: P3) -> P3 {
    let r = qmul(qmul(q, [v[0], v[1], v[2], 0.0]), conj(q));
    [r[0], r[1], r[2]]
}

// ---------------------------------------------------------------- parsing --

fn field<'a>(v: &'a Value, key: &str) -> &'a Value {
    v.get(key)
        .unwrap_or_else(|| panic!("primitive lacks field {key:?}: {v}"))
}

fn number(v: &Value, key: &str) -> f64 {
    let x = field(v, key)
        .as_f64()
        .unwrap_or_else(|| panic!("field {key:?} is not a number: {v}"));
    assert!(x.is_finite(), "field {key:?} is not finite: {v}");
    x
}

fn non_negative(v: &Value, key: &str) -> f64 {
    let x = number(v, key);
    assert!(x >= 0.0, "field {key:?} is negative: {v}");
    x
}

fn numbers<const N: usize>(v: &Value, key: &str) -> [f64; N] {
    let arr = field(v, key)
        .as_array()
        .filter(|a| a.len() == N)
        .unwrap_or_else(|| panic!("field {key:?} is not an array of {N} numbers: {v}"));
    let mut out = [0.0; N];
    for (o, x) in out.iter_mut().zip(arr) {
        *o = x
            .as_f64()
            .filter(|x| x.is_finite())
            .unwrap_or_else(|| panic!("field {key:?} has a non-finite entry: {v}"));
    }
    out
}

fn rotation(v: &Value) -> Quat {
    let q: Quat = numbers(v, "rotation");
    let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
    assert!(
        (n - 1.0).abs() <= 1e-4,
        "rotation is not a unit quaternion (norm {n}): {v}"
    );
    q.map(|x| x / n)
}

/// Parses one primitive (see the module docs for the accepted forms).
/// Panics with a descriptive message on malformed input.
pub fn parse_primitive(v: &Value) -> Shape {
    let kind = field(v, "kind")
        .as_str()
        .unwrap_or_else(|| panic!("field \"kind\" is not a string: {v}"));
    let geom = match kind {
        "sphere" => Geom::Ball {
            c: numbers(v, "center"),
            r: non_negative(v, "radius"),
        },
        "capsule" => Geom::Sweep {
            a: numbers(v, "p0"),
            b: numbers(v, "p1"),
            r: non_negative(v, "radius"),
        },
        "cylinder" => {
            let r = non_negative(v, "radius");
            revolved(numbers(v, "p0"), numbers(v, "p1"), r, r)
        }
        "frustum" => revolved(
            numbers(v, "p0"),
            numbers(v, "p1"),
            non_negative(v, "radius0"),
            non_negative(v, "radius1"),
        ),
        "box" => Geom::Cuboid {
            c: numbers(v, "center"),
            q: rotation(v),
            h: non_negative_vec(v, "half_extents"),
        },
        "prism" => prism(v),
        other => panic!("unknown primitive kind {other:?}: {v}"),
    };
    let (lo, hi) = bounds(&geom);
    Shape { geom, lo, hi }
}

fn non_negative_vec(v: &Value, key: &str) -> P3 {
    let h: P3 = numbers(v, key);
    assert!(
        h.iter().all(|x| *x >= 0.0),
        "field {key:?} is negative: {v}"
    );
    h
}

fn revolved(a: P3, b: P3, r0: f64, r1: f64) -> Geom {
    let d = sub(b, a);
    let len = len3(d);
    let axis = if len > 0.0 {
        mul(d, 1.0 / len)
    } else {
        [0.0; 3]
    };
    Geom::Revolved {
        a,
        axis,
        len,
        r0,
        r1,
    }
}

fn prism(v: &Value) -> Geom {
    let hy = non_negative(v, "half_y");
    let a = non_negative(v, "half_z_top");
    let b = non_negative(v, "half_z_bottom");
    // A skewed section's top side is centred at z = shift_z, its bottom at −shift_z
    // (absent: the isosceles prism).
    let t = if v.get("shift_z").is_some() {
        number(v, "shift_z")
    } else {
        0.0
    };
    // (y, z) corners, counter-clockwise: bottom-left, top-left, top-right, bottom-right.
    let corners = [[-hy, -t - b], [hy, t - a], [hy, t + a], [-hy, -t + b]];
    Geom::Prism {
        c: numbers(v, "center"),
        q: rotation(v),
        hx: non_negative(v, "half_x"),
        corners,
    }
}

// ------------------------------------------------------------------ AABBs --

/// Conservative AABB, padded by a small relative epsilon against rounding.
fn bounds(g: &Geom) -> (P3, P3) {
    let pts: Vec<(P3, f64)> = match *g {
        Geom::Ball { c, r } => vec![(c, r)],
        Geom::Sweep { a, b, r } => vec![(a, r), (b, r)],
        Geom::Revolved {
            a,
            axis,
            len,
            r0,
            r1,
        } => return disc_bounds(a, add(a, mul(axis, len)), axis, r0, r1, len),
        Geom::Cuboid { c, q, h } => {
            let yz = [[-h[1], -h[2]], [-h[1], h[2]], [h[1], -h[2]], [h[1], h[2]]];
            box_corners(c, q, h[0], &yz)
        }
        Geom::Prism { c, q, hx, corners } => box_corners(c, q, hx, &corners),
    };
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for (p, r) in pts {
        for i in 0..3 {
            lo[i] = lo[i].min(p[i] - r);
            hi[i] = hi[i].max(p[i] + r);
        }
    }
    pad(lo, hi)
}

/// World corners (with zero "radius") of `[-hx, hx] ×` the (y, z) points.
fn box_corners(c: P3, q: Quat, hx: f64, yz: &[P2; 4]) -> Vec<(P3, f64)> {
    let mut out = Vec::with_capacity(8);
    for x in [-hx, hx] {
        for &[y, z] in yz {
            out.push((add(c, to_world(q, [x, y, z])), 0.0));
        }
    }
    out
}

/// AABB of two discs (centres `a`, `b`, unit normal `axis`): a disc of radius
/// `r` spans `r·√(1 − axis_i²)` along world axis `i`.
fn disc_bounds(a: P3, b: P3, axis: P3, r0: f64, r1: f64, len: f64) -> (P3, P3) {
    if len == 0.0 {
        return pad(a, a);
    }
    let mut lo = [0.0; 3];
    let mut hi = [0.0; 3];
    for i in 0..3 {
        let s = (1.0 - axis[i] * axis[i]).max(0.0).sqrt();
        lo[i] = (a[i] - r0 * s).min(b[i] - r1 * s);
        hi[i] = (a[i] + r0 * s).max(b[i] + r1 * s);
    }
    pad(lo, hi)
}

fn pad(lo: P3, hi: P3) -> (P3, P3) {
    let scale = (0..3).fold(0.0f64, |m, i| m.max(lo[i].abs()).max(hi[i].abs()));
    let e = 1e-9 * (scale + 1e-300);
    (lo.map(|x| x - e), hi.map(|x| x + e))
}

// ------------------------------------------------------------ containment --

/// True iff the Euclidean distance from `p` to shape `s` is at most `tol`.
/// Non-finite points are never contained.
pub fn shape_contains(s: &Shape, p: [f64; 3], tol: f64) -> bool {
    if !p.iter().all(|x| x.is_finite()) {
        return false;
    }
    match s.geom {
        Geom::Ball { c, r } => len3(sub(p, c)) <= r + tol,
        Geom::Sweep { a, b, r } => segment_distance(p, a, b) <= r + tol,
        Geom::Revolved {
            a,
            axis,
            len,
            r0,
            r1,
        } => revolved_contains(p, a, axis, len, r0, r1, tol),
        Geom::Cuboid { c, q, h } => {
            let l = to_local(q, sub(p, c));
            let ex = [0, 1, 2].map(|i| (l[i].abs() - h[i]).max(0.0));
            len3(ex) <= tol
        }
        Geom::Prism { c, q, hx, corners } => {
            let l = to_local(q, sub(p, c));
            let dx = (l[0].abs() - hx).max(0.0);
            let dyz = polygon_distance([l[1], l[2]], &corners);
            (dx * dx + dyz * dyz).sqrt() <= tol
        }
    }
}

fn segment_distance(p: P3, a: P3, b: P3) -> f64 {
    let d = sub(b, a);
    let dd = dot(d, d);
    let t = if dd > 0.0 {
        (dot(sub(p, a), d) / dd).clamp(0.0, 1.0)
    } else {
        0.0
    };
    len3(sub(p, add(a, mul(d, t))))
}

fn revolved_contains(p: P3, a: P3, axis: P3, len: f64, r0: f64, r1: f64, tol: f64) -> bool {
    let d = sub(p, a);
    if len == 0.0 {
        return len3(d) <= tol;
    }
    let t = dot(d, axis);
    let rho = len3(sub(d, mul(axis, t)));
    let radius_here = r0 + (r1 - r0) * (t / len);
    if (0.0..=len).contains(&t) && rho <= radius_here {
        return true;
    }
    // Outside: exact distance in the (axial, radial) half-plane to the
    // profile polygon (the axis edge is never the nearest for rho ≥ 0).
    let profile = [[0.0, 0.0], [len, 0.0], [len, r1], [0.0, r0]];
    polygon_distance([t, rho], &profile) <= tol
}

/// Distance from `p` to the convex polygon with counter-clockwise `corners`
/// (degenerate edges allowed): 0 when `p` is left of (or on) every line
/// through consecutive corners, else the distance to the nearest edge.
fn polygon_distance(p: P2, corners: &[P2; 4]) -> f64 {
    let edges = [0, 1, 2, 3].map(|i| (corners[i], corners[(i + 1) % 4]));
    let inside = edges.iter().all(|&(s, e)| {
        let (ex, ey) = (e[0] - s[0], e[1] - s[1]);
        ex * (p[1] - s[1]) - ey * (p[0] - s[0]) >= 0.0
    });
    if inside {
        return 0.0;
    }
    edges
        .iter()
        .map(|&(s, e)| segment_distance([p[0], p[1], 0.0], [s[0], s[1], 0.0], [e[0], e[1], 0.0]))
        .fold(f64::INFINITY, f64::min)
}

// ------------------------------------------------------------ enclosure --

/// Uniform grid over the shapes' tol-grown AABBs; each cell lists the shapes
/// whose AABB overlaps it (CSR layout).
struct Grid {
    lo: P3,
    n: [usize; 3],
    inv_cell: P3,
    starts: Vec<usize>,
    items: Vec<u32>,
}

/// Upper bounds on grid cells and on (shape, cell) registrations.
const MAX_CELLS: usize = 1 << 20;
const MAX_ENTRIES: usize = 16_000_000;

impl Grid {
    fn build(boxes: &[(P3, P3)]) -> Grid {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for (l, h) in boxes {
            for i in 0..3 {
                lo[i] = lo[i].min(l[i]);
                hi[i] = hi[i].max(h[i]);
            }
        }
        let ext = [0, 1, 2].map(|i| (hi[i] - lo[i]).max(0.0));
        let target = (16 * boxes.len()).clamp(1, MAX_CELLS / 8);
        let mut cell = cell_size(ext, target as f64);
        loop {
            let g = Grid::with_cell(lo, ext, cell);
            let cells = g.n.iter().product::<usize>();
            let small = cells <= MAX_CELLS && g.entry_count(boxes) <= MAX_ENTRIES;
            if small || g.n == [1, 1, 1] {
                return g.fill(boxes);
            }
            cell *= 2.0;
        }
    }

    fn with_cell(lo: P3, ext: P3, cell: f64) -> Grid {
        let n = ext.map(|e| ((e / cell).ceil() as usize).clamp(1, 1024));
        let inv_cell = [0, 1, 2].map(|i| {
            if ext[i] > 0.0 {
                n[i] as f64 / ext[i]
            } else {
                0.0
            }
        });
        Grid {
            lo,
            n,
            inv_cell,
            starts: Vec::new(),
            items: Vec::new(),
        }
    }

    /// Cell coordinate of `x` along axis `i`, or `None` outside the grid.
    fn coord(&self, i: usize, x: f64) -> Option<usize> {
        let f = (x - self.lo[i]) * self.inv_cell[i];
        if f < 0.0 || f.is_nan() {
            return None;
        }
        let c = f as usize;
        let clamp = self.n[i] - 1;
        // Points past the top by more than a cell are outside every shape.
        (c <= self.n[i]).then_some(c.min(clamp))
    }

    /// Inclusive cell range covered by `[l, h]` along each axis.
    fn range(&self, l: P3, h: P3) -> [(usize, usize); 3] {
        [0, 1, 2].map(|i| {
            let a = self.coord(i, l[i]).unwrap_or(0);
            let b = self.coord(i, h[i]).unwrap_or(self.n[i] - 1);
            (a, b)
        })
    }

    fn entry_count(&self, boxes: &[(P3, P3)]) -> usize {
        boxes
            .iter()
            .map(|&(l, h)| {
                let r = self.range(l, h);
                r.iter().map(|(a, b)| b - a + 1).product::<usize>()
            })
            .sum()
    }

    /// Counting-sort fill of the per-cell shape lists.
    fn fill(mut self, boxes: &[(P3, P3)]) -> Grid {
        let cells = self.n.iter().product::<usize>();
        let mut starts = vec![0usize; cells + 1];
        self.for_each_cell(boxes, |cell, _| starts[cell + 1] += 1);
        for k in 0..cells {
            starts[k + 1] += starts[k];
        }
        let mut next = starts.clone();
        let mut items = vec![0u32; starts[cells]];
        self.for_each_cell(boxes, |cell, shape| {
            items[next[cell]] = shape;
            next[cell] += 1;
        });
        self.starts = starts;
        self.items = items;
        self
    }

    /// Calls `f(cell, shape)` for every cell each shape's box overlaps.
    fn for_each_cell(&self, boxes: &[(P3, P3)], mut f: impl FnMut(usize, u32)) {
        for (k, &(l, h)) in boxes.iter().enumerate() {
            let [(x0, x1), (y0, y1), (z0, z1)] = self.range(l, h);
            for x in x0..=x1 {
                for y in y0..=y1 {
                    for z in z0..=z1 {
                        f(self.index([x, y, z]), k as u32);
                    }
                }
            }
        }
    }

    fn index(&self, c: [usize; 3]) -> usize {
        (c[0] * self.n[1] + c[1]) * self.n[2] + c[2]
    }

    /// Shapes whose AABB may contain the point `p`.
    fn candidates(&self, p: P3) -> &[u32] {
        match (
            self.coord(0, p[0]),
            self.coord(1, p[1]),
            self.coord(2, p[2]),
        ) {
            (Some(x), Some(y), Some(z)) => {
                let k = self.index([x, y, z]);
                &self.items[self.starts[k]..self.starts[k + 1]]
            }
            _ => &[],
        }
    }
}

/// Cell edge giving about `target` cells over the extents `ext`.
fn cell_size(ext: P3, target: f64) -> f64 {
    let longest = ext.iter().fold(0.0f64, |m, e| m.max(*e));
    if longest <= 0.0 {
        return 1.0;
    }
    // Flat axes count as one cell; solve Π max(e_i/h, 1) ≈ target roughly.
    let floor = longest * 1e-6;
    let vol: f64 = ext.iter().map(|e| e.max(floor)).product();
    (vol / target).cbrt().max(longest / 1024.0)
}

/// For each face (its world-space vertices), true iff some shape contains all
/// of its vertices within `tol` (equivalently, the whole face: shapes are
/// convex).  Uses a uniform grid over the shapes' AABBs; parallel over faces.
pub fn faces_enclosed(shapes: &[Shape], faces: &[Vec<[f64; 3]>], tol: f64) -> Vec<bool> {
    faces_enclosed_with_work(shapes, faces, tol).0
}

/// The work [`faces_enclosed`] does, counted: what grows with the input when
/// the grid stops pruning, and what a timed test would only see through a
/// clock.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct EnclosureWork {
    /// The grid's cells plus its (shape, cell) registrations.
    pub grid: usize,
    /// Shapes whose box a face was tested against, over all faces.
    pub candidates: usize,
}

impl EnclosureWork {
    pub fn total(&self) -> usize {
        self.grid + self.candidates
    }
}

/// [`faces_enclosed`] and the work it did.
pub fn faces_enclosed_with_work(
    shapes: &[Shape],
    faces: &[Vec<[f64; 3]>],
    tol: f64,
) -> (Vec<bool>, EnclosureWork) {
    let boxes: Vec<(P3, P3)> = shapes
        .iter()
        .map(|s| (s.lo.map(|x| x - tol), s.hi.map(|x| x + tol)))
        .collect();
    if boxes.is_empty() {
        return (vec![false; faces.len()], EnclosureWork::default());
    }
    let grid = Grid::build(&boxes);
    let (inside, tried): (Vec<bool>, Vec<usize>) = faces
        .par_iter()
        .map(|f| face_enclosed(shapes, &boxes, &grid, f, tol))
        .unzip();
    let work = EnclosureWork {
        grid: grid.starts.len() - 1 + grid.items.len(),
        candidates: tried.iter().sum(),
    };
    (inside, work)
}

/// Whether some shape encloses the face, and how many candidate shapes were tried.
fn face_enclosed(
    shapes: &[Shape],
    boxes: &[(P3, P3)],
    grid: &Grid,
    f: &[P3],
    tol: f64,
) -> (bool, usize) {
    let Some(&first) = f.first() else {
        return (true, 0); // no vertices: trivially inside any shape (shapes non-empty)
    };
    let (mut lo, mut hi) = (first, first);
    for v in f {
        for i in 0..3 {
            lo[i] = lo[i].min(v[i]);
            hi[i] = hi[i].max(v[i]);
        }
    }
    let mut tried = 0;
    let inside = grid.candidates(first).iter().any(|&k| {
        tried += 1;
        let (bl, bh) = boxes[k as usize];
        (0..3).all(|i| bl[i] <= lo[i] && hi[i] <= bh[i])
            && f.iter()
                .all(|&v| shape_contains(&shapes[k as usize], v, tol))
    });
    (inside, tried)
}
