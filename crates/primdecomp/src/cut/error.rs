//! A node's error: the one-way distance from its primitive's surface to the input's
//! surface, the quantity `primdecomp eval` reports as Hausdorff (there over the union
//! of the output; here over one primitive, so an upper bound of its share). Estimated
//! by sampling: the primitive's conservative tessellation (`export::tessellate`), its
//! vertices and points on each triangle in proportion to area, each measured to the
//! nearest input triangle anywhere in the mesh (`mesh::triangles`): the whole mesh, as
//! eval measures, not only the node's faces, so a primitive lying on another part's
//! surface is not charged for it, and one hierarchy serves every node.

use crate::export::tessellate;
use crate::math::{add, cross, norm, scale, sub, V3};
use crate::mesh::triangles::Triangles;
use crate::primitive::Primitive;

/// Segments around circles of the tessellation (its polygons stand at most
/// 1/cos(π/24) − 1 ≈ 0.9% of a radius outside a round primitive).
const DETAIL: usize = 24;
/// Points spread over the primitive's surface in proportion to area (plus every
/// vertex of its tessellation).
const SAMPLES: usize = 192;

/// The estimated error of `prim` (0 for an empty surface).
pub(crate) fn error_of(prim: &Primitive, surface: &Triangles) -> f64 {
    let tess = tessellate(prim, DETAIL);
    let mut tris: Vec<[V3; 3]> = Vec::new();
    for f in &tess.faces {
        let v = |i: usize| tess.vertices[f[i] as usize];
        for k in 2..f.len() {
            tris.push([v(0), v(k - 1), v(k)]);
        }
    }
    let area = |t: &[V3; 3]| 0.5 * norm(cross(sub(t[1], t[0]), sub(t[2], t[0])));
    let total: f64 = tris.iter().map(area).sum();
    let mut stack = Vec::new();
    let mut worst = 0.0f64;
    for &p in &tess.vertices {
        worst = worst.max(surface.distance_beyond(p, worst, &mut stack));
    }
    if !(total > 0.0 && total.is_finite()) {
        return worst;
    }
    for t in &tris {
        let k = (SAMPLES as f64 * area(t) / total).ceil() as usize;
        for i in 0..k.min(SAMPLES) {
            worst = worst.max(surface.distance_beyond(point_on(t, i), worst, &mut stack));
        }
    }
    worst
}

/// The `i`-th point of a low-discrepancy sequence (Roberts' R2) on triangle `t`,
/// folded into it; deterministic.
fn point_on(t: &[V3; 3], i: usize) -> V3 {
    const G1: f64 = 0.754_877_666_246_692_7;
    const G2: f64 = 0.569_840_290_998_053_3;
    let (mut u, mut v) = ((0.5 + G1 * i as f64).fract(), (0.5 + G2 * i as f64).fract());
    if u + v > 1.0 {
        (u, v) = (1.0 - u, 1.0 - v);
    }
    add(
        t[0],
        add(scale(sub(t[1], t[0]), u), scale(sub(t[2], t[0]), v)),
    )
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::primitive::Primitive;

    fn unit_box(half: V3) -> Primitive {
        Primitive::Box(crate::primitive::obb::Obb {
            center: [0.0; 3],
            axes: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            half,
        })
    }

    /// A box's error against its own surface is 0; against a smaller box inside it,
    /// the distance of its farthest point (a corner: √3 × the gap).
    #[test]
    fn a_box_is_as_far_as_its_farthest_corner() {
        let inner = Triangles::new(&cube_mesh(1.0));
        assert!(error_of(&unit_box([1.0; 3]), &inner) < 1e-12);
        let e = error_of(&unit_box([1.5; 3]), &inner);
        assert!((e - 0.5 * 3f64.sqrt()).abs() < 1e-12, "{e}");
    }

    /// A closed cube of half-extent `h` about the origin, as quads.
    pub(in crate::cut) fn cube_mesh(h: f64) -> crate::mesh::Mesh {
        let mut b = crate::mesh::MeshBuilder::new();
        for i in 0..8u32 {
            let s = |bit: u32| if i >> bit & 1 == 1 { h } else { -h };
            b.positions.push([s(0), s(1), s(2)]);
        }
        for f in [
            [0, 4, 6, 2],
            [1, 3, 7, 5],
            [0, 1, 5, 4],
            [2, 6, 7, 3],
            [0, 2, 3, 1],
            [4, 5, 7, 6],
        ] {
            b.push_face(&f);
        }
        crate::mesh::Mesh::from_builder(b)
    }

    #[test]
    fn points_stay_on_the_triangle() {
        let t = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        for i in 0..100 {
            let p = point_on(&t, i);
            assert!(p[0] >= 0.0 && p[1] >= 0.0 && p[0] + p[1] <= 1.0 + 1e-12);
        }
    }
}
