//! How close a collider is to its input, and whether it encloses it (the metrics of
//! the paper's §4.4, Table 3 and appendix), for our primitives and for convex hulls.
//!
//! - `hausdorff`, `chamfer`: max and mean distance from area-uniform samples of the
//!   collider's surface to the input surface, over the input's AABB diagonal. The
//!   default surface is the boundary of the union: a sample lying more than the
//!   tolerance inside another part is dropped (a buried face is nothing a ball can
//!   touch). `hausdorff_all`, `chamfer_all` keep every part's whole surface.
//! - `reverse_hausdorff`, `reverse_chamfer`: from input-surface samples to the
//!   nearest point of any part's surface.
//! - `enclosure`: the fraction of input-surface samples inside some part, with a
//!   tolerance of 1e-6 of the diagonal.
//!
//! With [`Input::to_solid`] (`primdecomp eval --solid`) the forward distances are to
//! the input's solid, what `decompose --solid` bounds (docs/decisions/0056): a
//! collider sample inside the input stands at 0. Inside is decided here on its own,
//! not by the core's grid: the parity of the input's triangles crossed by rays from
//! the sample in three fixed skew directions, the majority of the three (a closed
//! input; a ray through an edge or a vertex, where the count may be off, is rare and
//! outvoted).
//!
//! Distances are exact point-to-surface distances (triangles through a BVH, the
//! primitives in closed form). Everything runs in the input's re-centred frame, in
//! parallel, and is the same for a seed whatever the thread count: samples come from
//! per-chunk generators and every reduction runs in sample order.

pub use primdecomp_math::bvh;
pub mod collider;
pub mod report;
pub mod sample;
pub mod shape;

use crate::collider::{Collider, Hull};
use bvh::{point_tri_dist2, ray_tri, tri_box, Bvh};
use primdecomp::Mesh;
use primdecomp::Primitive;
use primdecomp_math::{cross, dot, norm, normalize, scale, sub, V3};
use rayon::prelude::*;
use sample::{Sample, Surface};
use shape::Piece;

/// Samples per surface when none is given; `primdecomp eval --help` states the
/// sampling error measured at this count.
pub const DEFAULT_SAMPLES: usize = 200_000;

/// Enclosure and burial tolerance, relative to the input's AABB diagonal.
pub const REL_TOL: f64 = 1e-6;

/// The metrics of one collider (distances relative to the input's AABB diagonal).
#[derive(Clone, Debug, PartialEq)]
pub struct Metrics {
    pub hausdorff: f64,
    pub chamfer: f64,
    pub hausdorff_all: f64,
    pub chamfer_all: f64,
    pub reverse_hausdorff: f64,
    pub reverse_chamfer: f64,
    pub enclosure: f64,
    pub bytes: usize,
    /// Parts by kind: box … prism, then hull.
    pub counts: Vec<(&'static str, usize)>,
    /// Whether the forward distances are to the input's solid ([`Input::to_solid`]).
    pub to_solid: bool,
}

/// The input surface, ready for distance queries and sampling.
pub struct Input {
    tris: Vec<[V3; 3]>,
    bvh: Bvh,
    surface: Surface,
    offset: V3,
    diag: f64,
    /// Forward distances to the solid ([`Input::to_solid`]).
    solid: bool,
}

/// The directions of the rays whose crossings' parity decides inside
/// ([`Input::inside`]): skew to the axes and to each other, so that a ray runs
/// along no face of a mesh built on a grid nor through its edges but by chance.
const RAYS: [V3; 3] = [[1.0, 2.0, 3.0], [-3.31, 1.0, 3.85], [3.0, -6.0, 2.0]];

impl Input {
    /// Fan-triangulates the mesh's polygons (re-centred frame).
    pub fn new(mesh: &Mesh) -> Input {
        let mut tris = Vec::with_capacity(mesh.face_count());
        for f in 0..mesh.face_count() {
            let v = mesh.face(f);
            for k in 2..v.len() {
                tris.push([mesh.pos(v[0]), mesh.pos(v[k - 1]), mesh.pos(v[k])]);
            }
        }
        let boxes: Vec<_> = tris.par_iter().map(tri_box).collect();
        let surface = Surface::new(
            tris.iter().map(|&t| Piece::Tri(t)).collect(),
            vec![0; tris.len()],
        );
        Input {
            bvh: Bvh::build(&boxes),
            tris,
            surface,
            offset: mesh.centre(),
            diag: mesh.diagonal(),
            solid: false,
        }
    }

