//! A bounding-volume hierarchy over the input's triangles and the exact
//! point-to-triangle distance, for the merge tree's node errors (`cut::error`): the
//! same construction and query as `primdecomp-eval`'s (which the core must not
//! depend on), cut down to the nearest-triangle query.
//!
//! Built by median splits on the longest axis of the triangle centroids (ties broken
//! by index, so the tree is the same on every run); queried depth-first, nearer child
//! first, pruning nodes farther than the best distance so far.

use crate::math::{add, dot, norm2, scale, sub, V3};
use crate::mesh::Mesh;

const LEAF: usize = 4;

#[derive(Clone, Copy, Debug)]
struct Node {
    lo: V3,
    hi: V3,
    /// Leaf: first item in `items`; inner: index of the left child (right = left + 1).
    first: u32,
    /// Leaf: item count; inner: 0.
    count: u32,
}

/// The input's surface as triangles (fan-triangulated polygons, re-centred frame)
/// with a hierarchy over them.
#[derive(Clone, Debug, Default)]
pub(crate) struct Surface {
    tris: Vec<[V3; 3]>,
    nodes: Vec<Node>,
    items: Vec<u32>,
}

fn box_dist2(p: V3, lo: V3, hi: V3) -> f64 {
    let mut d = 0.0;
    for k in 0..3 {
        let e = (lo[k] - p[k]).max(p[k] - hi[k]).max(0.0);
        d += e * e;
    }
    d
}

fn tri_box(t: &[V3; 3]) -> (V3, V3) {
    let (mut lo, mut hi) = (t[0], t[0]);
    for v in &t[1..] {
        for k in 0..3 {
            (lo[k], hi[k]) = (lo[k].min(v[k]), hi[k].max(v[k]));
        }
    }
    (lo, hi)
}

impl Surface {
    /// The surface of every face of `mesh`.
    pub(crate) fn new(mesh: &Mesh) -> Surface {
        let mut tris = Vec::with_capacity(mesh.face_count());
        for f in 0..mesh.face_count() {
            let v = mesh.face(f);
            for k in 2..v.len() {
                tris.push([mesh.pos(v[0]), mesh.pos(v[k - 1]), mesh.pos(v[k])]);
            }
        }
        let boxes: Vec<(V3, V3)> = tris.iter().map(tri_box).collect();
        let mut s = Surface {
            tris,
            nodes: Vec::with_capacity(2 * boxes.len() / LEAF + 1),
            items: (0..boxes.len() as u32).collect(),
        };
        if !boxes.is_empty() {
            s.build(&boxes);
        }
        s
    }

