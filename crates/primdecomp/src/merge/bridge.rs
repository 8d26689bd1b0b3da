//! Component bridging (§3.4 "Pairwise Component Merging",
//! docs/decisions/0006-component-bridging-nearest-12.md): when adjacency runs out above the
//! target, every live cluster is linked to its
//! [`BRIDGE_K`] nearest clusters by centroid, found with a k-d tree in O(C log C)
//! instead of the paper's C(C−1)/2 pairs. If the links leave several groups, the loop
//! runs out again with one cluster per group and bridges those: each round at least
//! halves the clusters, so there are O(log C) rounds.
//!
//! The links used to be each cluster's 2 successors in the x, y and z orders of the
//! centroids. On 10,000 tetrahedra on a 3D grid those join clusters that share one
//! coordinate but lie anywhere in that plane; the first such merge made a box
//! spanning the plane, which then swallowed everything it covered one merge at a time
//! while re-pricing a neighbour list that grew with it
//! (docs/decisions/hostile-input-limits.md, "Many components").

use crate::math::V3;
use rayon::prelude::*;

/// Nearest clusters each cluster is linked to: on multi-component corpus meshes,
/// 4 or 8 links left more total primitive volume than the old axis-order links, 12
/// about as much or less (docs/decisions/0006-component-bridging-nearest-12.md). The
/// cost is linear in k.
pub const BRIDGE_K: usize = 12;

/// Pairs `(i, j)`, `i < j`, sorted and distinct, linking every point to its `k`
/// nearest others (ties broken by index, so the result depends on nothing else).
pub fn nearest_pairs(points: &[V3], k: usize) -> Vec<(u32, u32)> {
    let tree = KdTree::build(points);
    let mut pairs: Vec<(u32, u32)> = (0..points.len())
        .into_par_iter()
        .with_min_len(256)
        .flat_map_iter(|i| {
            let mut best = Vec::with_capacity(k + 1);
            tree.nearest(points[i], i as u32, k, &mut best);
            best.into_iter()
                .map(move |(_, j)| (j.min(i as u32), j.max(i as u32)))
        })
        .collect();
    pairs.par_sort_unstable();
    pairs.dedup();
    pairs
}

/// A k-d tree over point indices: `order` is permuted so that each node's median sits
/// at the middle of its range, split on the range's widest axis.
struct KdTree<'a> {
    points: &'a [V3],
    order: Vec<u32>,
    /// Split axis of the node whose median is at each position of `order`.
    axis: Vec<u8>,
}

impl<'a> KdTree<'a> {
    fn build(points: &'a [V3]) -> Self {
        let mut t = KdTree {
            points,
            order: (0..points.len() as u32).collect(),
            axis: vec![0; points.len()],
        };
        t.split(0, points.len());
        t
    }

    fn split(&mut self, lo: usize, hi: usize) {
        if hi - lo <= 1 {
            return;
        }
        let pts = self.points;
        let (mut min, mut max) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for &i in &self.order[lo..hi] {
            for k in 0..3 {
                min[k] = min[k].min(pts[i as usize][k]);
                max[k] = max[k].max(pts[i as usize][k]);
            }
        }
        let ax = (0..3)
            .max_by(|&a, &b| {
                (max[a] - min[a])
                    .total_cmp(&(max[b] - min[b]))
                    .then(b.cmp(&a))
            })
            .unwrap_or(0);
        let mid = (lo + hi) / 2;
        self.order[lo..hi].select_nth_unstable_by(mid - lo, |&a, &b| {
            pts[a as usize][ax]
                .total_cmp(&pts[b as usize][ax])
                .then(a.cmp(&b))
        });
        self.axis[mid] = ax as u8;
        self.split(lo, mid);
        self.split(mid + 1, hi);
    }

    /// The `k` nearest points to `q` other than `skip`, as `(squared distance, index)`
    /// in `best`, nearest first (by distance, then index).
    fn nearest(&self, q: V3, skip: u32, k: usize, best: &mut Vec<(f64, u32)>) {
        best.clear();
        if k > 0 {
            self.search(0, self.order.len(), q, skip, k, best);
        }
    }

    fn search(&self, lo: usize, hi: usize, q: V3, skip: u32, k: usize, best: &mut Vec<(f64, u32)>) {
        if lo >= hi {
            return;
        }
        let mid = (lo + hi) / 2;
        let i = self.order[mid];
        let p = self.points[i as usize];
        if i != skip {
            let d = (0..3).map(|a| (p[a] - q[a]) * (p[a] - q[a])).sum::<f64>();
            offer(best, k, (d, i));
        }
        let ax = self.axis[mid] as usize;
        let gap = q[ax] - p[ax];
        let (near, far) = if gap < 0.0 {
            ((lo, mid), (mid + 1, hi))
        } else {
            ((mid + 1, hi), (lo, mid))
        };
        self.search(near.0, near.1, q, skip, k, best);
        // `<=`: a point at exactly the worst distance may still win on its index.
        if best.len() < k || gap * gap <= best[k - 1].0 {
            self.search(far.0, far.1, q, skip, k, best);
        }
    }
}

/// `a` comes before `b`: nearer, or as near with a lower index.
fn before(a: (f64, u32), b: (f64, u32)) -> bool {
    a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)).is_lt()
}

/// Keeps the `k` smallest `(distance, index)` entries, sorted, so the one to drop
/// and the pruning distance are the last entry: O(1) per visited node to reject,
/// where a scan for the worst of an unsorted list cost O(k) at every node
/// (docs/decisions/perf-bridging-kd-tree.md).
fn offer(best: &mut Vec<(f64, u32)>, k: usize, c: (f64, u32)) {
    if best.len() == k {
        if !before(c, best[k - 1]) {
            return;
        }
        best.pop();
    }
    let at = best.partition_point(|&e| before(e, c));
    best.insert(at, c);
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// The k-d tree finds the same neighbours as a brute-force scan, ties included
    /// (points on an integer grid have many equal distances).
    #[test]
    fn nearest_pairs_match_brute_force() {
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        for (n, grid) in [
            (1, false),
            (2, true),
            (50, false),
            (300, true),
            (500, false),
        ] {
            let pts: Vec<V3> = (0..n)
                .map(|_| {
                    [0; 3].map(|_| {
                        if grid {
                            rng.gen_range(0..6) as f64
                        } else {
                            rng.gen_range(-1.0..1.0)
                        }
                    })
                })
                .collect();
            for k in [1, BRIDGE_K, 7] {
                let mut want = Vec::new();
                for i in 0..n {
                    let mut d: Vec<(f64, u32)> = (0..n)
                        .filter(|&j| j != i)
                        .map(|j| {
                            let s = (0..3).map(|a| (pts[i][a] - pts[j][a]).powi(2)).sum();
                            (s, j as u32)
                        })
                        .collect();
                    d.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
                    for &(_, j) in d.iter().take(k) {
                        want.push((j.min(i as u32), j.max(i as u32)));
                    }
                }
                want.sort_unstable();
                want.dedup();
                assert_eq!(nearest_pairs(&pts, k), want, "n {n} k {k} grid {grid}");
            }
        }
    }
}
