//! The merge tree of one bottom-up pass (§3.3, Alg. 1: every merge joins two clusters,
//! so the pass defines a binary forest), kept compactly: the clusters of a fine
//! snapshot are its leaves, every merge after that snapshot a node naming its two
//! children, and each node's faces a contiguous range of one permutation of the faces
//! (children's ranges side by side), with the node's operator Q — enough to refit any
//! node's primitive (`Fitter::fit_output` on the range's faces and Q).

use super::pieces;
use crate::input::mesh::Mesh;
use crate::math::Sym3;
use crate::merge::{Fitter, MergeLog, MergeOutput, TreeHulls};
use crate::params::Params;
use std::collections::HashMap;
use std::ops::Range;

/// No child: the node is a leaf (a cluster of the fine snapshot).
const NONE: u32 = u32::MAX;

/// One cluster of the forest: a leaf, or the merge of two earlier nodes.
#[derive(Clone, Copy, Debug)]
pub(crate) struct TreeNode {
    /// The two merged nodes, [`NONE`] for a leaf.
    pub children: [u32; 2],
    /// The node's faces: `order[start..end]` of [`MergeTree::order`].
    pub start: u32,
    pub end: u32,
}

impl TreeNode {
    pub(crate) fn is_leaf(&self) -> bool {
        self.children[0] == NONE
    }
}

/// The forest: nodes in merge order (leaves first), its roots (the clusters alive when
/// merging stopped, in increasing order of their first leaf), the faces permuted so
/// that every node's faces are contiguous, and the hull vertices the merge loop kept
/// for some nodes.
#[derive(Clone, Debug, Default)]
pub(crate) struct MergeTree {
    pub nodes: Vec<TreeNode>,
    /// Each node's operator Q, the sum of its faces' quadrics ([`MergeTree::q`]).
    ops: NodeOps,
    pub roots: Vec<u32>,
    pub order: Vec<u32>,
    /// Nodes' hull vertices as the merge loop priced them: vertex ids whose positions
    /// are the faces' own (`merge::TreeHulls`).
    pub hulls: HashMap<u32, Vec<u32>>,
}

impl MergeTree {
    /// The forest whose leaves are the clusters `members` (with operators `q`) and whose
    /// merges are `log`, in order: each a pair of faces, one in each merged cluster (the
    /// merge loop names clusters by a face of theirs), with the `hulls` the loop kept
    /// (its merges' indices into `log`). `faces` is the input's face count.
    #[cfg(test)]
    pub(crate) fn build<M: AsRef<[u32]>>(
        members: &[M],
        q: &[Sym3],
        log: &[(u32, u32)],
        hulls: TreeHulls,
        faces: usize,
    ) -> Self {
        Self::build_with(members, (q.to_vec(), Singles::NONE), log, hulls, faces)
    }

    /// [`Self::build`], with the operators of the leaves `singles` names (leaves of one
    /// face) found again from the mesh rather than kept: `q` holds every other leaf's.
    fn build_with<M: AsRef<[u32]>>(
        members: &[M],
        (q, singles): (Vec<Sym3>, Singles),
        log: &[(u32, u32)],
        hulls: TreeHulls,
        faces: usize,
    ) -> Self {
        let mut leaf_of = vec![NONE; faces];
        for (i, m) in members.iter().enumerate() {
            (m.as_ref().iter()).for_each(|&f| leaf_of[f as usize] = i as u32);
        }
        let leaf = TreeNode {
            children: [NONE; 2],
            start: 0,
            end: 0,
        };
        let mut nodes = vec![leaf; members.len()];
        let mut ops = NodeOps {
            singles: singles.nodes.clone(),
            kept: q,
            tangent_eps: singles.tangent_eps,
        };
        // A single face's operator while the faces have no place in `order` yet.
        let face_op = |n: u32| match singles.mesh {
            Some(mesh) => face_op(mesh, members[n as usize].as_ref()[0], singles.tangent_eps),
            None => unreachable!("leaves of one face found again name their mesh"),
        };
        let leaves = (&leaf_of[..], members.len());
        let (roots, kept) = replay(&mut nodes, &mut ops, &face_op, leaves, log, hulls);
        let mut tree = MergeTree {
            nodes,
            ops,
            roots,
            order: Vec::with_capacity(faces),
            hulls: kept,
        };
        tree.lay_out(members);
        tree
    }

