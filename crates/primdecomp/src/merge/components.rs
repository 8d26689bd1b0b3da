//! Parallelism across connected components (Alg. 1, §3.3, unchanged). The greedy
//! loop only merges adjacent clusters until adjacency runs out, and only then links
//! components (docs/decisions/0006-component-bridging-nearest-12.md). Entries of one component
//! never change another's, and
//! the queue's order between two entries of the same component (cost, then ids, then
//! pricing time) does not depend on what happens elsewhere, so the global loop does
//! each component's merges in the order a loop on that component alone would, and it
//! merges every component into one cluster before it links any. Here that is done
//! in parallel, by groups of whole components, each with the run's own settings
//! ([`partition::merge_groups`], [`Kind::Components`]), on a sub-mesh whose face ids
//! keep their order; each group's loop records its merges ([`Traced`]) when a target
//! needs them. Then:
//!
//! - a target at or above the number of components is reached before any linking:
//!   the global loop's clusters there are the first `faces − target` merges of all
//!   groups in the order the global loop interleaves them (each merge's key says
//!   where), and the free ones after them (docs/decisions/0025-free-merges-into-plates.md: each
//!   traced merge says
//!   whether it is), replayed by [`snapshots`] — no global loop at all;
//! - a smaller target is reached by phase 2, the global loop started from every
//!   component whole (with the neighbour lists the global loop would hold), which
//!   starts by linking components.
//!
//! One thing is not the same: queue purges (`merge::driver::purge`) happen at other
//! queue sizes in a smaller loop, and under deferred re-pricing a purge can drop a
//! stale key that the global loop would have re-priced when popped (another, later key
//! of the same pair then stands for it), which can change the order inside a
//! component. Measured: the same primitives on the demo scene under every re-pricing
//! mode, at targets above, at and below its component count (the tests below); on
//! the corpus, docs/decisions/perf-components-merged-apart.md.

use super::cluster::Clusters;
use super::cost::Fitter;
use super::driver::{snapshot, Scope, Snapshot, Traced};
use super::partition::{self, Kind, Phase1};
use crate::math::Sym3;

/// Inputs with fewer faces are merged by the global loop alone (the sub-meshes are
/// not worth building).
pub const MIN_FACES: usize = 4096;

/// At most this many groups of components are merged side by side.
const GROUPS: usize = 16;

/// Whether the faces form more than one connected component (by shared edges),
/// leaving out the faces `point` says are points (all corners welded into one
/// vertex: no part of the surface, as the dragon's nine). `None` when `go_on`, asked
/// every `BLOCK` pairs and faces, said stop.
pub(crate) fn several(
    faces: usize,
    pairs: &[(u32, u32)],
    point: impl Fn(usize) -> bool,
    go_on: &dyn Fn() -> bool,
) -> Option<bool> {
    const BLOCK: usize = 1 << 20;
    let mut parent: Vec<u32> = (0..faces as u32).collect();
    for block in pairs.chunks(BLOCK) {
        for &(a, b) in block {
            let (ra, rb) = (root(&mut parent, a), root(&mut parent, b));
            parent[ra.max(rb) as usize] = ra.min(rb);
        }
        if !go_on() {
            return None;
        }
    }
    let mut first = None;
    for f in (0..faces).filter(|&f| !point(f)) {
        if f % BLOCK == 0 && !go_on() {
            return None;
        }
        let r = root(&mut parent, f as u32);
        if *first.get_or_insert(r) != r {
            return Some(true);
        }
    }
    Some(false)
}

/// The root of `x` in a union-find forest, halving the path on the way.
pub(crate) fn root(p: &mut [u32], mut x: u32) -> u32 {
    while p[x as usize] != x {
        let up = p[p[x as usize] as usize];
        p[x as usize] = up;
        x = up;
    }
    x
}

