//! Rim reach: how far an output primitive pokes past the planes of the faces just
//! outside its cluster, across the cluster's convex boundary edges (not in the paper;
//! docs/decisions/0024-output-primitives-priced-by-rim-reach.md and
//! docs/decisions/0029-gentle-convex-bends-are-rims.md).
//!
//! The paper chooses a primitive by k·V alone (§3.3). Around a single face or a flat
//! cluster every enclosure is a plate of the same thickness, so k·V is its area, and
//! the least area is often a plate turned off the face's edges: a sliver triangle on a
//! wall's side is enclosed by a rectangle along its longest edge that stands up past
//! the wall's top as a curb, and an isosceles prism around a top triangle reaches out
//! past the wall's side. In a physics scene a curb holds balls that fall off the mesh.
//! The rim reach prices that: for each boundary edge of the cluster where the face
//! across falls away (turns by more than [`RIM_GENTLE_DEG`] and lies below the member
//! face's plane, faces oriented outward by `input::orient`: a crease, or a tessellated
//! rounded edge whose enclosing plate would otherwise stand past it as a lip), the
//! distance the primitive's support reaches past that face's plane on its outer side,
//! squared, times the edge's length (a volume, like k·V: the wedge a curb of that
//! height stands in), counted only beyond the cluster's own points. Concave creases
//! are not rims: past them is the object's inside. Creases one face away count too,
//! across a neighbour that continues the cluster's surface (turns by less than
//! [`RIM_ANGLE_DEG`]).

use crate::input::dedup::{Corners, Weld};
use crate::input::mesh::outward_normal_and_centre;
use crate::input::mesh::Mesh;
use crate::math::{dot, norm, sub, V3};
use crate::primitive::Primitive;

/// Edges whose two faces' normals differ by less than this join faces of one surface
/// (a tessellated curve): the face across continues the cluster's surface, so its own
/// creases one face away are rims too. Past this it is a crease.
pub const RIM_ANGLE_DEG: f64 = 20.0;

/// A face across a boundary edge that continues the surface but falls away by more
/// than this is a rim of the cluster too: a plate around a run of a tessellated
/// convex curve (a rounded roof) is tangent to the run's middle and can stand past the
/// gently turned face beside it, leaving a pocket a ball cannot roll out of
/// (truck_shrec at N = 128: basins for a ball of 1% of the diagonal over 379 cells of
/// a 0.1% grid against the mesh's 36, 125 with this; `tests/rim.rs`). Below it, the
/// face across is the same plane up to tessellation noise. A rim is a plane, raised
/// to the cluster's own points: a cluster along a surface that rises and falls
/// crosses its neighbours' planes itself, and there it prices nothing.
pub const RIM_GENTLE_DEG: f64 = 2.0;

/// The input's face adjacency as CSR lists (`input::adjacency::neighbour_lists`): face
/// `f`'s neighbours are `adj[offsets[f]..offsets[f + 1]]`. Empty = no rim reach.
#[derive(Clone, Copy, Debug, Default)]
pub struct FaceAdjacency<'a> {
    pub offsets: &'a [u32],
    pub adj: &'a [u32],
}

impl FaceAdjacency<'_> {
    pub fn is_empty(&self) -> bool {
        self.offsets.is_empty()
    }
    /// Face `f`'s neighbours.
    pub fn of(&self, f: u32) -> &[u32] {
        let f = f as usize;
        match (self.offsets.get(f), self.offsets.get(f + 1)) {
            (Some(&a), Some(&b)) => &self.adj[a as usize..b as usize],
            _ => &[],
        }
    }
}

/// One rim: the outward unit normal `d` of the face beyond a convex crease, its plane's
/// offset `d·x` (raised by [`clamp_to_points`] to the cluster's own reach), and the
/// crease's length.
#[derive(Clone, Copy, Debug)]
pub struct Rim {
    d: V3,
    offset: f64,
    len: f64,
}

