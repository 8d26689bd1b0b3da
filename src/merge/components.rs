//! Parallelism across connected components (Alg. 1, §3.3, unchanged). The greedy
//! loop only merges adjacent clusters until adjacency runs out, and only then links
//! components (deviation 6). Entries of one component never change another's, and
//! the queue's order between two entries of the same component (cost, then ids, then
//! pricing time) does not depend on what happens elsewhere, so the global loop does
//! each component's merges in the order a loop on that component alone would. When
//! the largest target is below the number of components, the global loop merges every
//! component into one cluster before it links any, so that state can be computed per
//! component: here, in parallel, by groups of whole components, each with the run's
//! own settings ([`partition::merge_groups`], not lazy), on a sub-mesh whose face ids
//! keep their order, and handed to phase 2 with the neighbour lists the global loop
//! would hold. Phase 2 is the global loop from those clusters, which starts by linking
//! components.
//!
//! One thing is not the same: queue purges (`merge::driver::purge`) happen at other
//! queue sizes in a smaller loop, and under deferred re-pricing a purge can drop a
//! stale key that the global loop would have re-priced when popped (another, later key
//! of the same pair then stands for it), which can change the order inside a
//! component. Measured: the same primitives on the demo scene under every re-pricing
//! mode (the tests below), on all 79 corpus meshes below 871k faces at `-n 1%` and
//! `-n 200,40`, and on 78 of 79 at `-n 32` (ARCHITECTURE.md, "Performance").

use super::cost::Evaluator;
use super::partition::{self, Phase1};
use crate::math::Sym3;

/// Inputs with fewer faces are merged by the global loop alone (the sub-meshes are
/// not worth building).
pub const MIN_FACES: usize = 4096;

/// At most this many groups of components are merged side by side.
const GROUPS: usize = 16;

/// Connected components of the adjacency `pairs` over `faces` faces, each a list of
/// increasing face ids, ordered by their lowest face.
pub fn components(faces: usize, pairs: &[(u32, u32)]) -> Vec<Vec<u32>> {
    let mut parent: Vec<u32> = (0..faces as u32).collect();
    fn find(p: &mut [u32], mut x: u32) -> u32 {
        while p[x as usize] != x {
            let up = p[p[x as usize] as usize];
            p[x as usize] = up;
            x = up;
        }
        x
    }
    for &(a, b) in pairs {
        let (ra, rb) = (find(&mut parent, a), find(&mut parent, b));
        // The lower root wins, so a component's root is its lowest face.
        let (lo, hi) = (ra.min(rb), ra.max(rb));
        parent[hi as usize] = lo;
    }
    let mut index = vec![u32::MAX; faces];
    let mut out: Vec<Vec<u32>> = Vec::new();
    for f in 0..faces as u32 {
        let r = find(&mut parent, f) as usize;
        if index[r] == u32::MAX {
            index[r] = out.len() as u32;
            out.push(Vec::new());
        }
        out[index[r] as usize].push(f);
    }
    out
}

/// Whether the run's first phase can be merged per component: at least [`MIN_FACES`]
/// faces, no excess cap (it can refuse merges and leave a component in pieces, which
/// this phase does not claim to reproduce), and the largest target below the number
/// of components.
pub fn applies(faces: usize, components: usize, largest_target: usize, capped: bool) -> bool {
    faces >= MIN_FACES && !capped && components >= 2 && largest_target < components
}

/// Splits `comps` into at most [`GROUPS`] groups of whole components balanced by
/// faces (largest component first, each to the lightest group, ties to the lowest
/// index): each group's faces increasing, and how many components it holds.
fn groups(comps: Vec<Vec<u32>>) -> (Vec<Vec<u32>>, Vec<usize>) {
    let k = GROUPS.min(comps.len()).max(1);
    let mut order: Vec<usize> = (0..comps.len()).collect();
    order.sort_by(|&a, &b| comps[b].len().cmp(&comps[a].len()).then(a.cmp(&b)));
    let (mut faces, mut counts, mut load) = (vec![Vec::new(); k], vec![0; k], vec![0; k]);
    for c in order {
        let g = (0..k).min_by_key(|&g| (load[g], g)).unwrap_or(0);
        load[g] += comps[c].len();
        counts[g] += 1;
        faces[g].extend_from_slice(&comps[c]);
    }
    for f in &mut faces {
        f.sort_unstable();
    }
    (faces, counts)
}

