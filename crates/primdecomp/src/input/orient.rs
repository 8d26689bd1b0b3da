//! Consistent face orientation, for the rim reach of the output fits and flush plates
//! (`Plates::rim_weight`, `Plates::flush_plates`; docs/decisions/0024, 0026 and 0027;
//! not in the paper). Many
//! inputs mix windings (truck_shrec: 46% of its area faces outward by its winding), so
//! a face's own normal does not say which side is outside. Faces sharing an edge that
//! no third face is on are made to agree (a shared edge runs in opposite directions in
//! two agreeing faces), one patch at a time from its lowest face, and each patch is
//! then turned: a closed one so that its signed volume is positive (outward), an open
//! one by what rays from its faces see (`visibility`, docs/decisions/0027), and by its signed
//! volume only when they cannot tell.

use super::dedup::{Corners, Weld};
use super::mesh::Mesh;
use super::visibility::{self, RayTree};
use crate::math::{cross, dot, sub, V3};
use std::collections::VecDeque;

/// An open patch's rays must favour one side by this much (in escaped rays per
/// face, of 5 each way, area-weighted) to decide; else its signed volume does.
const MIN_VOTE: f64 = 0.5;

/// Per face, +1 to keep its winding or −1 to reverse it. `weld` gives the faces'
/// welded vertex indices ([`Weld::face`]) and `pairs` the faces sharing an
/// edge ([`super::adjacency::face_pairs`]). Deterministic: breadth-first in face order.
#[cfg(test)]
pub(crate) fn face_signs(mesh: &Mesh, weld: &Weld, pairs: &[(u32, u32)]) -> Vec<i8> {
    let (deg, adj) = super::adjacency::neighbour_lists(mesh.face_count(), pairs);
    face_signs_of_lists(mesh, weld, &deg, &adj)
}

/// [`face_signs`] from the adjacency as CSR neighbour lists
/// ([`super::adjacency::neighbour_lists`]), when the caller has them already.
///
/// Windings propagate across manifold edges only (two faces on the edge): across an
/// edge three faces share, "agreeing" means nothing, and truck_shrec's body, joined
/// through such edges (54 of its 7,822) into one component, came
/// out with its hood facing down and its fenders out. Each patch so found is turned
/// on its own.
#[cfg(any(test, feature = "test-internals"))]
pub fn face_signs_of_lists(mesh: &Mesh, weld: &Weld, deg: &[u32], adj: &[u32]) -> Vec<i8> {
    face_signs_checked(mesh, weld, deg, adj, &|_| true).unwrap_or_default()
}

/// Faces between checks of `go_on` in [`face_signs_checked`].
const CHECK_EVERY: usize = 1 << 16;

/// [`face_signs_of_lists`] that asks `go_on` whether to go on every
/// [`CHECK_EVERY`] faces and stops (`None`) when it says no.
pub fn face_signs_checked(
    mesh: &Mesh,
    weld: &Weld,
    deg: &[u32],
    adj: &[u32],
    go_on: crate::progress::Checkpoint,
) -> Option<Vec<i8>> {
    let n = mesh.face_count();
    let face = |f: usize| weld.face(mesh, f);
    let neighbours = |f: usize| &adj[deg[f] as usize..deg[f + 1] as usize];
    // Most of the walk's work is finding each pair's shared edge: done first, for
    // every face at once (the walk below only reads it).
    let relations = relations_checked(n, &face, &neighbours, go_on)?;
    let mut walk = Walk {
        face,
        neighbours,
        relations: &relations,
        sign: vec![0i8; n],
        queue: VecDeque::new(),
        members: Vec::new(),
        next_check: CHECK_EVERY,
    };
    let mut grid: Option<RayTree> = None;
    for start in 0..n {
        if walk.sign[start] != 0 {
            continue;
        }
        let open = walk.patch(start, go_on)?;
        turn_outward(mesh, &walk.members, &mut walk.sign, open, &mut grid, go_on)?;
    }
    Some(walk.sign)
}

/// The breadth-first walk over the patches: each face's welded corners (`face`),
/// neighbours (`neighbours`) and packed relations with them, and the signs so far.
struct Walk<'r, F, N> {
    face: F,
    neighbours: N,
    relations: &'r [u8],
    sign: Vec<i8>,
    /// Face ids as u32 (the engine's), 4 bytes a face of a patch spanning the input.
    queue: VecDeque<u32>,
    /// The faces of the last patch walked.
    members: Vec<u32>,
    /// Faces left before `go_on` is asked again.
    next_check: usize,
}

