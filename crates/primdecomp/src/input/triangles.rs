//! The input's surface as triangles under the hierarchy of [`crate::math::bvh`] (the
//! one `primdecomp eval` measures with), built once per run for whatever needs it:
//! the merge tree's node errors (`cut::error`, nearest triangle) and plates thickened
//! inward (`postprocess::thicken`, first triangle along a ray). Under `--solid` it
//! also holds the input's interior ([`Triangles::with_solid`]): the cut's distances
//! are then to the input's solid, a point proven inside it at 0 ([`Triangles::inside`],
//! docs/decisions/0056).

use crate::input::mesh::Mesh;
use crate::input::solid::Solid;
use crate::math::bvh::{point_tri_dist2, ray_tri, tri_box, tris_apart, Bvh, Compact};
use crate::math::{madd, norm, sub, V3};

/// A point is proven inside only when its distance to the surface exceeds its
/// distance to an inside cell's centre by this fraction of the diagonal: far above
/// the rounding of either distance.
const INSIDE_MARGIN: f64 = 1e-9;
/// Most balls a proof of a point inside ([`Triangles::inside`]) is made of,
const MARCH_STEPS: usize = 12;
/// and the least share of the way left the next may reach (1/this).
const MARCH_STALL: f64 = 32.0;

/// The input's surface as triangles (fan-triangulated polygons, re-centred frame)
/// with a hierarchy over them. A triangle's index here is its place in the
/// hierarchy's order (`Bvh::order`), so that a leaf's are neighbours. Each triangle
/// is its corners' vertex ids in the mesh, whose positions it reads: an all-triangle
/// mesh's faces are read through the order (no copy: 12 bytes a triangle fewer, for
/// a scattered read of the face's three ids), a polygon mesh's fans are stored in
/// the order (12 bytes a triangle). The hierarchy's boxes are [`Compact`] (f32,
/// rounded outwards): about 19 bytes a triangle instead of 34, the same answers.
#[derive(Clone, Debug)]
pub(crate) struct Triangles<'m> {
    /// The fans in the hierarchy's order; empty when every face is a triangle (read
    /// from the mesh through `Bvh::order`).
    fans: Vec<[u32; 3]>,
    mesh: &'m Mesh,
    bvh: Bvh<Compact>,
    /// The mesh's bounding-box diagonal.
    pub diagonal: f64,
    /// The input's interior where distances are to its solid ([`Triangles::with_solid`]).
    solid: Option<&'m Solid>,
}

impl<'m> Triangles<'m> {
    /// The surface of every face of `mesh`.
    #[cfg(test)]
    pub(crate) fn new(mesh: &'m Mesh) -> Triangles<'m> {
        Triangles::new_checked(mesh, &|_| true).expect("never told to stop")
    }

    /// [`Triangles::new`] that asks `go_on` whether to go on while the hierarchy is
    /// built ([`Bvh::build_by_checked`]); `None` when it said stop.
    pub(crate) fn new_checked(
        mesh: &'m Mesh,
        go_on: crate::progress::Checkpoint,
    ) -> Option<Triangles<'m>> {
        // Each face's fan as vertex indices (the faces themselves when all are
        // triangles), then, for polygons, the fans in the hierarchy's order.
        let all_triangles = mesh.face_indices.len() == 3 * mesh.face_count();
        let mut fans: Vec<[u32; 3]> = Vec::new();
        if !all_triangles {
            for f in 0..mesh.face_count() {
                let v = mesh.face(f);
                fans.extend((2..v.len()).map(|k| [v[0], v[k - 1], v[k]]));
            }
        }
        let fan = |i: u32| match all_triangles {
            true => {
                let v = mesh.face(i as usize);
                [v[0], v[1], v[2]]
            }
            false => fans[i as usize],
        };
        let count = if all_triangles {
            mesh.face_count()
        } else {
            fans.len()
        };
        // Boxes from the corners as the build asks (no table of 48 bytes a
        // triangle), the hierarchy `Bvh::build` makes.
        let bbox = |i: u32| tri_box(&fan(i).map(|v| mesh.pos(v)));
        let bvh = Bvh::build_compact(count, crate::math::bvh::LEAF, &bbox, go_on)?;
        // In blocks, asking between them (a pass over every triangle).
        let mut ordered = Vec::new();
        if !all_triangles {
            ordered.reserve_exact(count);
            for (b, block) in bvh.order().chunks(1 << 20).enumerate() {
                if b > 0 && !go_on(0.0) {
                    return None;
                }
                ordered.extend(block.iter().map(|&i| fans[i as usize]));
            }
        }
        Some(Triangles {
            bvh,
            fans: ordered,
            mesh,
            diagonal: mesh.diagonal(),
            solid: None,
        })
    }

