//! The scale ladder's inputs, written straight to binary PLY files (float32
//! positions, int32 triangle lists) without holding the large mesh in memory: a mesh
//! subdivided `levels` times (each triangle into 4^levels on its barycentric grid,
//! the topology of repeated 1-to-4 midpoint splits) with a small seeded displacement
//! of every new vertex, and a made-up city block of many separate parts (buildings,
//! pipes, props). Both are the same bytes for the same arguments on every machine.

use primdecomp::Mesh;
use std::io::{BufWriter, Write};
use std::path::Path;

/// A new vertex moves by up to this fraction of its sub-triangle's edge on each axis,
/// so that new vertices are not exact midpoints (a flat patch stays nearly flat).
const DISPLACEMENT: f64 = 0.05;

/// Faces and vertices of what [`subdivided_ply`] writes for `mesh` and `levels`.
pub fn subdivided_counts(mesh: &Mesh, levels: u32) -> (u64, u64) {
    let s = 1u64 << levels;
    let tris = triangles(mesh);
    let edges = edges(&tris).len() as u64;
    let inner = (s - 1) * s.saturating_sub(2) / 2;
    let verts = mesh.vertex_count() as u64 + edges * (s - 1) + tris.len() as u64 * inner;
    (tris.len() as u64 * s * s, verts)
}

/// Writes `mesh` (polygons fanned into triangles) with each triangle split into
/// 4^`levels` on its barycentric grid, every new vertex displaced by a hash of
/// `seed` and its index, to `path`; returns (faces, vertices) written. Memory: the
/// source mesh, its triangles and its sorted edges.
pub fn subdivided_ply(
    mesh: &Mesh,
    levels: u32,
    seed: u64,
    path: &Path,
) -> std::io::Result<(u64, u64)> {
    let g = Grid::new(mesh, levels);
    let (verts, faces) = g.counts();
    assert!(
        verts < i32::MAX as u64,
        "{verts} vertices do not fit int32 indices"
    );
    let mut w = BufWriter::with_capacity(1 << 20, std::fs::File::create(path)?);
    header(&mut w, verts, faces)?;
    g.write_points(&mut w, mesh, seed)?;
    g.write_faces(&mut w)?;
    w.flush()?;
    Ok((faces, verts))
}

/// A mesh's triangles on their barycentric grid of `s` steps a side: the source's
/// vertices first, then each edge's `s` − 1 points (edges sorted, `lo << 32 | hi`),
/// then each triangle's `inner` points.
struct Grid {
    s: u32,
    tris: Vec<[u32; 3]>,
    edges: Vec<u64>,
    nv: u64,
    per_edge: u64,
    inner: u64,
}

impl Grid {
    fn new(mesh: &Mesh, levels: u32) -> Grid {
        let s = 1u32 << levels;
        let tris = triangles(mesh);
        let edges = edges(&tris);
        Grid {
            s,
            tris,
            edges,
            nv: mesh.vertex_count() as u64,
            per_edge: u64::from(s - 1),
            inner: u64::from(s - 1) * u64::from(s.saturating_sub(2)) / 2,
        }
    }

    /// (vertices, faces) of the subdivided mesh.
    fn counts(&self) -> (u64, u64) {
        let ne = self.edges.len() as u64;
        let verts = self.nv + ne * self.per_edge + self.tris.len() as u64 * self.inner;
        let s = u64::from(self.s);
        (verts, self.tris.len() as u64 * s * s)
    }

    /// The id of the first triangle's first inner point.
    fn first_inner(&self) -> u64 {
        self.nv + self.edges.len() as u64 * self.per_edge
    }

