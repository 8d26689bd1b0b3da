//! Which side of an open surface is outside, by what can be seen from afar (not in the
//! paper; docs/decisions/0027-open-surfaces-oriented-by-visibility.md). `orient` turns a closed
//! patch by its signed
//! volume, which is exact; an open one (a car's body panels, a wall's shell with the
//! hidden faces left out) has no inside, and its signed volume about any point says
//! little: truck_shrec's hood came out facing down, so the fender beside it met the
//! hood at a "concave" crease and its plate stood 0.03 past the hood's edge, a fin that
//! held the balls. Here rays from sampled faces of each open patch, along both sides of
//! their normals, vote: the side whose rays leave without meeting the input is outside.
//! The rays are exact against the faces (a uniform grid of face lists, walked cell by
//! cell), so a thin wall's other side blocks them.

use super::Mesh;
use crate::math::{cross, dot, norm, sub, V3};
use rayon::prelude::*;

/// Cells along the grid's longest side, at most; fewer for small inputs
/// (2·∛faces, at least 8).
pub const CELLS: usize = 128;
/// Face-in-cell entries, at most (32 MiB): past this the grid is coarsened, so a few
/// giant faces spanning the box cannot make the grid's lists outgrow the input; real
/// inputs stay far below it (docs/decisions/0027-open-surfaces-oriented-by-visibility.md).
const MAX_ENTRIES: usize = 1 << 23;
/// Faces sampled over the whole input, at most: a patch of p of the n faces gets
/// ⌊SAMPLED_FACES·p/n⌋ of them (all when fewer), evenly spread, so rays stay bounded;
/// a patch too small for one keeps its signed volume.
pub const SAMPLED_FACES: usize = 1_024;

/// The input's faces listed per cell of a uniform grid over its AABB, for exact ray
/// queries.
#[derive(Debug)]
pub struct RayGrid<'a> {
    mesh: &'a Mesh,
    min: V3,
    cell: f64,
    dims: [usize; 3],
    /// CSR: cell c's faces are `faces[start[c]..start[c + 1]]`.
    start: Vec<u32>,
    faces: Vec<u32>,
    /// Hits nearer than this are the ray's own surface (1e-9 of the diagonal).
    eps: f64,
}

