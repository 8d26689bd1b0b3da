//! Vertex deduplication (§3.4 "Vertex Deduplication"): overlapping vertices from
//! kit-bashed parts are merged so that adjacency sees them. Produces a table of each
//! vertex's weld target ([`Weld`]), read per corner; positions and face indices are
//! untouched (every vertex keeps its slot, and a vertex welds to the lowest-numbered
//! vertex of its group, so results do not depend on thread count).

use super::mesh::Mesh;
use crate::params::Dedup;
use crate::progress::Checkpoint;
use rayon::prelude::*;

/// Each mesh vertex's weld target: the lowest-numbered vertex of its group. A face's
/// welded corners are its own corners read through it ([`Weld::face`]). Empty when
/// no vertex moves (no duplicates, or welding off): every corner is its own. Four
/// bytes a vertex (about two a face on a closed mesh) where a welded copy of the
/// faces' indices took twelve a face.
#[derive(Clone, Debug, Default)]
pub struct Weld {
    target: Vec<u32>,
}

impl Weld {
    /// The weld where no vertex moves.
    #[cfg(any(test, feature = "test-internals"))]
    pub fn none() -> Self {
        Weld::default()
    }

    /// Vertex `v`'s weld target.
    #[inline]
    pub fn of(&self, v: u32) -> u32 {
        target_of(&self.target, v)
    }

    /// The vertex ids `ids` read through the weld.
    #[inline]
    pub fn corners<'a>(&'a self, ids: &'a [u32]) -> Corners<'a> {
        Corners {
            ids,
            weld: &self.target,
        }
    }

    /// The welded corners of face `f` of `mesh` (the mesh the weld was made for).
    #[inline]
    pub fn face<'a>(&'a self, mesh: &'a Mesh, f: usize) -> Corners<'a> {
        self.corners(mesh.face(f))
    }

    /// The weld of a sub-mesh whose vertex `l` is this mesh's `global[l]`, `local`
    /// giving the sub-mesh's id of a vertex it holds (every held vertex's target
    /// among them).
    pub(crate) fn restricted(&self, global: &[u32], local: impl Fn(u32) -> u32) -> Weld {
        let target = match self.target.is_empty() {
            true => Vec::new(),
            false => global.iter().map(|&v| local(self.of(v))).collect(),
        };
        Weld { target }
    }

    /// Every face's welded corners in order (the mesh's CSR offsets), for tests.
    #[cfg(any(test, feature = "test-internals"))]
    pub fn indices(&self, mesh: &Mesh) -> Vec<u32> {
        mesh.face_indices.iter().map(|&v| self.of(v)).collect()
    }
}

/// Vertex `v`'s target in `target` (each vertex's, or empty: every vertex its own).
#[inline]
fn target_of(target: &[u32], v: u32) -> u32 {
    target.get(v as usize).copied().unwrap_or(v)
}

/// A list of vertex ids read through a weld (a face's corners), or as they are
/// ([`Corners::plain`]: ids already welded). Copy, and as cheap to pass as a slice.
#[derive(Clone, Copy, Debug)]
pub struct Corners<'a> {
    ids: &'a [u32],
    /// Each vertex's target, or empty: the ids as they are.
    weld: &'a [u32],
}

impl<'a> Corners<'a> {
    /// Ids already welded, read as they are.
    #[inline]
    pub fn plain(ids: &'a [u32]) -> Self {
        Corners { ids, weld: &[] }
    }

    /// How many ids.
    #[inline]
    pub fn len(self) -> usize {
        self.ids.len()
    }

    /// The `i`-th id, welded.
    #[inline]
    pub fn get(self, i: usize) -> u32 {
        target_of(self.weld, self.ids[i])
    }

    /// The ids in order, welded.
    #[inline]
    pub fn iter(self) -> impl ExactSizeIterator<Item = u32> + Clone + 'a {
        let weld = self.weld;
        (self.ids.iter()).map(move |&v| target_of(weld, v))
    }

    /// Whether welded id `v` is among them.
    #[inline]
    pub fn contains(self, v: u32) -> bool {
        self.iter().any(|u| u == v)
    }

    /// The ids welded, as a vector.
    pub fn to_vec(self) -> Vec<u32> {
        self.iter().collect()
    }
}

