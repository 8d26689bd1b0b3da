//! Leaves of the merge tree after spatial parts too large to be taken apart down to
//! their faces within the tree's budget ([`super::tree::Split`]) are taken apart into
//! pieces instead: the largest clusters of at most a size that the leaf's own logged
//! merges made (§3.3, Alg. 1: every merge joins two clusters, so a leaf's merges form
//! a binary tree, and its subtrees are clusters the loop held), the size doubled from
//! a floor until the pieces fit the leaf's share of the budget
//! (docs/decisions/0058-the-largest-leaves-taken-apart-into-pieces.md,
//! docs/decisions/0059-pieces-no-finer-than-an-eighth-of-the-mean.md).

use crate::merge::components::{components, root};

/// The merges of `log` inside each of `leaves` (each leaf's faces, increasing), in
/// order, as pairs of indices into that leaf; `faces`: the input's face count.
pub(super) fn merges_inside(
    leaves: &[&[u32]],
    log: &[(u32, u32)],
    faces: usize,
) -> Vec<Vec<(u32, u32)>> {
    // Each face's place in the leaves laid end to end.
    let mut place = vec![u32::MAX; faces];
    let mut starts = Vec::with_capacity(leaves.len() + 1);
    let mut next = 0u32;
    for leaf in leaves {
        starts.push(next);
        for &f in *leaf {
            place[f as usize] = next;
            next += 1;
        }
    }
    starts.push(next);
    let leaf_at = |p: u32| starts.partition_point(|&s| s <= p) - 1;
    let mut inside = vec![Vec::new(); leaves.len()];
    for &(a, b) in log {
        let (pa, pb) = (place[a as usize], place[b as usize]);
        if pa == u32::MAX || pb == u32::MAX {
            continue;
        }
        let k = leaf_at(pa);
        if leaf_at(pb) == k {
            inside[k].push((pa - starts[k], pb - starts[k]));
        }
    }
    inside
}

/// The pieces of `leaf` (its faces, increasing) whose merges inside are `merges`
/// ([`merges_inside`]): the largest clusters of at most `floor` faces (rounded up to a
/// power of two, at least 2) its merges made, or of twice that, and so on: the finest
/// whose pieces number at most `left`. Each piece's faces increasing, the pieces
/// ordered by their first face; `None` where no size below the leaf's own gives at
/// most `left` pieces.
pub(super) fn pieces(
    leaf: &[u32],
    merges: &[(u32, u32)],
    left: usize,
    floor: usize,
) -> Option<Vec<Vec<u32>>> {
    let mut size = floor.next_power_of_two().max(2);
    while size < leaf.len() {
        let parts = pieces_under(leaf.len(), merges, size);
        if parts.len() <= left {
            let faces = |p: Vec<u32>| p.into_iter().map(|i| leaf[i as usize]).collect();
            return Some(parts.into_iter().map(faces).collect());
        }
        size = size.saturating_mul(2);
    }
    None
}

/// The largest clusters of at most `size` of `n` items that `merges` (pairs of items,
/// one in each of two clusters, in order) made: the components of the merges whose
/// cluster holds at most `size` items, since a cluster of at most `size` was made by
/// merges of at most `size` alone. Items of each piece increasing, the pieces ordered
/// by their first item.
fn pieces_under(n: usize, merges: &[(u32, u32)], size: usize) -> Vec<Vec<u32>> {
    let mut whole: Vec<u32> = (0..n as u32).collect();
    let mut count = vec![1usize; n];
    let mut within = Vec::new();
    for &(a, b) in merges {
        let (ra, rb) = (root(&mut whole, a), root(&mut whole, b));
        if ra == rb {
            continue;
        }
        let joined = count[ra as usize] + count[rb as usize];
        if joined <= size {
            within.push((a, b));
        }
        whole[ra.max(rb) as usize] = ra.min(rb);
        count[ra.min(rb) as usize] = joined;
    }
    components(n, &within)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Eight items merged pairwise, then the pairs, then the fours (a balanced tree):
    /// under 2 the pairs, under 3 still the pairs (no cluster of three was made), under
    /// 4 the fours; pieces are what the merges made, never a cut across them.
    #[test]
    fn pieces_are_the_largest_clusters_the_merges_made_under_the_size() {
        let m = [(0, 1), (2, 3), (4, 5), (6, 7), (0, 2), (4, 6), (0, 4)];
        let pairs = vec![vec![0, 1], vec![2, 3], vec![4, 5], vec![6, 7]];
        assert_eq!(pieces_under(8, &m, 2), pairs);
        assert_eq!(pieces_under(8, &m, 3), pairs);
        assert_eq!(
            pieces_under(8, &m, 4),
            vec![vec![0, 1, 2, 3], vec![4, 5, 6, 7]]
        );
        assert_eq!(pieces_under(8, &m, 8), vec![(0..8).collect::<Vec<u32>>()]);
        // A chain (one item at a time onto a growing cluster): past the size, every
        // item joined after is a piece of its own.
        let chain: Vec<(u32, u32)> = (1..6).map(|i| (0, i)).collect();
        assert_eq!(
            pieces_under(6, &chain, 3),
            vec![vec![0, 1, 2], vec![3], vec![4], vec![5]]
        );
    }

    /// The size doubles from the floor until the pieces fit in `left`; the pieces name
    /// the leaf's faces; none fit where even the coarsest size below the leaf's gives
    /// more.
    #[test]
    fn the_size_doubles_until_the_pieces_fit() {
        let leaf: Vec<u32> = (100..108).collect();
        let m = [(0, 1), (2, 3), (4, 5), (6, 7), (0, 2), (4, 6), (0, 4)];
        let two = pieces(&leaf, &m, 4, 2).unwrap();
        assert_eq!(two.len(), 4);
        assert_eq!(two[0], vec![100, 101]);
        let halves = pieces(&leaf, &m, 3, 2).unwrap();
        assert_eq!(
            halves,
            vec![(100..104).collect::<Vec<u32>>(), (104..108).collect()]
        );
        assert_eq!(pieces(&leaf, &m, 1, 2), None);
        // A floor of 3 (rounded up to 4) skips the pairs, though 4 of them would fit.
        assert_eq!(pieces(&leaf, &m, 4, 3), Some(halves));
    }

    /// Only merges with both faces in one leaf count, as indices into it.
    #[test]
    fn merges_inside_keep_each_leafs_own() {
        let (a, b): (Vec<u32>, Vec<u32>) = (vec![2, 5, 9], vec![0, 7]);
        let log = [(5, 9), (0, 7), (2, 7), (9, 2), (1, 3)];
        let inside = merges_inside(&[&a, &b], &log, 10);
        assert_eq!(inside, vec![vec![(1, 2), (2, 0)], vec![(0, 1)]]);
    }
}
