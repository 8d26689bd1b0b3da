//! Which side of an open surface is outside, by what can be seen from afar (not in the
//! paper; docs/decisions/0027-open-surfaces-oriented-by-visibility.md). `orient` turns a closed
//! patch by its signed
//! volume, which is exact; an open one (a car's body panels, a wall's shell with the
//! hidden faces left out) has no inside, and its signed volume about any point says
//! little: truck_shrec's hood came out facing down, so the fender beside it met the
//! hood at a "concave" crease and its plate stood 0.03 past the hood's edge, a fin that
//! held the balls. Here rays from sampled faces of each open patch, along both sides of
//! their normals, vote: the side whose rays leave without meeting the input is outside.
//! The rays are exact against the faces (a hierarchy of boxes over them,
//! `math::bvh`, asked whether any face is hit), so a thin wall's other side blocks
//! them. A uniform grid did this before; capped at 128 cells a side and 2^23 entries,
//! it coarsened on large inputs until each cell listed thousands of faces, and
//! 14M faces took minutes per ray batch.

use super::mesh::Mesh;
use crate::math::bvh::{Bvh, Compact};
use crate::math::{cross, dot, norm, sub, V3};

/// Faces per leaf of the hierarchy: few rays are cast (at most 10 ×
/// [`SAMPLED_FACES`]), so leaves sixteen times the cut's trade little time for a
/// sixteenth of its nodes (one byte a face, with [`Compact`] boxes). The walk builds
/// this hierarchy beside the spatial parts' groups, where a run's memory peaks.
const LEAF: usize = 64;
/// Faces sampled over the whole input, at most: a patch of p of the n faces gets
/// ⌊SAMPLED_FACES·p/n⌋ of them (all when fewer), evenly spread, so rays stay bounded;
/// a patch too small for one keeps its signed volume.
pub const SAMPLED_FACES: usize = 1_024;

/// The input's faces under a hierarchy of boxes, for exact ray queries.
#[derive(Debug)]
pub struct RayTree<'a> {
    mesh: &'a Mesh,
    bvh: Bvh<Compact>,
    /// Hits nearer than this are the ray's own surface (1e-9 of the diagonal).
    eps: f64,
}

impl<'a> RayTree<'a> {
    /// Every face of `mesh` under the hierarchy (its box from its own vertices).
    #[cfg(test)]
    pub fn build(mesh: &'a Mesh) -> RayTree<'a> {
        RayTree::build_checked(mesh, &|_| true).expect("never told to stop")
    }

    /// [`RayTree::build`] that asks `go_on` whether to go on while the hierarchy is
    /// built; `None` when it said stop.
    pub fn build_checked(
        mesh: &'a Mesh,
        go_on: crate::progress::Checkpoint,
    ) -> Option<RayTree<'a>> {
        let (lo, hi) = mesh.aabb();
        let bbox = |f: u32| {
            let vs = mesh.face(f as usize);
            crate::math::aabb_of(vs.iter().map(|&v| mesh.pos(v)))
        };
        Some(RayTree {
            mesh,
            // Whether any face blocks a ray does not depend on the tree: centres in
            // f32 halve the build's table (16 bytes a face), and boxes rounded out
            // to f32 only let a ray visit a few more leaves.
            bvh: Bvh::build_coarse(mesh.face_count(), LEAF, &bbox, go_on)?,
            eps: 1e-9 * norm(sub(hi, lo)).max(f64::MIN_POSITIVE),
        })
    }

    /// Whether the ray from `p` along unit `d` meets a face other than `own` (at a
    /// distance past `eps`), testing each face's fan triangles exactly.
    pub fn blocked(&self, p: V3, d: V3, own: u32) -> bool {
        let mut stack = Vec::with_capacity(64);
        self.bvh.ray_any(p, d, f64::INFINITY, &mut stack, |f| {
            f != own && self.hits(f, p, d)
        })
    }

    /// Whether the ray meets face `f` (fan-triangulated; Möller–Trumbore) past `eps`.
    fn hits(&self, f: u32, p: V3, d: V3) -> bool {
        let vs = self.mesh.face(f as usize);
        let a = self.mesh.pos(vs[0]);
        (1..vs.len().saturating_sub(1)).any(|i| {
            let (b, c) = (self.mesh.pos(vs[i]), self.mesh.pos(vs[i + 1]));
            let (e1, e2) = (sub(b, a), sub(c, a));
            let h = cross(d, e2);
            let det = dot(e1, h);
            if det.abs() < 1e-300 {
                return false;
            }
            let inv = 1.0 / det;
            let s = sub(p, a);
            let u = dot(s, h) * inv;
            if !(0.0..=1.0).contains(&u) {
                return false;
            }
            let q = cross(s, e1);
            let v = dot(d, q) * inv;
            if v < 0.0 || u + v > 1.0 {
                return false;
            }
            dot(e2, q) * inv > self.eps
        })
    }

    /// Rays from face `own`'s point `p` that leave on side `n` (unit), minus those
    /// leaving on −n: along n and tilted 45° towards ±t1 and ±t2, so in [−5, 5].
    pub fn side_score(&self, p: V3, n: V3, own: u32) -> i32 {
        let helper = if n[0].abs() < 0.6 {
            [1.0, 0.0, 0.0]
        } else {
            [0.0, 1.0, 0.0]
        };
        let t1 = unit(cross(n, helper));
        let t2 = cross(n, t1);
        let mut score = 0;
        for t in [[0.0; 3], t1, t1.map(|x| -x), t2, t2.map(|x| -x)] {
            let d = unit([0, 1, 2].map(|k| n[k] + t[k]));
            score += i32::from(!self.blocked(p, d, own))
                - i32::from(!self.blocked(p, d.map(|x| -x), own));
        }
        score
    }
}