/// Each vertex's weld target, and the number of distinct vertices in use.
#[cfg(any(test, feature = "test-internals"))]
pub fn weld(mesh: &Mesh, mode: Dedup) -> (Weld, usize) {
    weld_checked(mesh, mode, &|_| true).unwrap_or_default()
}

/// [`weld`] that reports the fraction done to `go_on` and stops (`None`) when it
/// says so: exact welding asks between blocks of fixed work (buckets, and
/// [`BLOCK`] vertices or corners of each pass), so a cancel waits for one block,
/// not a pass over the input (the tolerance weld's sort and union-find do not
/// ask). Where no vertex moves the table is empty.
pub fn weld_checked(mesh: &Mesh, mode: Dedup, go_on: Checkpoint) -> Option<(Weld, usize)> {
    let remap: Vec<u32> = match mode {
        Dedup::Off => Vec::new(),
        Dedup::Exact => exact_remap(mesh, go_on)?,
        Dedup::Tolerance(t) if t > 0.0 => tolerance_remap(mesh, t),
        Dedup::Tolerance(_) => exact_remap(mesh, go_on)?,
    };
    let moved = (remap.par_iter().enumerate()).any(|(v, &r)| r as usize != v);
    let weld = Weld {
        target: if moved { remap } else { Vec::new() },
    };
    let distinct = distinct_in_use(mesh, &weld, go_on)?;
    Some((weld, distinct))
}

/// Items a pass over every vertex or corner handles between two checks of `go_on`
/// (milliseconds of work, whatever the input's size).
const BLOCK: usize = 1 << 20;

/// How many distinct welded vertices the faces use: each corner's target marked, in
/// parallel within blocks of [`BLOCK`] corners, asking `go_on` between them.
fn distinct_in_use(mesh: &Mesh, weld: &Weld, go_on: Checkpoint) -> Option<usize> {
    use std::sync::atomic::{AtomicBool, Ordering::Relaxed};
    let used: Vec<AtomicBool> = (0..mesh.vertex_count())
        .map(|_| AtomicBool::new(false))
        .collect();
    for (b, block) in mesh.face_indices.chunks(BLOCK).enumerate() {
        if b > 0 && !go_on(0.95) {
            return None;
        }
        let corners = block.par_iter().with_min_len(1 << 14);
        corners.for_each(|&v| {
            let u = &used[weld.of(v) as usize];
            if !u.load(Relaxed) {
                u.store(true, Relaxed);
            }
        });
    }
    Some(used.par_iter().filter(|u| u.load(Relaxed)).count())
}

/// Bit pattern of a coordinate with −0 folded onto +0.
#[inline]
fn key(v: f64) -> u64 {
    (v + 0.0).to_bits()
}

/// Vertices a task hashes and places at a time in the exact weld's first pass (its
/// counts, one per partition, stay in cache).
const CHUNK: usize = 1 << 16;

/// Vertices per bucket of the exact weld, about: a sort that stays in the first
/// level of cache.
const BUCKET: usize = 1 << 8;

/// Each vertex → the lowest index with bit-identical (re-centred) coordinates.
///
/// Each vertex is a record (32 bits of a hash of its coordinates, its index),
/// partitioned by other bits of the hash in two counting passes of at most a few
/// hundred ways each (the first over the input in chunks, the second within a
/// partition, in cache), down to buckets of about [`BUCKET`] records, each sorted on
/// its own: equal coordinates share a bucket and a hash, and a run of equal hashes
/// is split by exact coordinates, each group welding to its lowest index. Every pass
/// reads and writes in streams (positions in order, records in a few hundred places
/// at a time), so the time per vertex holds as the input outgrows the caches; only a
/// vertex with a twin in its bucket reads its coordinates again.
fn exact_remap(mesh: &Mesh, go_on: Checkpoint) -> Option<Vec<u32>> {
    let n = mesh.vertex_count();
    // Bucket bits, split between the two passes; the records keep the hash's low 32
    // bits, the partitions its top ones.
    let bits = (n / BUCKET)
        .max(1)
        .next_power_of_two()
        .trailing_zeros()
        .min(24);
    let (bits1, bits2) = (bits.div_ceil(2), bits / 2);
    // First pass: the records in partitions, streaming over the input in chunks.
    let (mut records, start) = partitioned(mesh, bits1, go_on)?;
    if !go_on(0.4) {
        return None;
    }
    // Second pass: each partition into buckets in cache, each bucket's twins welded.
    weld_partitions(mesh, &mut records, &start, bits2, go_on)
}

