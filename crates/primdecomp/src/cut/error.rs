//! A node's error: the one-way distance from its primitive's surface to the input's
//! surface, the quantity `primdecomp eval` reports as Hausdorff (there over the union
//! of the output; here over one primitive, so an upper bound of its share). Estimated
//! by sampling: the primitive's conservative tessellation (`export::tessellate`), its
//! vertices, points along its faces' edges and points on each triangle in proportion
//! to area (the first at its centroid; docs/decisions/0036), each measured to the
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
/// vertex of its tessellation): at least this many,
const SAMPLES: usize = 192;
/// and one per square of this fraction of the mesh's diagonal on a side, up to
/// [`MAX_SAMPLES`]: a fixed count left points 0.06 of the diagonal apart on a large
/// plate, where the farthest point went unmeasured (docs/decisions/0036).
const SPACING: f64 = 0.01;
const MAX_SAMPLES: usize = 4096;
/// Points along one edge of the tessellation's faces, at most (one per spacing).
const EDGE_SAMPLES: usize = 64;

/// The estimated error of `prim` (0 for an empty surface).
pub(crate) fn error_of(prim: &Primitive, surface: &Triangles) -> f64 {
    error_until(prim, surface, f64::INFINITY)
}

/// [`error_of`] while it is at most `above`; past that, the running maximum as soon
/// as it exceeds `above`: a lower bound of the error, enough to know it is over.
/// Either way the result is over `above` exactly when [`error_of`]'s is.
pub(crate) fn error_until(prim: &Primitive, surface: &Triangles, above: f64) -> f64 {
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
    if !(total > 0.0 && total.is_finite()) || worst > above {
        return worst;
    }
    let spacing = SPACING * surface.diagonal;
    // Along every edge of the tessellation's faces (once, though two faces share
    // it), where a box stands farthest from a surface curving away under it
    // (docs/decisions/0036).
    let mut edges: Vec<(u32, u32)> = tess
        .faces
        .iter()
        .flat_map(|f| (0..f.len()).map(|i| (f[i], f[(i + 1) % f.len()])))
        .map(|(a, b)| (a.min(b), a.max(b)))
        .collect();
    edges.sort_unstable();
    edges.dedup();
    for (a, b) in edges {
        let (a, b) = (tess.vertices[a as usize], tess.vertices[b as usize]);
        let k = ((norm(sub(b, a)) / spacing).ceil() as usize).min(EDGE_SAMPLES);
        for j in 0..k {
            let p = add(a, scale(sub(b, a), (j as f64 + 0.5) / k as f64));
            worst = worst.max(surface.distance_beyond(p, worst, &mut stack));
        }
        if worst > above {
            return worst;
        }
    }
    let wanted = (total / (spacing * spacing)).ceil();
    let samples = wanted.clamp(SAMPLES as f64, MAX_SAMPLES as f64) as usize;
    for t in &tris {
        let k = (samples as f64 * area(t) / total).ceil() as usize;
        for i in 0..k.min(samples) {
            worst = worst.max(surface.distance_beyond(point_on(t, i), worst, &mut stack));
        }
        if worst > above {
            return worst;
        }
    }
    worst
}

/// The `i`-th point of a low-discrepancy sequence (Roberts' R2) on triangle `t`,
/// folded into it, the first at its centroid (starting at (½, ½) put it on an edge:
/// a cap's fan triangles given one point each left the cap's centre unmeasured);
/// deterministic.
fn point_on(t: &[V3; 3], i: usize) -> V3 {
    const G1: f64 = 0.754_877_666_246_692_7;
    const G2: f64 = 0.569_840_290_998_053_3;
    const THIRD: f64 = 1.0 / 3.0;
    let (mut u, mut v) = (
        (THIRD + G1 * i as f64).fract(),
        (THIRD + G2 * i as f64).fract(),
    );
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

    /// A long thin cylinder around an open tube (its side only): the caps' centres
    /// stand a radius from the tube, its side nowhere. The caps get about one point
    /// per fan triangle; those points must lie inside the cap, not on its rim (where
    /// the error read as 0), so at least half the radius is found.
    #[test]
    fn a_capped_cylinder_over_an_open_tube_is_a_radius_off() {
        let (r, h, n) = (0.1, 10.0, 48u32);
        let ring = |z: f64| {
            (0..n).map(move |i| {
                let a = std::f64::consts::TAU * i as f64 / n as f64;
                [r * a.cos(), r * a.sin(), z]
            })
        };
        // About the origin, where the mesh keeps its positions.
        let points: Vec<V3> = ring(-h / 2.0).chain(ring(h / 2.0)).collect();
        let quads: Vec<Vec<u32>> = (0..n)
            .map(|i| vec![i, (i + 1) % n, n + (i + 1) % n, n + i])
            .collect();
        let tube = crate::mesh::Mesh::from_polygons(&points, &quads).expect("a tube");
        let cyl = Primitive::Cylinder(crate::primitive::cylinder::Cylinder {
            p0: [0.0, 0.0, -h / 2.0],
            p1: [0.0, 0.0, h / 2.0],
            radius: r,
        });
        let e = error_of(&cyl, &Triangles::new(&tube));
        assert!(e >= 0.5 * r && e <= r * 1.01, "{e}");
    }

    /// The early exit the exploration uses: at or below `above` the error is exact,
    /// over it only known to be over (a lower bound, never above the error itself),
    /// for boxes of several sizes around a cube and levels below, at and above them.
    #[test]
    fn an_early_exit_is_exact_below_its_level_and_over_it_above() {
        let inner = Triangles::new(&cube_mesh(1.0));
        for half in [1.0, 1.01, 1.2, 1.5, 3.0] {
            let prim = unit_box([half, 1.0, 2.0 * half - 1.0]);
            let exact = error_of(&prim, &inner);
            for above in [0.0, 0.5 * exact, exact, 2.0 * exact + 0.1] {
                let e = error_until(&prim, &inner, above);
                assert_eq!(e > above, exact > above, "{half} {above}");
                match exact <= above {
                    true => assert_eq!(e, exact),
                    false => assert!(e <= exact, "{e} > {exact}"),
                }
            }
        }
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