fn unit(v: V3) -> V3 {
    let l = norm(v);
    if l > 0.0 {
        v.map(|x| x / l)
    } else {
        v
    }
}

/// Area-weighted mean of [`RayTree::side_score`] over `quota` faces spread evenly
/// through `members` (all when fewer; unit outward normals by `sign`, rays from each
/// face's centroid), or `None` when none has area: > 0 when the patch's present
/// winding faces outside.
pub fn vote(grid: &RayTree, members: &[u32], sign: &[i8], quota: usize) -> Option<f64> {
    use rayon::prelude::*;
    let mesh = grid.mesh;
    let q = quota.clamp(1, members.len().max(1));
    // The rays in parallel, summed in the faces' order (the same sum on any thread
    // count).
    let scores: Vec<Option<(f64, i32)>> = (0..q.min(members.len()))
        .into_par_iter()
        .map(|i| {
            let f = members[i * members.len() / q];
            let (n, c, len) = super::mesh::outward_normal_and_centre(mesh, sign, f)?;
            Some((len, grid.side_score(c, n, f)))
        })
        .collect();
    let (mut sum, mut area) = (0.0, 0.0);
    for (len, score) in scores.into_iter().flatten() {
        sum += 0.5 * len * f64::from(score);
        area += 0.5 * len;
    }
    (area > 0.0).then(|| sum / area)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit square in the plane y = 0 under a larger roof at y = 0.5 (faces 0 and
    /// 1): from the square, rays up meet the roof, rays down leave; a thin wall's
    /// other side, a thousandth away, blocks rays through it.
    #[test]
    fn rays_leave_on_the_open_side_only() {
        let p = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 0.0, 1.0],
            [0.0, 0.0, 1.0],
            [-1.0, 0.5, -1.0],
            [2.0, 0.5, -1.0],
            [2.0, 0.5, 2.0],
            [-1.0, 0.5, 2.0],
        ];
        let m = Mesh::from_polygons(&p, &[vec![0, 3, 2, 1], vec![4, 7, 6, 5]]).unwrap();
        let grid = RayTree::build(&m);
        let c = sub([0.5, 0.0, 0.5], m.offset);
        assert!(!grid.blocked(c, [0.0, -1.0, 0.0], 0));
        assert!(grid.blocked(c, [0.0, 1.0, 0.0], 0));
        assert_eq!(grid.side_score(c, [0.0, -1.0, 0.0], 0), 5);
        assert_eq!(grid.side_score(c, [0.0, 1.0, 0.0], 0), -5);
        // The square alone: both sides are open, the vote says nothing.
        let m = Mesh::from_polygons(&p[..4], &[vec![0, 3, 2, 1]]).unwrap();
        let grid = RayTree::build(&m);
        let c = sub([0.5, 0.0, 0.5], m.offset);
        assert_eq!(grid.side_score(c, [0.0, 1.0, 0.0], 0), 0);
        // A wall of two sheets 0.001 apart: from the lower, up is blocked at once.
        let mut q = p[..4].to_vec();
        q.extend(p[..4].iter().map(|v| [v[0], 0.001, v[2]]));
        let m = Mesh::from_polygons(&q, &[vec![0, 3, 2, 1], vec![4, 5, 6, 7]]).unwrap();
        let grid = RayTree::build(&m);
        let c = sub([0.5, 0.0, 0.5], m.offset);
        assert_eq!(grid.side_score(c, [0.0, -1.0, 0.0], 0), 5);
    }

    /// Faces that each span most of the box (3,000 triangles across a sphere, each
    /// joining two nearly opposite points; the old grid coarsened under them) and
    /// rays from the centre and from points on the sphere: the tree blocks a ray
    /// exactly when some face other than the ray's own is hit, as a scan over every
    /// face finds.
    #[test]
    fn rays_meet_giant_faces_as_a_linear_scan_does() {
        let n = 3000;
        let mut p = vec![[0.0, 0.0, 0.0]];
        for i in 0..=n {
            let t = i as f64 * 2.399;
            let z = 1.0 - 2.0 * (i as f64 + 0.5) / (n as f64 + 1.0);
            let r = (1.0 - z * z).sqrt();
            p.push([r * t.cos(), r * t.sin(), z]);
        }
        let half = n as u32 / 2;
        let f: Vec<Vec<u32>> = (1..=n as u32)
            .map(|i| vec![i, (i + half - 1) % n as u32 + 1, i % n as u32 + 1])
            .collect();
        let m = Mesh::from_polygons(&p, &f).unwrap();
        let tree = RayTree::build(&m);
        let scan = |o: V3, d: V3, own: u32| {
            (0..m.face_count() as u32).any(|g| g != own && tree.hits(g, o, d))
        };
        let mut hits = 0;
        for k in 0..200u32 {
            let t = f64::from(k) * 0.77;
            let d = unit([t.cos(), t.sin(), (t * 0.3).cos()]);
            let (o, own) = match k % 2 {
                0 => (m.pos(0), u32::MAX),
                _ => (m.pos(1 + k), k % n as u32),
            };
            let blocked = tree.blocked(o, d, own);
            assert_eq!(blocked, scan(o, d, own), "ray {k}");
            hits += usize::from(blocked);
        }
        assert!(hits > 0);
    }
}