/// Vertex `i`'s coordinates' bit patterns, −0 folded onto +0: equal exactly when
/// the positions are.
#[inline]
fn coordinates(mesh: &Mesh, i: u32) -> (u64, u64, u64) {
    let i = i as usize;
    (key(mesh.x[i]), key(mesh.y[i]), key(mesh.z[i]))
}

/// A 64-bit hash of vertex `i`'s coordinates (equal coordinates, equal hash).
#[inline]
fn vertex_hash(mesh: &Mesh, i: u32) -> u64 {
    let (x, y, z) = coordinates(mesh, i);
    let mut h = x.wrapping_mul(0x9E37_79B9_7F4A_7C15)
        ^ y.rotate_left(21).wrapping_mul(0xC2B2_AE3D_27D4_EB4F)
        ^ z.rotate_left(42).wrapping_mul(0x1656_67B1_9E37_79F9);
    h ^= h >> 33;
    h = h.wrapping_mul(0xFF51_AFD7_ED55_8CCD);
    h ^= h >> 33;
    h = h.wrapping_mul(0xC4CE_B9FE_1A85_EC53);
    h ^ (h >> 33)
}

/// Every vertex's record (hash's low 32 bits, index) placed in its partition by the
/// hash's top `bits` bits, and each partition's start (one more entry than
/// partitions): each chunk of [`CHUNK`] vertices counts, then places, its own, so
/// the order is the same for any thread count; `None` when `go_on` said stop.
fn partitioned(mesh: &Mesh, bits: u32, go_on: Checkpoint) -> Option<(Vec<u64>, Vec<u32>)> {
    use std::sync::atomic::{AtomicU64, Ordering::Relaxed};
    let n = mesh.vertex_count();
    let parts = 1usize << bits;
    let part = |h: u64| (h >> 32 >> (32 - bits)) as usize & (parts - 1);
    let chunks = n.div_ceil(CHUNK);
    let mut counts = vec![0u32; chunks * parts];
    let counted = blocks_of_chunks(&mut counts, parts, 0.0, go_on, |c, row| {
        let chunk = c * CHUNK..((c + 1) * CHUNK).min(n);
        chunk.for_each(|i| row[part(vertex_hash(mesh, i as u32))] += 1);
    });
    if !counted {
        return None;
    }
    // Each chunk's first slot per partition, partitions in order, chunks within.
    let mut start = vec![0u32; parts + 1];
    let mut at = 0u32;
    for p in 0..parts {
        start[p] = at;
        for c in 0..chunks {
            let count = counts[c * parts + p];
            counts[c * parts + p] = at;
            at += count;
        }
    }
    start[parts] = at;
    let records: Vec<AtomicU64> = (0..n).map(|_| AtomicU64::new(0)).collect();
    let placed = blocks_of_chunks(&mut counts, parts, 0.2, go_on, |c, next| {
        for i in c * CHUNK..((c + 1) * CHUNK).min(n) {
            let h = vertex_hash(mesh, i as u32);
            let slot = &mut next[part(h)];
            records[*slot as usize].store((h << 32) | i as u64, Relaxed);
            *slot += 1;
        }
    });
    let records = records.into_iter().map(AtomicU64::into_inner).collect();
    placed.then_some((records, start))
}

