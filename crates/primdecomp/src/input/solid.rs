//! The input's interior on a voxel grid, for pricing merges by the empty space they
//! add (`Plates::solid`, docs/decisions/0023-merges-priced-by-the-air-they-add.md; not in the
//! paper, whose §3.3
//! cost is a primitive's whole volume).
//!
//! The paper prices a merge by the volume it adds, so a closed part's six faces stay
//! six thin plates as long as cheaper merges exist: filling the part costs its volume
//! although that volume is the part itself. With this grid, volume inside the input
//! is free and only volume outside it (air: gaps, holes, the space above a roof) is
//! priced.
//!
//! Inside is decided by ray parity voted over the six axis directions: from each
//! cell's centre, a ray along ±x, ±y and ±z that crosses the surface an odd number of
//! times votes inside. Game assets leave hidden faces out (a wall's bottom, where two
//! parts meet), so one ray can miss a wall that the others see; a cell is inside when
//! at least [`VOTES`] of the six agree. Crossings are counted per grid column: every
//! triangle (polygons fanned) is tested against the columns its projection covers,
//! with the top-left rule so that a ray through a shared edge counts once. Only
//! parities are kept, so a face given twice (two-sided) cancels itself: such a part
//! has no inside and is priced as in the paper, never filled by mistake.

use super::mesh::Mesh;
use crate::math::V3;
use crate::primitive::Primitive;

/// Cells along the input's longest side.
pub const CELLS: usize = 64;
/// Rays of six that must cross the surface an odd number of times for a cell to be
/// inside.
pub const VOTES: u8 = 5;
/// Most samples per axis of a primitive's bounding box when measuring its inside
/// fraction.
const SAMPLES: usize = 8;

/// Which cells of a regular grid over the input's bounds are inside it.
#[derive(Clone, Debug, Default)]
pub struct Solid {
    lo: V3,
    cell: f64,
    dims: [usize; 3],
    inside: Vec<bool>,
    /// Inside cells in `[0, i) × [0, j) × [0, k)`, at `((k·(ny+1) + j)·(nx+1) + i)`: a
    /// box of cells is counted in O(1), so a primitive over no inside cell (or only
    /// inside cells) needs no sampling.
    prefix: Vec<u32>,
    /// Whether the input has an edge only one face holds (the adjacency's count,
    /// `adjacency::face_pairs_checked`): its inside is then the vote's alone, and the cut measures to its surface (docs/decisions/0056).
    open: bool,
}

impl Solid {
    /// The interior of `mesh` on a grid of `cells` along its longest side, a cell
    /// inside when at least `votes` of its six axis rays cross the surface an odd
    /// number of times. An empty or flat input has no inside.
    pub fn build(mesh: &Mesh, cells: usize, votes: u8) -> Solid {
        let (lo, hi) = mesh.aabb();
        let side = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
        if !(side > 0.0 && side.is_finite()) || cells == 0 {
            return Solid::default();
        }
        let cell = side / cells as f64;
        let dims = [0, 1, 2].map(|k| (((hi[k] - lo[k]) / cell).ceil() as usize).clamp(1, cells));
        let mut s = Solid {
            lo,
            cell,
            dims,
            inside: Vec::new(),
            prefix: Vec::new(),
            open: false,
        };
        let mut count = vec![0u8; dims[0] * dims[1] * dims[2]];
        for axis in 0..3 {
            s.vote_along(mesh, axis, &mut count);
        }
        s.inside = count.into_iter().map(|c| c >= votes).collect();
        s.prefix = s.prefix_sums();
        s
    }

    /// Whether the cell holding `p` is inside (false outside the grid).
    pub fn contains(&self, p: V3) -> bool {
        self.cell_of(p)
            .is_some_and(|idx| self.inside[self.index(idx)])
    }

