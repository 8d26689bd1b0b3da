//! Clusters of faces (§3.4 "Collapsible Primitive Data Structure"): a disjoint-set
//! forest over faces, a cyclic linked list of each cluster's faces (O(1) splice), and
//! per-cluster operator Q, volume, the merge-clock time it last changed (for lazy
//! deletion), distinct vertices and neighbours. A cluster is named by its root face,
//! or, where the loop starts from groups of faces a first phase left
//! ([`Clusters::of_groups`]), by its root group: the same order, for a group is named
//! by its lowest face and ids follow them.

use crate::math::Sym3;
use std::sync::Arc;

/// Lists owned by a cluster once it stops being a single face.
#[derive(Debug, Default)]
struct Lists {
    /// Distinct (hull-reduced) vertices; empty = the single face's own vertices.
    verts: Vec<u32>,
    /// Neighbouring clusters (may name merged-away ids; resolve with `find`).
    neighbors: Vec<u32>,
    /// Length of `neighbors` when it was last resolved.
    resolved: u32,
}

/// No lists: the cluster is still one face, its neighbours those of the input graph.
const NO_LISTS: u32 = u32::MAX;

/// The per-face fields read together on every queue pop (is it a root, has it changed
/// since the entry was priced, where are its lists): one 16-byte record, four to a
/// cache line, so checking an entry costs one line per cluster instead of four
/// (docs/decisions/perf-cluster-node-packing.md).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(C, align(16))]
struct Node {
    parent: u32,
    /// The merge clock when the cluster last changed (0: never merged).
    changed: u32,
    /// The merge clock when all the cluster's pairs were last priced (≤ `changed`;
    /// equal unless its last merge was deferred, `Params::reprice`).
    repriced: u32,
    /// Index into `slab`, or [`NO_LISTS`].
    slot: u32,
}

/// The faces of each group a loop starts from ([`Clusters::of_groups`]), in CSR: group
/// `g`'s block is `faces[offsets[g]..offsets[g + 1]]`, its faces decreasing, so that
/// its head (lowest face, the group's name in the input's ids) comes last. Merging
/// the groups' blocks into one cyclic list by their heads, as [`Clusters::merge`]
/// splices faces, lists a cluster's faces in the order one face at a time would.
#[derive(Debug, Default)]
struct Blocks {
    faces: Vec<u32>,
    offsets: Vec<u32>,
}

/// Cluster state, indexed by id (valid at roots): struct-of-arrays except for the hot
/// [`Node`] fields. An id is a face, or a group of faces ([`Clusters::of_groups`]).
///
/// Per id it stores only fixed-size fields (~76 bytes); vertex and neighbour lists
/// live in a slab and exist only for clusters that merged or were bridged, so a
/// million-face input does not pay for a million small allocations. Started from
/// groups, it holds 4 bytes a face besides (their blocks).
#[derive(Debug, Default)]
pub struct Clusters {
    node: Vec<Node>,
    pub q: Vec<Sym3>,
    pub volume: Vec<f64>,
    /// Merges done so far; a queue entry priced at `t` is stale once either cluster's
    /// last change (`changed`) is later than `t`.
    pub clock: u32,
    /// Cyclic list: the next id of the same cluster.
    next_face: Vec<u32>,
    /// Faces in each cluster.
    pub face_count: Vec<u32>,
    /// The groups' faces, when ids are groups (empty when they are faces).
    blocks: Blocks,
    /// The input's face adjacency as CSR (neighbours of never-merged faces), shared
    /// with whoever else reads it (the output fits' surface).
    adj_offsets: Arc<[u32]>,
    adj: Arc<[u32]>,
    slab: Vec<Lists>,
    free: Vec<u32>,
    /// Number of live clusters.
    pub live: usize,
}

impl Clusters {
    /// One cluster per face, with the given per-face operators and volumes.
    pub fn new(q: Vec<Sym3>, volume: Vec<f64>, pairs: &[(u32, u32)]) -> Clusters {
        let (adj_offsets, adj) = crate::input::adjacency::neighbour_lists(q.len(), pairs);
        Clusters::with_lists(q, volume, (adj_offsets.into(), adj.into()))
    }

