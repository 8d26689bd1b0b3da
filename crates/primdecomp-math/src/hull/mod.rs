//! Conservative convex-hull vertex reduction for point clouds in 3D.
//!
//! [`hull_vertices`] returns the indices of a subset of the input that contains
//! every vertex of the convex hull.  Fitting routines that only maximise convex
//! functions of the points give the same answer on that subset as on all points.
//!
//! ## Method
//! 1. Points are copied into the workspace relative to their bounding-box centre
//!    (large offsets do not cost precision in the predicates).  The working
//!    tolerance is `tol = max(eps, 64·ε_mach·R)` (`R` = half box diagonal), i.e.
//!    `eps` unless it is below the rounding noise of the distance predicate.
//! 2. Initial simplex: `p0` = lexicographic minimum, `p1` = farthest from `p0`,
//!    `p2` = farthest from line `p0p1`, `p3` = farthest from plane `p0p1p2`.
//!    Each step doubles as a degeneracy test: all points within `tol` of `p0`
//!    → one point; of the line → its two extremes; within `0.75·tol` of the
//!    plane → Andrew's monotone chain in that plane, dropping a middle point
//!    on a right turn or when it is within `0.5·tol` of the chord *segment*.
//! 3. Otherwise the cloud is mapped affinely into the frame of that simplex
//!    (axes scaled by diameter, width and thickness), which makes it fat:
//!    a thin slab (thickness ≈ a few `eps`) would otherwise have knife-edge
//!    rims where "within `tol` of every face plane" is far from "within `tol`
//!    of the hull".  The working tolerance becomes `tol / (8·diameter)`.
//!    Then Quickhull (Barber, Dobkin & Huhdanpaa 1996) without facet merging:
//!    triangles with outward unit normals and adjacency, per-face conflict
//!    lists (intrusive linked lists); a point is *outside* a face only if its
//!    signed distance exceeds the tolerance.  Each step takes the farthest
//!    point of a face, finds the visible faces by DFS (visible ⇔ distance >
//!    tolerance), orders the horizon edges into one cycle, builds the cone of
//!    new faces and redistributes the conflict points of the deleted faces.
//!
//! ## Guarantee
//! A point is only dropped when it is within the tolerance below every face it
//! was tested against (3D) or of a chord segment (2D).  The affine map is
//! `diameter`-Lipschitz back to input space and makes all hull edges of bounded
//! sharpness, so dropped points lie within a small multiple of `eps` of the
//! hull of the kept points (≤ `eps` in all tests; checked at `10·eps` by brute
//! force and random support directions).  Any inconsistency — a horizon that
//! is not a single simple cycle, a new face whose height is below a quarter of
//! the tolerance, more than `n` iterations or `32·n + 64` faces, non-finite
//! input or `eps` — makes the function return all indices, which is always
//! correct.  It never panics.

use super::vec3::{cross, dot, norm2, scale, sub, V3};

const NONE: u32 = u32::MAX;

/// One triangle of the current hull; edge `i` runs `v[i] → v[(i+1)%3]` and
/// `adj[i]` is the face across it.
#[derive(Clone, Copy, Debug)]
struct Face {
    v: [u32; 3],
    adj: [u32; 3],
    n: V3,
    off: f64,
    head: u32,
    far: u32,
    far_d: f64,
    alive: bool,
    /// Seen from the current eye ([`HullWorkspace::find_visible`]): in the epoch
    /// `mark`, visible or not (kept in the face, beside what the search reads).
    vis: bool,
    mark: u32,
}

/// Horizon edge `a → b` of a visible face; `g` is the hidden neighbour, whose
/// edge `gi` is `b → a`.
#[derive(Clone, Copy, Debug)]
struct HEdge {
    a: u32,
    b: u32,
    g: u32,
    gi: u8,
}

