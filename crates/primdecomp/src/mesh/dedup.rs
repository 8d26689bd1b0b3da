//! Vertex deduplication (§3.4 "Vertex Deduplication"): overlapping vertices from
//! kit-bashed parts are merged so that adjacency sees them. Produces a remapped copy of
//! the face indices; positions are untouched (every vertex keeps its slot, and faces
//! point at the lowest-numbered vertex of each group, so results do not depend on
//! thread count).

use super::Mesh;
use crate::params::Dedup;
use rayon::prelude::*;

/// Face indices with duplicates welded, and the number of distinct vertices in use.
pub fn weld(mesh: &Mesh, mode: Dedup) -> (Vec<u32>, usize) {
    let remap = match mode {
        Dedup::Off => (0..mesh.vertex_count() as u32).collect(),
        Dedup::Exact => exact_remap(mesh),
        Dedup::Tolerance(t) if t > 0.0 => tolerance_remap(mesh, t),
        Dedup::Tolerance(_) => exact_remap(mesh),
    };
    let faces: Vec<u32> = mesh
        .face_indices
        .par_iter()
        .with_min_len(1 << 14)
        .map(|&v| remap[v as usize])
        .collect();
    let mut used = vec![false; mesh.vertex_count()];
    faces.iter().for_each(|&v| used[v as usize] = true);
    let distinct = used.iter().filter(|&&u| u).count();
    (faces, distinct)
}

/// Bit pattern of a coordinate with −0 folded onto +0.
#[inline]
fn key(v: f64) -> u64 {
    (v + 0.0).to_bits()
}

/// Each vertex → the lowest index with bit-identical (re-centred) coordinates.
fn exact_remap(mesh: &Mesh) -> Vec<u32> {
    let n = mesh.vertex_count();
    let mut order: Vec<u32> = (0..n as u32).collect();
    let k = |i: u32| {
        let i = i as usize;
        (key(mesh.x[i]), key(mesh.y[i]), key(mesh.z[i]), i)
    };
    order.par_sort_unstable_by_key(|&i| k(i));
    let mut remap = vec![0u32; n];
    let mut start = 0;
    while start < n {
        let lead = order[start];
        let kl = k(lead);
        let mut end = start;
        while end < n
            && k(order[end]).0 == kl.0
            && k(order[end]).1 == kl.1
            && k(order[end]).2 == kl.2
        {
            remap[order[end] as usize] = lead;
            end += 1;
        }
        start = end;
    }
    remap
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