    fn build(&mut self, boxes: &[(V3, V3)]) {
        let centroid = |i: u32| scale(add(boxes[i as usize].0, boxes[i as usize].1), 0.5);
        self.nodes.push(Node {
            lo: [0.0; 3],
            hi: [0.0; 3],
            first: 0,
            count: boxes.len() as u32,
        });
        let mut stack = vec![0usize];
        while let Some(n) = stack.pop() {
            let (first, count) = (self.nodes[n].first as usize, self.nodes[n].count as usize);
            let span = &mut self.items[first..first + count];
            let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
            let (mut clo, mut chi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
            for &i in span.iter() {
                let ((blo, bhi), c) = (boxes[i as usize], centroid(i));
                for k in 0..3 {
                    (lo[k], hi[k]) = (lo[k].min(blo[k]), hi[k].max(bhi[k]));
                    (clo[k], chi[k]) = (clo[k].min(c[k]), chi[k].max(c[k]));
                }
            }
            (self.nodes[n].lo, self.nodes[n].hi) = (lo, hi);
            if count <= LEAF {
                continue;
            }
            let axis = (0..3)
                .max_by(|&a, &b| (chi[a] - clo[a]).total_cmp(&(chi[b] - clo[b])))
                .unwrap_or(0);
            let mid = count / 2;
            span.select_nth_unstable_by(mid, |&a, &b| {
                centroid(a)[axis]
                    .total_cmp(&centroid(b)[axis])
                    .then(a.cmp(&b))
            });
            let left = self.nodes.len();
            for (f, c) in [(first, mid), (first + mid, count - mid)] {
                self.nodes.push(Node {
                    lo: [0.0; 3],
                    hi: [0.0; 3],
                    first: f as u32,
                    count: c as u32,
                });
            }
            (self.nodes[n].first, self.nodes[n].count) = (left as u32, 0);
            stack.extend([left, left + 1]);
        }
    }

    /// Distance from `p` to the nearest triangle (infinite for an empty surface);
    /// `stack` is scratch.
    pub(crate) fn distance(&self, p: V3, stack: &mut Vec<(f64, u32)>) -> f64 {
        let mut best = f64::INFINITY;
        if self.nodes.is_empty() {
            return best;
        }
        stack.clear();
        stack.push((0.0, 0));
        while let Some((d, n)) = stack.pop() {
            if d >= best {
                continue;
            }
            let node = self.nodes[n as usize];
            if node.count > 0 {
                let span = node.first as usize..(node.first + node.count) as usize;
                for &i in &self.items[span] {
                    best = best.min(point_tri_dist2(p, &self.tris[i as usize]));
                }
                continue;
            }
            let (l, r) = (node.first, node.first + 1);
            let dl = self.node_dist2(l, p);
            let dr = self.node_dist2(r, p);
            if dl <= dr {
                stack.extend([(dr, r), (dl, l)]);
            } else {
                stack.extend([(dl, l), (dr, r)]);
            }
        }
        best.sqrt()
    }

    fn node_dist2(&self, n: u32, p: V3) -> f64 {
        let node = &self.nodes[n as usize];
        box_dist2(p, node.lo, node.hi)
    }
}

/// Squared distance from `p` to the closest point of triangle `t` (Ericson,
/// Real-Time Collision Detection §5.1.5: Voronoi regions of vertices, edges, face).
fn point_tri_dist2(p: V3, t: &[V3; 3]) -> f64 {
    let [a, b, c] = *t;
    let (ab, ac, ap) = (sub(b, a), sub(c, a), sub(p, a));
    let (d1, d2) = (dot(ab, ap), dot(ac, ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return norm2(ap);
    }
    let bp = sub(p, b);
    let (d3, d4) = (dot(ab, bp), dot(ac, bp));
    if d3 >= 0.0 && d4 <= d3 {
        return norm2(bp);
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let v = d1 / (d1 - d3);
        return norm2(sub(ap, scale(ab, v)));
    }
    let cp = sub(p, c);
    let (d5, d6) = (dot(ab, cp), dot(ac, cp));
    if d6 >= 0.0 && d5 <= d6 {
        return norm2(cp);
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let w = d2 / (d2 - d6);
        return norm2(sub(ap, scale(ac, w)));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return norm2(sub(bp, scale(sub(c, b), w)));
    }
    let denom = va + vb + vc;
    if denom <= 0.0 || !denom.is_finite() {
        // Degenerate triangle: the nearest of its three edges.
        return [(a, b), (b, c), (c, a)]
            .iter()
            .map(|&(s, e)| point_segment_dist2(p, s, e))
            .fold(f64::INFINITY, f64::min);
    }
    let (v, w) = (vb / denom, vc / denom);
    norm2(sub(ap, add(scale(ab, v), scale(ac, w))))
}

fn point_segment_dist2(p: V3, a: V3, b: V3) -> f64 {
    let ab = sub(b, a);
    let l2 = norm2(ab);
    let ap = sub(p, a);
    let t = if l2 > 0.0 {
        (dot(ap, ab) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    norm2(sub(ap, scale(ab, t)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The hierarchy's nearest distance equals a linear scan over every triangle.
    #[test]
    fn nearest_matches_a_linear_scan() {
        let mesh = crate::demo::demo_scene();
        let s = Surface::new(&mesh);
        let mut stack = Vec::new();
        for i in 0..200u32 {
            let t = i as f64;
            let p = [
                (t * 0.37).sin() * 3.0,
                (t * 0.11).cos() * 2.0,
                (t * 0.05).sin(),
            ];
            let brute = s
                .tris
                .iter()
                .map(|t| point_tri_dist2(p, t))
                .fold(f64::INFINITY, f64::min)
                .sqrt();
            assert_eq!(s.distance(p, &mut stack), brute, "point {p:?}");
        }
    }

    #[test]
    fn triangle_distance_regions() {
        let t = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        assert_eq!(point_tri_dist2([0.2, 0.2, 2.0], &t), 4.0);
        assert_eq!(point_tri_dist2([-1.0, 0.0, 0.0], &t), 1.0);
        assert!((point_tri_dist2([1.0, 1.0, 0.0], &t) - 0.5).abs() < 1e-15);
    }
}