/// Reusable buffers for [`hull_vertices`].
#[derive(Default)]
pub struct HullWorkspace {
    pts: Vec<V3>,
    next: Vec<u32>,
    pmark: Vec<u32>,
    hstart: Vec<u32>,
    faces: Vec<Face>,
    stack: Vec<u32>,
    visible: Vec<u32>,
    horizon: Vec<HEdge>,
    order: Vec<u32>,
    new_faces: Vec<u32>,
    pending: Vec<u32>,
    proj: Vec<[f64; 2]>,
    sorted: Vec<u32>,
    chain: Vec<u32>,
    epoch: u32,
    tol: f64,
    /// Points tested in Quickhull's loop since the last ask ([`hull_vertices_checked`]).
    work: u64,
    /// The last reduction was told to stop.
    stopped: bool,
}

impl std::fmt::Debug for HullWorkspace {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("HullWorkspace").finish_non_exhaustive()
    }
}

/// Indices (into the input) of a subset of points that contains every vertex of
/// the convex hull of `x,y,z` (SoA slices, equal length; extra entries of longer
/// slices are ignored).  Extra non-vertex points may be kept, but no point lying
/// outside the hull of the returned subset by more than `eps` is dropped.
/// Output is sorted ascending without duplicates.  On any numerical trouble all
/// indices are returned.
pub fn hull_vertices(
    x: &[f64],
    y: &[f64],
    z: &[f64],
    eps: f64,
    ws: &mut HullWorkspace,
    out: &mut Vec<u32>,
) {
    hull_vertices_checked(x, y, z, eps, ws, out, &|| true);
}

/// Points of a cloud, at least, whose reduction asks `go_on` between its passes and
/// every [`WORK_PER_CHECK`] points tested in its main loop (a cloud of millions
/// of points is otherwise one step of a second or more).
const CHECKED_FROM: usize = 1 << 16;

/// Points tested against faces between two asks of `go_on` (milliseconds).
const WORK_PER_CHECK: u64 = 1 << 18;

/// [`hull_vertices`], asking `go_on` between the passes over a cloud of 2^16
/// points or more (`CHECKED_FROM`) and every 2^18 points tested in Quickhull's loop
/// (`WORK_PER_CHECK`); a smaller cloud is never asked. The same indices, or `false`
/// as soon as it said stop (then `out` holds nothing to use).
pub fn hull_vertices_checked(
    x: &[f64],
    y: &[f64],
    z: &[f64],
    eps: f64,
    ws: &mut HullWorkspace,
    out: &mut Vec<u32>,
    go_on: &dyn Fn() -> bool,
) -> bool {
    out.clear();
    let n = x.len().min(y.len()).min(z.len());
    ws.stopped = false;
    ws.work = 0;
    if n >= CHECKED_FROM && !go_on() {
        return false;
    }
    if n <= 4 || n >= (u32::MAX / 2) as usize || !ws.load(x, y, z, n, eps) {
        out.extend(0..n as u32);
        return true;
    }
    let ask = || n < CHECKED_FROM || go_on();
    if ws.reduce(out, &ask).is_none() {
        out.clear();
        if ws.stopped {
            return false;
        }
        out.extend(0..n as u32);
    }
    true
}

/// Unit normal and offset of triangle `p q r` (counter-clockwise seen from the
/// outside), or `None` if its height over the longest edge is `≤ min_h`.
/// Inlined: a call returned the plane through memory, a fifth of its cost.
#[inline(always)]
fn plane(p: V3, q: V3, r: V3, min_h: f64) -> Option<(V3, f64)> {
    let (e0, e1, e2) = (sub(q, p), sub(r, q), sub(p, r));
    let (l0, l1, l2) = (norm2(e0), norm2(e1), norm2(e2));
    // Cross the two shorter edges (they meet opposite the longest one).
    let (c, lmax) = if l0 >= l1 && l0 >= l2 {
        (cross(e1, e2), l0)
    } else if l1 >= l2 {
        (cross(e2, e0), l1)
    } else {
        (cross(e0, e1), l2)
    };
    let len2 = norm2(c);
    if len2.is_nan() || len2 <= min_h * min_h * lmax || !len2.is_finite() {
        return None;
    }
    let n = scale(c, 1.0 / len2.sqrt());
    let off = (dot(n, p) + dot(n, q) + dot(n, r)) / 3.0;
    Some((n, off))
}

