//! Vertex deduplication (§3.4 "Vertex Deduplication"): overlapping vertices from
//! kit-bashed parts are merged so that adjacency sees them. Produces a remapped copy of
//! the face indices; positions are untouched (every vertex keeps its slot, and faces
//! point at the lowest-numbered vertex of each group, so results do not depend on
//! thread count).

use super::mesh::Mesh;
use crate::params::Dedup;
use crate::progress::Checkpoint;
use rayon::prelude::*;
use std::borrow::Cow;

/// Face indices with duplicates welded, and the number of distinct vertices in use.
#[cfg(any(test, feature = "test-internals"))]
pub fn weld(mesh: &Mesh, mode: Dedup) -> (Vec<u32>, usize) {
    weld_checked(mesh, mode, &|_| true).map_or_else(Default::default, |(f, d)| (f.into_owned(), d))
}

/// [`weld`] that reports the fraction done to `go_on` and stops (`None`) when it
/// says so: exact welding asks between blocks of fixed work (buckets, and
/// [`BLOCK`] vertices or corners of each pass), so a cancel waits for one block,
/// not a pass over the input (the tolerance weld's sort and union-find do not
/// ask). Where no vertex moves (no duplicates, or welding off) the welded indices
/// are the mesh's own, borrowed: no copy of 12 bytes a face.
pub fn weld_checked<'m>(
    mesh: &'m Mesh,
    mode: Dedup,
    go_on: Checkpoint,
) -> Option<(Cow<'m, [u32]>, usize)> {
    let remap: Vec<u32> = match mode {
        Dedup::Off => Vec::new(),
        Dedup::Exact => exact_remap(mesh, go_on)?,
        Dedup::Tolerance(t) if t > 0.0 => tolerance_remap(mesh, t),
        Dedup::Tolerance(_) => exact_remap(mesh, go_on)?,
    };
    let moved = (remap.par_iter().enumerate()).any(|(v, &r)| r as usize != v);
    let faces: Cow<'m, [u32]> = match moved {
        true => Cow::Owned(remapped(&mesh.face_indices, &remap, go_on)?),
        false => Cow::Borrowed(&mesh.face_indices),
    };
    let mut used = vec![false; mesh.vertex_count()];
    for (b, block) in faces.chunks(BLOCK).enumerate() {
        if b > 0 && !go_on(0.95) {
            return None;
        }
        block.iter().for_each(|&v| used[v as usize] = true);
    }
    let distinct = used.iter().filter(|&&u| u).count();
    Some((faces, distinct))
}

/// Items a pass over every vertex or corner handles between two checks of `go_on`
/// (milliseconds of work, whatever the input's size).
const BLOCK: usize = 1 << 20;

/// Every corner in `corners` mapped through `remap`, in parallel within blocks of
/// [`BLOCK`] and asking `go_on` between them; `None` when it said stop.
fn remapped(corners: &[u32], remap: &[u32], go_on: Checkpoint) -> Option<Vec<u32>> {
    let mut out = Vec::with_capacity(corners.len());
    for (b, block) in corners.chunks(BLOCK).enumerate() {
        if b > 0 && !go_on(0.9) {
            return None;
        }
        let mapped = block.par_iter().with_min_len(1 << 14);
        out.par_extend(mapped.map(|&v| remap[v as usize]));
    }
    Some(out)
}

/// Runs `f` on every index below `n`, in parallel within blocks of [`BLOCK`], asking
/// `go_on` (reporting `fraction`) between them; false when it said stop.
fn each_in_blocks(n: usize, fraction: f64, go_on: Checkpoint, f: impl Fn(u32) + Sync) -> bool {
    for from in (0..n).step_by(BLOCK) {
        if from > 0 && !go_on(fraction) {
            return false;
        }
        let to = (from + BLOCK).min(n);
        (from as u32..to as u32)
            .into_par_iter()
            .with_min_len(1 << 14)
            .for_each(&f);
    }
    true
}

/// Bit pattern of a coordinate with −0 folded onto +0.
#[inline]
fn key(v: f64) -> u64 {
    (v + 0.0).to_bits()
}

/// Vertices per bucket of the exact weld, about (a parallel task's sort, in cache).
const BUCKET: usize = 1 << 10;