/// Each vertex → the lowest index with its coordinates, from the `records` in
/// partitions (`start`): blocks of partitions in parallel, each partition counted
/// into buckets by `bits` more bits of the hash ([`buckets`]), each bucket sorted,
/// and each run of equal hashes split by exact coordinates, every group welding to
/// its first (lowest) index; asks `go_on` after each block.
fn weld_partitions(
    mesh: &Mesh,
    records: &mut [u64],
    start: &[u32],
    bits: u32,
    go_on: Checkpoint,
) -> Option<Vec<u32>> {
    use std::sync::atomic::{AtomicU32, Ordering::Relaxed};
    let n = mesh.vertex_count();
    let parts = start.len() - 1;
    let remap: Vec<AtomicU32> = (0..n as u32).into_par_iter().map(AtomicU32::new).collect();
    // Blocks of partitions own disjoint runs of `records`.
    let per_block = (parts / 64).max(1);
    let mut blocks = Vec::new();
    let mut rest = records;
    for p0 in (0..parts).step_by(per_block) {
        let p1 = (p0 + per_block).min(parts);
        let (head, tail) = rest.split_at_mut((start[p1] - start[p0]) as usize);
        blocks.push((p0, p1, head));
        rest = tail;
    }
    let total = blocks.len();
    let done = AtomicU32::new(0);
    let weld_twins = |run: &[u64], twins: &mut Vec<((u64, u64, u64), u32)>| {
        twins.clear();
        twins.extend(run.iter().map(|&r| (coordinates(mesh, r as u32), r as u32)));
        twins.sort_unstable();
        for group in twins.chunk_by(|a, b| a.0 == b.0) {
            (group[1..].iter()).for_each(|&(_, i)| remap[i as usize].store(group[0].1, Relaxed));
        }
    };
    let finished = blocks.into_par_iter().all(|(p0, p1, block)| {
        let (mut sorted, mut ends, mut twins) = (Vec::new(), Vec::new(), Vec::new());
        for p in p0..p1 {
            let from = (start[p] - start[p0]) as usize;
            let to = (start[p + 1] - start[p0]) as usize;
            buckets(&block[from..to], bits, &mut sorted, &mut ends);
            let mut begin = 0;
            for &end in &ends {
                let bucket = &mut sorted[begin..end as usize];
                begin = end as usize;
                bucket.sort_unstable();
                for run in bucket.chunk_by(|a, b| a >> 32 == b >> 32) {
                    if run.len() > 1 {
                        weld_twins(run, &mut twins);
                    }
                }
            }
        }
        let d = done.fetch_add(1, Relaxed) + 1;
        go_on(0.4 + 0.5 * f64::from(d) / total as f64)
    });
    finished.then(|| remap.into_iter().map(AtomicU32::into_inner).collect())
}

/// Runs `f(c, row)` on every chunk `c` of [`CHUNK`] vertices with its row of
/// `table` (`width` entries a chunk), in parallel within blocks of [`BLOCK`]
/// vertices, asking `go_on` (reporting `fraction`) between them; false when it said
/// stop.
fn blocks_of_chunks(
    table: &mut [u32],
    width: usize,
    fraction: f64,
    go_on: Checkpoint,
    f: impl Fn(usize, &mut [u32]) + Sync,
) -> bool {
    let per_block = BLOCK / CHUNK;
    for (b, rows) in table.chunks_mut(per_block * width).enumerate() {
        if b > 0 && !go_on(fraction) {
            return false;
        }
        (rows.par_chunks_mut(width).enumerate()).for_each(|(c, row)| f(b * per_block + c, row));
    }
    true
}