impl<'a> RayGrid<'a> {
    /// Lists every face of `mesh` in the cells its AABB overlaps.
    pub fn build(mesh: &'a Mesh, max_cells: usize) -> RayGrid<'a> {
        let by_size = 2.0 * (mesh.face_count() as f64).cbrt();
        let mut cells = (by_size as usize).clamp(8, max_cells.max(8));
        loop {
            if let Some(grid) = Self::try_build(mesh, cells) {
                return grid;
            }
            cells /= 2;
        }
    }

    /// The grid at `cells` along the longest side, or `None` when it would list more
    /// than [`MAX_ENTRIES`] (never at one cell).
    fn try_build(mesh: &'a Mesh, cells: usize) -> Option<RayGrid<'a>> {
        let (lo, hi) = mesh.aabb();
        let ext = sub(hi, lo);
        let longest = ext[0].max(ext[1]).max(ext[2]);
        let cell = if longest > 0.0 && longest.is_finite() {
            longest / cells.max(1) as f64
        } else {
            1.0
        };
        let dims = ext.map(|e| ((e / cell).floor() as usize + 1).clamp(1, cells.max(1) + 1));
        let mut grid = RayGrid {
            mesh,
            min: lo,
            cell,
            dims,
            start: vec![0; dims[0] * dims[1] * dims[2] + 1],
            faces: Vec::new(),
            eps: 1e-9 * norm(ext).max(f64::MIN_POSITIVE),
        };
        // Each face's cell range (in parallel), then count and fill (CSR).
        let ranges: Vec<([usize; 3], [usize; 3])> = (0..mesh.face_count())
            .into_par_iter()
            .map(|f| grid.cell_range(f))
            .collect();
        let span =
            |(a, b): &([usize; 3], [usize; 3])| (0..3).map(|k| b[k] - a[k] + 1).product::<usize>();
        let total: usize = ranges.iter().map(span).sum();
        if total > MAX_ENTRIES && cells > 1 {
            return None;
        }
        let each = |visit: &mut dyn FnMut(usize, usize)| {
            for (f, (a, b)) in ranges.iter().enumerate() {
                for z in a[2]..=b[2] {
                    for y in a[1]..=b[1] {
                        for x in a[0]..=b[0] {
                            visit(f, (z * dims[1] + y) * dims[0] + x);
                        }
                    }
                }
            }
        };
        each(&mut |_, c| grid.start[c + 1] += 1);
        for c in 1..grid.start.len() {
            grid.start[c] += grid.start[c - 1];
        }
        let mut next: Vec<u32> = grid.start[..grid.start.len() - 1].to_vec();
        let mut faces = vec![0u32; total];
        each(&mut |f, c| {
            faces[next[c] as usize] = f as u32;
            next[c] += 1;
        });
        grid.faces = faces;
        Some(grid)
    }

    fn index(&self, c: [usize; 3]) -> usize {
        (c[2] * self.dims[1] + c[1]) * self.dims[0] + c[0]
    }

    fn clamp_cell(&self, p: V3) -> [usize; 3] {
        [0, 1, 2].map(|k| {
            let x = ((p[k] - self.min[k]) / self.cell).floor();
            if x.is_nan() || x < 0.0 {
                0
            } else {
                (x as usize).min(self.dims[k] - 1)
            }
        })
    }

    /// The first and last cell of face `f`'s AABB.
    fn cell_range(&self, f: usize) -> ([usize; 3], [usize; 3]) {
        let vs = self.mesh.face(f);
        let (lo, hi) = super::aabb_of(vs.iter().map(|&v| self.mesh.pos(v)));
        (self.clamp_cell(lo), self.clamp_cell(hi))
    }

    /// Whether the ray from `p` along unit `d` meets a face other than `own` (at a
    /// distance past `eps`): walks the cells it crosses (3D DDA, Amanatides–Woo) and
    /// tests their faces' fan triangles exactly.
    pub fn blocked(&self, p: V3, d: V3, own: u32) -> bool {
        // Where the ray enters the grid's box (it starts inside: p is on a face).
        let mut c = self.clamp_cell(p);
        let mut t_max = [f64::INFINITY; 3];
        let mut t_delta = [f64::INFINITY; 3];
        let mut step = [0isize; 3];
        for k in 0..3 {
            if d[k] > 0.0 {
                step[k] = 1;
                t_max[k] = (self.min[k] + (c[k] + 1) as f64 * self.cell - p[k]) / d[k];
                t_delta[k] = self.cell / d[k];
            } else if d[k] < 0.0 {
                step[k] = -1;
                t_max[k] = (self.min[k] + c[k] as f64 * self.cell - p[k]) / d[k];
                t_delta[k] = -self.cell / d[k];
            }
        }
        loop {
            let i = self.index(c);
            let list = &self.faces[self.start[i] as usize..self.start[i + 1] as usize];
            if list.iter().any(|&f| f != own && self.hits(f, p, d)) {
                return true;
            }
            let k = if t_max[0] <= t_max[1] && t_max[0] <= t_max[2] {
                0
            } else if t_max[1] <= t_max[2] {
                1
            } else {
                2
            };
            let next = c[k] as isize + step[k];
            if step[k] == 0 || next < 0 || next as usize >= self.dims[k] {
                return false;
            }
            c[k] = next as usize;
            t_max[k] += t_delta[k];
        }
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

/// Area-weighted mean of [`RayGrid::side_score`] over `quota` faces spread evenly
/// through `members` (all when fewer; unit outward normals by `sign`, rays from each
/// face's centroid), or `None` when none has area: > 0 when the patch's present
/// winding faces outside.
pub fn vote(grid: &RayGrid, members: &[usize], sign: &[i8], quota: usize) -> Option<f64> {
    let mesh = grid.mesh;
    let (mut sum, mut area) = (0.0, 0.0);
    let q = quota.clamp(1, members.len().max(1));
    for i in 0..q.min(members.len()) {
        let f = members[i * members.len() / q];
        let Some((n, c, len)) = super::outward_normal_and_centre(mesh, sign, f as u32) else {
            continue;
        };
        sum += 0.5 * len * f64::from(grid.side_score(c, n, f as u32));
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
        let grid = RayGrid::build(&m, CELLS);
        let c = sub([0.5, 0.0, 0.5], m.offset);
        assert!(!grid.blocked(c, [0.0, -1.0, 0.0], 0));
        assert!(grid.blocked(c, [0.0, 1.0, 0.0], 0));
        assert_eq!(grid.side_score(c, [0.0, -1.0, 0.0], 0), 5);
        assert_eq!(grid.side_score(c, [0.0, 1.0, 0.0], 0), -5);
        // The square alone: both sides are open, the vote says nothing.
        let m = Mesh::from_polygons(&p[..4], &[vec![0, 3, 2, 1]]).unwrap();
        let grid = RayGrid::build(&m, CELLS);
        let c = sub([0.5, 0.0, 0.5], m.offset);
        assert_eq!(grid.side_score(c, [0.0, 1.0, 0.0], 0), 0);
        // A wall of two sheets 0.001 apart: from the lower, up is blocked at once.
        let mut q = p[..4].to_vec();
        q.extend(p[..4].iter().map(|v| [v[0], 0.001, v[2]]));
        let m = Mesh::from_polygons(&q, &[vec![0, 3, 2, 1], vec![4, 5, 6, 7]]).unwrap();
        let grid = RayGrid::build(&m, CELLS);
        let c = sub([0.5, 0.0, 0.5], m.offset);
        assert_eq!(grid.side_score(c, [0.0, -1.0, 0.0], 0), 5);
    }

    /// Faces that each span most of the box (3,000 triangles across a sphere, each
    /// joining two nearly opposite points; up to 73 M entries at the 29 cells their count
    /// asks for) coarsen the grid until it lists at most `MAX_ENTRIES`, and rays
    /// still meet them.
    #[test]
    fn giant_faces_coarsen_the_grid() {
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
        let grid = RayGrid::build(&m, CELLS);
        assert!(
            grid.faces.len() <= MAX_ENTRIES,
            "{} entries",
            grid.faces.len()
        );
        assert!(grid
            .dims
            .iter()
            .all(|&d| d < 2 * (n as f64).cbrt() as usize));
        // From the centre, some ray meets a face.
        let c = [0.0; 3];
        let hits = [
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [-1.0, 0.0, 0.0],
        ]
        .iter()
        .filter(|&&d| grid.blocked(c, d, 0))
        .count();
        assert!(hits > 0);
    }
}
