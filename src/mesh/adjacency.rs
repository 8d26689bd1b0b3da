//! Face adjacency (§3.3: merges follow the input's topology): two faces are adjacent
//! when they share an edge after deduplication. Built by sorting (edge, face) records
//! in parallel, so the result is the same for any thread count.

use rayon::prelude::*;

/// Faces around one edge beyond which we chain them instead of pairing all of them,
/// so a non-manifold "fan" edge cannot create a quadratic number of pairs.
const ALL_PAIRS_UP_TO: usize = 4;

/// Sorted, unique pairs `(a, b)` with `a < b` of faces sharing an edge. `offsets` and
/// `indices` are the CSR polygons (indices already welded).
pub fn face_pairs(offsets: &[u32], indices: &[u32]) -> Vec<(u32, u32)> {
    let faces = offsets.len().saturating_sub(1);
    let mut records: Vec<(u64, u32)> = (0..faces)
        .into_par_iter()
        .with_min_len(4096)
        .flat_map_iter(|f| {
            let idx = &indices[offsets[f] as usize..offsets[f + 1] as usize];
            (0..idx.len()).filter_map(move |i| {
                let (a, b) = (idx[i], idx[(i + 1) % idx.len()]);
                (a != b).then(|| (((a.min(b) as u64) << 32) | a.max(b) as u64, f as u32))
            })
        })
        .collect();
    records.par_sort_unstable();
    let mut pairs = Vec::with_capacity(records.len());
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
    pairs
}

/// Pairs of the distinct faces around one edge (records are sorted by face).
fn push_edge_pairs(run: &[(u64, u32)], pairs: &mut Vec<(u32, u32)>) {
    let mut fs: Vec<u32> = run.iter().map(|r| r.1).collect();
    fs.dedup();
    if fs.len() <= ALL_PAIRS_UP_TO {
        for i in 0..fs.len() {
            for j in i + 1..fs.len() {
                pairs.push((fs[i], fs[j]));
            }
        }
    } else {
        pairs.extend(fs.windows(2).map(|w| (w[0], w[1])));
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