    /// The cell holding `p` (`None` outside the grid).
    fn cell_of(&self, p: V3) -> Option<[usize; 3]> {
        let mut idx = [0usize; 3];
        for k in 0..3 {
            let t = (p[k] - self.lo[k]) / self.cell;
            if !(t >= 0.0 && t < self.dims[k] as f64) {
                return None;
            }
            idx[k] = t as usize;
        }
        Some(idx)
    }

    /// The centre nearest `p` of an inside cell among the cell holding `p` and its 26
    /// neighbours (`None` outside the grid or where none is inside): a point the rays'
    /// vote put inside, from which any point reached without crossing a face is inside
    /// too (`Triangles::inside`). The cell's own centre when it is inside.
    pub fn inside_centre(&self, p: V3) -> Option<V3> {
        let idx = self.cell_of(p)?;
        let centre = |c: [usize; 3]| [0, 1, 2].map(|k| self.centre(k, c[k]));
        if self.inside[self.index(idx)] {
            return Some(centre(idx));
        }
        let span = |k: usize| idx[k].saturating_sub(1)..(idx[k] + 2).min(self.dims[k]);
        let mut best: Option<(f64, V3)> = None;
        for k in span(2) {
            for j in span(1) {
                for i in span(0) {
                    if !self.inside[self.index([i, j, k])] {
                        continue;
                    }
                    let c = centre([i, j, k]);
                    let d2 = (0..3).map(|a| (c[a] - p[a]).powi(2)).sum::<f64>();
                    if best.is_none_or(|(b, _)| d2 < b) {
                        best = Some((d2, c));
                    }
                }
            }
        }
        best.map(|(_, c)| c)
    }

    /// This interior, of an input that is `open` (an edge one face holds) or not.
    pub(crate) fn with_open(self, open: bool) -> Solid {
        Solid { open, ..self }
    }

    /// Whether the input this interior is of has an edge only one face holds.
    pub(crate) fn is_open(&self) -> bool {
        self.open
    }

    /// Whether any cell is inside (an empty, flat or two-sided input has none).
    pub fn has_inside(&self) -> bool {
        self.prefix.last().is_some_and(|&n| n > 0)
    }

    /// The fraction of `prim` inside the input, from a regular sample of its bounding
    /// box (samples outside the primitive are skipped): one sample per cell it spans
    /// along each axis, at most [`SAMPLES`], so a primitive within one cell costs one
    /// lookup; 0 when no sample falls in the primitive or the input has no inside.
    pub fn inside_fraction(&self, prim: &Primitive) -> f64 {
        if self.inside.is_empty() {
            return 0.0;
        }
        let (lo, hi) = prim.aabb();
        match self.cells_inside(lo, hi) {
            (0, _) => return 0.0,
            (n, all) if n == all => return 1.0,
            _ => {}
        }
        let n = [0, 1, 2].map(|k| {
            ((hi[k] - lo[k]) / self.cell)
                .ceil()
                .clamp(1.0, SAMPLES as f64) as usize
        });
        let at = |k: usize, i: usize| lo[k] + (i as f64 + 0.5) / n[k] as f64 * (hi[k] - lo[k]);
        let (mut within, mut solid) = (0u32, 0u32);
        for i in 0..n[0] {
            for j in 0..n[1] {
                for l in 0..n[2] {
                    let p = [at(0, i), at(1, j), at(2, l)];
                    if prim.contains(p, 0.0) {
                        within += 1;
                        solid += u32::from(self.contains(p));
                    }
                }
            }
        }
        if within == 0 {
            0.0
        } else {
            f64::from(solid) / f64::from(within)
        }
    }