    /// This input with the forward distances measured to its solid (`on`), not its
    /// surface: a collider sample inside the input ([`Input::inside`]) stands at 0.
    pub fn to_solid(self, on: bool) -> Input {
        Input { solid: on, ..self }
    }

    /// Whether `p` is inside the input: for at least two of three rays from `p`
    /// ([`RAYS`]), the number of triangles crossed is odd.
    pub fn inside(&self, p: V3) -> bool {
        let mut stack = Vec::new();
        let odd = |d: V3, stack: &mut Vec<u32>| {
            let mut crossed = false;
            self.bvh.ray_any(p, d, f64::INFINITY, stack, |i| {
                crossed ^= ray_tri(p, d, &self.tris[i as usize], 0.0).is_some();
                false
            });
            crossed
        };
        RAYS.iter().filter(|&&d| odd(d, &mut stack)).count() >= 2
    }

    /// The input's AABB diagonal, the unit of every distance.
    pub fn diagonal(&self) -> f64 {
        self.diag
    }

    fn dist(&self, p: V3) -> f64 {
        let tris = &self.tris;
        self.bvh
            .nearest(p, |i| point_tri_dist2(p, &tris[i as usize]))
            .0
            .sqrt()
    }

    /// A collider sample's distance: to the surface, or to the solid
    /// ([`Input::to_solid`]).
    fn forward_dist(&self, p: V3) -> f64 {
        let d = self.dist(p);
        match self.solid && d > 0.0 && self.inside(p) {
            true => 0.0,
            false => d,
        }
    }
}

/// The box no point is in: the start of a fold over points.
const EMPTY_BOX: (V3, V3) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);

fn min3(a: V3, b: V3) -> V3 {
    [a[0].min(b[0]), a[1].min(b[1]), a[2].min(b[2])]
}

fn max3(a: V3, b: V3) -> V3 {
    [a[0].max(b[0]), a[1].max(b[1]), a[2].max(b[2])]
}

/// A collider's parts in the input's frame, with their surfaces and a BVH.
struct Parts {
    solids: Solids,
    surface: Surface,
    parts: Bvh,
}

enum Solids {
    Primitives(Vec<Primitive>),
    Hulls {
        /// Outward unit normal and offset of each face plane, per hull.
        planes: Vec<Vec<(V3, f64)>>,
        tris: Vec<[V3; 3]>,
        tri_bvh: Bvh,
    },
}

impl Parts {
    fn new(c: &Collider, offset: V3) -> Parts {
        let back = scale(offset, -1.0);
        match c {
            Collider::Primitives(ps) => {
                let ps: Vec<Primitive> = ps.iter().map(|p| p.translated(back)).collect();
                let (mut pieces, mut owner) = (Vec::new(), Vec::new());
                for (i, p) in ps.iter().enumerate() {
                    shape::pieces(p, &mut pieces);
                    owner.resize(pieces.len(), i as u32);
                }
                let boxes: Vec<_> = ps.iter().map(Primitive::aabb).collect();
                Parts {
                    surface: Surface::new(pieces, owner),
                    parts: Bvh::build(&boxes),
                    solids: Solids::Primitives(ps),
                }
            }
            Collider::Hulls(hs) => Parts::hulls(hs, offset),
        }
    }