/// Each vertex → the lowest index with bit-identical (re-centred) coordinates.
///
/// The vertices are bucketed by a hash of their coordinates (a counting sort: equal
/// coordinates share a bucket) and each bucket sorted on its own by (coordinates,
/// index): the groups and leaders one sort of every vertex finds, in linear time,
/// reading the coordinates of a bucket from cache, a block of buckets at a time.
fn exact_remap(mesh: &Mesh, go_on: Checkpoint) -> Option<Vec<u32>> {
    use std::sync::atomic::{AtomicU32, Ordering::Relaxed};
    let n = mesh.vertex_count();
    let k = |i: u32| {
        let i = i as usize;
        (key(mesh.x[i]), key(mesh.y[i]), key(mesh.z[i]))
    };
    let buckets = (n / BUCKET).max(1).next_power_of_two();
    let bucket = |i: u32| {
        let (x, y, z) = k(i);
        let h = (x.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ y).wrapping_mul(0xC2B2_AE3D_27D4_EB4F)
            ^ z.wrapping_mul(0x1656_67B1_9E37_79F9);
        (h.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> 32) as usize & (buckets - 1)
    };
    let count: Vec<AtomicU32> = (0..buckets + 1).map(|_| AtomicU32::new(0)).collect();
    let counted = each_in_blocks(n, 0.0, go_on, |i| {
        count[bucket(i) + 1].fetch_add(1, Relaxed);
    });
    if !counted {
        return None;
    }
    let mut start: Vec<u32> = count.into_iter().map(AtomicU32::into_inner).collect();
    for b in 0..buckets {
        start[b + 1] += start[b];
    }
    let next: Vec<AtomicU32> = start[..buckets]
        .iter()
        .map(|&s| AtomicU32::new(s))
        .collect();
    let order: Vec<AtomicU32> = (0..n).map(|_| AtomicU32::new(0)).collect();
    let placed = each_in_blocks(n, 0.2, go_on, |i| {
        let at = next[bucket(i)].fetch_add(1, Relaxed);
        order[at as usize].store(i, Relaxed);
    });
    if !placed {
        return None;
    }
    drop(next);
    let mut order: Vec<u32> = order.into_iter().map(AtomicU32::into_inner).collect();
    if !go_on(0.4) {
        return None;
    }
    let remap: Vec<AtomicU32> = (0..n).map(|_| AtomicU32::new(0)).collect();
    // Blocks of buckets own disjoint runs of `order`.
    let per_block = (buckets / 64).max(1);
    let mut blocks = Vec::new();
    let mut rest = &mut order[..];
    for b0 in (0..buckets).step_by(per_block) {
        let b1 = (b0 + per_block).min(buckets);
        let (head, tail) = rest.split_at_mut((start[b1] - start[b0]) as usize);
        blocks.push((b0, b1, head));
        rest = tail;
    }
    let total = blocks.len();
    let done = AtomicU32::new(0);
    let finished = blocks.into_par_iter().all(|(b0, b1, ids)| {
        let base = start[b0] as usize;
        for b in b0..b1 {
            let run = &mut ids[start[b] as usize - base..start[b + 1] as usize - base];
            run.sort_unstable_by_key(|&i| (k(i), i));
            for group in run.chunk_by(|&a, &b| k(a) == k(b)) {
                group
                    .iter()
                    .for_each(|&i| remap[i as usize].store(group[0], Relaxed));
            }
        }
        let d = done.fetch_add(1, Relaxed) + 1;
        go_on(0.4 + 0.5 * f64::from(d) / total as f64)
    });
    finished.then(|| remap.into_iter().map(AtomicU32::into_inner).collect())
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
        let (f, distinct) = weld(&m, Dedup::Exact);
        assert_eq!(f, vec![0, 1, 2, 1, 5, 2]);
        assert_eq!(distinct, 4);
        let m = two_triangles_with_seam(1e-9);
        let (f, _) = weld(&m, Dedup::Exact);
        assert_eq!(f, vec![0, 1, 2, 3, 5, 2]);
    }

    #[test]
    fn tolerance_merges_near_positions() {
        let m = two_triangles_with_seam(1e-9);
        let (f, distinct) = weld(&m, Dedup::Tolerance(1e-6));
        assert_eq!(f, vec![0, 1, 2, 1, 5, 2]);
        assert_eq!(distinct, 4);
    }

    #[test]
    fn off_keeps_topology() {
        let m = two_triangles_with_seam(0.0);
        let (f, distinct) = weld(&m, Dedup::Off);
        assert_eq!(f, m.face_indices);
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
            let (faces, distinct) = weld_checked(m, Dedup::Exact, &go_on).expect("not stopped");
            assert_eq!((faces.into_owned(), distinct), weld(m, Dedup::Exact));
            asked.into_inner()
        };
        let (small, large) = (mesh(3 * BLOCK / 4), mesh(3 * BLOCK));
        let (a, b) = (asks(&small), asks(&large));
        // Two passes over the vertices and two over the corners, each 2 blocks more.
        assert!(b >= a + 8, "{a} asks, then {b}");
        let asked = AtomicUsize::new(0);
        let once = |_: f64| asked.fetch_add(1, Relaxed) < 1;
        assert!(weld_checked(&large, Dedup::Exact, &once).is_none());
        assert_eq!(asked.into_inner(), 2);
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
        let (f, _) = weld(&m, Dedup::Exact);
        assert_eq!(f[3], f[0]);
    }
}