/// `records` counted into `sorted` by their top `bits` bits (a partition's
/// buckets, in cache), with each bucket's end in `ends`.
fn buckets(records: &[u64], bits: u32, sorted: &mut Vec<u64>, ends: &mut Vec<u32>) {
    let bucket = |r: u64| match bits {
        0 => 0,
        _ => (r >> (64 - bits)) as usize,
    };
    ends.clear();
    ends.resize(1 << bits, 0);
    records.iter().for_each(|&r| ends[bucket(r)] += 1);
    let mut at = 0;
    for e in ends.iter_mut() {
        at += *e;
        *e = at;
    }
    sorted.clear();
    sorted.resize(records.len(), 0);
    // Filled from each bucket's end backwards; `ends` is back to the starts after.
    for &r in records.iter().rev() {
        let e = &mut ends[bucket(r)];
        *e -= 1;
        sorted[*e as usize] = r;
    }
    // The starts, shifted by one bucket: each bucket's end.
    ends.rotate_left(1);
    let last = ends.len() - 1;
    ends[last] = records.len() as u32;
}

/// Vertices closer than `tol` are merged transitively (union-find over a grid of cell
/// size `tol`); each group maps to its lowest index.
fn tolerance_remap(mesh: &Mesh, tol: f64) -> Vec<u32> {
    let n = mesh.vertex_count();
    let cell = |i: usize| {
        [mesh.x[i], mesh.y[i], mesh.z[i]].map(|c| (c / tol).floor().clamp(-1e15, 1e15) as i64)
    };
    let mut order: Vec<u32> = (0..n as u32).collect();
    order.par_sort_unstable_by_key(|&i| (cell(i as usize), i));
    let cells: Vec<[i64; 3]> = order.iter().map(|&i| cell(i as usize)).collect();
    let mut parent: Vec<u32> = (0..n as u32).collect();
    let tol2 = tol * tol;
    let offsets = (0..27).map(|k| [k % 3 - 1, k / 3 % 3 - 1, k / 9 - 1]);
    let offsets: Vec<[i64; 3]> = offsets.collect();
    for (pos, &i) in order.iter().enumerate() {
        let c = cells[pos];
        for d in &offsets {
            let target = [c[0] + d[0], c[1] + d[1], c[2] + d[2]];
            let mut k = cells.partition_point(|x| *x < target);
            while k < n && cells[k] == target {
                let j = order[k];
                if j < i && dist2(mesh, i, j) <= tol2 {
                    union(&mut parent, i, j);
                }
                k += 1;
            }
        }
    }
    (0..n as u32).map(|i| find(&mut parent, i)).collect()
}

fn dist2(mesh: &Mesh, a: u32, b: u32) -> f64 {
    let (a, b) = (a as usize, b as usize);
    let d = [
        mesh.x[a] - mesh.x[b],
        mesh.y[a] - mesh.y[b],
        mesh.z[a] - mesh.z[b],
    ];
    d[0] * d[0] + d[1] * d[1] + d[2] * d[2]
}

fn find(parent: &mut [u32], mut i: u32) -> u32 {
    while parent[i as usize] != i {
        let g = parent[parent[i as usize] as usize];
        parent[i as usize] = g;
        i = g;
    }
    i
}

/// Union keeping the smaller index as root, so each group maps to its lowest index.
fn union(parent: &mut [u32], a: u32, b: u32) {
    let (ra, rb) = (find(parent, a), find(parent, b));
    let (lo, hi) = (ra.min(rb), ra.max(rb));
    parent[hi as usize] = lo;
}

#[cfg(test)]
mod tests {
    use super::*;