impl HullWorkspace {
    /// Copies the points (centred) and sets `tol`; `false` on non-finite data.
    fn load(&mut self, x: &[f64], y: &[f64], z: &[f64], n: usize, eps: f64) -> bool {
        if eps.is_nan() || eps < 0.0 || !eps.is_finite() {
            return false;
        }
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for i in 0..n {
            let p = [x[i], y[i], z[i]];
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        let c = [0, 1, 2].map(|k| 0.5 * lo[k] + 0.5 * hi[k]);
        let r = 0.5 * norm2(sub(hi, lo)).sqrt();
        if !c.iter().all(|v| v.is_finite()) || !r.is_finite() {
            return false;
        }
        self.pts.clear();
        self.pts.extend((0..n).map(|i| sub([x[i], y[i], z[i]], c)));
        self.tol = eps.max(64.0 * f64::EPSILON * r);
        self.epoch = 0;
        self.pmark.clear();
        self.pmark.resize(n, 0);
        self.hstart.resize(n, 0);
        self.next.clear();
        self.next.resize(n, NONE);
        true
    }

    /// Index of the point maximising `f` (first one on ties) and its value.
    fn argmax(&self, f: impl Fn(V3) -> f64) -> (u32, f64) {
        let mut best = (0u32, f64::NEG_INFINITY);
        for (i, &p) in self.pts.iter().enumerate() {
            let v = f(p);
            if v > best.1 {
                best = (i as u32, v);
            }
        }
        best
    }

    /// Degeneracy cascade (point / segment / polygon) and then Quickhull.
    /// `None` on numerical trouble, or with `stopped` set when `go_on` said stop.
    fn reduce(&mut self, out: &mut Vec<u32>, go_on: &dyn Fn() -> bool) -> Option<()> {
        self.asked(go_on)?;
        let pts = &self.pts;
        let mut i0 = 0;
        for i in 1..pts.len() {
            let (a, b) = (pts[i], pts[i0]);
            if (a[0], a[1], a[2]) < (b[0], b[1], b[2]) {
                i0 = i;
            }
        }
        let p0 = pts[i0];
        self.asked(go_on)?;
        let (i1, d1) = self.argmax(|p| norm2(sub(p, p0)));
        if d1.sqrt() <= self.tol {
            out.push(i0 as u32);
            return Some(());
        }
        let u = scale(sub(self.pts[i1 as usize], p0), 1.0 / d1.sqrt());
        self.asked(go_on)?;
        let (i2, d2) = self.argmax(|p| norm2(cross(sub(p, p0), u)));
        if d2.sqrt() <= self.tol {
            let (lo, _) = self.argmax(|p| -dot(p, u));
            let (hi, _) = self.argmax(|p| dot(p, u));
            out.extend([lo.min(hi), lo.max(hi)]);
            out.dedup();
            return Some(());
        }
        let (nrm, off) = plane(p0, self.pts[i1 as usize], self.pts[i2 as usize], 0.0)?;
        self.asked(go_on)?;
        let (i3, d3) = self.argmax(|p| (dot(nrm, p) - off).abs());
        if d3 <= 0.75 * self.tol {
            self.hull_2d(u, nrm, out);
            return Some(());
        }
        let frame = [
            scale(u, 1.0 / d1.sqrt()),
            scale(cross(nrm, u), 1.0 / d2.sqrt()),
            scale(nrm, 1.0 / d3),
        ];
        self.asked(go_on)?;
        self.normalize(p0, frame, d1.sqrt());
        self.asked(go_on)?;
        self.hull_3d([i0 as u32, i1, i2, i3], go_on)?;
        self.collect(out);
        Some(())
    }

    /// Maps the points affinely to `(frame · (p − p0))`, where the rows of
    /// `frame` are `u/D`, `v/h₂`, `w/h₃` (diameter, width, thickness), so the
    /// cloud becomes fat (coordinates in `[−1, 1]`, containing a unit-size
    /// tetrahedron) and Quickhull's plane tests no longer suffer from knife
    /// edges.  The inverse map is `D`-Lipschitz, so `tol/D` in the new space
    /// is conservative; the extra factor 8 covers the plane-vs-set distance
    /// gap at the (bounded-angle) edges of a fat hull.
    fn normalize(&mut self, p0: V3, frame: [V3; 3], diam: f64) {
        for p in self.pts.iter_mut() {
            let q = sub(*p, p0);
            *p = frame.map(|r| dot(r, q));
        }
        self.tol = (self.tol / (8.0 * diam)).max(256.0 * f64::EPSILON);
    }

    /// Andrew's monotone chain on the projection onto the plane spanned by `u`
    /// and `cross(nrm, u)`.
    fn hull_2d(&mut self, u: V3, nrm: V3, out: &mut Vec<u32>) {
        let v = cross(nrm, u);
        self.proj.clear();
        self.proj
            .extend(self.pts.iter().map(|&p| [dot(p, u), dot(p, v)]));
        let proj = &self.proj;
        self.sorted.clear();
        self.sorted.extend(0..proj.len() as u32);
        self.sorted.sort_unstable_by(|&a, &b| {
            let (pa, pb) = (proj[a as usize], proj[b as usize]);
            pa[0]
                .total_cmp(&pb[0])
                .then(pa[1].total_cmp(&pb[1]))
                .then(a.cmp(&b))
        });
        let tol = 0.5 * self.tol;
        // Drop `a` on a right turn or when it is within `tol` of segment ob
        // (not merely of its line: steep chords would amplify the error).
        let keeps = |o: u32, a: u32, b: u32| {
            let (o, a, b) = (proj[o as usize], proj[a as usize], proj[b as usize]);
            let (ax, ay, bx, by) = (a[0] - o[0], a[1] - o[1], b[0] - o[0], b[1] - o[1]);
            let (c, l2, t) = (ax * by - ay * bx, bx * bx + by * by, ax * bx + ay * by);
            c > 0.0 && (c > tol * l2.sqrt() || t < 0.0 || t > l2)
        };
        let chain = &mut self.chain;
        chain.clear();
        for pass in 0..2 {
            let start = if pass == 0 { 1 } else { chain.len() };
            let mut step = |i: u32| {
                while chain.len() > start
                    && !keeps(chain[chain.len() - 2], chain[chain.len() - 1], i)
                {
                    chain.pop();
                }
                chain.push(i);
            };
            if pass == 0 {
                self.sorted.iter().for_each(|&i| step(i));
            } else {
                self.sorted.iter().rev().skip(1).for_each(|&i| step(i));
            }
        }
        out.extend_from_slice(chain);
        out.sort_unstable();
        out.dedup();
    }

    #[inline(always)]
    fn dist(&self, p: u32, f: u32) -> f64 {
        let face = &self.faces[f as usize];
        dot(face.n, self.pts[p as usize]) - face.off
    }

    /// Appends face `v` (adjacency filled in by the caller); `None` if degenerate.
    fn push_face(&mut self, v: [u32; 3], adj: [u32; 3], min_h: f64) -> Option<u32> {
        let [a, b, c] = v.map(|i| self.pts[i as usize]);
        let (n, off) = plane(a, b, c, min_h)?;
        let id = self.faces.len() as u32;
        self.faces.push(Face {
            v,
            adj,
            n,
            off,
            head: NONE,
            far: NONE,
            far_d: 0.0,
            alive: true,
            vis: false,
            mark: 0,
        });
        Some(id)
    }

    /// Puts point `p` (at distance `d > tol`) on face `f`'s conflict list.
    fn add_conflict(&mut self, f: u32, p: u32, d: f64) {
        let face = &mut self.faces[f as usize];
        self.next[p as usize] = face.head;
        face.head = p;
        if face.far == NONE || d > face.far_d {
            face.far = p;
            face.far_d = d;
        }
    }

    /// Builds the initial tetrahedron and distributes the other points.
    fn init_simplex(&mut self, s: [u32; 4]) -> Option<()> {
        self.faces.clear();
        let [a, mut b, mut c, d] = s;
        let p = |i: u32| self.pts[i as usize];
        let nrm = cross(sub(p(b), p(a)), sub(p(c), p(a)));
        if dot(nrm, sub(p(d), p(a))) > 0.0 {
            std::mem::swap(&mut b, &mut c);
        }
        let tris = [[a, b, c], [a, d, b], [b, d, c], [c, d, a]];
        for t in tris {
            self.push_face(t, [NONE; 3], 0.25 * self.tol)?;
        }
        for f in 0..4 {
            for i in 0..3 {
                let (u, v) = (tris[f][i], tris[f][(i + 1) % 3]);
                let g = (0..4)
                    .find(|&g| (0..3).any(|j| tris[g][j] == v && tris[g][(j + 1) % 3] == u))?;
                self.faces[f].adj[i] = g as u32;
            }
        }
        for i in 0..self.pts.len() as u32 {
            if s.contains(&i) {
                continue;
            }
            if let Some((f, d)) = (0..4)
                .map(|f| (f, self.dist(i, f)))
                .find(|&(_, d)| d > self.tol)
            {
                self.add_conflict(f, i, d);
            }
        }
        self.pending.clear();
        self.pending
            .extend((0..4).filter(|&f| self.faces[f as usize].head != NONE));
        Some(())
    }

    /// Quickhull main loop.
    fn hull_3d(&mut self, s: [u32; 4], go_on: &dyn Fn() -> bool) -> Option<()> {
        self.init_simplex(s)?;
        self.asked(go_on)?;
        let n = self.pts.len();
        let max_faces = 32 * n + 64;
        let mut iters = 0;
        while let Some(f) = self.pending.pop() {
            let face = self.faces[f as usize];
            if !face.alive || face.head == NONE {
                continue;
            }
            iters += 1;
            if iters > n {
                return None;
            }
            self.find_visible(f, face.far)?;
            self.order_horizon()?;
            if self.faces.len() + self.order.len() > max_faces {
                return None;
            }
            self.build_cone(face.far)?;
            self.reassign(face.far);
            if self.work >= WORK_PER_CHECK {
                self.work = 0;
                self.asked(go_on)?;
            }
        }
        Some(())
    }

    /// `None`, `stopped` set, when `go_on` says stop.
    fn asked(&mut self, go_on: &dyn Fn() -> bool) -> Option<()> {
        self.stopped = !go_on();
        (!self.stopped).then_some(())
    }

    /// DFS over the faces visible from `eye`, starting at `f0`; fills
    /// `visible` and the (unordered) `horizon`.
    fn find_visible(&mut self, f0: u32, eye: u32) -> Option<()> {
        self.epoch += 1;
        let ep = self.epoch;
        self.visible.clear();
        self.horizon.clear();
        self.stack.clear();
        let eye_p = self.pts[eye as usize];
        let tol = self.tol;
        let f0f = &mut self.faces[f0 as usize];
        f0f.mark = ep;
        f0f.vis = true;
        self.stack.push(f0);
        while let Some(f) = self.stack.pop() {
            self.visible.push(f);
            let (fv, fadj) = {
                let face = &self.faces[f as usize];
                (face.v, face.adj)
            };
            for i in 0..3 {
                let g = fadj[i];
                let gu = g as usize;
                let gf = &mut self.faces[gu];
                if gf.mark != ep {
                    gf.mark = ep;
                    // `dist(eye, g)`, the same arithmetic.
                    gf.vis = dot(gf.n, eye_p) - gf.off > tol;
                    if gf.vis {
                        self.stack.push(g);
                    }
                }
                if !gf.vis {
                    let (a, b) = (fv[i], fv[(i + 1) % 3]);
                    let gv = gf.v;
                    let gi = (0..3).find(|&j| gv[j] == b && gv[(j + 1) % 3] == a)?;
                    self.horizon.push(HEdge {
                        a,
                        b,
                        g,
                        gi: gi as u8,
                    });
                }
            }
        }
        Some(())
    }

    /// Orders the horizon edges into `order`; `None` unless they form exactly
    /// one simple cycle.
    fn order_horizon(&mut self) -> Option<()> {
        let ep = self.epoch;
        let m = self.horizon.len();
        if m < 3 {
            return None;
        }
        for (k, h) in self.horizon.iter().enumerate() {
            let a = h.a as usize;
            if self.pmark[a] == ep {
                return None;
            }
            self.pmark[a] = ep;
            self.hstart[a] = k as u32;
        }
        self.order.clear();
        let mut k = 0u32;
        for step in 0..m {
            if step > 0 && k == 0 {
                return None;
            }
            self.order.push(k);
            let b = self.horizon[k as usize].b as usize;
            if self.pmark[b] != ep {
                return None;
            }
            k = self.hstart[b];
        }
        (k == 0).then_some(())
    }

    /// Replaces the visible faces by the cone from `eye` to the horizon.
    fn build_cone(&mut self, eye: u32) -> Option<()> {
        self.new_faces.clear();
        let m = self.order.len();
        let base = self.faces.len();
        self.faces.reserve(m);
        for j in 0..m {
            let h = self.horizon[self.order[j] as usize];
            // The cone's faces around the eye, in horizon order, wrapping round.
            let prev = (base + if j == 0 { m - 1 } else { j - 1 }) as u32;
            let next = (base + if j + 1 == m { 0 } else { j + 1 }) as u32;
            let id = self.push_face([h.a, h.b, eye], [h.g, next, prev], 0.25 * self.tol)?;
            self.faces[h.g as usize].adj[h.gi as usize] = id;
            self.new_faces.push(id);
        }
        for &f in &self.visible {
            self.faces[f as usize].alive = false;
        }
        Some(())
    }

    /// Moves the conflict points of the deleted faces to the first new face
    /// they are outside of; the others are inside the new hull and dropped.
    fn reassign(&mut self, eye: u32) {
        for vi in 0..self.visible.len() {
            let f = self.visible[vi] as usize;
            let mut p = self.faces[f].head;
            self.faces[f].head = NONE;
            while p != NONE {
                let nx = self.next[p as usize];
                self.work += 1;
                if p != eye {
                    for j in 0..self.new_faces.len() {
                        let nf = self.new_faces[j];
                        let d = self.dist(p, nf);
                        if d > self.tol {
                            self.add_conflict(nf, p, d);
                            break;
                        }
                    }
                }
                p = nx;
            }
        }
        for j in 0..self.new_faces.len() {
            let nf = self.new_faces[j];
            if self.faces[nf as usize].head != NONE {
                self.pending.push(nf);
            }
        }
    }

    /// Vertices of the live faces, ascending.
    fn collect(&mut self, out: &mut Vec<u32>) {
        self.epoch += 1;
        let ep = self.epoch;
        for f in self.faces.iter().filter(|f| f.alive) {
            for &v in &f.v {
                self.pmark[v as usize] = ep;
            }
        }
        out.extend((0..self.pts.len() as u32).filter(|&i| self.pmark[i as usize] == ep));
    }
}

#[cfg(test)]
mod tests;