    /// Node `n`'s operator Q (the sum of its faces' quadrics, in the order the merges
    /// added them); `mesh`: the input, whose faces' quadrics a leaf of one face has.
    pub(crate) fn q(&self, n: u32, mesh: &Mesh) -> Sym3 {
        let face = || face_op(mesh, self.faces(n)[0], self.ops.tangent_eps);
        self.ops.at(n, face)
    }

    /// Assigns each node its range of [`Self::order`], depth-first from each root.
    fn lay_out<M: AsRef<[u32]>>(&mut self, members: &[M]) {
        let mut stack: Vec<(u32, bool)> = self.roots.iter().rev().map(|&r| (r, false)).collect();
        while let Some((n, done)) = stack.pop() {
            let node = self.nodes[n as usize];
            if done {
                self.nodes[n as usize].end = self.order.len() as u32;
                continue;
            }
            self.nodes[n as usize].start = self.order.len() as u32;
            if node.is_leaf() {
                self.order.extend_from_slice(members[n as usize].as_ref());
                self.nodes[n as usize].end = self.order.len() as u32;
                continue;
            }
            stack.push((n, true));
            stack.push((node.children[1], false));
            stack.push((node.children[0], false));
        }
    }

    /// The faces of node `n`.
    pub(crate) fn faces(&self, n: u32) -> &[u32] {
        let node = &self.nodes[n as usize];
        &self.order[node.start as usize..node.end as usize]
    }
}

/// The nodes' operators ([`MergeTree::q`]): a leaf of one face has its face's
/// quadric, found again from the mesh when asked rather than kept (48 bytes less for
/// every face the tree holds alone: all of them without spatial parts, those of the
/// leaves taken apart after them); every other node's is kept, in node order.
#[derive(Clone, Debug, Default)]
struct NodeOps {
    /// The leaves of one face whose operators are found again.
    singles: Range<u32>,
    /// Every other node's operator, in node order.
    kept: Vec<Sym3>,
    /// `Fit::tangent_eps`, with which the faces' quadrics were made.
    tangent_eps: f64,
}

impl NodeOps {
    /// Node `n`'s operator; `face` finds a single face's.
    fn at(&self, n: u32, face: impl FnOnce() -> Sym3) -> Sym3 {
        let singles = &self.singles;
        match n {
            _ if singles.contains(&n) => face(),
            _ if n < singles.start => self.kept[n as usize],
            _ => self.kept[(n - singles.len() as u32) as usize],
        }
    }
}

/// Which leaves of a tree being built are single faces whose operators are found again
/// ([`NodeOps`]), from which mesh and with which `tangent_eps`.
struct Singles<'a> {
    nodes: Range<u32>,
    mesh: Option<&'a Mesh>,
    tangent_eps: f64,
}

#[cfg(test)]
impl Singles<'_> {
    /// Every leaf's operator is kept.
    const NONE: Singles<'static> = Singles {
        nodes: 0..0,
        mesh: None,
        tangent_eps: 0.0,
    };
}

/// Face `f`'s quadric, as the merge loop seeded it (`seed::quadric::face_quadrics`).
fn face_op(mesh: &Mesh, f: u32, tangent_eps: f64) -> Sym3 {
    crate::seed::quadric::face_quadric(mesh.face(f as usize), |v| mesh.pos(v), tangent_eps)
}

