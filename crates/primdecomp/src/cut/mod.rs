//! Cutting the merge tree where the error is (issue 26; a deviation from §3.3, which
//! outputs the clusters alive when N remain: docs/decisions/0032). The pass's merges
//! form a forest ([`tree`]); each node's primitive gets an error, the one-way distance
//! from its surface to the input's (as `primdecomp eval` defines Hausdorff, estimated
//! by sampling, [`error`]); a target of N primitives is the cut reached from the roots
//! by splitting the worst node until N nodes remain, or until nothing is left worth
//! splitting. Every node's primitive encloses its faces, so every cut encloses the mesh.

mod bvh;
mod error;
pub(crate) mod tree;

use crate::math::Sym3;
use crate::merge::{Evaluator, Snapshot, Workspace};
use crate::primitive::Primitive;
use bvh::Surface;
use error::error_of;
use rayon::prelude::*;
use std::cmp::Ordering;
use std::collections::{BTreeMap, BinaryHeap, HashMap};
pub(crate) use tree::MergeTree;

/// The tree's leaves are the clusters of the snapshot at this many times the largest
/// target (or every face): deep enough that a cut of N rarely reaches them.
pub(crate) const LEAVES_PER_TARGET: usize = 4;

/// Nodes whose error is at most this many minimum half-extents are not split: a
/// flush plate already stands two of them off its faces, and the estimate's own
/// tessellation error is of that order.
const FLOOR_HALVES: f64 = 4.0;

/// A node of the cut with its fitted primitive and estimated error.
#[derive(Clone, Debug)]
struct Entry {
    error: f64,
    node: u32,
    prim: Primitive,
}

impl PartialEq for Entry {
    fn eq(&self, o: &Self) -> bool {
        self.cmp(o) == Ordering::Equal
    }
}
impl Eq for Entry {}
impl PartialOrd for Entry {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Entry {
    /// Worst error first; ties to the lower node id (deterministic).
    fn cmp(&self, o: &Self) -> Ordering {
        self.error.total_cmp(&o.error).then(o.node.cmp(&self.node))
    }
}

/// What a cut is made from: the fit settings, the tree and the input's surface.
pub(crate) struct Cutter<'a> {
    ev: &'a Evaluator<'a>,
    tree: &'a MergeTree,
    surface: Surface,
    floor: f64,
}

impl<'a> Cutter<'a> {
    pub(crate) fn new(ev: &'a Evaluator<'a>, tree: &'a MergeTree) -> Self {
        Cutter {
            ev,
            tree,
            surface: Surface::new(ev.mesh),
            floor: FLOOR_HALVES * ev.cfg.min_half,
        }
    }

    /// Node `n`'s output primitive and its error.
    fn entry(&self, n: u32, ws: &mut Workspace) -> Entry {
        let faces = self.tree.faces(n);
        let q = &self.tree.nodes[n as usize].q;
        let prim = self.ev.fit_output(faces.iter().copied(), q, ws).prim;
        Entry {
            error: error_of(&prim, &self.surface),
            node: n,
            prim,
        }
    }

    /// One snapshot per target of `targets` (any order), from one sequence of splits
    /// (the worst node each time, until the largest target's count or nothing is left
    /// worth splitting): the prefix of at most that many nodes whose worst error is the
    /// least (the longest on ties). A larger target chooses among more prefixes, so
    /// its estimated worst error is never above a smaller one's.
    pub(crate) fn snapshots(&self, targets: &[usize]) -> Vec<Snapshot> {
        let largest = targets.iter().copied().max().unwrap_or(1);
        let roots: Vec<Entry> = self
            .tree
            .roots
            .par_iter()
            .map_init(Workspace::default, |ws, &r| self.entry(r, ws))
            .collect();
        let (splits, worst, fitted) = self.split_sequence(roots.clone(), largest);
        targets
            .iter()
            .map(|&t| {
                let most = t.saturating_sub(roots.len()).min(splits.len());
                let k = best_prefix(&worst, most);
                self.snapshot(t, cut_after(self.tree, &roots, &splits[..k], &fitted))
            })
            .collect()
    }

    /// Splits the worst node of the cut from `roots` on until `largest` nodes remain or
    /// none is worth splitting; returns the nodes split in order, the worst error of
    /// the cut before each split and after the last, and every child fitted.
    fn split_sequence(
        &self,
        roots: Vec<Entry>,
        largest: usize,
    ) -> (Vec<u32>, Vec<f64>, HashMap<u32, Entry>) {
        let mut count = roots.len();
        let mut heap: BinaryHeap<Entry> = roots.into_iter().collect();
        // Worst error among nodes that will never be split (leaves, below the floor).
        let mut kept = 0.0f64;
        let mut splits = Vec::new();
        let mut worst = Vec::new();
        let mut fitted = HashMap::new();
        let top = |h: &BinaryHeap<Entry>, kept: f64| h.peek().map_or(kept, |e| e.error.max(kept));
        worst.push(top(&heap, kept));
        while count < largest {
            let Some(e) = heap.pop() else { break };
            let node = self.tree.nodes[e.node as usize];
            if node.is_leaf() || e.error <= self.floor {
                kept = kept.max(e.error);
                continue;
            }
            let [a, b] = node.children;
            let (ea, eb) = rayon::join(
                || self.entry(a, &mut Workspace::default()),
                || self.entry(b, &mut Workspace::default()),
            );
            fitted.insert(a, ea.clone());
            fitted.insert(b, eb.clone());
            heap.extend([ea, eb]);
            splits.push(e.node);
            count += 1;
            worst.push(top(&heap, kept));
        }
        (splits, worst, fitted)
    }