    /// [`Clusters::new`] with the adjacency as neighbour lists already built
    /// ([`crate::input::adjacency::neighbour_lists`] of the pairs), shared.
    pub fn with_lists(q: Vec<Sym3>, volume: Vec<f64>, lists: (Arc<[u32]>, Arc<[u32]>)) -> Clusters {
        let n = q.len();
        let (adj_offsets, adj) = lists;
        Clusters {
            node: (0..n as u32)
                .map(|c| Node {
                    parent: c,
                    changed: 0,
                    repriced: 0,
                    slot: NO_LISTS,
                })
                .collect(),
            q,
            volume,
            clock: 0,
            next_face: (0..n as u32).collect(),
            face_count: vec![1; n],
            blocks: Blocks::default(),
            adj_offsets,
            adj,
            slab: Vec::new(),
            free: Vec::new(),
            live: n,
        }
    }

    /// Clusters started from `groups` of faces, each named by its lowest face: group
    /// `g`'s faces (increasing), operator, volume, points (hull-reduced welded
    /// vertices; empty for a single face) and neighbour list, as ids of groups with
    /// its length when resolved. Groups must be ordered by their lowest faces: ids then
    /// order clusters as their root faces would.
    pub fn of_groups(groups: Vec<Group>) -> Clusters {
        let n = groups.len();
        let faces: usize = groups.iter().map(|g| g.faces.len()).sum();
        let mut blocks = Blocks {
            faces: Vec::with_capacity(faces),
            offsets: Vec::with_capacity(n + 1),
        };
        blocks.offsets.push(0);
        let mut cl = Clusters {
            node: Vec::with_capacity(n),
            q: Vec::with_capacity(n),
            volume: Vec::with_capacity(n),
            next_face: (0..n as u32).collect(),
            face_count: Vec::with_capacity(n),
            adj_offsets: vec![0u32; n + 1].into(),
            live: n,
            ..Clusters::default()
        };
        for (g, group) in groups.into_iter().enumerate() {
            debug_assert!(group.faces.windows(2).all(|w| w[0] < w[1]));
            blocks.faces.extend(group.faces.iter().rev());
            blocks.offsets.push(blocks.faces.len() as u32);
            cl.node.push(Node {
                parent: g as u32,
                changed: 0,
                repriced: 0,
                slot: cl.slab.len() as u32,
            });
            cl.q.push(group.q);
            cl.volume.push(group.volume);
            cl.face_count.push(group.faces.len() as u32);
            cl.slab.push(Lists {
                verts: group.verts,
                neighbors: group.neighbors,
                resolved: group.resolved,
            });
        }
        cl.blocks = blocks;
        cl
    }

    /// Faces in id `g`'s own block (1 for a face).
    fn block_len(&self, g: u32) -> u32 {
        match self.blocks.offsets.is_empty() {
            true => 1,
            false => self.blocks.offsets[g as usize + 1] - self.blocks.offsets[g as usize],
        }
    }

    /// Face `k` of id `g`'s own block (the head last).
    fn block_face(&self, g: u32, k: u32) -> u32 {
        match self.blocks.offsets.is_empty() {
            true => g,
            false => self.blocks.faces[(self.blocks.offsets[g as usize] + k) as usize],
        }
    }

    /// The face id `g` is named by: itself, or its group's lowest face.
    pub fn head(&self, g: u32) -> u32 {
        self.block_face(g, self.block_len(g) - 1)
    }

    /// Number of ids (cluster ids are `0..len()`): faces, or groups.
    pub fn len(&self) -> usize {
        self.node.len()
    }
    #[cfg(any(test, feature = "test-internals"))]
    pub fn is_empty(&self) -> bool {
        self.node.is_empty()
    }

    pub fn is_root(&self, c: u32) -> bool {
        self.node[c as usize].parent == c
    }

    /// The merge clock when cluster `c` last changed (0: never merged).
    pub fn changed(&self, c: u32) -> u32 {
        self.node[c as usize].changed
    }

    /// The merge clock when all of `c`'s pairs were last priced.
    pub fn repriced(&self, c: u32) -> u32 {
        self.node[c as usize].repriced
    }

    /// Records that all of root `c`'s pairs were priced now.
    pub fn mark_repriced(&mut self, c: u32) {
        self.node[c as usize].repriced = self.clock;
    }

    /// Restarts the merge clock: every cluster counts as never changed (phase 2 of
    /// `Params::partitions` prices everything afresh).
    pub fn reset_clock(&mut self) {
        self.clock = 0;
        for n in &mut self.node {
            n.changed = 0;
            n.repriced = 0;
        }
    }

    /// Root of `c`'s cluster, without shortening the path (for shared borrows).
    pub fn root(&self, mut c: u32) -> u32 {
        while self.node[c as usize].parent != c {
            c = self.node[c as usize].parent;
        }
        c
    }