impl<'a, F, N> Walk<'_, F, N>
where
    F: Fn(usize) -> Corners<'a>,
    N: Fn(usize) -> &'a [u32],
{
    /// The patch of `start` (unsigned yet), its faces made to agree with it across
    /// manifold edges, in `members`: whether it is open (a face with an edge crossed
    /// to no neighbour); `None` when `go_on` said stop.
    fn patch(&mut self, start: usize, go_on: crate::progress::Checkpoint) -> Option<bool> {
        self.sign[start] = 1;
        self.queue.push_back(start as u32);
        self.members.clear();
        let mut open = false;
        while let Some(f) = self.queue.pop_front() {
            self.members.push(f);
            let f = f as usize;
            self.next_check -= 1;
            if self.next_check == 0 {
                self.next_check = CHECK_EVERY;
                if !go_on(0.0) {
                    return None;
                }
            }
            open |= self.cross_from(f) < (self.face)(f).len();
        }
        Some(open)
    }

    /// Signs and queues `f`'s unsigned neighbours across its manifold edges; the
    /// number of edges crossed.
    fn cross_from(&mut self, f: usize) -> usize {
        let mut crossed = 0;
        for (slot, &g) in (self.neighbours)(f).iter().enumerate() {
            let rel = match Relations::packed(self.relations[f], slot) {
                Some(packed) => packed,
                None => manifold_relation((self.face)(f), g, (self.neighbours)(f), &self.face),
            };
            let Some(rel) = rel else {
                continue;
            };
            crossed += 1;
            if self.sign[g as usize] == 0 {
                // Opposed windings flip; agreeing keep.
                self.sign[g as usize] = rel * self.sign[f];
                self.queue.push_back(g);
            }
        }
        crossed
    }
}

/// Turns the patch `members` outward: an open one by what rays from its faces see
/// (the ray tree built on the first such patch, kept in `grid`), and by its signed
/// volume when they cannot tell or it is closed. `None` when `go_on` said stop.
fn turn_outward<'m>(
    mesh: &'m Mesh,
    members: &[u32],
    sign: &mut [i8],
    open: bool,
    grid: &mut Option<RayTree<'m>>,
    go_on: crate::progress::Checkpoint,
) -> Option<()> {
    let quota = visibility::SAMPLED_FACES * members.len() / mesh.face_count().max(1);
    let seen = if open && quota > 0 {
        if grid.is_none() {
            *grid = Some(RayTree::build_checked(mesh, go_on)?);
        }
        let grid = grid.as_ref()?;
        visibility::vote(grid, members, sign, quota)
    } else {
        None
    };
    let inward = match seen {
        Some(v) if v.abs() >= MIN_VOTE => v < 0.0,
        _ => signed_volume(mesh, members, sign) < 0.0,
    };
    if inward {
        members
            .iter()
            .for_each(|&f| sign[f as usize] = -sign[f as usize]);
    }
    Some(())
}

/// Each face's [`manifold_relation`] with its first [`Relations::SLOTS`] neighbours,
/// packed in a byte (two bits a neighbour: 0 none, 1 agree, 2 opposed), or
/// [`Relations::UNPACKED`] for a face of more neighbours (the walk finds those
/// itself). In parallel blocks of [`CHECK_EVERY`] faces, each checking `go_on`;
/// `None` when it said stop. One byte a face, the same for any thread count.
fn relations_checked<'a>(
    n: usize,
    face: &(impl Fn(usize) -> Corners<'a> + Sync),
    neighbours: &(impl Fn(usize) -> &'a [u32] + Sync),
    go_on: crate::progress::Checkpoint,
) -> Option<Vec<u8>> {
    use rayon::prelude::*;
    let mut packed = vec![0u8; n];
    let stopped = std::sync::atomic::AtomicBool::new(false);
    packed
        .par_chunks_mut(CHECK_EVERY)
        .enumerate()
        .for_each(|(block, out)| {
            if stopped.load(std::sync::atomic::Ordering::Relaxed) || !go_on(0.0) {
                stopped.store(true, std::sync::atomic::Ordering::Relaxed);
                return;
            }
            for (i, byte) in out.iter_mut().enumerate() {
                let f = block * CHECK_EVERY + i;
                let around = neighbours(f);
                *byte = match around.len() > Relations::SLOTS {
                    true => Relations::UNPACKED,
                    false => around.iter().enumerate().fold(0, |acc, (slot, &g)| {
                        let code = match manifold_relation(face(f), g, around, face) {
                            None => 0,
                            Some(1) => 1,
                            Some(_) => 2,
                        };
                        acc | code << (2 * slot)
                    }),
                };
            }
        });
    (!stopped.into_inner()).then_some(packed)
}

/// How [`relations_checked`] packs a face's relations in a byte.
struct Relations;

impl Relations {
    /// Neighbours a byte holds.
    const SLOTS: usize = 4;
    /// A face of more neighbours than [`Relations::SLOTS`]: every code 3, which no
    /// relation packs to.
    const UNPACKED: u8 = u8::MAX;

    /// The relation with neighbour `slot` as packed (`Some(None)`: no manifold shared
    /// edge), or `None` when the face's are not packed.
    fn packed(byte: u8, slot: usize) -> Option<Option<i8>> {
        match byte {
            Relations::UNPACKED => None,
            _ => Some(match (byte >> (2 * slot)) & 3 {
                1 => Some(1),
                2 => Some(-1),
                _ => None,
            }),
        }
    }
}

/// Whether polygon `a` (welded indices) and face `g` agree across their shared edge
/// when that edge is manifold (no other neighbour of `a` in `around` uses it): +1 when
/// they run it in opposite directions, −1 when in the same. `None` when they share no
/// edge or a third face is on it.
fn manifold_relation<'a>(
    a: Corners,
    g: u32,
    around: &[u32],
    face: &impl Fn(usize) -> Corners<'a>,
) -> Option<i8> {
    let (u, v, rel) = shared_edge(a, face(g as usize))?;
    let third = around.iter().any(|&h| {
        let c = face(h as usize);
        h != g && c.contains(u) && c.contains(v)
    });
    (!third).then_some(rel)
}