    /// Every vertex in id order, each new one displaced by a hash of `seed` and its id.
    fn write_points(&self, w: &mut impl Write, mesh: &Mesh, seed: u64) -> std::io::Result<()> {
        let (s, nv, per_edge, inner) = (self.s, self.nv, self.per_edge, self.inner);
        let pos = |v: u32| mesh.world_pos(v);
        for v in 0..nv as u32 {
            point(w, pos(v))?;
        }
        // Edge points from the lower vertex id towards the higher.
        for (e, &key) in self.edges.iter().enumerate() {
            let (a, b) = (pos((key >> 32) as u32), pos(key as u32));
            let len = primdecomp_math::norm(primdecomp_math::sub(b, a));
            for i in 1..s {
                let id = nv + e as u64 * per_edge + u64::from(i - 1);
                let t = f64::from(i) / f64::from(s);
                let p = std::array::from_fn(|k| a[k] + t * (b[k] - a[k]));
                point(w, displaced(p, len / f64::from(s), seed, id))?;
            }
        }
        let first_inner = self.first_inner();
        for (f, t) in self.tris.iter().enumerate() {
            let [a, b, c] = t.map(pos);
            let len = [(a, b), (b, c), (c, a)]
                .map(|(p, q)| primdecomp_math::norm(primdecomp_math::sub(q, p)))
                .into_iter()
                .fold(0.0, f64::max);
            for (id, (i, j)) in (first_inner + f as u64 * inner..).zip(inner_points(s)) {
                let (u, v) = (f64::from(i) / f64::from(s), f64::from(j) / f64::from(s));
                let p = std::array::from_fn(|k| a[k] + u * (b[k] - a[k]) + v * (c[k] - a[k]));
                point(w, displaced(p, len / f64::from(s), seed, id))?;
            }
        }
        Ok(())
    }

    /// Every triangle's s² small triangles, row by row of its grid.
    fn write_faces(&self, w: &mut impl Write) -> std::io::Result<()> {
        let (s, nv, per_edge, inner) = (self.s, self.nv, self.per_edge, self.inner);
        let first_inner = self.first_inner();
        let edge_point = |x: u32, y: u32, k: u32| -> u64 {
            let key = (u64::from(x.min(y)) << 32) | u64::from(x.max(y));
            let e = self
                .edges
                .binary_search(&key)
                .expect("every side is an edge") as u64;
            let k = if x < y { k } else { s - k };
            nv + e * per_edge + u64::from(k - 1)
        };
        for (f, t) in self.tris.iter().enumerate() {
            let [a, b, c] = *t;
            let base = first_inner + f as u64 * inner;
            // Grid point (i, j): a + i/s (b − a) + j/s (c − a).
            let id = |i: u32, j: u32| -> u64 {
                match (i, j) {
                    (0, 0) => u64::from(a),
                    _ if i == s => u64::from(b),
                    _ if j == s => u64::from(c),
                    (_, 0) => edge_point(a, b, i),
                    (0, _) => edge_point(a, c, j),
                    _ if i + j == s => edge_point(b, c, j),
                    _ => base + inner_index(s, i, j),
                }
            };
            for j in 0..s {
                for i in 0..s - j {
                    tri(w, [id(i, j), id(i + 1, j), id(i, j + 1)])?;
                    if i + j + 1 < s {
                        tri(w, [id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)])?;
                    }
                }
            }
        }
        Ok(())
    }
}

/// The source's triangles (polygons fanned from their first corner).
fn triangles(mesh: &Mesh) -> Vec<[u32; 3]> {
    let mut out = Vec::with_capacity(mesh.face_count());
    for f in 0..mesh.face_count() {
        let v = mesh.face(f);
        out.extend((2..v.len()).map(|k| [v[0], v[k - 1], v[k]]));
    }
    out
}

/// Every side of the triangles once, as (lower id << 32 | higher id), sorted.
fn edges(tris: &[[u32; 3]]) -> Vec<u64> {
    let mut e: Vec<u64> = tris
        .iter()
        .flat_map(|t| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])])
        .map(|(x, y)| (u64::from(x.min(y)) << 32) | u64::from(x.max(y)))
        .collect();
    e.sort_unstable();
    e.dedup();
    e
}

/// The grid points strictly inside the triangle, in the order [`inner_index`] counts.
fn inner_points(s: u32) -> impl Iterator<Item = (u32, u32)> {
    (1..s).flat_map(move |j| (1..s - j).map(move |i| (i, j)))
}

/// The place of inner point (i, j) in [`inner_points`]' order.
fn inner_index(s: u32, i: u32, j: u32) -> u64 {
    // Rows j' < j hold s − 1 − j' points each.
    let before: u64 = (1..j).map(|r| u64::from(s - 1 - r)).sum();
    before + u64::from(i - 1)
}

