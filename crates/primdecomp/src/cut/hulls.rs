//! What refitting a node of the merge tree needs, found bottom-up once (§3.3 fits a
//! cluster's primitive to its points): its hull vertices (a convex primitive encloses
//! the points iff it encloses their hull; a node's hull is the hull of its two
//! children's) and its boundary faces, those with a neighbour outside it (the only
//! ones with rims, `merge::rim`; a node's are among its children's). Exploring the
//! tree from its roots down then fits each node on a few points and faces instead of
//! gathering every face below it again at every level (docs/decisions/0035).

use super::tree::MergeTree;
use crate::input::mesh::Mesh;
use crate::math::hull::{hull_vertices, HullWorkspace};
use crate::merge::rim::FaceAdjacency;
use rayon::prelude::*;
use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, Ordering::Relaxed};

/// Nodes of at most this many faces are never stored: their sets are found from
/// their faces when asked, which costs about as much as reading stored ones.
const SMALL: usize = 16;

/// The sets are found in about this many subtrees at once (more than threads, so
/// that uneven subtrees even out).
const TASKS: usize = 64;

/// A node's hull vertices (the faces' own vertex indices) and boundary faces
/// (increasing).
#[derive(Clone, Debug, Default)]
pub(crate) struct NodeSets {
    pub hull: Vec<u32>,
    pub boundary: Vec<u32>,
}

/// A node's sets as [`NodeHulls::of`] finds them.
pub(crate) struct Sets<'s> {
    pub hull: &'s [u32],
    pub boundary: &'s [u32],
}

/// The sets of every node with more than `small` faces (at least [`SMALL`]), and
/// where each face sits in the tree's order (to tell whether a face is in a node).
pub(crate) struct NodeHulls<'a> {
    tree: &'a MergeTree,
    mesh: &'a Mesh,
    adj: FaceAdjacency<'a>,
    eps: f64,
    small: usize,
    at: Vec<u32>,
    stored: HashMap<u32, NodeSets>,
}

/// Reusable buffers for one thread.
#[derive(Default)]
pub(crate) struct HullScratch {
    ids: Vec<u32>,
    faces: Vec<u32>,
    own: NodeSets,
    x: Vec<f64>,
    y: Vec<f64>,
    z: Vec<f64>,
    hull: HullWorkspace,
    keep: Vec<u32>,
}

impl<'a> NodeHulls<'a> {
    /// The sets of every node of more than `small` faces, each root's subtree on its
    /// own thread (children before parents). Hull points within `eps` of a hull face
    /// may be dropped (`math::hull`'s guarantee); boundaries are left empty when `adj`
    /// is.
    #[cfg(test)]
    pub(crate) fn build(
        tree: &'a MergeTree,
        mesh: &'a Mesh,
        adj: FaceAdjacency<'a>,
        eps: f64,
        small: usize,
    ) -> Self {
        Self::build_checked(tree, mesh, adj, eps, small, &|_| true).0
    }

    /// [`Self::build`] asking `go_on` before each subtree's task; with false when it
    /// said stop (the tasks not started then are left out: a cutter stops at once).
    pub(crate) fn build_checked(
        tree: &'a MergeTree,
        mesh: &'a Mesh,
        adj: FaceAdjacency<'a>,
        eps: f64,
        small: usize,
        go_on: crate::progress::Checkpoint,
    ) -> (Self, bool) {
        let mut at = vec![0u32; mesh.face_count()];
        for (i, &f) in tree.order.iter().enumerate() {
            at[f as usize] = i as u32;
        }
        let mut sets = NodeHulls {
            tree,
            mesh,
            adj,
            eps,
            small: small.max(SMALL),
            at,
            stored: HashMap::new(),
        };
        // Subtrees of at most a share of the faces on their own threads, then the
        // few nodes above them, children before parents.
        let grain = (mesh.face_count() / TASKS).max(sets.small);
        let tasks = sets.tasks(grain);
        let stop = AtomicBool::new(false);
        let mut stored: HashMap<u32, NodeSets> = tasks
            .par_iter()
            .map_init(HullScratch::default, |s, &r| {
                // Once told to stop, no task asks again.
                match !stop.load(Relaxed) && go_on(0.0) {
                    true => sets.subtree(r, s),
                    false => {
                        stop.store(true, Relaxed);
                        Vec::new()
                    }
                }
            })
            .flatten_iter()
            .collect();
        let tops: Vec<(u32, NodeSets)> = (tree.roots.par_iter())
            .flat_map_iter(|&r| sets.above(r, grain, &stored))
            .collect();
        stored.extend(tops);
        sets.stored = stored;
        let whole = !stop.load(Relaxed);
        (sets, whole)
    }

