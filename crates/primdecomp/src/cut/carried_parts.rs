//! Parts carried by the primitive they lie in (beyond the paper, whose
//! §3.4 removes nested primitives after the pass: docs/decisions/0049). The greedy
//! pass (§3.3, Alg. 1) merges a part lying inside a cluster's primitive at no cost,
//! so a large cluster's subtree is often a chain that peels one such part at a time:
//! a building's box absorbing the beams, windows and furniture inside it. Splitting
//! down the chain counted one more node per peeled part, though post-processing
//! removes each again as nested, so a count ran out on the chain while its box stood
//! as far as before (samurai_monastery: `-n 256` gave 36 primitives).
//!
//! Here a child whose faces lie inside its sibling's primitive is carried by the
//! sibling: the split adds no node, and the sibling stands for both, its primitive
//! enclosing the faces of both. When a carrying node is split in turn, each part it
//! carries goes to a child whose primitive encloses it, or comes out as a part of its
//! own. The cut is then chosen over the nodes' parts ([`Explored::parts`]) instead of
//! their two children.

use super::hulls::HullScratch;
use super::tree::MergeTree;
use super::{Cutter, Entry, Explored, Scratch};
use crate::input::mesh::Mesh;
use crate::math::aabb_of;
use crate::math::{Sym3, V3};
use crate::merge::cost::Workspace;
use crate::primitive::fit::Fit;
use crate::primitive::Primitive;
use rayon::prelude::*;
use std::collections::HashMap;

/// Each node's bounding box, children before parents (a node is numbered after its
/// children): a leaf's from its faces' corners, a merge's from its children's boxes.
pub(super) fn node_boxes(tree: &MergeTree, mesh: &Mesh) -> Vec<(V3, V3)> {
    let leaves: Vec<Option<(V3, V3)>> = (tree.nodes.par_iter().enumerate())
        .map(|(n, node)| {
            let faces = tree.faces(n as u32).iter();
            let corners = faces
                .flat_map(|&f| mesh.face(f as usize))
                .map(|&v| mesh.pos(v));
            node.is_leaf().then(|| aabb_of(corners))
        })
        .collect();
    let mut boxes: Vec<(V3, V3)> = Vec::with_capacity(tree.nodes.len());
    for (node, leaf) in tree.nodes.iter().zip(leaves) {
        let joined = || boxes_box(node.children.iter().map(|&c| boxes[c as usize]));
        boxes.push(leaf.unwrap_or_else(joined));
    }
    boxes
}

/// The bounding box of `boxes`.
fn boxes_box(boxes: impl Iterator<Item = (V3, V3)>) -> (V3, V3) {
    aabb_of(boxes.flat_map(|(lo, hi)| [lo, hi]))
}