/// `p` moved by up to [`DISPLACEMENT`] × `scale` on each axis, by a hash of `seed`
/// and the vertex `id`.
fn displaced(p: [f64; 3], scale: f64, seed: u64, id: u64) -> [f64; 3] {
    let mut h = splitmix(seed ^ id.wrapping_mul(0x9E37_79B9_7F4A_7C15));
    std::array::from_fn(|k| {
        h = splitmix(h);
        let unit = (h >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0;
        p[k] + DISPLACEMENT * scale * unit
    })
}

fn splitmix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

fn header(w: &mut impl Write, verts: u64, faces: u64) -> std::io::Result<()> {
    write!(
        w,
        "ply\nformat binary_little_endian 1.0\nelement vertex {verts}\nproperty float x\n\
         property float y\nproperty float z\nelement face {faces}\n\
         property list uchar int vertex_indices\nend_header\n"
    )
}

fn point(w: &mut impl Write, p: [f64; 3]) -> std::io::Result<()> {
    for c in p {
        w.write_all(&(c as f32).to_le_bytes())?;
    }
    Ok(())
}

fn tri(w: &mut impl Write, t: [u64; 3]) -> std::io::Result<()> {
    w.write_all(&[3u8])?;
    for v in t {
        w.write_all(&(v as i32).to_le_bytes())?;
    }
    Ok(())
}

/// A made-up city block: `parts` separate closed parts on a square site — tessellated
/// buildings (boxes whose sides are grids of quads split in two), pipes (capped
/// cylinders along x or y) and props (UV spheres and small crates) — written to
/// `path` in two passes (count, then write) so that nothing is held; returns (faces,
/// vertices). About 250 faces per part.
pub fn city_block_ply(parts: u32, seed: u64, path: &Path) -> std::io::Result<(u64, u64)> {
    let mut count = Counter::default();
    city_block(parts, seed, &mut count)?;
    let mut w = BufWriter::with_capacity(1 << 20, std::fs::File::create(path)?);
    header(&mut w, count.verts, count.faces)?;
    // Vertices first, then faces: two more passes with the same seed.
    city_block(parts, seed, &mut Points(&mut w))?;
    city_block(parts, seed, &mut Faces { w: &mut w, next: 0 })?;
    w.flush()?;
    Ok((count.faces, count.verts))
}

/// Where the city block's parts go: each part's vertices, then its triangles (local
/// indices).
trait Sink {
    fn part(&mut self, verts: &[[f64; 3]], tris: &[[u32; 3]]) -> std::io::Result<()>;
}

#[derive(Default)]
struct Counter {
    faces: u64,
    verts: u64,
}

impl Sink for Counter {
    fn part(&mut self, verts: &[[f64; 3]], tris: &[[u32; 3]]) -> std::io::Result<()> {
        self.verts += verts.len() as u64;
        self.faces += tris.len() as u64;
        Ok(())
    }
}

struct Points<'a, W: Write>(&'a mut W);

impl<W: Write> Sink for Points<'_, W> {
    fn part(&mut self, verts: &[[f64; 3]], _: &[[u32; 3]]) -> std::io::Result<()> {
        verts.iter().try_for_each(|&p| point(self.0, p))
    }
}

struct Faces<'a, W: Write> {
    w: &'a mut W,
    next: u64,
}

impl<W: Write> Sink for Faces<'_, W> {
    fn part(&mut self, verts: &[[f64; 3]], tris: &[[u32; 3]]) -> std::io::Result<()> {
        for t in tris {
            tri(self.w, t.map(|v| self.next + u64::from(v)))?;
        }
        self.next += verts.len() as u64;
        Ok(())
    }
}

/// The parts of the block, in order, into `sink`.
fn city_block(parts: u32, seed: u64, sink: &mut impl Sink) -> std::io::Result<()> {
    let mut rng = splitmix(seed);
    let mut r = move || {
        rng = splitmix(rng);
        (rng >> 11) as f64 / (1u64 << 53) as f64
    };
    // Lots on a square grid, 20 units apart; each lot holds one part.
    let side = f64::from(parts).sqrt().ceil() as u32;
    let (mut verts, mut tris) = (Vec::new(), Vec::new());
    for p in 0..parts {
        let (gx, gy) = (f64::from(p % side) * 20.0, f64::from(p / side) * 20.0);
        verts.clear();
        tris.clear();
        match p % 8 {
            // One lot in eight: a building of 4–12 by 4–12 by 6–60 units.
            0 => {
                let size = [4.0 + 8.0 * r(), 4.0 + 8.0 * r(), 6.0 + 54.0 * r()];
                let cells = [
                    (size[0] / 1.5) as u32 + 1,
                    (size[1] / 1.5) as u32 + 1,
                    (size[2] / 1.5) as u32 + 1,
                ];
                grid_box(&mut verts, &mut tris, [gx, gy, 0.0], size, cells);
            }
            // Three in eight: pipes 6–16 long, radius 0.2–0.8, along x or y.
            1..=3 => {
                let (len, rad) = (6.0 + 10.0 * r(), 0.2 + 0.6 * r());
                let along_x = r() < 0.5;
                let h = 0.5 + 4.0 * r();
                cylinder(&mut verts, &mut tris, [gx, gy, h], len, rad, along_x, 16, 8);
            }
            // Two in eight: lamps and bollards as spheres of radius 0.3–1.5.
            4 | 5 => {
                let rad = 0.3 + 1.2 * r();
                sphere(&mut verts, &mut tris, [gx, gy, rad + 2.0 * r()], rad, 12, 8);
            }
            // Two in eight: crates of 1–3 units, each side a 3 × 3 grid.
            _ => {
                let s = 1.0 + 2.0 * r();
                grid_box(
                    &mut verts,
                    &mut tris,
                    [gx + 5.0 * r(), gy, 0.0],
                    [s, s, s],
                    [3, 3, 3],
                );
            }
        }
        sink.part(&verts, &tris)?;
    }
    Ok(())
}