/// Replays the merges `log` over the `leaves` first `nodes` (`leaf_of`: each face's
/// leaf, or `NONE`): a node pushed per merge that joined two sets, with its operator the sum
/// of theirs and its hull where the loop kept one. The roots, in the order of their
/// lowest leaves, and the kept hulls by node.
fn replay(
    nodes: &mut Vec<TreeNode>,
    ops: &mut NodeOps,
    face_op: &dyn Fn(u32) -> Sym3,
    (leaf_of, leaves): (&[u32], usize),
    log: &[(u32, u32)],
    hulls: TreeHulls,
) -> (Vec<u32>, HashMap<u32, Vec<u32>>) {
    // Union-find over leaves; `top[r]` is the node a set rooted at leaf r is now.
    let mut parent: Vec<u32> = (0..leaves as u32).collect();
    let mut top: Vec<u32> = parent.clone();
    let TreeHulls {
        leaves: leaf_hulls,
        merges,
    } = hulls;
    let mut kept: HashMap<u32, Vec<u32>> = (0..).zip(leaf_hulls).collect();
    let mut merges = merges.into_iter().peekable();
    for (i, &(a, b)) in log.iter().enumerate() {
        // A kept hull whose merge made no node (it joined no two) is dropped.
        let hull = merges.next_if(|(at, _)| *at as usize == i).map(|(_, h)| h);
        let (la, lb) = (leaf_of[a as usize], leaf_of[b as usize]);
        if la == NONE || lb == NONE {
            continue;
        }
        let (ra, rb) = (find(&mut parent, la), find(&mut parent, lb));
        if ra == rb {
            continue;
        }
        if let Some(hull) = hull {
            kept.insert(nodes.len() as u32, hull);
        }
        let (na, nb) = (top[ra as usize], top[rb as usize]);
        let q = ops.at(na, || face_op(na)).add(&ops.at(nb, || face_op(nb)));
        ops.kept.push(q);
        nodes.push(TreeNode {
            children: [na.min(nb), na.max(nb)],
            start: 0,
            end: 0,
        });
        let (r, o) = (ra.min(rb), ra.max(rb));
        parent[o as usize] = r;
        top[r as usize] = (nodes.len() - 1) as u32;
    }
    let roots: Vec<u32> = (0..leaves as u32)
        .filter(|&l| parent[l as usize] == l)
        .map(|l| top[l as usize])
        .collect();
    (roots, kept)
}

fn find(parent: &mut [u32], mut x: u32) -> u32 {
    while parent[x as usize] != x {
        let g = parent[parent[x as usize] as usize];
        parent[x as usize] = g;
        x = g;
    }
    x
}

/// The tree of `log`'s merges (leaves: `merged`'s first snapshot's clusters, or the
/// faces, of operators `face_q`, when every merge was logged from them), with the
/// points the loop kept for its nodes. After spatial parts (`log.from_faces` false)
/// `log` holds every merge too, the parts' first, but the leaves stay the snapshot's
/// clusters but for the largest, taken apart down to their faces ([`Split`]).
pub(crate) fn merge_tree(
    fitter: &Fitter,
    merged: &MergeOutput,
    log: MergeLog,
    split: Split,
) -> MergeTree {
    let mesh = fitter.input.mesh;
    let faces = mesh.face_count();
    let hulls = log.hulls;
    if log.from_faces {
        // Every merge is known: the leaves are single faces, so any cluster can be
        // taken apart down to its faces (the loop's first snapshot is not the leaves).
        let ids: Vec<u32> = (0..faces as u32).collect();
        let leaves: Vec<&[u32]> = ids.chunks(1).collect();
        let merges = TreeHulls {
            leaves: Vec::new(),
            ..hulls
        };
        let singles = Singles {
            nodes: 0..faces as u32,
            mesh: Some(mesh),
            tangent_eps: split.tangent_eps,
        };
        let ops = (Vec::new(), singles);
        MergeTree::build_with(&leaves, ops, &log.merges, merges, faces)
    } else {
        after_parts(fitter, &merged.snapshots[0], (&log.merges, hulls), split)
    }
}