impl Rim {
    /// The outward unit normal of the face beyond the crease: the direction a
    /// primitive must not reach along past the rim's plane.
    #[cfg(any(test, feature = "test-internals"))]
    pub fn direction(&self) -> V3 {
        self.d
    }
}

/// Raises each rim's plane to the farthest of the cluster's points along its
/// direction: where the cluster's own faces cross a rim plane (a face across the
/// edge that only touches the cluster there), every enclosure reaches that far, and
/// only reach beyond it is a curb. Without this such a rim's unavoidable gap, squared,
/// outweighed k·V between frames (cesium_milk_truck's roof fascia at 595 stood 0.15
/// above the roof).
pub fn clamp_to_points(rims: &mut [Rim], x: &[f64], y: &[f64], z: &[f64]) {
    for r in rims {
        let [dx, dy, dz] = r.d;
        let reach = (0..x.len())
            .map(|i| dx * x[i] + dy * y[i] + dz * z[i])
            .fold(f64::NEG_INFINITY, f64::max);
        r.offset = r.offset.max(reach);
    }
}

/// [`rim_penalty`]'s whole sum, unweighted.
#[cfg(test)]
fn rim_reach(prim: &Primitive, rims: &[Rim]) -> f64 {
    rim_penalty(prim, rims, 1.0, 0.0, f64::INFINITY)
}

/// `weight` × Σ len·(h(d) − offset)² over the rims, h the primitive's support
/// function (zero when the primitive stays behind every rim plane); or, once `cost`
/// plus `weight` × the part summed reaches `limit`, `weight` × that part: the whole
/// sum, of terms ≥ 0, is no less (a [`crate::primitive::fit::Penalty`]).
pub fn rim_penalty(prim: &Primitive, rims: &[Rim], weight: f64, cost: f64, limit: f64) -> f64 {
    let mut sum = 0.0;
    for r in rims {
        let gap = (prim.support(r.d) - r.offset).max(0.0);
        sum += r.len * gap * gap;
        if cost + weight * sum >= limit {
            break;
        }
    }
    weight * sum
}

/// The faces around one cluster and how to tell its rims: the input with its weld,
/// its adjacency, and each face's outward sign (`input::orient`).
#[derive(Clone, Copy, Debug)]
pub struct Surroundings<'a> {
    pub mesh: &'a Mesh,
    pub weld: &'a Weld,
    pub adj: FaceAdjacency<'a>,
    pub signs: &'a [i8],
}

