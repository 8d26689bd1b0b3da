//! Face adjacency (§3.3: merges follow the input's topology): two faces are adjacent
//! when they share an edge after deduplication. Built by sorting (edge, face) records
//! in parallel, so the result is the same for any thread count.

use rayon::prelude::*;

/// Faces around one edge beyond which we chain them instead of pairing all of them,
/// so a non-manifold "fan" edge cannot create a quadratic number of pairs.
const ALL_PAIRS_UP_TO: usize = 4;

/// The pairs as neighbour lists of `n` faces, CSR: face `f`'s neighbours are
/// `adj[offsets[f]..offsets[f + 1]]`, in the pairs' order.
pub fn neighbour_lists(n: usize, pairs: &[(u32, u32)]) -> (Vec<u32>, Vec<u32>) {
    let mut offsets = vec![0u32; n + 1];
    for &(a, b) in pairs {
        offsets[a as usize + 1] += 1;
        offsets[b as usize + 1] += 1;
    }
    for i in 0..n {
        offsets[i + 1] += offsets[i];
    }
    let mut fill = offsets.clone();
    let mut adj = vec![0u32; 2 * pairs.len()];
    for &(a, b) in pairs {
        adj[fill[a as usize] as usize] = b;
        fill[a as usize] += 1;
        adj[fill[b as usize] as usize] = a;
        fill[b as usize] += 1;
    }
    (offsets, adj)
}

/// Sorted, unique pairs `(a, b)` with `a < b` of faces sharing an edge. `offsets` and
/// `indices` are the CSR polygons (indices already welded).
///
/// One (edge, face) record per polygon side, written in place at the side's CSR slot
/// (no intermediate lists: the records are the stage's only large buffer).
pub fn face_pairs(offsets: &[u32], indices: &[u32]) -> Vec<(u32, u32)> {
    let mut records = vec![(u64::MAX, u32::MAX); indices.len()];
    let faces = offsets.len().saturating_sub(1);
    debug_assert!(
        offsets.first().is_none_or(|&o| o == 0),
        "CSR offsets start at 0"
    );
    // Split the record buffer at face boundaries so each task owns whole faces.
    let mut slices = Vec::new();
    let mut rest = &mut records[..];
    let mut f0 = 0;
    while f0 < faces {
        let f1 = (f0 + 4096).min(faces);
        let len = (offsets[f1] - offsets[f0]) as usize;
        let (head, tail) = rest.split_at_mut(len);
        slices.push((f0, f1, head));
        rest = tail;
        f0 = f1;
    }
    slices.into_par_iter().for_each(|(f0, f1, out)| {
        let start = offsets[f0] as usize;
        for f in f0..f1 {
            let (lo, hi) = (offsets[f] as usize, offsets[f + 1] as usize);
            let idx = &indices[lo..hi];
            for i in 0..idx.len() {
                let (a, b) = (idx[i], idx[(i + 1) % idx.len()]);
                if a != b {
                    let key = ((a.min(b) as u64) << 32) | a.max(b) as u64;
                    out[lo - start + i] = (key, f as u32);
                }
            }
        }
    });
    records.par_sort_unstable();
    // Degenerate sides kept the sentinel key and sorted last.
    let used = records.partition_point(|r| r.0 != u64::MAX);
    let records = &records[..used];
    let mut pairs = Vec::new();
    let mut start = 0;
    while start < records.len() {
        let mut end = start + 1;
        while end < records.len() && records[end].0 == records[start].0 {
            end += 1;
        }
        push_edge_pairs(&records[start..end], &mut pairs);
        start = end;
    }
    pairs.par_sort_unstable();
    pairs.dedup();
    pairs.shrink_to_fit();
    pairs
}

/// Pairs of the distinct faces around one edge (records are sorted by face): all of
/// them for up to [`ALL_PAIRS_UP_TO`] faces, a chain beyond. No allocation.
fn push_edge_pairs(run: &[(u64, u32)], pairs: &mut Vec<(u32, u32)>) {
    let steps = || run.windows(2).filter(|w| w[0].1 != w[1].1);
    if 1 + steps().count() > ALL_PAIRS_UP_TO {
        pairs.extend(steps().map(|w| (w[0].1, w[1].1)));
        return;
    }
    let mut fs = [0u32; ALL_PAIRS_UP_TO];
    let mut n = 0;
    for &(_, f) in run {
        if n == 0 || fs[n - 1] != f {
            fs[n] = f;
            n += 1;
        }
    }
    for i in 0..n {
        for j in i + 1..n {
            pairs.push((fs[i], fs[j]));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quad_strip_and_isolated_triangle() {
        // Two quads sharing edge 1–4, and a triangle touching only at vertex 0.
        let offsets = [0, 4, 8, 11];
        let indices = [0, 1, 4, 3, 1, 2, 5, 4, 0, 6, 7];
        assert_eq!(face_pairs(&offsets, &indices), vec![(0, 1)]);
    }

    #[test]
    fn duplicate_faces_pair_once_and_fans_chain() {
        let offsets = [0, 3, 6];
        assert_eq!(face_pairs(&offsets, &[0, 1, 2, 2, 1, 0]), vec![(0, 1)]);
        // Six triangles around edge 0–1: chained, 5 pairs, not 15.
        let offsets: Vec<u32> = (0..=6).map(|i| i * 3).collect();
        let indices: Vec<u32> = (0..6).flat_map(|i| [0, 1, 2 + i]).collect();
        let p = face_pairs(&offsets, &indices);
        assert_eq!(p, vec![(0, 1), (1, 2), (2, 3), (3, 4), (4, 5)]);
    }

    #[test]
    fn degenerate_edges_are_ignored() {
        let offsets = [0, 3, 6];
        assert!(face_pairs(&offsets, &[0, 0, 1, 2, 2, 3]).is_empty());
    }
}