    fn hulls(hs: &[Hull], offset: V3) -> Parts {
        let (mut tris, mut owner, mut boxes, mut planes) =
            (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        for (i, h) in hs.iter().enumerate() {
            let first = tris.len();
            for t in &h.triangles {
                tris.push(t.map(|v| sub(h.positions[v as usize], offset)));
            }
            owner.resize(tris.len(), i as u32);
            let pts = tris[first..].iter().flatten().copied();
            boxes.push(pts.fold(EMPTY_BOX, |(lo, hi), p| (min3(lo, p), max3(hi, p))));
            planes.push(hull_planes(&tris[first..]));
        }
        let tri_boxes: Vec<_> = tris.iter().map(tri_box).collect();
        Parts {
            surface: Surface::new(tris.iter().map(|&t| Piece::Tri(t)).collect(), owner),
            parts: Bvh::build(&boxes),
            solids: Solids::Hulls {
                planes,
                tri_bvh: Bvh::build(&tri_boxes),
                tris,
            },
        }
    }

    /// Whether `p` lies in part `j`, grown by `tol` (shrunk when `tol < 0`).
    fn contains(&self, j: u32, p: V3, tol: f64) -> bool {
        match &self.solids {
            Solids::Primitives(ps) => ps[j as usize].contains(p, tol),
            Solids::Hulls { planes, .. } => {
                let pl = &planes[j as usize];
                !pl.is_empty() && pl.iter().all(|&(n, d)| dot(n, p) - d <= tol)
            }
        }
    }

    /// Whether `p` lies in some part other than `except`, grown by `tol`.
    fn inside_any(&self, p: V3, tol: f64, except: u32) -> bool {
        self.parts
            .any_at(p, tol, |j| j != except && self.contains(j, p, tol))
    }

    /// Distance from `p` to the nearest point of any part's surface.
    fn surface_dist(&self, p: V3) -> f64 {
        let d2 = match &self.solids {
            Solids::Primitives(ps) => {
                self.parts
                    .nearest(p, |j| shape::surface_dist2(&ps[j as usize], p))
                    .0
            }
            Solids::Hulls { tris, tri_bvh, .. } => {
                tri_bvh
                    .nearest(p, |i| point_tri_dist2(p, &tris[i as usize]))
                    .0
            }
        };
        d2.sqrt()
    }
}

/// Face planes of a convex hull, oriented away from its vertex centroid. A face
/// through the centroid (a flat hull) contributes both orientations.
fn hull_planes(tris: &[[V3; 3]]) -> Vec<(V3, f64)> {
    let n = (3 * tris.len()).max(1) as f64;
    let mut c = [0.0; 3];
    for p in tris.iter().flatten() {
        for k in 0..3 {
            c[k] += p[k] / n;
        }
    }
    let scale_len = tris
        .iter()
        .flatten()
        .map(|p| norm(sub(*p, c)))
        .fold(0.0, f64::max);
    let mut out = Vec::with_capacity(tris.len());
    for [a, b, t] in tris {
        let Some(nrm) = normalize(cross(sub(*b, *a), sub(*t, *a))) else {
            continue;
        };
        let side = dot(nrm, sub(c, *a));
        if side.abs() <= 1e-12 * scale_len {
            out.push((nrm, dot(nrm, *a)));
            out.push((scale(nrm, -1.0), -dot(nrm, *a)));
        } else {
            let n = if side > 0.0 { scale(nrm, -1.0) } else { nrm };
            out.push((n, dot(n, *a)));
        }
    }
    out
}

/// Max and mean of `d` over the entries where `keep` holds, in order (0, 0 when none).
fn max_mean(d: &[f64], keep: impl Fn(usize) -> bool) -> (f64, f64) {
    let (mut max, mut sum, mut n) = (0.0f64, 0.0, 0usize);
    for (i, &x) in d.iter().enumerate() {
        if keep(i) {
            (max, sum, n) = (max.max(x), sum + x, n + 1);
        }
    }
    (max, if n > 0 { sum / n as f64 } else { 0.0 })
}

/// Evaluates `collider` against `input` with `samples` samples per surface.
pub fn evaluate(input: &Input, collider: &Collider, samples: usize, seed: u64) -> Metrics {
    let parts = Parts::new(collider, input.offset);
    let diag = input.diag.max(f64::MIN_POSITIVE);
    let tol = REL_TOL * diag;
    let forward: Vec<Sample> = parts.surface.sample(samples, seed, 1);
    let fwd: Vec<(f64, bool)> = forward
        .par_iter()
        .map(|s| {
            let buried = parts.inside_any(s.p, -tol, s.part);
            (input.forward_dist(s.p) / diag, buried)
        })
        .collect();
    let d: Vec<f64> = fwd.iter().map(|x| x.0).collect();
    let (hausdorff_all, chamfer_all) = max_mean(&d, |_| true);
    let (hausdorff, chamfer) = max_mean(&d, |i| !fwd[i].1);
    let backward = input.surface.sample(samples, seed, 2);
    let rev: Vec<(f64, bool)> = backward
        .par_iter()
        .map(|s| {
            let inside = parts.inside_any(s.p, tol, u32::MAX);
            (parts.surface_dist(s.p) / diag, inside)
        })
        .collect();
    let d: Vec<f64> = rev.iter().map(|x| x.0).collect();
    let (reverse_hausdorff, reverse_chamfer) = max_mean(&d, |_| true);
    let inside = rev.iter().filter(|x| x.1).count();
    Metrics {
        hausdorff,
        chamfer,
        hausdorff_all,
        chamfer_all,
        reverse_hausdorff,
        reverse_chamfer,
        enclosure: if rev.is_empty() {
            0.0
        } else {
            inside as f64 / rev.len() as f64
        },
        bytes: collider.bytes(),
        counts: collider.counts(),
        to_solid: input.solid,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use primdecomp::{Obb, Sphere};

    /// The box's surface as a triangle mesh.
    pub(crate) fn box_mesh(b: &Primitive) -> Mesh {
        let Primitive::Box(b) = b else {
            panic!("not a box")
        };
        let v: Vec<V3> = shape::box_triangles(b).into_iter().flatten().collect();
        let f: Vec<Vec<u32>> = (0..12).map(|i| vec![3 * i, 3 * i + 1, 3 * i + 2]).collect();
        Mesh::from_polygons(&v, &f).unwrap()
    }

    fn cube(h: f64) -> Primitive {
        Primitive::Box(Obb {
            center: [0.0; 3],
            axes: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            half: [h; 3],
        })
    }

    #[test]
    fn buried_samples_are_dropped() {
        // A small sphere wholly inside the box: its surface counts in the *_all
        // metrics only.
        let input = Input::new(&box_mesh(&cube(1.0)));
        let inner = Primitive::Sphere(Sphere {
            center: [0.0; 3],
            radius: 0.5,
        });
        let c = Collider::Primitives(vec![cube(1.0), inner]);
        let m = evaluate(&input, &c, 20_000, 1);
        let diag = 2.0 * 3f64.sqrt();
        assert!(m.hausdorff < 1e-12, "{m:?}");
        // The farthest sphere points face the cube's corners: 1 − 0.5/√3 from a face.
        let far = (1.0 - 0.5 / 3f64.sqrt()) / diag;
        assert!(
            m.hausdorff_all <= far + 1e-12 && m.hausdorff_all > 0.98 * far,
            "{m:?}"
        );
        assert!(m.chamfer_all > 0.0 && m.enclosure == 1.0, "{m:?}");
    }

    /// The three rays' parity tells inside from outside of a closed cube (points not
    /// within a hair of its faces); measured to the solid, a collider inside the cube
    /// stands at 0 where to the surface it stands off.
    #[test]
    fn inside_by_parity_and_distances_to_the_solid() {
        let input = Input::new(&box_mesh(&cube(1.0)));
        let mut rng = <rand_chacha::ChaCha8Rng as rand::SeedableRng>::seed_from_u64(3);
        for _ in 0..5000 {
            let p: V3 = std::array::from_fn(|_| rand::Rng::gen_range(&mut rng, -1.5..1.5));
            let far = p.iter().map(|c| c.abs()).fold(0.0, f64::max);
            if (far - 1.0).abs() > 1e-9 {
                assert_eq!(input.inside(p), far < 1.0, "{p:?}");
            }
        }
        let inner = Collider::Primitives(vec![cube(0.5)]);
        let m = evaluate(&input, &inner, 5000, 1);
        assert!(!m.to_solid && m.hausdorff_all > 0.1, "{m:?}");
        let m = evaluate(&input.to_solid(true), &inner, 5000, 1);
        assert!(
            m.to_solid && m.hausdorff_all == 0.0 && m.chamfer_all == 0.0,
            "{m:?}"
        );
    }

    #[test]
    fn flat_hull_planes_have_both_sides() {
        let t = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let pl = hull_planes(&[t, [t[0], t[2], t[1]]]);
        assert_eq!(pl.len(), 4);
        let inside = |p: V3, tol: f64| pl.iter().all(|&(n, d)| dot(n, p) - d <= tol);
        assert!(inside([0.2, 0.2, 0.0], 1e-9));
        assert!(!inside([0.2, 0.2, 0.1], 1e-9));
        assert!(!inside([0.2, 0.2, -0.1], 1e-9));
    }
}