impl Surroundings<'_> {
    /// Whether faces a and b (normals `na`, `nb`, centres `ca`, `cb`) meet at a convex
    /// crease: they turn by more than the angle whose cosine is `cos_max` and b falls
    /// away below a's plane. At a concave crease (a wall rising from a floor) the space
    /// past b's plane is inside the object, where reaching costs nothing.
    fn convex_crease(na: V3, ca: V3, nb: V3, cb: V3, cos_max: f64) -> bool {
        dot(na, nb) < cos_max && dot(na, sub(cb, ca)) < 0.0
    }

    /// The rims of the cluster whose faces are `members` (sorted, unique) into `out`:
    /// for each member face f and neighbour g outside the cluster, g's plane when g
    /// falls away from f by more than [`RIM_GENTLE_DEG`] (a convex bend or crease);
    /// and, when g continues f's surface (they turn by less than [`RIM_ANGLE_DEG`]),
    /// the planes of g's own convex creases with neighbours outside the cluster, since
    /// a primitive turned off f's edges can stand past a rim one face away (a sliver
    /// whose corner alone touches a wall's top).
    pub fn rims(&self, members: &[u32], out: &mut Vec<Rim>) {
        self.rims_where(members, |g| members.binary_search(&g).is_err(), out);
    }

    /// [`Self::rims`] of a cluster told by `outside` (true for a face not in it), from
    /// `faces`, its members with a neighbour outside it, in increasing order (the
    /// others have no rims): the same rims in the same order.
    pub fn rims_where(&self, faces: &[u32], outside: impl Fn(u32) -> bool, out: &mut Vec<Rim>) {
        out.clear();
        self.rims_added(faces, outside, out);
    }

    /// [`Self::rims_where`] appended to `out`: a cluster's faces taken in blocks, in
    /// order, give its rims in order.
    pub fn rims_added(&self, faces: &[u32], outside: impl Fn(u32) -> bool, out: &mut Vec<Rim>) {
        let cos_max = RIM_ANGLE_DEG.to_radians().cos();
        let cos_gentle = RIM_GENTLE_DEG.to_radians().cos();
        let at =
            |f: u32| outward_normal_and_centre(self.mesh, self.signs, f).map(|(n, c, _)| (n, c));
        for &f in faces {
            let Some((nf, cf)) = at(f) else {
                continue;
            };
            for &g in self.adj.of(f).iter().filter(|&&g| outside(g)) {
                let Some((ng, cg)) = at(g) else {
                    continue;
                };
                if Self::convex_crease(nf, cf, ng, cg, cos_gentle) {
                    out.extend(self.rim(f, g, ng));
                }
                if dot(nf, ng) < cos_max {
                    continue; // a crease: g does not continue f's surface
                }
                for &h in self.adj.of(g).iter().filter(|&&h| h != f && outside(h)) {
                    match at(h) {
                        Some((nh, ch)) if Self::convex_crease(ng, cg, nh, ch, cos_max) => {
                            out.extend(self.rim(g, h, nh));
                        }
                        _ => {}
                    }
                }
            }
        }
    }

    /// The rim of face `g` (outward unit normal `ng`) across its edge with face `e`;
    /// `None` when the two share no edge.
    fn rim(&self, e: u32, g: u32, ng: V3) -> Option<Rim> {
        let wface = |f: u32| self.weld.face(self.mesh, f as usize);
        let (a, b) = shared_edge(wface(e), wface(g))?;
        let offset = self
            .mesh
            .face(g as usize)
            .iter()
            .map(|&v| dot(ng, self.mesh.pos(v)))
            .fold(f64::NEG_INFINITY, f64::max);
        Some(Rim {
            d: ng,
            offset,
            len: norm(sub(self.mesh.pos(b), self.mesh.pos(a))),
        })
    }
}