/// A closed box from `lo` of `size`, each side a grid of `cells` quads (split in two),
/// with shared corner and edge vertices, outward windings.
fn grid_box(
    v: &mut Vec<[f64; 3]>,
    t: &mut Vec<[u32; 3]>,
    lo: [f64; 3],
    size: [f64; 3],
    cells: [u32; 3],
) {
    let [nx, ny, nz] = cells;
    let mut index = std::collections::HashMap::new();
    let mut id = |v: &mut Vec<[f64; 3]>, g: [u32; 3]| -> u32 {
        *index.entry(g).or_insert_with(|| {
            v.push(std::array::from_fn(|k| {
                lo[k] + size[k] * f64::from(g[k]) / f64::from(cells[k])
            }));
            (v.len() - 1) as u32
        })
    };
    // Each side: the fixed axis k at 0 or its count, the other two (a, b) spanning it.
    for (k, a, b) in [(0usize, 1usize, 2usize), (1, 2, 0), (2, 0, 1)] {
        let n = [nx, ny, nz];
        for high in [false, true] {
            for i in 0..n[a] {
                for j in 0..n[b] {
                    let g = |di: u32, dj: u32| {
                        let mut g = [0u32; 3];
                        g[k] = if high { n[k] } else { 0 };
                        g[a] = i + di;
                        g[b] = j + dj;
                        g
                    };
                    let q = [g(0, 0), g(1, 0), g(1, 1), g(0, 1)].map(|g| id(v, g));
                    // (a, b, k) is right-handed: counter-clockwise seen from +k.
                    if high {
                        t.extend([[q[0], q[1], q[2]], [q[0], q[2], q[3]]]);
                    } else {
                        t.extend([[q[0], q[2], q[1]], [q[0], q[3], q[2]]]);
                    }
                }
            }
        }
    }
}

/// A capped cylinder from `start` along x (or y) of `len` and `rad`, `around` sides
/// and `along` rings.
#[allow(clippy::too_many_arguments)]
fn cylinder(
    v: &mut Vec<[f64; 3]>,
    t: &mut Vec<[u32; 3]>,
    start: [f64; 3],
    len: f64,
    rad: f64,
    along_x: bool,
    around: u32,
    along: u32,
) {
    let at = |s: f64, c: f64, d: f64| -> [f64; 3] {
        if along_x {
            [start[0] + s, start[1] + c, start[2] + d]
        } else {
            [start[0] + d, start[1] + s, start[2] + c]
        }
    };
    for r in 0..=along {
        for k in 0..around {
            let ang = std::f64::consts::TAU * f64::from(k) / f64::from(around);
            v.push(at(
                len * f64::from(r) / f64::from(along),
                rad * ang.cos(),
                rad * ang.sin(),
            ));
        }
    }
    let ring = |r: u32, k: u32| r * around + k % around;
    for r in 0..along {
        for k in 0..around {
            let q = [
                ring(r, k),
                ring(r + 1, k),
                ring(r + 1, k + 1),
                ring(r, k + 1),
            ];
            t.extend([[q[0], q[2], q[1]], [q[0], q[3], q[2]]]);
        }
    }
    // Caps: a centre point each, fanned.
    v.push(at(0.0, 0.0, 0.0));
    v.push(at(len, 0.0, 0.0));
    let (c0, c1) = (v.len() as u32 - 2, v.len() as u32 - 1);
    for k in 0..around {
        t.push([c0, ring(0, k + 1), ring(0, k)]);
        t.push([c1, ring(along, k), ring(along, k + 1)]);
    }
}