/// Merges every component into one cluster (or as far as its adjacency goes), groups
/// of components in parallel; phase 2 continues from the result
/// ([`partition::clusters`]).
pub fn merge_components(
    ev: &Evaluator,
    q: &[Sym3],
    volume: &[f64],
    pairs: &[(u32, u32)],
    comps: Vec<Vec<u32>>,
    merged: &(dyn Fn(usize) + Sync),
) -> Phase1 {
    let (parts, targets) = groups(comps);
    partition::merge_groups(ev, q, volume, pairs, &parts, targets, false, merged)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::merge::driver::tests::{reprice_modes, with_input};
    use crate::merge::{run, Clusters};
    use crate::{Params, Reduction};

    /// The demo scene (several separate objects) merged to `n` < its component count
    /// by the global loop alone and by this module's phase 1 then the global loop:
    /// the same primitives and members at every target.
    fn same_as_global(p: Params, targets: &[usize]) {
        let mesh = crate::Mesh::from_builder(crate::demo::demo_scene());
        with_input(&mesh, &p, |ev, q, vols, pairs| {
            let comps = components(mesh.face_count(), pairs);
            assert!(targets[0] < comps.len(), "{} components", comps.len());
            let fresh = || Clusters::new(q.to_vec(), vols.to_vec(), pairs);
            let global = run(ev, fresh(), targets, &|_| {});
            let p1 = merge_components(ev, q, vols, pairs, comps, &|_| {});
            let cl = partition::clusters(p1, q.to_vec(), vols.to_vec(), pairs);
            let split = run(ev, cl, targets, &|_| {});
            assert_eq!(global.snapshots.len(), split.snapshots.len());
            let sorted = |m: &[Vec<u32>]| {
                let mut m: Vec<Vec<u32>> = m.to_vec();
                m.iter_mut().for_each(|f| f.sort_unstable());
                m
            };
            for (a, b) in global.snapshots.iter().zip(&split.snapshots) {
                assert_eq!(format!("{:?}", a.prims), format!("{:?}", b.prims), "{p:?}");
                assert_eq!(sorted(&a.members), sorted(&b.members));
            }
        });
    }

    #[test]
    fn merging_components_apart_changes_nothing() {
        for reprice in reprice_modes() {
            for reduction in [Reduction::Hull, Reduction::Extremes] {
                let p = Params {
                    reprice,
                    reduction,
                    ..Params::default()
                };
                same_as_global(p, &[3, 2, 1]);
            }
        }
    }

    #[test]
    fn components_are_the_connected_sets_in_face_order() {
        let pairs = [(0, 3), (3, 5), (1, 2), (6, 5)];
        let c = components(8, &pairs);
        assert_eq!(c, vec![vec![0, 3, 5, 6], vec![1, 2], vec![4], vec![7]]);
    }

    #[test]
    fn groups_hold_whole_components_balanced() {
        let comps = vec![vec![0, 1, 2, 3], vec![4, 5], vec![6, 7], vec![8]];
        let (g, n) = groups(comps);
        assert_eq!(g.len(), 4);
        assert_eq!(n, vec![1, 1, 1, 1]);
        let many: Vec<Vec<u32>> = (0..40).map(|i| vec![2 * i, 2 * i + 1]).collect();
        let (g, n) = groups(many);
        assert_eq!(g.len(), GROUPS);
        assert_eq!(n.iter().sum::<usize>(), 40);
        assert!(g.iter().all(|f| f.windows(2).all(|w| w[0] < w[1])));
        let sizes: Vec<usize> = g.iter().map(Vec::len).collect();
        assert!(sizes.iter().max().unwrap() - sizes.iter().min().unwrap() <= 2);
    }

    #[test]
    fn applies_only_below_the_component_count() {
        assert!(applies(MIN_FACES, 10, 9, false));
        assert!(!applies(MIN_FACES, 10, 10, false));
        assert!(!applies(MIN_FACES, 10, 9, true));
        assert!(!applies(MIN_FACES - 1, 10, 9, false));
    }
}