    /// The sets of the nodes above the subtrees of `grain` faces ([`Self::splits`])
    /// from `n` down, children before parents: by height above those subtrees, the
    /// nodes of one height on their own threads; the nodes below them are in
    /// `stored`. No recursion and no search through what is found: a merge tree can
    /// be a chain as deep as it has faces (a plate taking one face after another).
    fn above(&self, n: u32, grain: usize, stored: &HashMap<u32, NodeSets>) -> Vec<(u32, NodeSets)> {
        let mut found: HashMap<u32, NodeSets> = HashMap::new();
        for level in self.heights_above(n, grain) {
            let done: Vec<(u32, NodeSets)> = level
                .par_iter()
                .map_init(HullScratch::default, |s, &m| {
                    let kid = |c: u32| found.get(&c).or_else(|| stored.get(&c));
                    let [a, b] = self.tree.nodes[m as usize].children;
                    (m, self.joined(m, [kid(a), kid(b)], s))
                })
                .collect();
            found.extend(done);
        }
        let mut found: Vec<(u32, NodeSets)> = found.into_iter().collect();
        found.sort_unstable_by_key(|(m, _)| *m);
        found
    }

    /// The nodes that split from `n` down, by their height above the nodes that do
    /// not (0: both children below `grain` faces or leaves): each node's children
    /// come in a lower entry.
    fn heights_above(&self, n: u32, grain: usize) -> Vec<Vec<u32>> {
        // Parents before children; reversed, children before parents.
        let (mut order, mut stack) = (Vec::new(), vec![n]);
        while let Some(m) = stack.pop() {
            if self.splits(m, grain) {
                order.push(m);
                stack.extend(self.tree.nodes[m as usize].children);
            }
        }
        let mut height: HashMap<u32, usize> = HashMap::with_capacity(order.len());
        let mut levels: Vec<Vec<u32>> = Vec::new();
        for &m in order.iter().rev() {
            let kids = self.tree.nodes[m as usize].children;
            let h = kids
                .iter()
                .filter_map(|c| height.get(c))
                .map(|h| h + 1)
                .max()
                .unwrap_or(0);
            height.insert(m, h);
            if levels.len() <= h {
                levels.resize(h + 1, Vec::new());
            }
            levels[h].push(m);
        }
        levels
    }

    /// The subtrees below the nodes that [split](Self::splits), each of at most
    /// `grain` faces or a leaf.
    fn tasks(&self, grain: usize) -> Vec<u32> {
        let mut tasks = Vec::new();
        let mut stack: Vec<u32> = self.tree.roots.clone();
        while let Some(n) = stack.pop() {
            match self.splits(n, grain) {
                true => stack.extend(self.tree.nodes[n as usize].children),
                false => tasks.push(n),
            }
        }
        tasks
    }

    /// Whether node `n` lies above the subtrees of `grain` faces: an inner node of
    /// more faces.
    fn splits(&self, n: u32, grain: usize) -> bool {
        self.tree.faces(n).len() > grain && !self.tree.nodes[n as usize].is_leaf()
    }

    /// Whether face `f` lies outside node `n`.
    pub(crate) fn outside(&self, n: u32, f: u32) -> bool {
        let node = &self.tree.nodes[n as usize];
        let i = self.at[f as usize];
        i < node.start || i >= node.end
    }

    /// Node `n`'s sets: stored, or found from its faces into `s`; its hull the one
    /// the merge loop kept, where it kept one.
    pub(crate) fn of<'s>(&'s self, n: u32, s: &'s mut HullScratch) -> Sets<'s> {
        let sets = match self.stored.get(&n) {
            Some(sets) => sets,
            None => {
                let mut own = std::mem::take(&mut s.own);
                self.gather(n, s, &mut own);
                s.own = own;
                &s.own
            }
        };
        Sets {
            hull: self.tree.hulls.get(&n).unwrap_or(&sets.hull),
            boundary: &sets.boundary,
        }
    }

    /// The sets of the large nodes under root `r`, in post-order.
    fn subtree(&self, r: u32, s: &mut HullScratch) -> Vec<(u32, NodeSets)> {
        let mut done: HashMap<u32, NodeSets> = HashMap::new();
        let mut stack = vec![(r, false)];
        while let Some((n, expanded)) = stack.pop() {
            let node = self.tree.nodes[n as usize];
            if (node.end - node.start) as usize <= self.small || node.is_leaf() {
                continue;
            }
            if !expanded {
                stack.push((n, true));
                stack.extend(node.children.iter().map(|&c| (c, false)));
                continue;
            }
            let out = self.joined(n, node.children.map(|c| done.get(&c)), s);
            done.insert(n, out);
        }
        let mut all: Vec<(u32, NodeSets)> = done
            .into_iter()
            .filter(|(n, _)| self.tree.faces(*n).len() > self.small)
            .collect();
        all.sort_unstable_by_key(|(n, _)| *n);
        all
    }