/// The tree after spatial parts: the leaves are `snap`'s clusters, those `split` takes
/// apart replaced by their faces (after the others, each leaf's in increasing order;
/// a leaf's kept hull is its place's), over every merge of `merges` (with the `hulls`
/// the loop kept): those within a leaf kept whole join no two leaves and make no
/// node, those within a leaf taken apart make its subtree.
fn after_parts(
    fitter: &Fitter,
    snap: &crate::merge::Snapshot,
    (merges, hulls): (&[(u32, u32)], TreeHulls),
    split: Split,
) -> MergeTree {
    let mesh = fitter.input.mesh;
    let faces = mesh.face_count();
    let (taken, _) = split.leaves(&snap.members, faces);
    // Where a large leaf stays whole, the leaves are taken apart into pieces instead.
    let n = snap.members.len();
    let (taken, in_pieces, pieces) = match split.pieces(&snap.members, &taken, merges, faces) {
        Some(r) => (vec![false; n], r.in_pieces, r.pieces),
        None => (taken, vec![false; n], Vec::new()),
    };
    let mut apart: Vec<u32> = Vec::new();
    let (mut members, mut q, mut leaf_hulls) = (Vec::new(), Vec::new(), Vec::new());
    let mut kept = hulls.leaves.into_iter();
    for (((m, &t), &p), &mq) in (snap.members.iter().zip(&taken).zip(&in_pieces)).zip(&snap.q) {
        let hull = kept.next();
        if t {
            let from = apart.len();
            apart.extend(m);
            apart[from..].sort_unstable();
        } else if !p {
            members.push(m.as_slice());
            q.push(mq);
            leaf_hulls.extend(hull);
        }
    }
    // The faces taken apart are leaves of one face, whose operators are found again.
    let singles = Singles {
        nodes: members.len() as u32..(members.len() + apart.len()) as u32,
        mesh: Some(mesh),
        tangent_eps: split.tangent_eps,
    };
    members.extend(apart.chunks(1));
    for piece in &pieces {
        let ops = split.face_ops(mesh, piece);
        q.push(ops.iter().fold(Sym3::ZERO, |s, o| s.add(o)));
        members.push(piece.as_slice());
    }
    let hulls = TreeHulls {
        leaves: leaf_hulls,
        merges: hulls.merges,
    };
    MergeTree::build_with(&members, (q, singles), merges, hulls, faces)
}

/// Which leaves of the merge tree after spatial parts are taken apart down to their
/// faces (the parts' and the global loop's merges logged rebuild them): those of more
/// than `over` faces (a primitive's mean at the largest count), the largest first
/// (ties: the lower leaf), each that fits in what is left of 1/[`SPLIT_SHARE`] of the
/// input's faces. A face taken apart costs the tree two nodes (its leaf, 16 bytes,
/// whose operator is found again ([`NodeOps`]), and a merge, 16 bytes and its
/// operator's 48) where its leaf cost one for all its faces: taking every leaf apart
/// would hold 80 bytes a face through the cut, against 100 asked of a count's run
/// and 150 of a tolerance's from 14M faces (docs/decisions/perf-scale-ladder.md).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Split {
    pub over: usize,
    /// `Fit::tangent_eps`: the faces' operators (`seed::quadric::face_quadric`).
    pub tangent_eps: f64,
}

/// Which leaves [`Split::pieces`] takes apart, when it decides again: per leaf,
/// whether into pieces; the pieces, leaf after leaf.
#[derive(Debug)]
struct Retaken {
    in_pieces: Vec<bool>,
    pieces: Vec<Vec<u32>>,
}

/// Pieces are no finer than this share of a primitive's mean at the largest count
/// (`Split::over`): finer ones spent the budget on the largest leaves and left none
/// for a bent leaf under the mean
/// (docs/decisions/0059-pieces-no-finer-than-an-eighth-of-the-mean.md).
const PIECES_PER_MEAN: usize = 8;

/// The faces taken apart after spatial parts stay within this share of the input
/// (1/8: at most 10 bytes a face in the tree's nodes).
pub(crate) const SPLIT_SHARE: usize = 8;

impl Split {
    /// The operators of `faces`, as the parts' loops seeded them.
    fn face_ops(&self, mesh: &Mesh, faces: &[u32]) -> Vec<Sym3> {
        (faces.iter())
            .map(|&f| face_op(mesh, f, self.tangent_eps))
            .collect()
    }

