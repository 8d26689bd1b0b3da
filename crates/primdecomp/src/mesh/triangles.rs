//! The input's surface as triangles under the hierarchy of [`crate::math::bvh`] (the
//! one `primdecomp eval` measures with), built once per run for whatever needs it:
//! the merge tree's node errors (`cut::error`, nearest triangle) and plates thickened
//! inward (`postprocess::thicken`, first triangle along a ray).

use crate::math::bvh::{point_tri_dist2, ray_tri, tri_box, Bvh};
use crate::math::V3;
use crate::mesh::Mesh;
use rayon::prelude::*;

/// The input's surface as triangles (fan-triangulated polygons, re-centred frame)
/// with a hierarchy over them. The triangles are stored in the hierarchy's order
/// (`Bvh::order`), so that a leaf's lie side by side; a triangle's index here is its
/// place in that order.
#[derive(Clone, Debug, Default)]
pub(crate) struct Triangles {
    tris: Vec<[V3; 3]>,
    bvh: Bvh,
    /// The mesh's bounding-box diagonal.
    pub diagonal: f64,
}

impl Triangles {
    /// The surface of every face of `mesh`.
    pub(crate) fn new(mesh: &Mesh) -> Triangles {
        // Each face's fan as vertex indices, then the triangles' corners written once,
        // in the hierarchy's order, on every thread.
        let mut fans: Vec<[u32; 3]> = Vec::with_capacity(mesh.face_count());
        for f in 0..mesh.face_count() {
            let v = mesh.face(f);
            fans.extend((2..v.len()).map(|k| [v[0], v[k - 1], v[k]]));
        }
        let corners = |t: &[u32; 3]| t.map(|v| mesh.pos(v));
        // Boxes from the corners as the build asks (no table of 48 bytes a
        // triangle), the hierarchy `Bvh::build` makes.
        let bbox = |i: u32| tri_box(&corners(&fans[i as usize]));
        let bvh = Bvh::build_by(fans.len(), crate::math::bvh::LEAF, &bbox);
        let tris = (bvh.order().par_iter())
            .map(|&i| corners(&fans[i as usize]))
            .collect();
        Triangles {
            bvh,
            tris,
            diagonal: mesh.diagonal(),
        }
    }

    /// Distance from `p` to the nearest triangle (infinite for an empty surface);
    /// `stack` is scratch.
    #[cfg(test)]
    pub(crate) fn distance(&self, p: V3, stack: &mut Vec<(f64, u32)>) -> f64 {
        self.nearest(p, stack).0
    }

    /// [`Triangles::distance`] when it is more than `bound`, otherwise some distance
    /// at most `bound` (found sooner): `bound.max(..)` is the same either way.
    pub(crate) fn distance_beyond(&self, p: V3, bound: f64, stack: &mut Vec<(f64, u32)>) -> f64 {
        let enough = if bound > 0.0 {
            bound * bound
        } else {
            f64::NEG_INFINITY
        };
        self.search(p, enough, u32::MAX, stack).0
    }

    /// Distance from `p` to the nearest triangle and that triangle's index (infinite
    /// and `u32::MAX` for an empty surface); `stack` is scratch.
    #[cfg(test)]
    pub(crate) fn nearest(&self, p: V3, stack: &mut Vec<(f64, u32)>) -> (f64, u32) {
        self.nearest_from(p, u32::MAX, stack)
    }

    /// [`Triangles::nearest`] searched from triangle `start` (a guess, such as the
    /// nearest to a point close by), of least index in the input's order among the
    /// nearest, whatever the guess.
    pub(crate) fn nearest_from(
        &self,
        p: V3,
        start: u32,
        stack: &mut Vec<(f64, u32)>,
    ) -> (f64, u32) {
        self.search(p, f64::NEG_INFINITY, start, stack)
    }

    /// `Bvh::nearest_slot` over the triangles, the distance not squared.
    fn search(&self, p: V3, enough: f64, start: u32, stack: &mut Vec<(f64, u32)>) -> (f64, u32) {
        let dist2 = |k: u32| point_tri_dist2(p, &self.tris[k as usize]);
        let (d2, k) = self.bvh.nearest_slot(p, enough, start, stack, dist2);
        (d2.sqrt(), k)
    }

    /// Distance from `p` to triangle `i` (infinite for `u32::MAX`).
    pub(crate) fn distance_to(&self, p: V3, i: u32) -> f64 {
        self.tris
            .get(i as usize)
            .map_or(f64::INFINITY, |t| point_tri_dist2(p, t).sqrt())
    }

    /// The triangles whose box meets the box `lo..hi` (and perhaps some more near
    /// it), into `out` in index order; or `false` once there are more than `most`.
    pub(crate) fn meeting(
        &self,
        lo_hi: (V3, V3),
        most: usize,
        stack: &mut Vec<u32>,
        out: &mut Vec<u32>,
    ) -> bool {
        self.bvh.slots_meeting(lo_hi, most, stack, out)
    }

    /// Triangle `i`'s corners.
    pub(crate) fn corners(&self, i: u32) -> &[V3; 3] {
        &self.tris[i as usize]
    }

    /// How far along the ray `o + t·d` (`t` in `(tmin, tmax]`) it first meets a
    /// triangle, or `None` for a miss; `stack` is scratch.
    pub(crate) fn ray_first(
        &self,
        o: V3,
        d: V3,
        (tmin, tmax): (f64, f64),
        stack: &mut Vec<u32>,
    ) -> Option<f64> {
        let (t, tri) = self.bvh.ray_slot_first(o, d, tmax, stack, |k| {
            ray_tri(o, d, &self.tris[k as usize], tmin)
        });
        (tri != u32::MAX).then_some(t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The hierarchy's nearest distance equals a linear scan over every triangle.
    #[test]
    fn nearest_matches_a_linear_scan() {
        let mesh = crate::demo::demo_scene();
        let s = Triangles::new(&mesh);
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
            // A running maximum sees the same value through the early exit.
            for bound in [0.0, 0.5 * brute, brute, 2.0 * brute] {
                let d = s.distance_beyond(p, bound, &mut stack);
                assert_eq!(bound.max(d), bound.max(brute), "point {p:?}, bound {bound}");
            }
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