    /// (inside cells, all cells) among the cells the box [lo, hi] touches (clamped
    /// to the grid; (0, 0) when it misses the grid or is not finite).
    fn cells_inside(&self, lo: V3, hi: V3) -> (u32, u32) {
        let mut r = [(0usize, 0usize); 3];
        for k in 0..3 {
            let a = ((lo[k] - self.lo[k]) / self.cell).floor();
            let b = ((hi[k] - self.lo[k]) / self.cell).floor() + 1.0;
            let n = self.dims[k] as f64;
            if !(a < n && b > 0.0) {
                return (0, 0);
            }
            r[k] = (a.max(0.0) as usize, b.min(n) as usize);
        }
        let (nx, ny) = (self.dims[0] + 1, self.dims[1] + 1);
        let at = |i: usize, j: usize, k: usize| i64::from(self.prefix[(k * ny + j) * nx + i]);
        let [(i0, i1), (j0, j1), (k0, k1)] = r;
        let n = at(i1, j1, k1) - at(i0, j1, k1) - at(i1, j0, k1) - at(i1, j1, k0)
            + at(i0, j0, k1)
            + at(i0, j1, k0)
            + at(i1, j0, k0)
            - at(i0, j0, k0);
        let all = (i1 - i0) * (j1 - j0) * (k1 - k0);
        (n as u32, all as u32)
    }

    /// The summed-volume table of the inside cells (see `prefix`).
    fn prefix_sums(&self) -> Vec<u32> {
        let [dx, dy, dz] = self.dims;
        let (nx, ny) = (dx + 1, dy + 1);
        let at = |i: usize, j: usize, k: usize| (k * ny + j) * nx + i;
        let mut p = vec![0u32; nx * ny * (dz + 1)];
        for k in 0..dz {
            for j in 0..dy {
                for i in 0..dx {
                    let v = u32::from(self.inside[self.index([i, j, k])]);
                    p[at(i + 1, j + 1, k + 1)] = v
                        + p[at(i, j + 1, k + 1)]
                        + p[at(i + 1, j, k + 1)]
                        + p[at(i + 1, j + 1, k)]
                        - p[at(i, j, k + 1)]
                        - p[at(i, j + 1, k)]
                        - p[at(i + 1, j, k)]
                        + p[at(i, j, k)];
                }
            }
        }
        p
    }

    /// How many cells are inside.
    #[cfg(test)]
    pub fn inside_cells(&self) -> usize {
        self.inside.iter().filter(|&&b| b).count()
    }

    fn index(&self, [i, j, k]: [usize; 3]) -> usize {
        (k * self.dims[1] + j) * self.dims[0] + i
    }

    /// The centre of cell `i` along axis `k`.
    fn centre(&self, k: usize, i: usize) -> f64 {
        self.lo[k] + (i as f64 + 0.5) * self.cell
    }

    /// Adds the votes of the rays along `axis` (both directions) to every cell. Each
    /// column keeps only the parity of the crossings between consecutive cell centres
    /// (`dims[axis] + 1` intervals), so memory stays at one byte per interval however
    /// many triangles cross it.
    fn vote_along(&self, mesh: &Mesh, axis: usize, count: &mut [u8]) {
        let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
        let len = self.dims[axis] + 1;
        let mut odd = vec![false; self.dims[u] * self.dims[v] * len];
        for_each_triangle(mesh, |t| self.cross_columns(t, axis, &mut odd));
        for (col, runs) in odd.chunks_exact(len).enumerate() {
            let total = runs.iter().fold(false, |p, &r| p ^ r);
            let (i, j) = (col % self.dims[u], col / self.dims[u]);
            let mut below = false;
            for (a, &r) in runs[..self.dims[axis]].iter().enumerate() {
                below ^= r;
                let mut idx = [0; 3];
                (idx[axis], idx[u], idx[v]) = (a, i, j);
                count[self.index(idx)] += u8::from(below) + u8::from(total ^ below);
            }
        }
    }