    /// For each of `leaves` (the faces of each), whether it is taken apart, and what
    /// is left of the budget; `faces`: the input's face count.
    fn leaves(&self, leaves: &[Vec<u32>], faces: usize) -> (Vec<bool>, usize) {
        let mut order: Vec<usize> = (0..leaves.len())
            .filter(|&i| leaves[i].len() > self.over)
            .collect();
        order.sort_by(|&a, &b| leaves[b].len().cmp(&leaves[a].len()).then(a.cmp(&b)));
        let mut taken = vec![false; leaves.len()];
        let mut left = faces / SPLIT_SHARE;
        for i in order {
            // A leaf too large for what is left stays whole; smaller ones may fit.
            if leaves[i].len() > left {
                continue;
            }
            left -= leaves[i].len();
            taken[i] = true;
        }
        (taken, left)
    }

    /// Where [`Self::leaves`] leaves a leaf of more than `over` faces whole, the
    /// budget is shared out again among every leaf of more than a [`PIECES_PER_MEAN`]th
    /// of `over` faces (those under the mean too: one may be bent), in proportion to
    /// their faces: largest first (ties: the lower leaf), each leaf's share of what is
    /// left (of the faces of the leaves still to come) takes it apart into the finest
    /// [`pieces::pieces`] that fit, no finer than that floor (a piece costs the tree
    /// two nodes, as a face taken apart does), else keeps it whole. Whether each leaf
    /// is taken apart into pieces, and the pieces, leaf after leaf; `None` where every
    /// large leaf was taken apart to its faces (then nothing changes). `log`: every
    /// merge, as the tree replays them.
    fn pieces(
        &self,
        leaves: &[Vec<u32>],
        taken: &[bool],
        log: &[(u32, u32)],
        faces: usize,
    ) -> Option<Retaken> {
        let mut large = (0..leaves.len()).filter(|&i| leaves[i].len() > self.over);
        if large.all(|i| taken[i]) {
            return None;
        }
        let floor = (self.over / PIECES_PER_MEAN).max(2);
        let mut order: Vec<usize> = (0..leaves.len())
            .filter(|&i| leaves[i].len() > floor)
            .collect();
        order.sort_by(|&a, &b| leaves[b].len().cmp(&leaves[a].len()).then(a.cmp(&b)));
        let shared: Vec<&[u32]> = order.iter().map(|&i| leaves[i].as_slice()).collect();
        let inside = pieces::merges_inside(&shared, log, faces);
        let mut in_pieces = vec![false; leaves.len()];
        let mut out = Vec::new();
        let mut left = faces / SPLIT_SHARE;
        let mut to_come: usize = shared.iter().map(|l| l.len()).sum();
        for ((&i, leaf), merges) in order.iter().zip(&shared).zip(&inside) {
            let share = (left as u128 * leaf.len() as u128 / to_come as u128) as usize;
            to_come -= leaf.len();
            if let Some(p) = pieces::pieces(leaf, merges, share, floor) {
                left -= p.len();
                in_pieces[i] = true;
                out.extend(p);
            }
        }
        Some(Retaken {
            in_pieces,
            pieces: out,
        })
    }
}