    /// Root of `c`'s cluster, with path halving.
    pub fn find(&mut self, mut c: u32) -> u32 {
        while self.node[c as usize].parent != c {
            let g = self.node[self.node[c as usize].parent as usize].parent;
            self.node[c as usize].parent = g;
            c = g;
        }
        c
    }

    /// Live cluster roots in increasing order.
    pub fn roots(&self) -> Vec<u32> {
        (0..self.len() as u32)
            .filter(|&c| self.is_root(c))
            .collect()
    }

    /// Faces of cluster `c` in list order: its head, the blocks of the ids after it in
    /// its cyclic list, then the rest of its own block.
    pub fn faces(&self, c: u32) -> Faces<'_> {
        Faces {
            cl: self,
            root: c,
            cur: c,
            k: self.block_len(c) - 1,
            end: self.block_len(c),
            done: false,
        }
    }

    /// Neighbours of face `f` in the input's adjacency graph, increasing.
    pub fn input_neighbors(&self, f: u32) -> &[u32] {
        let (lo, hi) = (
            self.adj_offsets[f as usize] as usize,
            self.adj_offsets[f as usize + 1] as usize,
        );
        &self.adj[lo..hi]
    }

    /// The reduced vertex list of cluster `c`; empty while it is a single face.
    pub fn verts(&self, c: u32) -> &[u32] {
        match self.node[c as usize].slot {
            NO_LISTS => &[],
            s => &self.slab[s as usize].verts,
        }
    }

    /// The lists of `c`, created (neighbours copied from the input graph) if needed.
    fn lists_mut(&mut self, c: u32) -> &mut Lists {
        if self.node[c as usize].slot == NO_LISTS {
            let neighbors = self.input_neighbors(c).to_vec();
            let lists = Lists {
                verts: Vec::new(),
                resolved: neighbors.len() as u32,
                neighbors,
            };
            let s = match self.free.pop() {
                Some(s) => {
                    self.slab[s as usize] = lists;
                    s
                }
                None => {
                    self.slab.push(lists);
                    (self.slab.len() - 1) as u32
                }
            };
            self.node[c as usize].slot = s;
        }
        &mut self.slab[self.node[c as usize].slot as usize]
    }

    /// Takes `c`'s lists out of the slab (freeing its slot).
    fn take_lists(&mut self, c: u32) -> Lists {
        let lists = std::mem::take(self.lists_mut(c));
        self.free.push(self.node[c as usize].slot);
        self.node[c as usize].slot = NO_LISTS;
        lists
    }

    /// Records that `a` and `b` are neighbours (component bridging).
    pub fn link(&mut self, a: u32, b: u32) {
        self.lists_mut(a).neighbors.push(b);
        self.lists_mut(b).neighbors.push(a);
    }

    /// Neighbours of root `c` resolved to live roots, sorted, without `c` itself;
    /// also stores the resolved list back.
    pub fn resolved_neighbors(&mut self, c: u32) -> Vec<u32> {
        self.resolve_neighbors(c);
        self.lists_mut(c).neighbors.clone()
    }

    fn resolve_neighbors(&mut self, c: u32) {
        let mut n = std::mem::take(&mut self.lists_mut(c).neighbors);
        for v in n.iter_mut() {
            *v = self.find(*v);
        }
        n.sort_unstable();
        n.dedup();
        n.retain(|&v| v != c);
        let lists = self.lists_mut(c);
        lists.resolved = n.len() as u32;
        lists.neighbors = n;
    }

    /// Root `c`'s neighbour list as stored and its length when last resolved.
    pub fn neighbor_list(&self, c: u32) -> (&[u32], u32) {
        match self.node[c as usize].slot {
            NO_LISTS => (
                self.input_neighbors(c),
                self.input_neighbors(c).len() as u32,
            ),
            s => {
                let l = &self.slab[s as usize];
                (&l.neighbors, l.resolved)
            }
        }
    }

    /// Replaces root `c`'s neighbour list and its resolved length (a cluster carried
    /// over from a loop on part of the input, `merge::components`).
    pub fn set_neighbor_list(&mut self, c: u32, neighbors: Vec<u32>, resolved: u32) {
        let l = self.lists_mut(c);
        l.neighbors = neighbors;
        l.resolved = resolved;
    }

    /// Length of root `c`'s neighbour list: its degree when just resolved, else an
    /// upper bound (merged-away ids and duplicates count until the next resolve).
    pub fn neighbor_len(&self, c: u32) -> usize {
        match self.node[c as usize].slot {
            NO_LISTS => self.input_neighbors(c).len(),
            s => self.slab[s as usize].neighbors.len(),
        }
    }

    /// Root `c`'s neighbour list as stored: the input's adjacency while it is a single
    /// face, else its list (resolved to live roots only if just resolved).
    pub fn neighbors(&self, c: u32) -> &[u32] {
        match self.node[c as usize].slot {
            NO_LISTS => self.input_neighbors(c),
            s => &self.slab[s as usize].neighbors,
        }
    }

    /// Resolves root `c`'s neighbour list once it has grown past twice its length at
    /// the last resolve (amortised O(1) per entry; keeps `neighbor_len` within about
    /// twice the degree while merges skip resolving it).
    pub fn compact_neighbors(&mut self, c: u32) {
        let l = self.lists_mut(c);
        if l.neighbors.len() > 2 * l.resolved as usize + 8 {
            self.resolve_neighbors(c);
        }
    }

    /// Merges roots `a` and `b` (the lower id stays root); `verts` is the merged
    /// cluster's distinct vertex list, `volume` its primitive's volume.
    pub fn merge(&mut self, a: u32, b: u32, verts: Vec<u32>, volume: f64) -> u32 {
        let (root, other) = (a.min(b), a.max(b));
        let (r, o) = (root as usize, other as usize);
        self.node[o].parent = root;
        self.q[r] = self.q[r].add(&self.q[o]);
        self.volume[r] = volume;
        self.clock += 1;
        self.node[r].changed = self.clock;
        self.next_face.swap(r, o);
        self.face_count[r] += self.face_count[o];
        let moved = self.take_lists(other);
        let lists = self.lists_mut(root);
        lists.verts = verts;
        lists.neighbors.extend(moved.neighbors);
        self.live -= 1;
        root
    }
}