/// Two welded vertices both faces use (the first two found in `f`'s order), if any.
fn shared_edge(f: Corners, g: Corners) -> Option<(u32, u32)> {
    let mut it = f.iter().filter(|&v| g.contains(v));
    let a = it.next()?;
    let b = it.find(|&v| v != a)?;
    Some((a, b))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::input::adjacency::{face_pairs, neighbour_lists};
    use crate::math::{add, scale};
    use crate::primitive::obb::Obb;

    /// The rims of `members` in `m` (unwelded, windings as given: outward here).
    fn rims_of(m: &Mesh, members: &[u32]) -> Vec<Rim> {
        let pairs = face_pairs(&m.face_offsets, &m.face_indices);
        let (offsets, adj) = neighbour_lists(m.face_count(), &pairs);
        let s = Surroundings {
            mesh: m,
            weld: &Weld::none(),
            adj: FaceAdjacency {
                offsets: &offsets,
                adj: &adj,
            },
            signs: &[],
        };
        let mut out = vec![];
        s.rims(members, &mut out);
        out
    }

    /// An L of two outward faces: a top square at y = 1 over x, z ∈ [0, 1] (normal +y)
    /// and a side square at z = 1 hanging below it (x, y ∈ [0, 1], normal +z), sharing
    /// the edge z = 1, y = 1: a convex crease.
    fn ell() -> Mesh {
        Mesh::from_polygons(&ell_points(), &[vec![0, 3, 2, 1], vec![3, 4, 5, 2]]).unwrap()
    }

    fn ell_points() -> [V3; 6] {
        [
            [0.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],
            [1.0, 1.0, 1.0],
            [0.0, 1.0, 1.0],
            [0.0, 0.0, 1.0],
            [1.0, 0.0, 1.0],
        ]
    }

    fn plate(center: V3, axes: [V3; 3], half: V3) -> Primitive {
        Primitive::Box(Obb { center, axes, half })
    }

    #[test]
    fn side_plate_standing_past_the_top_is_priced_and_a_flush_one_is_not() {
        let m = ell();
        let out = rims_of(&m, &[1]);
        assert_eq!(out.len(), 1, "the side face has one rim: the top");
        let r = out[0];
        // Past the top is up: +y, the top's plane at y = 1.
        let top = 1.0 - m.offset[1];
        assert!((r.d[1] - 1.0).abs() < 1e-12 && (r.offset - top).abs() < 1e-12);
        assert!((r.len - 1.0).abs() < 1e-12);
        let axes = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let local = |p: V3| sub(p, m.offset);
        let flush = plate(local([0.5, 0.5, 1.0]), axes, [0.5, 0.5, 0.001]);
        assert_eq!(rim_reach(&flush, &out), 0.0);
        let curb = plate(local([0.5, 0.55, 1.0]), axes, [0.5, 0.55, 0.001]);
        assert!((rim_reach(&curb, &out) - 0.01).abs() < 1e-12, "1 · 0.1²");
        // The top face's rim is the side's plane z = 1, crossed towards +z.
        let out = rims_of(&m, &[0]);
        assert_eq!(out.len(), 1);
        let side = 1.0 - m.offset[2];
        assert!((out[0].d[2] - 1.0).abs() < 1e-12 && (out[0].offset - side).abs() < 1e-12);
        // Both faces in the cluster: no boundary edge has a face across it.
        assert!(rims_of(&m, &[0, 1]).is_empty());
    }

    #[test]
    fn rims_the_cluster_itself_crosses_start_at_its_points() {
        let mut rims = vec![
            Rim {
                d: [0.0, 1.0, 0.0],
                offset: 0.5,
                len: 1.0,
            },
            Rim {
                d: [1.0, 0.0, 0.0],
                offset: 2.0,
                len: 1.0,
            },
        ];
        clamp_to_points(&mut rims, &[0.0, 1.0], &[0.8, 0.2], &[0.0, 0.0]);
        assert_eq!(rims[0].offset, 0.8, "raised to the highest point");
        assert_eq!(rims[1].offset, 2.0, "already past every point: kept");
    }

    #[test]
    fn a_rim_one_face_away_counts() {
        // The L's side continued downwards by a coplanar face 2 (y ∈ [-1, 0]): its
        // cluster's only neighbour is the side, whose creased neighbour is the top.
        let mut p = ell_points().to_vec();
        p.extend([[0.0, -1.0, 1.0], [1.0, -1.0, 1.0]]);
        let faces = [vec![0, 3, 2, 1], vec![3, 4, 5, 2], vec![4, 6, 7, 5]];
        let m = Mesh::from_polygons(&p, &faces).unwrap();
        let out = rims_of(&m, &[2]);
        assert_eq!(out.len(), 1, "the top, across the side");
        let top = 1.0 - m.offset[1];
        assert!((out[0].d[1] - 1.0).abs() < 1e-12 && (out[0].offset - top).abs() < 1e-12);
    }

    /// The L with its second face continuing the top outwards (z > 1), bent down by
    /// `deg` degrees across the shared edge: a convex bend, a crease past 20°.
    fn bent_ell(deg: f64) -> Mesh {
        let t = deg.to_radians();
        let mut p = ell_points();
        p[4] = [0.0, 1.0 - t.sin(), 1.0 + t.cos()];
        p[5] = [1.0, 1.0 - t.sin(), 1.0 + t.cos()];
        Mesh::from_polygons(&p, &[vec![0, 3, 2, 1], vec![3, 4, 5, 2]]).unwrap()
    }

    /// A gentle convex bend (10°, past [`RIM_GENTLE_DEG`], short of a crease) makes each
    /// face a rim of the other: a plate around the bent face that stands past the top's
    /// plane is priced, one flush with it is not.
    #[test]
    fn a_gentle_convex_bend_is_a_rim() {
        let m = bent_ell(10.0);
        let out = rims_of(&m, &[1]);
        assert_eq!(out.len(), 1, "the top, across the bend");
        let top = 1.0 - m.offset[1];
        assert!((out[0].d[1] - 1.0).abs() < 1e-12 && (out[0].offset - top).abs() < 1e-12);
        assert_eq!(rims_of(&m, &[0]).len(), 1, "and the bent face of the top");
        // An upright box around the bent face, its top 0.01 above the top's plane,
        // stands past it; a plate lying on the bent face, under its plane, does not.
        let local = |p: V3| sub(p, m.offset);
        let h = 10f64.to_radians();
        let axes = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let (lo, hi) = (1.0 - h.sin(), 1.01);
        let upright = plate(
            local([0.5, 0.5 * (lo + hi), 1.0 + 0.5 * h.cos()]),
            axes,
            [0.5, 0.5 * (hi - lo), 0.5 * h.cos()],
        );
        assert!(
            (rim_reach(&upright, &out) - 1e-4).abs() < 1e-12,
            "1 · 0.01²"
        );
        let (f, along) = ([0.0, h.cos(), h.sin()], [0.0, -h.sin(), h.cos()]);
        let mid = [0.5, 1.0 - 0.5 * h.sin(), 1.0 + 0.5 * h.cos()];
        let lying = plate(
            local(add(mid, scale(f, -0.001))),
            [[1.0, 0.0, 0.0], f, along],
            [0.5, 0.001, 0.5],
        );
        assert!(rim_reach(&lying, &out) < 1e-24);
    }

    #[test]
    fn concave_creases_slight_bends_and_missing_adjacency_give_no_rims() {
        // A floor (y = 0, normal +y) and a wall rising from its edge z = 0 (normal
        // +z, into the room): past either's plane from the other is inside.
        let p = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 0.0, 1.0],
            [0.0, 0.0, 1.0],
            [0.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],
        ];
        let m = Mesh::from_polygons(&p, &[vec![0, 3, 2, 1], vec![0, 1, 5, 4]]).unwrap();
        assert!(m.newell(0)[1] > 0.0 && m.newell(1)[2] > 0.0);
        assert!(rims_of(&m, &[0]).is_empty() && rims_of(&m, &[1]).is_empty());
        // Reversed windings make the same crease convex: the sign decides.
        let m = Mesh::from_polygons(&p, &[vec![0, 1, 2, 3], vec![0, 4, 5, 1]]).unwrap();
        assert_eq!(rims_of(&m, &[0]).len(), 1);
        // The L's side tilted to 1° below the top's plane: the same surface.
        let m = bent_ell(1.0);
        assert!(rims_of(&m, &[1]).is_empty());
        let s = Surroundings {
            mesh: &m,
            weld: &Weld::none(),
            adj: FaceAdjacency::default(),
            signs: &[],
        };
        let mut out = vec![];
        s.rims(&[1], &mut out);
        assert!(out.is_empty());
    }

    /// A random unit vector (none from a draw shorter than 0.1).
    fn random_unit(rng: &mut rand_chacha::ChaCha8Rng) -> V3 {
        use rand::Rng;
        loop {
            let v = [0, 1, 2].map(|_| rng.gen_range(-1.0..1.0));
            if let Some(u) = crate::math::normalize(v).filter(|_| crate::math::norm(v) > 0.1) {
                break u;
            }
        }
    }

    /// A random cloud of 4 to 39 points in a box, up to 29 rims each at most 0.3 in
    /// from the cloud's reach along its direction, and a rim weight.
    fn random_case(rng: &mut rand_chacha::ChaCha8Rng) -> (Vec<V3>, Vec<Rim>, f64) {
        use rand::Rng;
        let n = rng.gen_range(4..40);
        let h: V3 = [0, 1, 2].map(|_| rng.gen_range(0.01..1.0));
        let pts: Vec<V3> = (0..n).map(|_| h.map(|h| rng.gen_range(-h..h))).collect();
        let rims: Vec<Rim> = (0..rng.gen_range(0..30))
            .map(|_| {
                let d = random_unit(rng);
                let reach = (0..n).map(|i| dot(d, pts[i])).fold(f64::MIN, f64::max);
                Rim {
                    d,
                    offset: reach - rng.gen_range(0.0..0.3),
                    len: rng.gen_range(0.01..1.0),
                }
            })
            .collect();
        let w = [0.1, 1.0, 30.0][rng.gen_range(0..3)];
        (pts, rims, w)
    }

    /// A penalty that stops once its offer cannot win changes no fit: over random
    /// clouds, rims and bars, every frame's fit and score with `rim_penalty` stopping
    /// early are those with its whole sum, and a stopped sum is at most the whole and
    /// reaches its limit.
    #[test]
    fn a_penalty_stopped_short_chooses_as_the_whole_one() {
        use crate::primitive::fit::{fit_frame_priced, FitConfig, FrameSearch};
        use crate::primitive::{Cloud, FitScratch};
        use rand::SeedableRng;
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(26);
        let cfg = FitConfig {
            weights: [1.0, 1.0, 1.0, 1.05, 2.1, 1.4],
            enabled: [true; 6],
            min_half: 1e-6,
            frames: FrameSearch::Degenerate,
        };
        let (stopped, mut s) = (std::cell::Cell::new(0), FitScratch::default());
        for _ in 0..300 {
            let (pts, rims, w) = random_case(&mut rng);
            let (x, y, z): (Vec<f64>, Vec<f64>, Vec<f64>) = (
                pts.iter().map(|p| p[0]).collect(),
                pts.iter().map(|p| p[1]).collect(),
                pts.iter().map(|p| p[2]).collect(),
            );
            let cloud = Cloud {
                x: &x,
                y: &y,
                z: &z,
            };
            let whole =
                |p: &Primitive, _: f64, _: f64| rim_penalty(p, &rims, w, 0.0, f64::INFINITY);
            let short = |p: &Primitive, cost: f64, limit: f64| {
                let got = rim_penalty(p, &rims, w, cost, limit);
                let all = whole(p, cost, limit);
                assert!(got <= all && (got == all || cost + got >= limit));
                stopped.set(stopped.get() + usize::from(got < all));
                got
            };
            let a = random_unit(&mut rng);
            let b = crate::math::normalize(crate::math::cross(a, random_unit(&mut rng)))
                .expect("apart");
            let axes = [a, b, crate::math::cross(a, b)];
            let free = fit_frame_priced(&cloud, axes, &cfg, &mut s, &whole, f64::INFINITY);
            let (_, score) = free.expect("no bar");
            for bar in [
                f64::INFINITY,
                score * 1.5,
                score * 1.0001,
                score,
                score * 0.9,
            ] {
                let a = fit_frame_priced(&cloud, axes, &cfg, &mut s, &whole, bar);
                let b = fit_frame_priced(&cloud, axes, &cfg, &mut s, &short, bar);
                let key = |f: Option<(crate::primitive::fit::Fit, f64)>| {
                    f.map(|(f, score)| format!("{:?} {} {score}", f.prim, f.cost))
                };
                assert_eq!(key(a), key(b), "bar {bar}");
            }
        }
        let stopped = stopped.get();
        assert!(
            stopped > 100,
            "only {stopped} sums stopped short: the test is vacuous"
        );
    }
}