/// A UV sphere about `c` of `rad`, `around` × `rings` (poles one vertex each).
fn sphere(
    v: &mut Vec<[f64; 3]>,
    t: &mut Vec<[u32; 3]>,
    c: [f64; 3],
    rad: f64,
    around: u32,
    rings: u32,
) {
    let first = v.len() as u32;
    v.push([c[0], c[1], c[2] - rad]);
    for r in 1..rings {
        let phi = std::f64::consts::PI * f64::from(r) / f64::from(rings);
        for k in 0..around {
            let th = std::f64::consts::TAU * f64::from(k) / f64::from(around);
            v.push([
                c[0] + rad * phi.sin() * th.cos(),
                c[1] + rad * phi.sin() * th.sin(),
                c[2] - rad * phi.cos(),
            ]);
        }
    }
    v.push([c[0], c[1], c[2] + rad]);
    let top = v.len() as u32 - 1;
    let at = |r: u32, k: u32| first + 1 + (r - 1) * around + k % around;
    for k in 0..around {
        t.push([first, at(1, k + 1), at(1, k)]);
        t.push([top, at(rings - 1, k), at(rings - 1, k + 1)]);
    }
    for r in 1..rings - 1 {
        for k in 0..around {
            let q = [at(r, k), at(r, k + 1), at(r + 1, k + 1), at(r + 1, k)];
            t.extend([[q[0], q[1], q[2]], [q[0], q[2], q[3]]]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A subdivided cube: 4^levels faces per triangle, the vertex count the formula
    /// gives, closed (every edge shared by two faces after loading), and the same
    /// bytes twice.
    #[test]
    fn a_subdivided_cube_is_closed_and_repeatable() {
        let cube = crate::shapes::mesh(&crate::shapes::cuboid([0.0; 3], [1.0, 2.0, 3.0]));
        let dir = std::env::temp_dir();
        for levels in 1..=3 {
            let path = dir.join(format!(
                "primdecomp_ladder_cube_{levels}_{}.ply",
                std::process::id()
            ));
            let (f, v) = subdivided_ply(&cube, levels, 7, &path).unwrap();
            assert_eq!((f, v), subdivided_counts(&cube, levels));
            assert_eq!(f, 12 * 4u64.pow(levels));
            let m = primdecomp::Mesh::load(&path).unwrap();
            assert_eq!((m.face_count() as u64, m.vertex_count() as u64), (f, v));
            let first = std::fs::read(&path).unwrap();
            subdivided_ply(&cube, levels, 7, &path).unwrap();
            assert_eq!(first, std::fs::read(&path).unwrap());
            let mut sides: Vec<(u32, u32)> = (0..m.face_count())
                .flat_map(|i| {
                    let t = m.face(i).to_vec();
                    (0..3).map(move |k| (t[k].min(t[(k + 1) % 3]), t[k].max(t[(k + 1) % 3])))
                })
                .collect();
            sides.sort_unstable();
            let mut runs = sides.chunk_by(|a, b| a == b);
            assert!(
                runs.all(|r| r.len() == 2),
                "level {levels}: an edge is not shared by two faces"
            );
            let _ = std::fs::remove_file(&path);
        }
    }

    /// The city block: as many parts as asked, each closed, the counts the header says.
    #[test]
    fn a_city_block_has_its_parts() {
        let path = std::env::temp_dir().join(format!("primdecomp_city_{}.ply", std::process::id()));
        let (f, v) = city_block_ply(40, 3, &path).unwrap();
        let m = primdecomp::Mesh::load(&path).unwrap();
        assert_eq!((m.face_count() as u64, m.vertex_count() as u64), (f, v));
        let mut sides: Vec<(u32, u32)> = (0..m.face_count())
            .flat_map(|i| {
                let t = m.face(i).to_vec();
                (0..3).map(move |k| (t[k].min(t[(k + 1) % 3]), t[k].max(t[(k + 1) % 3])))
            })
            .collect();
        sides.sort_unstable();
        assert!(sides.chunk_by(|a, b| a == b).all(|r| r.len() == 2));
        let _ = std::fs::remove_file(&path);
    }
}