    fn two_triangles_with_seam(gap: f64) -> Mesh {
        let p = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0 + gap, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],
        ];
        Mesh::from_polygons(&p, &[vec![0, 1, 2], vec![3, 5, 4]]).unwrap()
    }

    #[test]
    fn exact_merges_identical_positions_only() {
        let m = two_triangles_with_seam(0.0);
        let (w, distinct) = weld(&m, Dedup::Exact);
        assert_eq!(w.indices(&m), vec![0, 1, 2, 1, 5, 2]);
        assert_eq!(distinct, 4);
        let m = two_triangles_with_seam(1e-9);
        let (w, _) = weld(&m, Dedup::Exact);
        assert_eq!(w.indices(&m), vec![0, 1, 2, 3, 5, 2]);
    }

    #[test]
    fn tolerance_merges_near_positions() {
        let m = two_triangles_with_seam(1e-9);
        let (w, distinct) = weld(&m, Dedup::Tolerance(1e-6));
        assert_eq!(w.indices(&m), vec![0, 1, 2, 1, 5, 2]);
        assert_eq!(distinct, 4);
    }

    #[test]
    fn off_keeps_topology() {
        let m = two_triangles_with_seam(0.0);
        let (w, distinct) = weld(&m, Dedup::Off);
        assert_eq!(w.indices(&m), m.face_indices);
        assert!(w.target.is_empty(), "no vertex moves: no table");
        assert_eq!(distinct, 6);
    }

    /// Welding more vertices and corners than a block asks between blocks of every
    /// pass, more often for more vertices, with the same result as never asking;
    /// told to stop, it stops.
    #[test]
    fn a_large_weld_asks_between_blocks() {
        use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};
        // Vertex 2k + 1 repeats vertex 2k; triangles of consecutive vertices.
        let mesh = |n: usize| {
            let p: Vec<[f64; 3]> = (0..n)
                .map(|i| [(i / 2) as f64, (i / 2 % 7) as f64, 0.5])
                .collect();
            let tris: Vec<Vec<u32>> = (0..n as u32 / 3)
                .map(|t| vec![3 * t, 3 * t + 1, 3 * t + 2])
                .collect();
            Mesh::from_polygons(&p, &tris).unwrap()
        };
        let asks = |m: &Mesh| {
            let asked = AtomicUsize::new(0);
            let go_on = |_: f64| asked.fetch_add(1, Relaxed) < usize::MAX;
            let (w, distinct) = weld_checked(m, Dedup::Exact, &go_on).expect("not stopped");
            let (again, d) = weld(m, Dedup::Exact);
            assert_eq!((w.target, distinct), (again.target, d));
            asked.into_inner()
        };
        let (small, large) = (mesh(3 * BLOCK / 4), mesh(3 * BLOCK));
        let (a, b) = (asks(&small), asks(&large));
        // Two passes over the vertices and one over the corners, each 2 blocks more.
        assert!(b >= a + 6, "{a} asks, then {b}");
        let asked = AtomicUsize::new(0);
        let once = |_: f64| asked.fetch_add(1, Relaxed) < 1;
        assert!(weld_checked(&large, Dedup::Exact, &once).is_none());
        assert_eq!(asked.into_inner(), 2);
    }

    /// The exact weld maps each vertex to the lowest index of the same coordinates,
    /// as a map of every vertex's coordinates says, on enough vertices for both
    /// passes to split (many twins, some −0).
    #[test]
    fn exact_weld_is_lowest_index_of_equal_coordinates() {
        let n = 200_000usize;
        let mut s = 0x2545_F491_4F6C_DD1Du64;
        let mut next = || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            s
        };
        let c = |r: u64| match r % 50 {
            0 => -0.0,
            v => (v as f64) * 0.25,
        };
        let p: Vec<[f64; 3]> = (0..n)
            .map(|_| [c(next()), c(next()), c(next() % 3)])
            .collect();
        let tris: Vec<Vec<u32>> = (0..n as u32 / 3)
            .map(|t| vec![3 * t, 3 * t + 1, 3 * t + 2])
            .collect();
        let m = Mesh::from_polygons(&p, &tris).unwrap();
        let mut lowest = std::collections::HashMap::new();
        let expected: Vec<u32> = (0..m.vertex_count())
            .map(|i| {
                let k = (key(m.x[i]), key(m.y[i]), key(m.z[i]));
                *lowest.entry(k).or_insert(i as u32)
            })
            .collect();
        assert_eq!(exact_remap(&m, &|_| true).unwrap(), expected);
    }

    #[test]
    fn negative_zero_equals_zero() {
        let p = [
            [0.0, 0.0, 0.0],
            [-0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        let m = Mesh::from_polygons(&p, &[vec![0, 2, 3], vec![1, 3, 2]]).unwrap();
        let (w, _) = weld(&m, Dedup::Exact);
        assert_eq!(w.indices(&m)[3], w.indices(&m)[0]);
    }
}