    /// Flips the parity of the interval where triangle `t` crosses each column along
    /// `axis` through its projection (columns at cell centres; top-left rule on the
    /// projected edges). Interval `j` lies between centres `j − 1` and `j`; a crossing
    /// exactly at a centre counts below it.
    fn cross_columns(&self, t: [V3; 3], axis: usize, odd: &mut [bool]) {
        let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
        let mut p = t.map(|q| [q[u], q[v]]);
        let mut h = t.map(|q| q[axis]);
        let area = orient(p[0], p[1], p[2]);
        if area == 0.0 || !area.is_finite() {
            return;
        }
        if area < 0.0 {
            p.swap(1, 2);
            h.swap(1, 2);
        }
        let area = area.abs();
        let range = |k: usize, a: f64, b: f64| {
            let lo = ((a - self.lo[k]) / self.cell - 0.5).ceil().max(0.0) as usize;
            let hi = ((b - self.lo[k]) / self.cell - 0.5).floor();
            (
                lo,
                if hi < 0.0 {
                    0
                } else {
                    (hi as usize + 1).min(self.dims[k])
                },
            )
        };
        let (ulo, uhi) = range(u, min3(p.map(|q| q[0])), max3(p.map(|q| q[0])));
        let (vlo, vhi) = range(v, min3(p.map(|q| q[1])), max3(p.map(|q| q[1])));
        let len = self.dims[axis] + 1;
        for j in vlo..vhi {
            for i in ulo..uhi {
                let c = [self.centre(u, i), self.centre(v, j)];
                let w = [
                    edge(p[1], p[2], c),
                    edge(p[2], p[0], c),
                    edge(p[0], p[1], c),
                ];
                let [Some(w0), Some(w1), Some(w2)] = w else {
                    continue;
                };
                let at = (w0 * h[0] + w1 * h[1] + w2 * h[2]) / area;
                // The number of centres strictly below `at`: its interval.
                let below = ((at - self.lo[axis]) / self.cell - 0.5).ceil();
                let slot = below.clamp(0.0, (len - 1) as f64) as usize;
                odd[(j * self.dims[u] + i) * len + slot] ^= true;
            }
        }
    }
}

