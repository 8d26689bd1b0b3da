//! A level's mean distance from its primitives' surfaces to the input, the quantity
//! `primdecomp eval` reports as Chamfer (there sampled), estimated by the midpoint
//! rule: each primitive's tessellation (`output::tessellate`) cut into cells of at
//! most an equal share of the level's area, each cell weighed by its area at its
//! centroid's distance to the nearest input triangle (`input::triangles`; under
//! `--solid` to the input's solid, as `cut::error` measures). As eval's,
//! over the boundary of the union: a cell whose centroid lies inside another
//! primitive is buried, nothing a ball can touch, and left out. A cut of counts alone
//! may spend its count on this mean instead of on the worst distance
//! (docs/decisions/0051); this tells whether that paid. Beyond the paper.

use rayon::prelude::*;

use super::error::{halves, triangles};
use crate::input::triangles::Triangles;
use crate::math::bvh::Bvh;
use crate::math::{add, cross, norm, scale, sub, V3};
use crate::output::tessellate;
use crate::primitive::Primitive;

/// Segments around circles of the tessellation.
const DETAIL: usize = 24;
/// A level's surface is cut into about this many cells (at least),
const CELLS: usize = 4096;
/// or this many per primitive.
const CELLS_PER_PRIMITIVE: usize = 8;
/// A point is buried when it lies this fraction of the diagonal inside another
/// primitive (eval's tolerance).
const BURIED: f64 = 1e-6;

/// The area-weighted mean distance from the boundary of `prims`' union to `surface`
/// (0 for none): the same on any thread count (each primitive's sums are added in
/// order).
pub(crate) fn mean_distance(prims: &[Primitive], surface: &Triangles) -> f64 {
    let tess: Vec<Vec<[V3; 3]>> = prims
        .par_iter()
        .map(|p| triangles(&tessellate(p, DETAIL)))
        .collect();
    let area: f64 = tess.iter().flatten().map(area_of).sum();
    if area <= 0.0 {
        return 0.0;
    }
    let cell = area / CELLS.max(CELLS_PER_PRIMITIVE * prims.len()) as f64;
    let bvh = Bvh::build(&prims.iter().map(Primitive::aabb).collect::<Vec<_>>());
    let tol = BURIED * surface.diagonal;
    let sums: Vec<(f64, f64)> = (tess.par_iter().enumerate())
        .map_init(Vec::new, |stack, (i, tris)| {
            let buried = |c: V3| {
                let other = |j: u32| j as usize != i && prims[j as usize].contains(c, -tol);
                bvh.any_at(c, 0.0, other)
            };
            weighed(tris, cell, (surface, buried), stack)
        })
        .collect();
    let (sum, weight) = sums
        .iter()
        .fold((0.0, 0.0), |(s, w), &(a, b)| (s + a, w + b));
    match weight > 0.0 {
        true => sum / weight,
        false => 0.0,
    }
}

/// The sum over `tris`, cut into cells of at most `cell` area, of each cell's area
/// times its centroid's distance to `surface`, and the summed area, the cells whose
/// centroid is `buried` left out.
fn weighed(
    tris: &[[V3; 3]],
    cell: f64,
    (surface, buried): (&Triangles, impl Fn(V3) -> bool),
    stack: &mut Vec<(f64, u32)>,
) -> (f64, f64) {
    let (mut sum, mut weight) = (0.0, 0.0);
    // Each cell's search starts from the last one's nearest triangle: cells follow
    // each other over the surface.
    let mut near = u32::MAX;
    let mut todo: Vec<[V3; 3]> = Vec::new();
    for t in tris {
        todo.push(*t);
        while let Some(t) = todo.pop() {
            let a = area_of(&t);
            if a > cell {
                todo.extend(halves(&t));
                continue;
            }
            let c = scale(add(add(t[0], t[1]), t[2]), 1.0 / 3.0);
            if buried(c) {
                continue;
            }
            let (d, k) = surface.nearest_from(c, near, stack);
            // Under `--solid`, a centroid proven inside the input stands at 0.
            let d = if surface.inside(c, d, stack) { 0.0 } else { d };
            if d.is_finite() {
                (sum, weight, near) = (sum + a * d, weight + a, k);
            }
        }
    }
    (sum, weight)
}

fn area_of(t: &[V3; 3]) -> f64 {
    0.5 * norm(cross(sub(t[1], t[0]), sub(t[2], t[0])))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::primitive::Sphere;

    /// A ball centred on a tiny triangle stands its radius from it everywhere (up
    /// to the triangle's size and the tessellation's rounding), so its mean is its
    /// radius; two of them the same (neither lies inside the other), and none 0.
    #[test]
    fn a_ball_about_a_point_stands_its_radius_off_it() {
        let mesh = crate::input::mesh::Mesh::from_triangles(
            &[[0.0, 0.0, 0.0], [1e-6, 0.0, 0.0], [0.0, 1e-6, 0.0]],
            &[[0, 1, 2]],
        )
        .expect("a triangle");
        let surface = Triangles::new(&mesh);
        let ball = Primitive::Sphere(Sphere {
            center: [0.0; 3],
            radius: 2.0,
        });
        let mean = mean_distance(&[ball], &surface);
        // The tessellation stands at most 1.7% outside the ball (cut::error).
        assert!((2.0 * (1.0 - 1e-6)..=2.0 * 1.02).contains(&mean), "{mean}");
        let two = mean_distance(&[ball, ball], &surface);
        assert_eq!(mean_distance(&[], &surface), 0.0);
        assert!((two - mean).abs() <= 1e-3 * mean, "{two} vs {mean}");
        // A ball of radius 1 inside it is buried: over both whole surfaces the mean
        // would be (4 · 2 + 1 · 1) / 5 = 1.8.
        let inner = Primitive::Sphere(Sphere {
            center: [0.0; 3],
            radius: 1.0,
        });
        let union = mean_distance(&[inner, ball], &surface);
        assert!((union - mean).abs() <= 1e-3 * mean, "{union} vs {mean}");
    }
}