/// Connected components of the adjacency `pairs` over `faces` faces, each a list of
/// increasing face ids, ordered by their lowest face.
pub fn components(faces: usize, pairs: &[(u32, u32)]) -> Vec<Vec<u32>> {
    let mut parent: Vec<u32> = (0..faces as u32).collect();
    for &(a, b) in pairs {
        let (ra, rb) = (root(&mut parent, a), root(&mut parent, b));
        // The lower root wins, so a component's root is its lowest face.
        let (lo, hi) = (ra.min(rb), ra.max(rb));
        parent[hi as usize] = lo;
    }
    let mut index = vec![u32::MAX; faces];
    let mut out: Vec<Vec<u32>> = Vec::new();
    for f in 0..faces as u32 {
        let r = root(&mut parent, f) as usize;
        if index[r] == u32::MAX {
            index[r] = out.len() as u32;
            out.push(Vec::new());
        }
        out[index[r] as usize].push(f);
    }
    out
}

/// The largest component may hold at most this share of the faces: its group's loop
/// runs alone on one thread without the global loop's re-pricing worker, so a
/// dominant component is merged faster by the global loop: measured shares up to 0.66
/// gained or broke even, 0.87 and more lost (docs/decisions/perf-components-merged-apart.md).
pub const MAX_SHARE: f64 = 0.6;