    /// Node `n`'s sets from its children's (`None`: a child's found from its faces);
    /// no hull where the merge loop kept one.
    fn joined(&self, n: u32, kids: [Option<&NodeSets>; 2], s: &mut HullScratch) -> NodeSets {
        let kept = self.tree.hulls.contains_key(&n);
        let mut own = NodeSets::default();
        let (mut kid_ids, mut kid_faces) = (Vec::new(), Vec::new());
        for (c, sets) in self.tree.nodes[n as usize].children.into_iter().zip(kids) {
            let sets = match sets {
                Some(sets) => sets,
                None if kept => {
                    self.gather_boundary(c, s, &mut own);
                    &own
                }
                None => {
                    self.gather(c, s, &mut own);
                    &own
                }
            };
            if !kept {
                kid_ids.extend_from_slice(self.tree.hulls.get(&c).unwrap_or(&sets.hull));
            }
            kid_faces.extend_from_slice(&sets.boundary);
        }
        (s.ids, s.faces) = (kid_ids, kid_faces);
        let mut out = NodeSets::default();
        if !kept {
            self.reduce(s, &mut out.hull);
        }
        s.faces.sort_unstable();
        out.boundary = self.on_boundary(n, &s.faces);
        out
    }

    /// Node `n`'s sets from its faces (no hull where the merge loop kept one).
    fn gather(&self, n: u32, s: &mut HullScratch, out: &mut NodeSets) {
        out.hull.clear();
        if !self.tree.hulls.contains_key(&n) {
            s.ids.clear();
            for &f in self.tree.faces(n) {
                s.ids.extend_from_slice(self.mesh.face(f as usize));
            }
            s.ids.sort_unstable();
            s.ids.dedup();
            self.reduce(s, &mut out.hull);
        }
        self.gather_boundary(n, s, out);
    }

    /// Node `n`'s boundary from its faces.
    fn gather_boundary(&self, n: u32, s: &mut HullScratch, out: &mut NodeSets) {
        s.faces.clear();
        s.faces.extend_from_slice(self.tree.faces(n));
        s.faces.sort_unstable();
        out.boundary = self.on_boundary(n, &s.faces);
    }

    /// Those of `faces` (increasing) with a neighbour outside node `n`.
    fn on_boundary(&self, n: u32, faces: &[u32]) -> Vec<u32> {
        if self.adj.is_empty() {
            return Vec::new();
        }
        faces
            .iter()
            .copied()
            .filter(|&f| self.adj.of(f).iter().any(|&g| self.outside(n, g)))
            .collect()
    }