    /// These triangles measuring distances to the input's solid, the interior
    /// `solid` (built on the same mesh) holds, where it has an inside: a point of a
    /// primitive inside the input is at 0, not at its distance to the surface
    /// (`--solid`, docs/decisions/0056). Without an inside, or where the input is open
    /// (`Solid::is_open`), as before: to the surface.
    pub(crate) fn with_solid(self, solid: Option<&'m Solid>) -> Triangles<'m> {
        Triangles {
            solid: solid.filter(|s| s.has_inside() && !s.is_open()),
            ..self
        }
    }

    /// Whether distances are to the input's solid ([`Triangles::with_solid`]).
    pub(crate) fn to_solid(&self) -> bool {
        self.solid.is_some()
    }

    /// Whether `p`, `d` from the surface (its exact distance, or a lower bound of it,
    /// which proves less), is proven inside the input's solid: a path from `p` to the
    /// centre of the grid's cell holding it, which the rays' vote put inside, crosses
    /// no face. The path is straight, covered by balls that meet no face (sphere
    /// tracing): the first of radius `d` around `p`, each next around a point within
    /// the last, of radius its distance to the surface, until one holds the centre;
    /// at most [`MARCH_STEPS`] of them, given up where they shrink below
    /// 1/[`MARCH_STALL`] of the way left (the path nears a face). Always false
    /// without a solid; `stack` is scratch.
    pub(crate) fn inside(&self, p: V3, d: f64, stack: &mut Vec<(f64, u32)>) -> bool {
        let Some(centre) = self.solid.and_then(|s| s.inside_centre(p)) else {
            return false;
        };
        let margin = INSIDE_MARGIN * self.diagonal;
        let (mut q, mut r, mut near) = (p, d, u32::MAX);
        for step in 0..MARCH_STEPS {
            let left = norm(sub(centre, q));
            if r > left + margin {
                return true;
            }
            if step + 1 == MARCH_STEPS || r * MARCH_STALL < left || r <= 2.0 * margin {
                return false;
            }
            // Within the ball around `q`, by a margin: the balls overlap.
            q = madd(q, sub(centre, q), (r - margin) / left);
            (r, near) = self.nearest_from(q, near, stack);
        }
        false
    }

    /// Whether triangle `t` certainly meets none of these triangles: each of those
    /// whose box meets its box is apart from it ([`tris_apart`], by the margin a
    /// proof inside takes); false where more than `most` boxes meet. `stack` and
    /// `slots` are scratch.
    pub(crate) fn apart(
        &self,
        t: &[V3; 3],
        most: usize,
        (stack, slots): (&mut Vec<u32>, &mut Vec<u32>),
    ) -> bool {
        let margin = INSIDE_MARGIN * self.diagonal;
        let (lo, hi) = tri_box(t);
        let grown = (lo.map(|c| c - margin), hi.map(|c| c + margin));
        self.meeting(grown, most, stack, slots)
            && slots.iter().all(|&k| tris_apart(t, &self.tri(k), margin))
    }

    /// Triangle `k`'s corners (`k` in the hierarchy's order).
    #[inline]
    fn tri(&self, k: u32) -> [V3; 3] {
        let ids = match self.fans.is_empty() {
            true => {
                let f = 3 * self.bvh.order()[k as usize] as usize;
                let v = &self.mesh.face_indices[f..f + 3];
                [v[0], v[1], v[2]]
            }
            false => self.fans[k as usize],
        };
        ids.map(|v| self.mesh.pos(v))
    }

    /// How many triangles.
    fn len(&self) -> usize {
        self.bvh.order().len()
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
        let dist2 = |k: u32| point_tri_dist2(p, &self.tri(k));
        let (d2, k) = self.bvh.nearest_slot(p, enough, start, stack, dist2);
        (d2.sqrt(), k)
    }

    /// Distance from `p` to triangle `i` (infinite for `u32::MAX`).
    pub(crate) fn distance_to(&self, p: V3, i: u32) -> f64 {
        match (i as usize) < self.len() {
            true => point_tri_dist2(p, &self.tri(i)).sqrt(),
            false => f64::INFINITY,
        }
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
        let slot_box = |k: u32| tri_box(&self.tri(k));
        self.bvh.slots_meeting(lo_hi, most, slot_box, stack, out)
    }

    /// Triangle `i`'s corners.
    pub(crate) fn corners(&self, i: u32) -> [V3; 3] {
        self.tri(i)
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
        let (t, tri) = self
            .bvh
            .ray_slot_first(o, d, tmax, stack, |k| ray_tri(o, d, &self.tri(k), tmin));
        (tri != u32::MAX).then_some(t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The hierarchy's nearest distance equals a linear scan over every triangle.
    #[test]
    fn nearest_matches_a_linear_scan() {
        let mesh = crate::input::demo::demo_scene();
        let s = Triangles::new(&mesh);
        let mut stack = Vec::new();
        for i in 0..200u32 {
            let t = i as f64;
            let p = [
                (t * 0.37).sin() * 3.0,
                (t * 0.11).cos() * 2.0,
                (t * 0.05).sin(),
            ];
            let brute = (0..s.len() as u32)
                .map(|k| point_tri_dist2(p, &s.tri(k)))
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

    /// An L-shaped prism: the L of [0, 2]² less (1, 2]², from z = 0 to 1; closed,
    /// outward windings (each polygon fanned from its first vertex, the L from its
    /// reflex corner, so that every fan triangle lies in the L).
    pub(crate) fn l_prism() -> Mesh {
        let l = [
            [1.0, 1.0],
            [1.0, 2.0],
            [0.0, 2.0],
            [0.0, 0.0],
            [2.0, 0.0],
            [2.0, 1.0],
        ];
        let mut b = crate::input::mesh::MeshBuilder::new();
        for z in [0.0, 1.0] {
            b.positions.extend(l.iter().map(|&[x, y]| [x, y, z]));
        }
        b.push_face(&[0, 5, 4, 3, 2, 1]);
        b.push_face(&[6, 7, 8, 9, 10, 11]);
        for i in 0..6u32 {
            let j = (i + 1) % 6;
            b.push_face(&[i, j, j + 6, i + 6]);
        }
        Mesh::from_builder(b)
    }

    /// Whether the world point `w` is strictly inside [`l_prism`].
    fn in_l(w: V3) -> bool {
        let [x, y, z] = w;
        let square = |a: f64, b: f64, lo: f64, hi: f64| a > lo && a < hi && b > lo && b < hi;
        z > 0.0 && z < 1.0 && square(x, y, 0.0, 2.0) && !(x >= 1.0 && y >= 1.0)
    }

    /// A point proven inside the solid is inside (never one in the L's notch or
    /// beyond a face, however near), and every point inside deeper than a grid cell's
    /// half-diagonal is proven (its cell's centre is inside). Nothing is inside
    /// without a solid.
    #[test]
    fn points_proven_inside_are_inside() {
        use crate::input::solid::{self, Solid};
        let mesh = l_prism();
        let solid = Solid::build(&mesh, solid::CELLS, solid::VOTES);
        let plain = Triangles::new(&mesh);
        let s = Triangles::new(&mesh).with_solid(Some(&solid));
        assert!(s.to_solid() && !plain.to_solid());
        let half_diagonal = 0.5 * 3f64.sqrt() * 2.0 / solid::CELLS as f64;
        let mut rng = <rand_chacha::ChaCha8Rng as rand::SeedableRng>::seed_from_u64(7);
        let (mut deep, mut near, mut near_proven) = (0, 0, 0);
        let mut stack = Vec::new();
        for _ in 0..20_000 {
            let w: V3 = std::array::from_fn(|k| {
                rand::Rng::gen_range(&mut rng, -0.2..if k == 2 { 1.2 } else { 2.2 })
            });
            let p = sub(w, mesh.offset);
            let d = s.distance(p, &mut stack);
            let proven = s.inside(p, d, &mut stack);
            assert!(
                !proven || in_l(w),
                "{w:?} proven inside, {d} from the surface"
            );
            assert!(!plain.inside(p, d, &mut stack));
            if in_l(w) && d > half_diagonal {
                deep += 1;
                assert!(proven, "{w:?} inside, {d} deep, not proven");
            } else if in_l(w) {
                near += 1;
                near_proven += usize::from(proven);
            }
        }
        assert!(deep > 1000 && near > 200, "{deep} {near}");
        // Near the surface the balls' march proves most (the centre alone a few).
        assert!(near_proven * 4 > near * 3, "{near_proven} of {near}");
    }

    /// Slot `k` is the fan triangle the hierarchy put there, whether read from the
    /// mesh through the order (every face a triangle: nothing copied) or stored
    /// (polygons).
    #[test]
    fn slots_are_the_fans_in_the_hierarchys_order() {
        let grid = |n: u32| {
            let pos: Vec<[f64; 3]> = (0..=n)
                .flat_map(|j| (0..=n).map(move |i| [i as f64, j as f64, ((i * j) % 3) as f64]))
                .collect();
            let at = |i: u32, j: u32| j * (n + 1) + i;
            let quads: Vec<Vec<u32>> = (0..n)
                .flat_map(|j| (0..n).map(move |i| (i, j)))
                .map(|(i, j)| vec![at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)])
                .collect();
            (pos, quads)
        };
        let (pos, quads) = grid(12);
        let tris: Vec<[u32; 3]> = (quads.iter())
            .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
            .collect();
        for mesh in [
            Mesh::from_polygons(&pos, &quads).unwrap(),
            Mesh::from_triangles(&pos, &tris).unwrap(),
            crate::input::demo::demo_scene(),
        ] {
            let fans: Vec<[u32; 3]> = (0..mesh.face_count())
                .flat_map(|f| {
                    let v = mesh.face(f).to_vec();
                    (2..v.len()).map(move |k| [v[0], v[k - 1], v[k]])
                })
                .collect();
            let s = Triangles::new(&mesh);
            let triangles_only = mesh.face_indices.len() == 3 * mesh.face_count();
            assert_eq!(s.fans.is_empty(), triangles_only);
            assert_eq!(s.len(), fans.len());
            for (k, &i) in s.bvh.order().iter().enumerate() {
                let want = fans[i as usize].map(|v| mesh.pos(v));
                assert_eq!(s.corners(k as u32), want, "slot {k}");
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
