//! Display geometry: the triangles of a collider's parts (primitives or hulls) with
//! the part each belongs to, its colour and the outline edges to draw, and the
//! input mesh's triangles.

use std::collections::BTreeMap;

/// Outlines are drawn where the faces on either side of an edge turn by more than
/// this (and along open borders): a box's edges and a cylinder's rims, not the
/// 22.5° facets of a 16-segment round shape or a polygon's fan diagonals.
pub const FEATURE_ANGLE_DEG: f64 = 30.0;

/// Triangles of several parts in world coordinates.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Parts {
    pub positions: Vec<[f64; 3]>,
    pub triangles: Vec<[u32; 3]>,
    /// Part `i` owns triangles `starts[i]..starts[i + 1]`; starts with 0.
    pub starts: Vec<u32>,
    /// Palette index of each part ([`crate::palette::rgb`]).
    pub colour: Vec<u8>,
    /// Outline edges: pairs of vertex indices.
    pub edges: Vec<[u32; 2]>,
}

impl Parts {
    pub fn new() -> Parts {
        Parts {
            starts: vec![0],
            ..Default::default()
        }
    }

    pub fn len(&self) -> usize {
        self.colour.len()
    }

    pub fn is_empty(&self) -> bool {
        self.colour.is_empty()
    }

    /// Adds one part from polygons (fan-triangulated).
    pub fn push_polygons(&mut self, vertices: &[[f64; 3]], polygons: &[Vec<u32>], colour: u8) {
        let tris: Vec<[u32; 3]> = polygons
            .iter()
            .flat_map(|f| (1..f.len().saturating_sub(1)).map(move |i| [f[0], f[i], f[i + 1]]))
            .collect();
        self.push_triangles(vertices, &tris, colour);
    }

    /// Adds one part from triangles; indices out of range are dropped.
    pub fn push_triangles(&mut self, vertices: &[[f64; 3]], triangles: &[[u32; 3]], colour: u8) {
        let base = self.positions.len() as u32;
        let n = vertices.len() as u32;
        let tris: Vec<[u32; 3]> = triangles
            .iter()
            .filter(|t| t.iter().all(|&i| i < n))
            .copied()
            .collect();
        self.edges.extend(
            feature_edges(vertices, &tris)
                .into_iter()
                .map(|[a, b]| [a + base, b + base]),
        );
        self.positions.extend_from_slice(vertices);
        self.triangles
            .extend(tris.iter().map(|t| t.map(|i| i + base)));
        self.starts.push(self.triangles.len() as u32);
        self.colour.push(colour);
    }

    /// Min and max corner over every vertex a triangle uses, if any.
    pub fn aabb(&self) -> Option<([f64; 3], [f64; 3])> {
        aabb(&self.positions, &self.triangles)
    }
}

/// Min and max corner of the vertices `triangles` use, if any.
pub fn aabb(positions: &[[f64; 3]], triangles: &[[u32; 3]]) -> Option<([f64; 3], [f64; 3])> {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for t in triangles {
        for &i in t {
            let p = positions[i as usize];
            for d in 0..3 {
                lo[d] = lo[d].min(p[d]);
                hi[d] = hi[d].max(p[d]);
            }
        }
    }
    (lo[0] <= hi[0]).then_some((lo, hi))
}

fn normal(v: &[[f64; 3]], t: [u32; 3]) -> Option<[f64; 3]> {
    let [a, b, c] = t.map(|i| v[i as usize]);
    let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let w = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    let n = [
        u[1] * w[2] - u[2] * w[1],
        u[2] * w[0] - u[0] * w[2],
        u[0] * w[1] - u[1] * w[0],
    ];
    let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    (l > 0.0 && l.is_finite()).then(|| n.map(|x| x / l))
}

/// Edges of `tris` that lie on a border, are shared by more than two triangles, or
/// where the two triangles turn by more than [`FEATURE_ANGLE_DEG`]; in index order.
/// Degenerate triangles do not count.
pub fn feature_edges(v: &[[f64; 3]], tris: &[[u32; 3]]) -> Vec<[u32; 2]> {
    let mut by_edge: BTreeMap<[u32; 2], Vec<[f64; 3]>> = BTreeMap::new();
    for &t in tris {
        let Some(n) = normal(v, t) else { continue };
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            by_edge.entry([a.min(b), a.max(b)]).or_default().push(n);
        }
    }
    let cos = FEATURE_ANGLE_DEG.to_radians().cos();
    by_edge
        .into_iter()
        .filter(|(_, ns)| match ns.as_slice() {
            [a, b] => a[0] * b[0] + a[1] * b[1] + a[2] * b[2] < cos,
            _ => true,
        })
        .map(|(e, _)| e)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube() -> primdecomp_testkit::shapes::Polys {
        primdecomp_testkit::shapes::cuboid([0.0; 3], [1.0; 3])
    }

    #[test]
    fn a_cube_has_its_twelve_edges_and_no_diagonal() {
        let (v, f) = cube();
        let mut p = Parts::new();
        p.push_polygons(&v, &f, 0);
        assert_eq!(p.triangles.len(), 12);
        assert_eq!(p.edges.len(), 12);
        for [a, b] in &p.edges {
            let (pa, pb) = (v[*a as usize], v[*b as usize]);
            let diff = (0..3).filter(|&d| pa[d] != pb[d]).count();
            assert_eq!(diff, 1, "edge {a}-{b} is a diagonal");
        }
    }

    #[test]
    fn parts_keep_their_ranges_colours_and_offsets() {
        let (v, f) = cube();
        let mut p = Parts::new();
        p.push_polygons(&v, &f, 2);
        p.push_triangles(&v, &[[0, 1, 2], [0, 1, 99]], 6);
        assert_eq!(p.starts, vec![0, 12, 13]);
        assert_eq!(p.colour, vec![2, 6]);
        assert_eq!(p.triangles[12], [8, 9, 10]);
        // The lone triangle's three border edges, offset past the cube's 8 vertices.
        assert_eq!(&p.edges[12..], &[[8, 9], [8, 10], [9, 10]]);
        assert_eq!(p.aabb(), Some(([0.0; 3], [1.0; 3])));
    }
}