/// Twice the signed area of the 2D triangle (a, b, c); positive when counter-clockwise.
fn orient(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// The edge function of the counter-clockwise edge a → b at `c` when `c` is on its
/// inner side, or on it and the edge is a top or left edge (so a point on an edge
/// shared by two triangles belongs to exactly one); `None` when outside.
fn edge(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> Option<f64> {
    // From the lesser endpoint, so that the two triangles sharing the edge (which run
    // it in opposite directions) get exactly opposite values: rounded separately, both
    // could be slightly positive and the point counted twice.
    let w = if (a[0], a[1]) <= (b[0], b[1]) {
        orient(a, b, c)
    } else {
        -orient(b, a, c)
    };
    let top_left = (b[1] == a[1] && b[0] < a[0]) || b[1] < a[1];
    (w > 0.0 || (w == 0.0 && top_left)).then_some(w)
}

fn min3(a: [f64; 3]) -> f64 {
    a[0].min(a[1]).min(a[2])
}

fn max3(a: [f64; 3]) -> f64 {
    a[0].max(a[1]).max(a[2])
}

/// Calls `f` on each triangle of the faces' fans.
fn for_each_triangle(mesh: &Mesh, mut f: impl FnMut([V3; 3])) {
    for face in 0..mesh.face_count() {
        let vs = mesh.face(face);
        let a = mesh.pos(vs[0]);
        for w in vs[1..].windows(2) {
            f([a, mesh.pos(w[0]), mesh.pos(w[1])]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::primitive::{Obb, Sphere};

    /// The quads as a mesh; it is re-centred, so queries go through [`at`].
    fn mesh_of(quads: &[[V3; 4]]) -> Mesh {
        let mut b = super::super::mesh::MeshBuilder::new();
        for q in quads {
            let base = b.positions.len() as u32;
            b.positions.extend_from_slice(q);
            b.push_face(&[base, base + 1, base + 2, base + 3]);
        }
        Mesh::from_builder(b)
    }

    /// `p` in the mesh's re-centred coordinates.
    fn at(m: &Mesh, p: V3) -> V3 {
        [p[0] - m.offset[0], p[1] - m.offset[1], p[2] - m.offset[2]]
    }

    /// The six faces of the box [lo, hi], outward windings; `skip` leaves faces out.
    fn box_quads(lo: V3, hi: V3, skip: &[usize]) -> Vec<[V3; 4]> {
        let c = |i: usize| {
            [
                if i & 1 == 0 { lo[0] } else { hi[0] },
                if i & 2 == 0 { lo[1] } else { hi[1] },
                if i & 4 == 0 { lo[2] } else { hi[2] },
            ]
        };
        (0..6)
            .filter(|f| !skip.contains(f))
            .map(|f| crate::input::demo::BOX_FACES[f].map(c))
            .collect()
    }

    fn cube(skip: &[usize]) -> Mesh {
        mesh_of(&box_quads([0.0; 3], [1.0, 0.5, 2.0], skip))
    }

    proptest::proptest! {
        /// A closed box, anywhere and of any proportions: a cell is inside exactly
        /// when its centre is strictly inside the box (every ray from an inner point
        /// crosses one face, through edges and corners too by the top-left rule; from
        /// an outer point none or two), and centres on a face are never inside twice.
        #[test]
        fn cells_of_a_box_follow_their_centres(
            lo in proptest::array::uniform3(-5i32..5),
            size in proptest::array::uniform3(1i32..6),
            other in proptest::array::uniform3(-8i32..8),
            cells in 4usize..24,
        ) {
            // Corners on a quarter grid, so that faces often pass through cell centres.
            let lo = lo.map(|c| f64::from(c) * 0.25);
            let hi = [0, 1, 2].map(|k| lo[k] + f64::from(size[k]) * 0.25);
            // A far vertex-only point stretches the grid without adding a face.
            let mut q = box_quads(lo, hi, &[]);
            let o = other.map(|c| f64::from(c) * 0.25);
            q.push([o, o, o, o]);
            let m = mesh_of(&q);
            let s = Solid::build(&m, cells, 6);
            for k in 0..s.dims[2] {
                for j in 0..s.dims[1] {
                    for i in 0..s.dims[0] {
                        let c = [s.centre(0, i), s.centre(1, j), s.centre(2, k)];
                        let w = [0, 1, 2].map(|a| c[a] + m.offset[a]);
                        let strictly = (0..3).all(|a| w[a] > lo[a] && w[a] < hi[a]);
                        let on = (0..3).all(|a| w[a] >= lo[a] && w[a] <= hi[a]);
                        let got = s.inside[s.index([i, j, k])];
                        if strictly {
                            proptest::prop_assert!(got, "centre {:?} inside {:?}..{:?}", w, lo, hi);
                        } else if !on {
                            proptest::prop_assert!(!got, "centre {:?} outside {:?}..{:?}", w, lo, hi);
                        }
                    }
                }
            }
        }
    }

    proptest::proptest! {
        /// The summed-volume count of any box of cells equals counting them one by one.
        #[test]
        fn cell_counts_match_a_scan(
            lo in proptest::array::uniform3(-0.3f64..1.2),
            size in proptest::array::uniform3(0.0f64..1.0),
        ) {
            let mut q = box_quads([0.0; 3], [0.5, 0.6, 0.7], &[]);
            q.extend(box_quads([0.6, 0.0, 0.0], [1.0, 0.3, 0.2], &[3]));
            let m = mesh_of(&q);
            let s = Solid::build(&m, 12, VOTES);
            let lo = [0, 1, 2].map(|k| lo[k] - m.offset[k]);
            let hi = [0, 1, 2].map(|k| lo[k] + size[k]);
            let mut scan = (0, 0);
            for k in 0..s.dims[2] {
                for j in 0..s.dims[1] {
                    for i in 0..s.dims[0] {
                        let idx = [i, j, k];
                        let touched = (0..3).all(|a| {
                            let c0 = s.lo[a] + idx[a] as f64 * s.cell;
                            let first = ((lo[a] - s.lo[a]) / s.cell).floor();
                            let last = ((hi[a] - s.lo[a]) / s.cell).floor();
                            let n = ((c0 - s.lo[a]) / s.cell).round();
                            n >= first && n <= last
                        });
                        if touched {
                            scan.1 += 1;
                            scan.0 += u32::from(s.inside[s.index(idx)]);
                        }
                    }
                }
            }
            proptest::prop_assert_eq!(s.cells_inside(lo, hi), scan);
        }
    }

    #[test]
    fn a_closed_box_is_inside_everywhere_and_nothing_beyond() {
        let m = cube(&[]);
        let s = Solid::build(&m, 16, VOTES);
        assert_eq!(
            s.inside_cells(),
            s.inside.len(),
            "every cell of a box is inside"
        );
        assert!(s.contains(at(&m, [0.5, 0.25, 1.0])));
        assert!(!s.contains(at(&m, [1.5, 0.25, 1.0])));
        assert!(!s.contains(at(&m, [-0.01, 0.25, 1.0])));
    }

    #[test]
    fn one_missing_face_still_leaves_the_box_solid_two_do_not() {
        // A game asset's hidden bottom face: the other five rays still see walls.
        let s = Solid::build(&cube(&[2]), 16, VOTES);
        assert_eq!(s.inside_cells(), s.inside.len());
        // Two opposite faces missing (a tube): only four rays can cross.
        let s = Solid::build(&cube(&[2, 3]), 16, VOTES);
        assert_eq!(s.inside_cells(), 0);
    }

    #[test]
    fn two_boxes_leave_the_gap_between_them_outside() {
        let mut q = box_quads([0.0; 3], [1.0, 1.0, 1.0], &[]);
        q.extend(box_quads([2.0, 0.0, 0.0], [3.0, 1.0, 1.0], &[]));
        let m = mesh_of(&q);
        let s = Solid::build(&m, 30, VOTES);
        assert!(s.contains(at(&m, [0.5, 0.5, 0.5])));
        assert!(s.contains(at(&m, [2.5, 0.5, 0.5])));
        assert!(!s.contains(at(&m, [1.5, 0.5, 0.5])));
        let gap = Primitive::Box(Obb {
            center: at(&m, [1.5, 0.5, 0.5]),
            axes: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            half: [0.45, 0.45, 0.45],
        });
        assert_eq!(s.inside_fraction(&gap), 0.0);
        let both = Primitive::Box(Obb {
            center: at(&m, [1.5, 0.5, 0.5]),
            axes: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            half: [1.5, 0.5, 0.5],
        });
        let f = s.inside_fraction(&both);
        // 8 samples across: 6 land in the boxes (0.75), the exact share is 2/3.
        assert!(
            (f - 2.0 / 3.0).abs() <= 0.1,
            "two thirds of the span is solid: {f}"
        );
    }

    #[test]
    fn doubled_faces_and_flat_inputs_have_no_inside() {
        // A single quad, and the same quad twice (a two-sided decal): flat, no inside.
        let quad = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        let s = Solid::build(&mesh_of(&[quad, quad]), 16, VOTES);
        assert_eq!(s.inside_cells(), 0);
        let ball = Primitive::Sphere(Sphere {
            center: [0.0; 3],
            radius: 0.5,
        });
        assert_eq!(s.inside_fraction(&ball), 0.0);
        // Every face twice, once per winding (two-sided): each ray crosses each wall
        // twice, so parity sees no walls and the box has no inside — priced as the
        // paper does, never filled by mistake.
        let mut q = box_quads([0.0; 3], [1.0; 3], &[]);
        q.extend(box_quads([0.0; 3], [1.0; 3], &[]).into_iter().map(|mut f| {
            f.reverse();
            f
        }));
        let s = Solid::build(&mesh_of(&q), 8, VOTES);
        assert_eq!(s.inside_cells(), 0);
    }
}