/// Whether the run's first phase can be merged per component: at least [`MIN_FACES`]
/// faces, no excess cap (it can refuse merges and leave a component in pieces, which
/// this phase does not claim to reproduce), two components or more, and none holding
/// more than [`MAX_SHARE`] of the faces.
pub fn applies(faces: usize, components: usize, largest: usize, capped: bool) -> bool {
    faces >= MIN_FACES && !capped && components >= 2 && largest as f64 <= MAX_SHARE * faces as f64
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
/// of components in parallel; [`snapshots`] and phase 2 ([`partition::clusters`])
/// continue from the result. The merges are traced only when [`snapshots`] will need
/// them: when the largest target is at least the number of components (`usize::MAX`
/// traces them for the merge tree, `cut::tree`).
pub fn merge_components(
    fitter: &Fitter,
    q: &[Sym3],
    volume: &[f64],
    pairs: &[(u32, u32)],
    comps: Vec<Vec<u32>>,
    largest_target: usize,
    merged: &(dyn Fn(usize) -> bool + Sync),
) -> Phase1 {
    let traced = largest_target >= comps.len();
    let (parts, targets) = groups(comps);
    let kind = Kind::Components { traced };
    let faces = partition::FaceData::Given { q, volume, pairs };
    partition::merge_groups(fitter, faces, &parts, (targets, kind), merged, &|_| {})
}

/// The global loop's snapshots at every target of `targets` (decreasing) that is at
/// least the number of `components`, from phase 1's traces: the global loop does each
/// group's merges in the group's order, interleaved by their keys ([`Traced`]), so a
/// target's clusters come from the first `faces − target` merges in that order. They
/// are replayed through [`Clusters::merge`] in that order — each group's merges keep
/// their own order and groups share no cluster, so the operators add up and the face
/// lists splice as in the global loop — and fitted as it fits them. Also returns how
/// many merges the last of them holds, and every merge of the global order, each as a
/// face of each merged cluster (the merge tree's from single faces, `cut::tree`).
pub fn snapshots(
    fitter: &Fitter,
    p1: &Phase1,
    q: &[Sym3],
    volume: &[f64],
    pairs: &[(u32, u32)],
    targets: &[usize],
    components: usize,
) -> (Vec<Snapshot>, usize, Vec<(u32, u32)>) {
    let traces = p1.traces();
    let order = global_order(&traces);
    let pair = |&(g, i): &(u32, u32)| {
        let t = &traces[g as usize][i as usize];
        (t.a, t.b)
    };
    if !targets.iter().any(|&t| t >= components) {
        return (Vec::new(), 0, order.iter().map(pair).collect());
    }
    let mut cl = Clusters::new(q.to_vec(), volume.to_vec(), pairs);
    let faces = cl.len();
    // Merges of the global order replayed so far (targets decrease, so this grows).
    let mut done = 0;
    let mut out = Vec::new();
    for &target in targets.iter().filter(|&&t| t >= components) {
        let mut m = faces.saturating_sub(target).min(order.len()).max(done);
        // Then the free merges, as the global loop does (`driver::free`).
        let free = |k: usize| {
            order
                .get(k)
                .is_some_and(|&(g, i)| traces[g as usize][i as usize].free)
        };
        while fitter.pricing.free_merges && free(m) {
            m += 1;
        }
        for &(g, i) in &order[done..m] {
            let t = &traces[g as usize][i as usize];
            cl.merge(t.a, t.b, Vec::new(), 0.0);
        }
        done = m;
        // The components' loops ran to the end: replaying them is not cancelled.
        out.extend(snapshot(fitter, &cl, target, Scope::Whole, &|| true));
    }
    (out, done, order.iter().map(pair).collect())
}

/// Every merge of `traces` as (group, index), in the global loop's order: by key,
/// each group's own order kept (its keys never decrease).
fn global_order(traces: &[&[Traced]]) -> Vec<(u32, u32)> {
    let mut order: Vec<(u32, u32)> = Vec::with_capacity(traces.iter().map(|t| t.len()).sum());
    for (g, t) in traces.iter().enumerate() {
        debug_assert!(t.windows(2).all(|w| w[0].cmp_key(&w[1]).is_le()));
        order.extend((0..t.len() as u32).map(|i| (g as u32, i)));
    }
    let key = |&(g, i): &(u32, u32)| &traces[g as usize][i as usize];
    order.sort_unstable_by(|x, y| key(x).cmp_key(key(y)).then(x.cmp(y)));
    order
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::merge::driver::tests::{reprice_modes, with_input};
    use crate::merge::{run, Clusters};
    use crate::params::Params;

    /// The demo scene (several separate objects) merged to `targets` (decreasing) by
    /// the global loop alone and as a run does when components apply (phase 1, the
    /// replayed snapshots at targets of at least one cluster per component, phase 2
    /// for the rest): the same primitives and members at every target.
    fn same_as_global(p: Params, targets: &[usize]) {
        let mesh = crate::input::demo::demo_scene();
        same_as_global_on(&mesh, p, targets);
    }

    /// [`same_as_global`] on `mesh`.
    fn same_as_global_on(mesh: &crate::input::mesh::Mesh, p: Params, targets: &[usize]) {
        with_input(mesh, &p, |fitter, q, vols, pairs| {
            let comps = components(mesh.face_count(), pairs);
            let count = comps.len();
            let fresh = || Clusters::new(q.to_vec(), vols.to_vec(), pairs);
            let global = run(fitter, fresh(), targets, &|_| true);
            let p1 = merge_components(fitter, q, vols, pairs, comps, targets[0], &|_| true);
            let mut split = snapshots(fitter, &p1, q, vols, pairs, targets, count).0;
            let rest = &targets[split.len()..];
            if !rest.is_empty() {
                let (o, a) = crate::input::adjacency::neighbour_lists(q.len(), pairs);
                let lists = (o.into(), a.into());
                let cl = partition::clusters(p1, q.to_vec(), vols.to_vec(), lists, &|_| true)
                    .expect("not stopped");
                split.extend(run(fitter, cl, rest, &|_| true).snapshots);
            }
            assert_eq!(global.snapshots.len(), split.len());
            let sorted = |m: &[Vec<u32>]| {
                let mut m: Vec<Vec<u32>> = m.to_vec();
                m.iter_mut().for_each(|f| f.sort_unstable());
                m
            };
            for (a, b) in global.snapshots.iter().zip(&split) {
                assert_eq!(a.target, b.target);
                assert_eq!(format!("{:?}", a.prims), format!("{:?}", b.prims), "{p:?}");
                assert_eq!(sorted(&a.members), sorted(&b.members));
            }
        });
    }

    /// Targets from every face down to one cluster, through the component count.
    fn demo_targets() -> Vec<usize> {
        let mesh = crate::input::demo::demo_scene();
        let p = Params::default();
        let (faces, count) = with_input(&mesh, &p, |_, _, _, pairs| {
            (
                mesh.face_count(),
                components(mesh.face_count(), pairs).len(),
            )
        });
        assert!(
            count >= 4 && faces > 8 * count,
            "{faces} faces, {count} components"
        );
        let mut t = vec![
            faces + 3,
            faces - 1,
            faces / 2,
            faces / 5,
            3 * count,
            count + 1,
        ];
        t.extend([count, count - 1, 2, 1]);
        t.sort_unstable_by(|a, b| b.cmp(a));
        t.dedup();
        t
    }

    /// Every merge's place in the global order matters at some target: under fully
    /// deferred re-pricing (the most entries re-priced when popped, whose keys order
    /// the merges too), the same as the global loop at every 4th target down to one.
    #[test]
    fn every_fourth_target_matches_the_global_loop() {
        let faces = demo_targets()[0] - 3;
        let all: Vec<usize> = (1..=faces).rev().step_by(4).collect();
        let reprice = crate::params::Reprice::Deferred { min_degree: 0 };
        same_as_global(
            Params {
                reprice,
                ..Params::default()
            },
            &all,
        );
    }

    #[test]
    fn merging_components_apart_changes_nothing() {
        let targets = demo_targets();
        for reprice in reprice_modes() {
            let p = Params {
                reprice,
                ..Params::default()
            };
            same_as_global(p, &targets);
        }
    }

    /// Bumpy grids of `sizes` quads (each quad two triangles, heights from a seeded
    /// generator, so costs differ and ties are rare), side by side: one component each.
    fn bumpy_grids(sizes: &[(u32, u32)], seed: u64) -> crate::input::mesh::Mesh {
        let mut b = crate::input::mesh::MeshBuilder::new();
        let mut x = seed | 1;
        let mut height = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut left = 0.0;
        for &(n, m) in sizes {
            let base = b.positions.len() as u32;
            for j in 0..=m {
                for i in 0..=n {
                    b.positions.push([left + i as f64, j as f64, height()]);
                }
            }
            let id = |i: u32, j: u32| base + j * (n + 1) + i;
            for j in 0..m {
                for i in 0..n {
                    b.push_face(&[id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                    b.push_face(&[id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
                }
            }
            left += n as f64 + 2.0;
        }
        crate::input::mesh::Mesh::from_builder(b)
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(24))]
        /// Random scenes of 2–5 components of random sizes, at random targets from
        /// every face down to one cluster (so above, at and below the component
        /// count): the same primitives and members as the global loop, under fully
        /// deferred and the default re-pricing.
        #[test]
        fn random_scenes_match_the_global_loop(
            sizes in proptest::collection::vec((1u32..8, 1u32..8), 2..6),
            seed in proptest::prelude::any::<u64>(),
            cuts in proptest::collection::vec(0.0f64..1.0, 1..6),
        ) {
            let mesh = bumpy_grids(&sizes, seed);
            let faces = mesh.face_count();
            let mut targets: Vec<usize> =
                cuts.iter().map(|c| 1 + (c * faces as f64) as usize).collect();
            targets.push(sizes.len());
            targets.sort_unstable_by(|a, b| b.cmp(a));
            targets.dedup();
            for reprice in [crate::params::Reprice::Deferred { min_degree: 0 }, Params::default().reprice] {
                same_as_global_on(&mesh, Params { reprice, ..Params::default() }, &targets);
            }
        }
    }

    /// Merges of two loops interleave by key, each loop's own order kept on equal keys.
    #[test]
    fn global_order_interleaves_by_key() {
        let t = |cost: f64, a: u32| Traced {
            cost,
            key_a: a,
            key_b: a + 1,
            a,
            b: a + 1,
            free: false,
        };
        let g0 = [t(1.0, 0), t(3.0, 0), t(3.0, 0), t(5.0, 2)];
        let g1 = [t(2.0, 10), t(3.0, 10), t(4.0, 12)];
        let order = global_order(&[&g0, &g1]);
        let want = [(0, 0), (1, 0), (0, 1), (0, 2), (1, 1), (1, 2), (0, 3)];
        assert_eq!(order, want);
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
    fn applies_only_without_a_dominant_component() {
        let big = MIN_FACES * 10;
        assert!(applies(big, 10, big * 6 / 10, false));
        assert!(!applies(big, 10, big * 6 / 10 + 1, false));
        assert!(!applies(big, 1, big / 2, false));
        assert!(!applies(big, 10, big / 2, true));
        assert!(!applies(MIN_FACES - 1, 10, 1, false));
    }
}
