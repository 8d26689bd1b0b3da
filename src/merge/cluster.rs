//! Clusters of faces (§3.4 "Collapsible Primitive Data Structure"): a disjoint-set
//! forest over faces, a cyclic linked list of each cluster's faces (O(1) splice), and
//! per-cluster operator Q, volume, version (for lazy deletion), distinct vertices and
//! neighbours. A cluster is named by its root face.

use crate::math::Sym3;

/// A cluster, named by its root face.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct ClusterId(pub u32);

/// Struct-of-arrays cluster state, indexed by face id (valid at roots).
#[derive(Debug, Default)]
pub struct Clusters {
    pub parent: Vec<u32>,
    pub q: Vec<Sym3>,
    pub volume: Vec<f64>,
    pub version: Vec<u32>,
    /// Cyclic list: the next face of the same cluster.
    pub next_face: Vec<u32>,
    pub face_count: Vec<u32>,
    /// Distinct vertices of a merged cluster; empty = the single face's own vertices.
    pub verts: Vec<Vec<u32>>,
    /// Neighbouring clusters (may name merged-away ids; resolve with `find`).
    pub neighbors: Vec<Vec<u32>>,
    /// Number of live clusters.
    pub live: usize,
}

impl Clusters {
    /// One cluster per face, with the given per-face operators and volumes.
    pub fn new(q: Vec<Sym3>, volume: Vec<f64>, pairs: &[(u32, u32)]) -> Clusters {
        let n = q.len();
        let mut degree = vec![0u32; n];
        for &(a, b) in pairs {
            degree[a as usize] += 1;
            degree[b as usize] += 1;
        }
        let mut neighbors: Vec<Vec<u32>> = degree
            .iter()
            .map(|&d| Vec::with_capacity(d as usize))
            .collect();
        for &(a, b) in pairs {
            neighbors[a as usize].push(b);
            neighbors[b as usize].push(a);
        }
        Clusters {
            parent: (0..n as u32).collect(),
            q,
            volume,
            version: vec![0; n],
            next_face: (0..n as u32).collect(),
            face_count: vec![1; n],
            verts: vec![Vec::new(); n],
            neighbors,
            live: n,
        }
    }

    pub fn is_root(&self, c: u32) -> bool {
        self.parent[c as usize] == c
    }

    /// Root of `c`'s cluster, with path halving.
    pub fn find(&mut self, mut c: u32) -> u32 {
        while self.parent[c as usize] != c {
            let g = self.parent[self.parent[c as usize] as usize];
            self.parent[c as usize] = g;
            c = g;
        }
        c
    }

    /// Live cluster roots in increasing order.
    pub fn roots(&self) -> Vec<u32> {
        (0..self.parent.len() as u32)
            .filter(|&c| self.is_root(c))
            .collect()
    }

    /// Faces of cluster `c` in list order.
    pub fn faces(&self, c: u32) -> impl Iterator<Item = u32> + '_ {
        let mut cur = c;
        let mut first = true;
        std::iter::from_fn(move || {
            if !first && cur == c {
                return None;
            }
            first = false;
            let f = cur;
            cur = self.next_face[cur as usize];
            Some(f)
        })
    }

    /// Neighbours of root `c` resolved to live roots, sorted, without `c` itself;
    /// also stores the resolved list back.
    pub fn resolved_neighbors(&mut self, c: u32) -> Vec<u32> {
        let mut n = std::mem::take(&mut self.neighbors[c as usize]);
        for v in n.iter_mut() {
            *v = self.find(*v);
        }
        n.sort_unstable();
        n.dedup();
        n.retain(|&v| v != c);
        self.neighbors[c as usize] = n.clone();
        n
    }

    /// Merges roots `a` and `b` (the lower id stays root); `verts` is the merged
    /// cluster's distinct vertex list, `volume` its primitive's volume.
    pub fn merge(&mut self, a: u32, b: u32, verts: Vec<u32>, volume: f64) -> u32 {
        let (root, other) = (a.min(b), a.max(b));
        let (r, o) = (root as usize, other as usize);
        self.parent[o] = root;
        self.q[r] = self.q[r].add(&self.q[o]);
        self.volume[r] = volume;
        self.version[r] += 1;
        self.version[o] += 1;
        self.next_face.swap(r, o);
        self.face_count[r] += self.face_count[o];
        self.verts[r] = verts;
        self.verts[o] = Vec::new();
        let moved = std::mem::take(&mut self.neighbors[o]);
        self.neighbors[r].extend(moved);
        self.live -= 1;
        root
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