impl Cutter<'_> {
    /// The parts `e`'s node is split into, the split recorded: a group's two halves
    /// ([`Cutter::halve`]), else its two children (from `ready`, fitted already, or
    /// fitted here with errors up to `above`, `known`'s fits kept), where one
    /// carries the other with the chain below walked at once ([`Cutter::descend`]).
    /// `None` for a leaf.
    pub(super) fn divide(
        &self,
        ex: &mut Explored,
        e: &Entry,
        ready: &HashMap<u32, Entry>,
        (sa, sb): (&mut Scratch, &mut Scratch),
        (above, known): (f64, &HashMap<u32, Entry>),
    ) -> Option<Vec<Entry>> {
        let node = self.tree.nodes.get(e.node as usize);
        let leaf = match ex.groups.get(&e.node) {
            Some(members) => members.len() == 1,
            None => node.is_some_and(|n| n.is_leaf()),
        };
        if leaf {
            return self.unload(ex, e, sa, above);
        }
        ex.splits.push(e.node);
        let Some(node) = node else {
            let halves = self.halve(ex, e.node, sa, above);
            return Some(self.split(ex, e.node, halves, sa, above));
        };
        let [a, b] = node.children;
        let have = |c: &u32| ready.get(c).or(ex.fitted.get(c)).cloned();
        let (ea, eb) = match (have(&a), have(&b)) {
            (Some(ea), Some(eb)) => (ea, eb),
            _ => rayon::join(
                || self.entry(a, sa, above, known),
                || self.entry(b, sb, above, known),
            ),
        };
        let parts = self.split(ex, e.node, [ea, eb], sa, above);
        let [only] = &parts[..] else {
            return Some(parts);
        };
        let only = only.node;
        match self.descend(ex, only, sa, above, known) {
            Some(deeper) => {
                ex.splits.push(only);
                Some(deeper)
            }
            None => Some(parts),
        }
    }

    /// A leaf that carries parts, split into itself alone (a group of one: the same
    /// primitive, standing for its own faces) and what it carried, as one part: it
    /// cannot be split, and its nearest fit should not have to hold them. `None` for
    /// a leaf that carries nothing.
    fn unload(
        &self,
        ex: &mut Explored,
        e: &Entry,
        s: &mut Scratch,
        above: f64,
    ) -> Option<Vec<Entry>> {
        let carried = ex.carried.get(&e.node)?.clone();
        let id = self.group(ex, vec![e.node]);
        let alone = Entry {
            node: id,
            ..e.clone()
        };
        let out = self.part(ex, carried);
        let out = self.part_entry(ex, out, s, above);
        ex.splits.push(e.node);
        ex.parts.insert(e.node, vec![id, out.node]);
        ex.fitted.insert(id, alone.clone());
        ex.fitted.insert(out.node, out.clone());
        Some(vec![alone, out])
    }

    /// Records the split of `n` into the nodes fitted as `ea` and `eb` and the
    /// split's parts ([`Cutter::settle`]): a node inside the other's primitive is
    /// carried by it (the first, if both are).
    fn split(
        &self,
        ex: &mut Explored,
        n: u32,
        [ea, eb]: [Entry; 2],
        s: &mut Scratch,
        above: f64,
    ) -> Vec<Entry> {
        let (a, b) = (ea.node, eb.node);
        ex.fitted.insert(a, ea.clone());
        ex.fitted.insert(b, eb.clone());
        let mut kept: Vec<(Entry, Vec<u32>)> = match () {
            _ if self.encloses(ex, &eb.prim, a, &mut s.hull) => vec![(eb, vec![a])],
            _ if self.encloses(ex, &ea.prim, b, &mut s.hull) => vec![(ea, vec![b])],
            _ => vec![(ea, Vec::new()), (eb, Vec::new())],
        };
        self.settle(ex, n, &mut kept, s, above)
    }

    /// Walks down the chain below `n`, a node of the tree that carries its sibling:
    /// its larger child, that one's, and so on. Where the fit of a node of the chain
    /// still encloses all of `n` (found by bisection, the fits above it unmade), `n`
    /// is split into that node alone, carrying the chain's smaller children, and the
    /// split's parts are returned ([`Cutter::settle`]). `None` where the chain is too
    /// short or its second node's fit leaves part of `n` out.
    fn descend(
        &self,
        ex: &mut Explored,
        n: u32,
        s: &mut Scratch,
        above: f64,
        known: &HashMap<u32, Entry>,
    ) -> Option<Vec<Entry>> {
        if ex.groups.contains_key(&n) {
            return None;
        }
        let (mut chain, mut peeled) = (vec![n], Vec::new());
        while let Some(&last) = chain.last() {
            let node = &self.tree.nodes[last as usize];
            if node.is_leaf() {
                break;
            }
            let [a, b] = node.children;
            let larger = self.tree.faces(a).len() >= self.tree.faces(b).len();
            let (big, small) = if larger { (a, b) } else { (b, a) };
            chain.push(big);
            peeled.push(small);
        }
        // `lo` encloses all of `n`, `hi` does not (or is past the chain's end).
        let (mut lo, mut hi, mut prim) = (0, chain.len(), None);
        while hi - lo > 1 {
            let mid = (lo + hi) / 2;
            let fit = self.fit(chain[mid], s);
            match self.encloses(ex, &fit, n, &mut s.hull) {
                true => (lo, prim) = (mid, Some(fit)),
                false => hi = mid,
            }
        }
        let prim = prim.filter(|_| lo >= 2)?;
        let m = chain[lo];
        // A nearest fit kept from an earlier cut may not enclose all of `n`.
        let entry = match known.get(&m) {
            Some(e) if !e.closest => self.remeasured(e, above),
            _ => self.measured(m, prim, above),
        };
        ex.fitted.insert(m, entry.clone());
        let mut kept = vec![(entry, peeled[..lo].to_vec())];
        Some(self.settle(ex, n, &mut kept, s, above))
    }

    /// Records the split of `n` into the fitted parts `kept`, each with the nodes it
    /// carries: what `n` carried goes to the first of them whose primitive encloses
    /// it (all lie inside `n`'s); the rest comes out as one more part, on its own or,
    /// several, as a group ([`Cutter::group`]). Returns the parts' entries.
    fn settle(
        &self,
        ex: &mut Explored,
        n: u32,
        kept: &mut [(Entry, Vec<u32>)],
        s: &mut Scratch,
        above: f64,
    ) -> Vec<Entry> {
        // `n` keeps its own: a cut may still take it whole.
        let carried = ex.carried.get(&n).cloned().unwrap_or_default();
        let mut out = Vec::new();
        for c in carried {
            let home = (kept.iter()).position(|(e, _)| self.encloses(ex, &e.prim, c, &mut s.hull));
            match home {
                Some(i) => kept[i].1.push(c),
                None => out.push(c),
            }
        }
        let mut parts: Vec<Entry> = Vec::with_capacity(kept.len() + 1);
        for (e, load) in kept.iter_mut() {
            if !load.is_empty() {
                ex.carried.insert(e.node, std::mem::take(load));
            }
            parts.push(e.clone());
        }
        if !out.is_empty() {
            let part = self.part(ex, out);
            let e = self.part_entry(ex, part, s, above);
            ex.fitted.insert(e.node, e.clone());
            parts.push(e);
        }
        ex.parts.insert(n, parts.iter().map(|e| e.node).collect());
        parts
    }

    /// The part made of `members`, nodes a split let out: the one node itself, or
    /// several as a group, a node of its own (its members nodes of the tree, a group
    /// among them giving its own) fitted on all their points. Released one by one,
    /// parts that lay inside a large primitive would each count at once where their
    /// cut may want one primitive over several (a hall's crates).
    fn part(&self, ex: &mut Explored, members: Vec<u32>) -> u32 {
        match members[..] {
            [one] => one,
            _ => self.group(ex, members),
        }
    }

    /// A new group standing for `nodes` (a group among them gives its members: a
    /// group's members are nodes of the tree), its bounding box kept.
    fn group(&self, ex: &mut Explored, nodes: Vec<u32>) -> u32 {
        let id = self.tree.nodes.len() as u32 + ex.groups.len() as u32;
        let members: Vec<u32> = nodes.iter().flat_map(|&m| self.members(ex, m)).collect();
        let b = boxes_box(members.iter().map(|&m| self.boxes[m as usize]));
        ex.groups.insert(id, members);
        ex.bounds.insert(id, b);
        id
    }

    /// Part `n`'s entry: fitted already, or its fit (a group's on all its points,
    /// a node's on its hull) with its error up to `above`.
    fn part_entry(&self, ex: &Explored, n: u32, s: &mut Scratch, above: f64) -> Entry {
        if let Some(e) = ex.fitted.get(&n) {
            return e.clone();
        }
        let prim = match ex.groups.contains_key(&n) {
            true if !self.goes_on() => super::STAND_IN,
            true => self.group_fit(ex, n, s),
            false => self.fit(n, s),
        };
        self.measured(n, prim, above)
    }

    /// Group `n`'s fit on all its points: kept from an earlier exploration that
    /// covered the same nodes, or made and kept ([`Cutter::group_fits`]).
    fn group_fit(&self, ex: &Explored, n: u32, s: &mut Scratch) -> Primitive {
        let covered = self.covered(ex, n);
        let lock = || self.group_fits.lock().unwrap_or_else(|e| e.into_inner());
        let kept = (!super::off(&super::GROUP_FITS_OFF)).then(|| lock().get(&covered).copied());
        if let Some(prim) = kept.flatten() {
            #[cfg(test)]
            super::GROUP_FITS_REUSED.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            return prim;
        }
        match self.fit_over(&covered, &mut s.ws) {
            Some(f) => {
                lock().insert(covered, f.prim);
                f.prim
            }
            // Told to stop: nothing kept.
            None => super::STAND_IN,
        }
    }

    /// Group `g`'s two halves, each a node or a group ([`Cutter::part`]), fitted
    /// together: its members ordered along the axis their boxes' centres spread most
    /// on, split at the middle.
    fn halve(&self, ex: &mut Explored, g: u32, sb: &mut Scratch, above: f64) -> [Entry; 2] {
        let mut members = ex.groups[&g].clone();
        let centre = |c: u32| {
            let (lo, hi) = self.boxes[c as usize];
            std::array::from_fn::<f64, 3, _>(|k| 0.5 * (lo[k] + hi[k]))
        };
        let spread = |k: usize| {
            let (lo, hi) = (members.iter())
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &c| {
                    (lo.min(centre(c)[k]), hi.max(centre(c)[k]))
                });
            hi - lo
        };
        let axis = (0..3).fold(0, |a, k| if spread(k) > spread(a) { k } else { a });
        members.sort_unstable_by(|&a, &b| {
            (centre(a)[axis].total_cmp(&centre(b)[axis])).then(a.cmp(&b))
        });
        let back = members.split_off(members.len() / 2);
        let [a, b] = [members, back].map(|half| self.part(ex, half));
        let ex = &*ex;
        let (ea, eb) = rayon::join(
            || self.part_entry(ex, a, &mut Scratch::default(), above),
            || self.part_entry(ex, b, sb, above),
        );
        [ea, eb]
    }

    /// Node `c`'s bounding box: a node of the tree's, or a group's.
    fn bounds(&self, ex: &Explored, c: u32) -> (V3, V3) {
        match self.boxes.get(c as usize) {
            Some(&b) => b,
            None => ex.bounds[&c],
        }
    }

    /// Whether `prim` encloses every point of node `c`'s faces, up to the point
    /// reduction's tolerance (as [`Cutter::enclosing`] checks an output): told by
    /// its bounding box where that lies outside `prim`'s or inside `prim` (a
    /// convex primitive then holds every point), else by its hull points (kept in
    /// `ex`; a group's are its members').
    fn encloses(&self, ex: &mut Explored, prim: &Primitive, c: u32, s: &mut HullScratch) -> bool {
        if let Some(answer) = self.by_box(self.bounds(ex, c), prim) {
            return answer;
        }
        if !ex.points.contains_key(&c) {
            let nodes = self.members(ex, c);
            let points = nodes.iter().flat_map(|&m| self.points(m, s)).collect();
            ex.points.insert(c, points);
        }
        let eps = self.fitter.pricing.hull_eps;
        ex.points[&c].iter().all(|&p| prim.contains(p, eps))
    }

    /// Whether one of two siblings, fitted as `ea` and `eb`, lies inside the other's
    /// primitive: the split is a step of a chain, which [`Cutter::descend`] walks.
    pub(super) fn carries(&self, [ea, eb]: [&Entry; 2], s: &mut HullScratch) -> bool {
        let eps = self.fitter.pricing.hull_eps;
        let mut inside = |e: &Entry, o: &Entry| {
            let by_box = self.by_box(self.boxes[e.node as usize], &o.prim);
            by_box.unwrap_or_else(|| {
                self.points(e.node, s)
                    .iter()
                    .all(|&p| o.prim.contains(p, eps))
            })
        };
        inside(ea, eb) || inside(eb, ea)
    }

    /// Node `c`'s hull points (the tree's node).
    fn points(&self, c: u32, s: &mut HullScratch) -> Vec<V3> {
        let mesh = self.fitter.input.mesh;
        (self.hulls.of(c, s).hull.iter())
            .map(|&v| mesh.pos(v))
            .collect()
    }

    /// Whether `prim` encloses every point in the box `(lo, hi)`, where the box
    /// tells: not if it pokes out of `prim`'s bounding box, so if its corners are
    /// inside `prim` (convex); `None` otherwise.
    fn by_box(&self, (lo, hi): (V3, V3), prim: &Primitive) -> Option<bool> {
        let eps = self.fitter.pricing.hull_eps;
        let (plo, phi) = prim.aabb();
        if (0..3).any(|k| lo[k] < plo[k] - eps || hi[k] > phi[k] + eps) {
            return Some(false);
        }
        let corner =
            |i: usize| std::array::from_fn(|k| if i >> k & 1 == 0 { lo[k] } else { hi[k] });
        (0..8)
            .all(|i| prim.contains(corner(i), eps))
            .then_some(true)
    }

    /// The nodes of the tree node `n` stands for: itself, or a group's members.
    pub(super) fn members(&self, ex: &Explored, n: u32) -> Vec<u32> {
        ex.groups.get(&n).cloned().unwrap_or_else(|| vec![n])
    }

    /// The nodes of the tree whose faces node `n`'s primitive encloses: those it
    /// stands for ([`Cutter::members`]) and those it carries.
    pub(super) fn covered(&self, ex: &Explored, n: u32) -> Vec<u32> {
        let carried = ex.carried.get(&n).map_or(&[][..], |c| &c[..]);
        let mut nodes = self.members(ex, n);
        nodes.extend(carried.iter().flat_map(|&c| self.members(ex, c)));
        nodes
    }

    /// Node `n`'s faces with those of the nodes it carries.
    pub(super) fn faces_of<'e>(
        &'e self,
        ex: &Explored,
        n: u32,
    ) -> impl Iterator<Item = u32> + Clone + 'e {
        let nodes = self.covered(ex, n).into_iter();
        nodes.flat_map(|c| self.tree.faces(c)).copied()
    }

    /// Node `n`'s operator with those of the nodes it carries.
    pub(super) fn q_of(&self, ex: &Explored, n: u32) -> Sym3 {
        self.q_over(&self.covered(ex, n))
    }

    /// The summed operators of `nodes`, in their order (a [`Cutter::covered`] list,
    /// never empty: it holds the node or its group's members).
    fn q_over(&self, nodes: &[u32]) -> Sym3 {
        let q = |c: u32| self.tree.q(c, self.fitter.input.mesh);
        let Some((&first, rest)) = nodes.split_first() else {
            return Sym3::default();
        };
        rest.iter().fold(q(first), |acc, &c| acc.add(&q(c)))
    }

    /// The output fit on every point of `nodes` (a [`Cutter::covered`] list) with
    /// their summed operators: what `faces_of` and `q_of` give for the node they
    /// cover, without finding the list again. `None` once told to stop.
    pub(super) fn fit_over(&self, nodes: &[u32], ws: &mut Workspace) -> Option<Fit> {
        let faces = nodes.iter().flat_map(|&c| self.tree.faces(c)).copied();
        let ask = || self.goes_on();
        (self.fitter).fit_output_checked(faces, &self.q_over(nodes), ws, &ask)
    }

    /// Where node `n`'s faces start in the tree's order (a group's first member's).
    pub(super) fn start(&self, ex: &Explored, n: u32) -> u32 {
        let nodes = self.members(ex, n).into_iter();
        nodes
            .map(|c| self.tree.nodes[c as usize].start)
            .min()
            .unwrap_or(0)
    }
}

impl Explored {
    /// Whether node `n` was split.
    pub(super) fn is_split(&self, n: u32) -> bool {
        self.parts.contains_key(&n)
    }

    /// The nodes reachable from the roots through the splits' parts, each after its
    /// parts (a carried node is reached only once it comes out on its own).
    pub(super) fn post_order(&self) -> Vec<u32> {
        let mut out = Vec::with_capacity(self.fitted.len());
        let mut stack: Vec<(u32, bool)> = self.roots.iter().rev().map(|&r| (r, false)).collect();
        while let Some((n, done)) = stack.pop() {
            if done {
                out.push(n);
                continue;
            }
            stack.push((n, true));
            if let Some(parts) = self.parts.get(&n) {
                stack.extend(parts.iter().rev().map(|&c| (c, false)));
            }
        }
        out
    }
}