    /// The snapshot of one cut, its nodes in order of their faces' ranges.
    fn snapshot(&self, target: usize, mut cut: Vec<Entry>) -> Snapshot {
        cut.sort_unstable_by_key(|e| self.tree.nodes[e.node as usize].start);
        let mesh = self.ev.mesh;
        let verts = cut
            .par_iter()
            .map(|e| {
                let mut v: Vec<u32> = self
                    .tree
                    .faces(e.node)
                    .iter()
                    .flat_map(|&f| mesh.face(f as usize).iter().copied())
                    .collect();
                v.sort_unstable();
                v.dedup();
                v
            })
            .collect();
        Snapshot {
            target,
            prims: cut.iter().map(|e| e.prim).collect(),
            faces: cut
                .iter()
                .map(|e| self.tree.faces(e.node).len() as u32)
                .collect(),
            verts,
            members: cut
                .iter()
                .map(|e| self.tree.faces(e.node).to_vec())
                .collect(),
            q: cut
                .iter()
                .map(|e| self.tree.nodes[e.node as usize].q)
                .collect::<Vec<Sym3>>(),
        }
    }
}

/// The cut from `roots` after `splits` (each node replaced by its two children, both
/// in `fitted`), in node order.
fn cut_after(
    tree: &MergeTree,
    roots: &[Entry],
    splits: &[u32],
    fitted: &HashMap<u32, Entry>,
) -> Vec<Entry> {
    let mut cut: BTreeMap<u32, &Entry> = roots.iter().map(|e| (e.node, e)).collect();
    for &n in splits {
        cut.remove(&n);
        for c in tree.nodes[n as usize].children {
            cut.insert(c, &fitted[&c]);
        }
    }
    cut.into_values().cloned().collect()
}

/// The number of splits, at most `most`, after which the worst error `worst[k]` is
/// least (the most splits on ties).
fn best_prefix(worst: &[f64], most: usize) -> usize {
    (0..=most.min(worst.len().saturating_sub(1)))
        .rev()
        .min_by(|&a, &b| worst[a].total_cmp(&worst[b]))
        .unwrap_or(0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{decompose, Params};

    /// A later prefix is chosen unless it is worse; a split that raised the worst
    /// error is skipped back over until a later one brings it lower.
    #[test]
    fn prefixes_never_get_worse_with_more_room() {
        let worst = [5.0, 4.0, 4.5, 4.5, 3.0, 3.0, 3.5];
        let picks: Vec<usize> = (0..8).map(|m| best_prefix(&worst, m)).collect();
        assert_eq!(picks, vec![0, 1, 1, 1, 4, 5, 5, 5]);
        let errs: Vec<f64> = picks.iter().map(|&k| worst[k]).collect();
        assert!(errs.windows(2).all(|w| w[1] <= w[0]), "{errs:?}");
    }

    /// The worst sampled error of a level's primitives, in the input's frame.
    fn worst_error(mesh: &crate::Mesh, prims: &[Primitive]) -> f64 {
        let surface = Surface::new(mesh);
        let back = mesh.offset.map(|x| -x);
        prims
            .iter()
            .map(|p| error_of(&p.translated(back), &surface))
            .fold(0.0, f64::max)
    }

    /// On the demo scene (several separate objects) cut at 4, 16 and 64 from one pass:
    /// at most N primitives each, every input vertex inside one of them (any cut
    /// encloses the mesh), and a larger N never stands farther from the input than a
    /// smaller one (up to the post-processing's plate joins, within the floor).
    #[test]
    fn cuts_enclose_and_improve_with_n() {
        let mesh = crate::demo::demo_scene();
        let p = Params {
            targets: vec![4, 16, 64],
            cut: true,
            ..Params::default()
        };
        let d = decompose(&mesh, &p).expect("decomposes");
        let tol = 1e-9 * mesh.diagonal();
        let mut errors = Vec::new();
        for level in &d.levels {
            assert!(
                level.primitives.len() <= level.target,
                "{}",
                level.primitives.len()
            );
            for v in 0..mesh.vertex_count() as u32 {
                let w = crate::math::add(mesh.pos(v), mesh.offset);
                assert!(
                    level.primitives.iter().any(|q| q.contains(w, tol)),
                    "vertex {v}"
                );
            }
            errors.push(worst_error(&mesh, &level.primitives));
        }
        let floor = FLOOR_HALVES * p.min_extent * mesh.diagonal();
        assert!(errors[0] > errors[2], "{errors:?}: the cut never helped");
        assert!(
            errors.windows(2).all(|w| w[1] <= w[0] + floor),
            "{errors:?}"
        );
    }

    /// The greedy snapshot and the cut agree at one primitive per tree root: with a
    /// target of one, both are the whole scene's single primitive.
    #[test]
    fn one_target_is_the_root() {
        let mesh = crate::demo::demo_scene();
        let greedy = Params {
            targets: vec![1],
            ..Params::default()
        };
        let cut = Params {
            cut: true,
            ..greedy.clone()
        };
        let a = decompose(&mesh, &greedy).expect("greedy");
        let b = decompose(&mesh, &cut).expect("cut");
        assert_eq!(a.levels[0].primitives, b.levels[0].primitives);
    }
}