/// The first edge (u, v) of polygon `a` that polygon `b` also has, with +1 when `b`
/// runs it the other way (the two agree) and −1 when the same way; `None` when they
/// share no edge (or only degenerate ones).
fn shared_edge(a: Corners, b: Corners) -> Option<(u32, u32, i8)> {
    fn edges(p: Corners<'_>) -> impl Iterator<Item = (u32, u32)> + '_ {
        let k = p.len();
        (0..k).map(move |i| (p.get(i), p.get((i + 1) % k)))
    }
    edges(a).filter(|(u, v)| u != v).find_map(|(u, v)| {
        edges(b).find_map(|e| {
            if e == (v, u) {
                Some((u, v, 1))
            } else if e == (u, v) {
                Some((u, v, -1))
            } else {
                None
            }
        })
    })
}

/// Signed volume of the faces `members` with the windings `sign`, about the centre
/// of their first face (fan triangulation; exact for a closed surface anywhere).
fn signed_volume(mesh: &Mesh, members: &[u32], sign: &[i8]) -> f64 {
    let pos = |v: u32| -> V3 { mesh.pos(v) };
    let origin = mesh
        .face(members[0] as usize)
        .first()
        .map_or([0.0; 3], |&v| pos(v));
    let mut vol = 0.0;
    for &f in members {
        let f = f as usize;
        let vs = mesh.face(f);
        for i in 1..vs.len().saturating_sub(1) {
            let (a, b, c) = (pos(vs[0]), pos(vs[i]), pos(vs[i + 1]));
            let t = dot(sub(a, origin), cross(sub(b, origin), sub(c, origin)));
            vol += f64::from(sign[f]) * t;
        }
    }
    vol
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit cube as six quads with outward windings.
    fn cube(flip: &[usize]) -> Mesh {
        let v: Vec<V3> = (0..8)
            .map(|i| [(i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64])
            .collect();
        // The demo's box quads: corner i has bit k set at the high end of axis k.
        let mut f: Vec<Vec<u32>> = crate::input::demo::BOX_FACES
            .map(|q| q.map(|i| i as u32).to_vec())
            .to_vec();
        for &i in flip {
            f[i].reverse();
        }
        Mesh::from_polygons(&v, &f).unwrap()
    }

    fn signs(m: &Mesh) -> Vec<i8> {
        let pairs = super::super::adjacency::face_pairs(&m.face_offsets, &m.face_indices);
        face_signs(m, &Weld::none(), &pairs)
    }

    /// The packed relations are what `manifold_relation` says for every neighbour of a
    /// face of at most four; a face of more is left to the walk. The cube with one
    /// face reversed (opposed neighbours) and a fin on one of its edges (a third face
    /// there: no manifold relation across it, and a fifth neighbour for two faces).
    #[test]
    fn packed_relations_are_the_walks() {
        let c = cube(&[2]);
        let mut v: Vec<V3> = (0..8).map(|i| c.pos(i)).collect();
        v.push([5.0, 5.0, 5.0]);
        let mut f: Vec<Vec<u32>> = (0..6).map(|i| c.face(i).to_vec()).collect();
        let e = &f[0];
        f.push(vec![e[0], e[1], 8]);
        let m = Mesh::from_polygons(&v, &f).unwrap();
        let pairs = super::super::adjacency::face_pairs(&m.face_offsets, &m.face_indices);
        let (deg, adj) = super::super::adjacency::neighbour_lists(m.face_count(), &pairs);
        let unwelded = Weld::none();
        let face = |f: usize| unwelded.face(&m, f);
        let nbrs = |f: usize| &adj[deg[f] as usize..deg[f + 1] as usize];
        let packed = relations_checked(m.face_count(), &face, &nbrs, &|_| true).unwrap();
        let (mut unpacked, mut opposed) = (0, 0);
        for (f, &byte) in packed.iter().enumerate() {
            for (slot, &g) in nbrs(f).iter().enumerate() {
                let walk = manifold_relation(face(f), g, nbrs(f), &face);
                match Relations::packed(byte, slot) {
                    Some(rel) => assert_eq!(rel, walk, "face {f}, neighbour {g}"),
                    None => unpacked += 1,
                }
                opposed += usize::from(walk == Some(-1));
            }
        }
        assert!(unpacked > 0 && opposed > 0);
        assert!(relations_checked(m.face_count(), &face, &nbrs, &|_| false).is_none());
    }

    /// Every face of the cube ends up facing outward, whichever faces were reversed in
    /// the input: the reversed ones get −1, the others +1.
    #[test]
    fn mixed_windings_become_outward() {
        let outward = cube(&[]);
        let n = |m: &Mesh, f: usize, s: i8| {
            let vs = m.face(f);
            let (a, b, c) = (m.pos(vs[0]), m.pos(vs[1]), m.pos(vs[2]));
            let nrm = cross(sub(b, a), sub(c, a));
            // Positions are re-centred: the cube's centre is its vertices' mean.
            let mid = (0..8u32).fold([0.0; 3], |s, v| {
                let p = m.pos(v);
                [s[0] + p[0] / 8.0, s[1] + p[1] / 8.0, s[2] + p[2] / 8.0]
            });
            let out = sub(a, mid);
            f64::from(s) * dot(nrm, out)
        };
        for f in 0..6 {
            assert!(
                n(&outward, f, 1) > 0.0,
                "the fixture's face {f} is not outward"
            );
        }
        for flip in [
            vec![],
            vec![0],
            vec![1, 3],
            vec![0, 1, 2, 3, 4, 5],
            vec![0, 2, 5],
        ] {
            let m = cube(&flip);
            let s = signs(&m);
            for f in 0..6 {
                assert!(
                    n(&m, f, s[f]) > 0.0,
                    "flipped {flip:?}: face {f} faces inward"
                );
            }
        }
    }

    /// A cube with a fin inside on one top edge (a triangle to its centre, listed first):
    /// that edge has three faces. Walking across it, the fin's winding decided the top
    /// and the side differently, and half the cube came out facing in; now windings
    /// cross manifold edges only and the cube, open where the fin joins it, is turned by
    /// the rays from its faces.
    #[test]
    fn a_third_face_on_an_edge_does_not_turn_the_cube_inside_out() {
        for fin in [[3u32, 7, 8], [7, 3, 8]] {
            for flip in [vec![], vec![0, 2, 5]] {
                let c = cube(&flip);
                let mut v: Vec<V3> = (0..8).map(|i| c.pos(i)).collect();
                v.push([0.0; 3]); // the cube's centre: positions are re-centred
                let mut f = vec![fin.to_vec()];
                f.extend((0..6).map(|i| c.face(i).to_vec()));
                let m = Mesh::from_polygons(&v, &f).unwrap();
                let s = signs(&m);
                for i in 0..6 {
                    let vs = m.face(i + 1);
                    let (a, b, d) = (m.pos(vs[0]), m.pos(vs[1]), m.pos(vs[2]));
                    let out = dot(cross(sub(b, a), sub(d, a)), a) * f64::from(s[i + 1]);
                    assert!(
                        out > 0.0,
                        "fin {fin:?}, flipped {flip:?}: face {i} faces inward"
                    );
                }
            }
        }
    }

    /// Two separate cubes, one wound inside out: each component is turned on its own.
    #[test]
    fn components_are_oriented_apart() {
        let a = cube(&[]);
        let b = cube(&[0, 1, 2, 3, 4, 5]);
        let mut v: Vec<V3> = (0..8).map(|i| a.pos(i)).collect();
        v.extend((0..8).map(|i| {
            let p = b.pos(i);
            [p[0] + 3.0, p[1], p[2]]
        }));
        let mut f: Vec<Vec<u32>> = (0..6).map(|i| a.face(i).to_vec()).collect();
        f.extend((0..6).map(|i| b.face(i).iter().map(|&x| x + 8).collect::<Vec<u32>>()));
        let m = Mesh::from_polygons(&v, &f).unwrap();
        let s = signs(&m);
        assert_eq!(&s[..6], &[1; 6]);
        assert_eq!(&s[6..], &[-1; 6]);
    }
}