/// The face count over which the merge loop keeps a cluster's points for the merge
/// tree: a cut's mean node's (the cut finds the hulls of larger nodes, `cut::hulls`).
/// `None` (found from the faces) where the welded vertices (whose ids the loop keeps)
/// may stand apart from the faces' own: a tolerance weld.
pub(crate) fn tree_hulls_over(mesh: &Mesh, params: &Params, largest: usize) -> Option<usize> {
    let welded_in_place =
        !matches!(params.fit.dedup, crate::params::Dedup::Tolerance(t) if t > 0.0);
    welded_in_place.then(|| mesh.face_count() / largest.max(1))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(w: f64) -> Sym3 {
        Sym3 {
            xx: w,
            ..Sym3::ZERO
        }
    }

    /// Leaves {0,1} {2} {3,4} {5}; merges 2+3 then 0+2: one root over the first four
    /// leaves' faces, leaf {5} alone; ranges nest and Q adds up.
    #[test]
    fn merges_make_nested_ranges_and_summed_operators() {
        let members = vec![vec![0, 1], vec![2], vec![4, 3], vec![5]];
        let qs = [q(1.0), q(2.0), q(4.0), q(8.0)];
        let t = MergeTree::build(
            &members,
            &qs,
            &[(2, 3), (0, 2), (4, 2)],
            TreeHulls::default(),
            6,
        );
        assert_eq!(t.nodes.len(), 6, "two merges; the third joins one cluster");
        assert_eq!(t.roots, vec![5, 3]);
        let mut all: Vec<u32> = t.faces(5).to_vec();
        all.sort();
        assert_eq!(all, vec![0, 1, 2, 3, 4]);
        assert_eq!(t.ops.at(5, || unreachable!()).xx, 7.0);
        assert_eq!(t.nodes[5].children, [0, 4]);
        assert_eq!(t.faces(4), &[2, 4, 3]);
        assert_eq!(t.faces(3), &[5]);
        assert_eq!(t.order.len(), 6);
    }

    /// A tree whose leaves of one face find their operators again from the mesh gives
    /// every node the bits of the tree that keeps them all: leaves kept before and
    /// after the single faces, and merges over both.
    #[test]
    fn single_faces_found_again_give_the_kept_operators() {
        let p: Vec<[f64; 3]> = (0..8)
            .map(|i| {
                let t = f64::from(i);
                [t, (t * 0.7).sin(), 0.3 * t * t]
            })
            .collect();
        let tris: Vec<Vec<u32>> = (0..6).map(|i| vec![i, i + 1, i + 2]).collect();
        let mesh = Mesh::from_polygons(&p, &tris).unwrap();
        let eps = 0.01;
        let members: Vec<Vec<u32>> = vec![vec![0, 1], vec![2], vec![3], vec![4], vec![5]];
        let log = [(2, 3), (0, 3), (4, 5), (5, 2)];
        let all: Vec<Sym3> = (members.iter())
            .map(|m| {
                m.iter()
                    .fold(Sym3::ZERO, |s, &f| s.add(&face_op(&mesh, f, eps)))
            })
            .collect();
        let kept = MergeTree::build(&members, &all, &log, TreeHulls::default(), 6);
        // Leaves 1..4 (faces 2, 3, 4) found again: leaves 0 and 4 keep theirs.
        let singles = Singles {
            nodes: 1..4,
            mesh: Some(&mesh),
            tangent_eps: eps,
        };
        let q = vec![all[0], all[4]];
        let found = MergeTree::build_with(&members, (q, singles), &log, TreeHulls::default(), 6);
        assert_eq!(found.nodes.len(), kept.nodes.len());
        assert_eq!(found.order, kept.order);
        for n in 0..kept.nodes.len() as u32 {
            let (a, b) = (found.q(n, &mesh), kept.q(n, &mesh));
            let bits = |q: Sym3| [q.xx, q.xy, q.xz, q.yy, q.yz, q.zz].map(f64::to_bits);
            assert_eq!(bits(a), bits(b), "node {n}");
        }
    }

    /// Leaves over `over` faces are taken apart largest first (ties: the lower leaf)
    /// while their faces fit in an eighth of the input's; one that does not fit stops
    /// the rest, however small.
    #[test]
    fn the_largest_leaves_are_taken_apart_within_an_eighth() {
        let sizes = [3, 40, 10, 40, 30, 5, 12];
        let mut next = 0u32;
        let leaves: Vec<Vec<u32>> = (sizes.iter())
            .map(|&n| {
                next += n;
                (next - n..next).collect()
            })
            .collect();
        let split = Split {
            over: 8,
            tangent_eps: 0.0,
        };
        // 720 faces: an eighth is 90, so the two leaves of 40; 10 left, too few
        // for the 30 and the 12, enough for the 10.
        let (taken, _) = split.leaves(&leaves, 720);
        assert_eq!(taken, [false, true, true, true, false, false, false]);
        // 960: 120, so the leaf of 30 too, and the 10 in the last 10; those of 8
        // faces or fewer never.
        let (taken, _) = split.leaves(&leaves, 960);
        assert_eq!(taken, [false, true, true, true, true, false, false]);
        let (taken, _) = split.leaves(&leaves, 8 * 10_000);
        assert_eq!(taken, [false, true, true, true, true, false, true]);
        // A leaf larger than the whole eighth stays whole, and the others are
        // still taken apart.
        let mut big = leaves.clone();
        big.push((1000..1100).collect());
        let (taken, left) = split.leaves(&big, 720);
        assert_eq!(taken, [false, true, true, true, false, false, false, false]);
        assert_eq!(left, 0);
    }

    /// Pieces stop at an eighth of a primitive's mean, though finer ones would fit, and
    /// what that leaves of the budget takes apart a leaf under the mean too (it may be
    /// bent); a leaf under the floor stays whole.
    #[test]
    fn pieces_stop_at_an_eighth_of_the_mean_and_the_rest_goes_to_smaller_leaves() {
        // Leaves of 512, 48 and 6 faces, each merged as a balanced tree, pairs first.
        let sizes = [512u32, 48, 6];
        let mut leaves: Vec<Vec<u32>> = Vec::new();
        let mut log: Vec<(u32, u32)> = Vec::new();
        let mut next = 0u32;
        for n in sizes {
            let mut step = 1u32;
            while step < n {
                let pairs = (next..next + n).step_by(2 * step as usize);
                log.extend(pairs.filter(|f| f + step < next + n).map(|f| (f, f + step)));
                step *= 2;
            }
            leaves.push((next..next + n).collect());
            next += n;
        }
        let split = Split {
            over: 64,
            tangent_eps: 0.0,
        };
        // 1,600 faces: an eighth is 200, too few for the 512, which stays whole.
        let (taken, _) = split.leaves(&leaves, 1600);
        assert_eq!(taken, [false; 3]);
        let r = split.pieces(&leaves, &taken, &log, 1600).unwrap();
        // The 512 gets 182 of the 200 (512 of the 560 faces over the floor of 8):
        // pieces of 8 (64 of them), not of 4 (128, which would fit too); the 48,
        // under the mean, gets what is left, in pieces of 8; the 6 stays whole.
        assert_eq!(r.in_pieces, [true, true, false]);
        assert_eq!(r.pieces.len(), 64 + 6);
        assert!(r.pieces.iter().all(|p| p.len() == 8));
        assert_eq!(r.pieces[64], (512..520).collect::<Vec<u32>>());
    }

    /// A leaf not taken apart for want of budget is taken apart into pieces that fit
    /// in what is left: the largest clusters its merges made under `over` faces, or
    /// under twice that, …; leaves at or under `over`, or taken apart, are left alone.
    #[test]
    fn a_leaf_too_large_for_the_budget_is_taken_apart_into_pieces() {
        let leaves: Vec<Vec<u32>> = vec![(0..64).collect(), (64..70).collect(), (70..80).collect()];
        // The first leaf merged as a balanced tree, pairs first (faces name clusters).
        let mut log: Vec<(u32, u32)> = Vec::new();
        let mut step = 1u32;
        while step < 64 {
            log.extend((0..64u32).step_by(2 * step as usize).map(|f| (f, f + step)));
            step *= 2;
        }
        let split = Split {
            over: 8,
            tangent_eps: 0.0,
        };
        // An eighth of 720 faces is 90: the 64 and the 10 fit as faces, and nothing
        // changes.
        let (taken, _) = split.leaves(&leaves, 720);
        assert_eq!(taken, [true, false, true]);
        assert!(split.pieces(&leaves, &taken, &log, 720).is_none());
        // Of 80 faces, 10: the 10 fit but not the 64, so all is decided again,
        // largest first: the 64 in pieces of 8 (8 pieces, the largest clusters under
        // 8 that its merges made), then the 10 no longer fit in the 2 left, nor do
        // its pieces (it has no merges: 10 of one face).
        let (taken, _) = split.leaves(&leaves, 80);
        assert_eq!(taken, [false, false, true]);
        let r = split.pieces(&leaves, &taken, &log, 80).unwrap();
        assert_eq!(r.in_pieces, vec![true, false, false]);
        assert_eq!(r.pieces.len(), 8);
        assert!(r.pieces.iter().all(|p| p.len() == 8));
        assert_eq!(r.pieces[1], (8..16).collect::<Vec<u32>>());
    }
}