    /// The hull vertices of the points `s.ids` into `out`.
    fn reduce(&self, s: &mut HullScratch, out: &mut Vec<u32>) {
        let m = self.mesh;
        s.x.clear();
        s.y.clear();
        s.z.clear();
        s.x.extend(s.ids.iter().map(|&v| m.x[v as usize]));
        s.y.extend(s.ids.iter().map(|&v| m.y[v as usize]));
        s.z.extend(s.ids.iter().map(|&v| m.z[v as usize]));
        hull_vertices(&s.x, &s.y, &s.z, self.eps, &mut s.hull, &mut s.keep);
        out.clear();
        out.extend(s.keep.iter().map(|&i| s.ids[i as usize]));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::input::adjacency::{face_pairs, neighbour_lists};
    use crate::math::Sym3;
    use crate::merge::TreeHulls;

    /// On the demo scene, faces merged into a tree: every stored node's hull reaches
    /// as far in every direction as the points of its faces found directly (the same
    /// convex hull; which of several coincident or coplanar points stands for it may
    /// differ) and its boundary is the faces with a neighbour outside it, so the
    /// bottom-up sets are what gathering every face would give.
    #[test]
    fn bottom_up_sets_equal_the_direct_ones() {
        let mesh = crate::input::demo::demo_scene();
        let faces = mesh.face_count() as u32;
        let members: Vec<Vec<u32>> = (0..faces).map(|f| vec![f]).collect();
        let q = vec![Sym3::ZERO; members.len()];
        let log: Vec<(u32, u32)> = (1..faces).map(|f| (f / 2, f)).collect();
        let hulls = TreeHulls::default();
        let tree = MergeTree::build(&members, &q, &log, hulls, faces as usize);
        let pairs = face_pairs(&mesh.face_offsets, &mesh.face_indices);
        let (offsets, adj) = neighbour_lists(mesh.face_count(), &pairs);
        let adj = FaceAdjacency {
            offsets: &offsets,
            adj: &adj,
        };
        let tol = 1e-9 * mesh.diagonal();
        let sets = NodeHulls::build(&tree, &mesh, adj, 1e-12 * mesh.diagonal(), 0);
        assert!(sets.stored.len() > 10, "{} stored", sets.stored.len());
        // Every node over the size, those above the parallel subtrees too.
        let grain = (mesh.face_count() / TASKS).max(sets.small);
        assert!(
            tree.roots.iter().any(|&r| sets.splits(r, grain)),
            "no node above the subtrees: the test is vacuous"
        );
        for n in 0..tree.nodes.len() as u32 {
            let large = tree.faces(n).len() > sets.small && !tree.nodes[n as usize].is_leaf();
            assert_eq!(sets.stored.contains_key(&n), large, "node {n}");
        }
        let reach = |ids: &[u32], d: [f64; 3]| {
            ids.iter()
                .map(|&v| crate::math::dot(d, mesh.pos(v)))
                .fold(f64::NEG_INFINITY, f64::max)
        };
        let mut s = HullScratch::default();
        for (&n, stored) in &sets.stored {
            let mut all: Vec<u32> = tree
                .faces(n)
                .iter()
                .flat_map(|&f| mesh.face(f as usize).iter().copied())
                .collect();
            all.sort_unstable();
            all.dedup();
            assert!(stored.hull.len() < all.len(), "node {n}: nothing dropped");
            for k in 0..64 {
                let (t, z) = (k as f64 * 2.399_963, 1.0 - (k as f64 + 0.5) / 32.0);
                let r = (1.0 - z * z).sqrt();
                let d = [r * t.cos(), r * t.sin(), z];
                let (a, b) = (reach(&stored.hull, d), reach(&all, d));
                assert!(
                    (a - b).abs() <= tol,
                    "node {n}, direction {d:?}: {a} vs {b}"
                );
            }
            let mut direct = NodeSets::default();
            sets.gather(n, &mut s, &mut direct);
            assert_eq!(stored.boundary, direct.boundary, "node {n}'s boundary");
            let mut own: Vec<u32> = tree.faces(n).to_vec();
            own.sort_unstable();
            let expected: Vec<u32> = own
                .iter()
                .copied()
                .filter(|&f| adj.of(f).iter().any(|g| own.binary_search(g).is_err()))
                .collect();
            assert_eq!(stored.boundary, expected, "node {n}'s boundary");
        }
    }

    /// A merge tree that is one chain as deep as the mesh has faces (a plate taking
    /// one face after another: the greedy loop's cheapest merges on a flat floor)
    /// builds its sets without recursing once per level, and the root's hull is the
    /// floor's. The recursive build overflowed the stack on such chains.
    #[test]
    fn a_chain_as_deep_as_the_faces_builds() {
        let n = 100u32;
        let positions: Vec<[f64; 3]> = (0..=n)
            .flat_map(|i| (0..=n).map(move |j| [f64::from(i), f64::from(j), 0.0]))
            .collect();
        let triangles: Vec<[u32; 3]> = (0..n)
            .flat_map(|i| (0..n).map(move |j| (i, j)))
            .flat_map(|(i, j)| {
                let a = i * (n + 1) + j;
                [[a, a + n + 1, a + 1], [a + 1, a + n + 1, a + n + 2]]
            })
            .collect();
        let mesh = Mesh::from_triangles(&positions, &triangles).expect("a grid");
        let faces = mesh.face_count() as u32;
        let members: Vec<Vec<u32>> = (0..faces).map(|f| vec![f]).collect();
        let q = vec![Sym3::ZERO; members.len()];
        let log: Vec<(u32, u32)> = (1..faces).map(|f| (0, f)).collect();
        let tree = MergeTree::build(&members, &q, &log, TreeHulls::default(), faces as usize);
        let pairs = face_pairs(&mesh.face_offsets, &mesh.face_indices);
        let (offsets, adj) = neighbour_lists(mesh.face_count(), &pairs);
        let adj = FaceAdjacency {
            offsets: &offsets,
            adj: &adj,
        };
        let sets = NodeHulls::build(&tree, &mesh, adj, 1e-12 * mesh.diagonal(), 0);
        let root = tree.roots[0];
        assert_eq!(tree.faces(root).len(), faces as usize);
        let mut hull = sets.stored[&root].hull.clone();
        hull.sort_unstable();
        // The root's hull as gathering every face finds it: the grid's four corners.
        let mut direct = NodeSets::default();
        sets.gather(root, &mut HullScratch::default(), &mut direct);
        direct.hull.sort_unstable();
        assert_eq!(hull, direct.hull);
        assert_eq!(hull.len(), 4, "{:?}", hull.iter().map(|&v| mesh.pos(v)));
        assert!(
            sets.stored.len() >= faces as usize / 2,
            "{} stored",
            sets.stored.len()
        );
    }
}