/// One group of faces a loop starts from ([`Clusters::of_groups`]).
#[derive(Debug, Default)]
pub struct Group {
    /// Its faces, increasing.
    pub faces: Vec<u32>,
    pub q: Sym3,
    pub volume: f64,
    /// Hull-reduced welded vertices; empty for a single face.
    pub verts: Vec<u32>,
    /// Neighbouring groups' ids, and the list's length when last resolved.
    pub neighbors: Vec<u32>,
    pub resolved: u32,
}

/// The faces of a cluster in list order ([`Clusters::faces`]).
#[derive(Clone, Debug)]
pub struct Faces<'a> {
    cl: &'a Clusters,
    root: u32,
    /// The id whose block is being listed, the next face's place in it and its end.
    cur: u32,
    k: u32,
    end: u32,
    done: bool,
}

impl Iterator for Faces<'_> {
    type Item = u32;

    fn next(&mut self) -> Option<u32> {
        while !self.done {
            if self.k < self.end {
                self.k += 1;
                return Some(self.cl.block_face(self.cur, self.k - 1));
            }
            if self.cur == self.root && self.end < self.cl.block_len(self.root) {
                // The root's block without its head, listed last.
                self.done = true;
                break;
            }
            self.cur = self.cl.next_face[self.cur as usize];
            (self.k, self.end) = match self.cur == self.root {
                true => (0, self.cl.block_len(self.root) - 1),
                false => (0, self.cl.block_len(self.cur)),
            };
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn merge_splices_face_lists_and_resolves_neighbors() {
        let pairs = [(0, 1), (1, 2), (2, 3)];
        let mut c = Clusters::new(vec![Sym3::ZERO; 4], vec![0.0; 4], &pairs);
        let r = c.merge(1, 2, vec![], 1.0);
        assert_eq!(r, 1);
        let mut f: Vec<u32> = c.faces(1).collect();
        f.sort();
        assert_eq!(f, vec![1, 2]);
        assert_eq!(c.resolved_neighbors(1), vec![0, 3]);
        let r = c.merge(3, 1, vec![], 2.0);
        assert_eq!(r, 1);
        let mut f: Vec<u32> = c.faces(1).collect();
        f.sort();
        assert_eq!(f, vec![1, 2, 3]);
        assert_eq!(c.resolved_neighbors(1), vec![0]);
        assert_eq!(c.resolved_neighbors(0), vec![1]);
        assert_eq!(c.live, 2);
        assert_eq!(c.roots(), vec![0, 1]);
    }
}
