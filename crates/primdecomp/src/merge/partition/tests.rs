//! Tests of the spatial parts: splits, the parts' own meshes and pairs, parts merged in turn
//! on any thread count, and the regroup into the global loop.

use super::*;

fn grid(n: u32) -> Mesh {
    grid_z(n, |_, _| 0.0)
}

/// An n × n grid of unit quads with heights `z(i, j)` at its vertices.
fn grid_z(n: u32, z: impl Fn(u32, u32) -> f64 + Copy) -> Mesh {
    let pos: Vec<[f64; 3]> = (0..=n)
        .flat_map(|j| (0..=n).map(move |i| [i as f64, j as f64, z(i, j)]))
        .collect();
    let faces: Vec<Vec<u32>> = (0..n)
        .flat_map(|j| {
            (0..n).map(move |i| {
                let v = j * (n + 1) + i;
                vec![v, v + 1, v + n + 2, v + n + 1]
            })
        })
        .collect();
    Mesh::from_polygons(&pos, &faces).unwrap()
}

/// Every face in exactly one part, parts increasing and balanced (sizes within one
/// per level), for K a power of two and not.
#[test]
fn split_covers_each_face_once_and_balances() {
    let mesh = crate::input::demo::demo_scene();
    let n = mesh.face_count();
    for k in [1, 2, 3, 4, 7, 8, 16] {
        let parts = split(&mesh, k);
        assert_eq!(parts.len(), k);
        let mut seen = vec![0u8; n];
        for p in &parts {
            assert!(p.windows(2).all(|w| w[0] < w[1]), "part not increasing");
            p.iter().for_each(|&f| seen[f as usize] += 1);
            let ideal = n as f64 / k as f64;
            assert!(
                (p.len() as f64 - ideal).abs() <= 4.0,
                "k={k}: {} faces, ideal {ideal}",
                p.len()
            );
        }
        assert!(
            seen.iter().all(|&s| s == 1),
            "k={k}: a face not in one part"
        );
    }
}

/// The split is a function of the input and K: same parts on 1 and 4 threads, and
/// spatial: on a 16×8 grid (longest extent x), 2 parts are the left and right
/// halves, and ties in the centroid coordinate go by face index.
#[test]
fn split_is_deterministic_and_spatial() {
    let mesh = grid(16);
    let one = crate::merge::driver::tests::in_pool(1, || split(&mesh, 8));
    let four = crate::merge::driver::tests::in_pool(4, || split(&mesh, 8));
    assert_eq!(one, four);
    let pos: Vec<[f64; 3]> = (0..=8)
        .flat_map(|j| (0..=16).map(move |i| [i as f64, j as f64, 0.0]))
        .collect();
    let faces: Vec<Vec<u32>> = (0..8)
        .flat_map(|j| {
            (0..16).map(move |i| {
                let v = j * 17 + i;
                vec![v, v + 1, v + 18, v + 17]
            })
        })
        .collect();
    let wide = Mesh::from_polygons(&pos, &faces).unwrap();
    let halves = split(&wide, 2);
    for (p, want_left) in halves.iter().zip([true, false]) {
        assert_eq!(p.len(), 64);
        assert!(p.iter().all(|&f| (f % 16 < 8) == want_left));
    }
    // A single row of 5 equal centroids' worth of ties: a degenerate mesh whose faces
    // all share one centroid splits by face index.
    let tri = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    let same = Mesh::from_polygons(&tri, &vec![vec![0, 1, 2]; 5]).unwrap();
    assert_eq!(split(&same, 2), vec![vec![0, 1], vec![2, 3, 4]]);
}

/// Every index is run once and its result comes back with it, whether the pool
/// has one thread, two or three and whatever the runs cost (uneven work, more
/// threads than indices, none at all); the work after them runs once.
#[test]
fn in_turn_runs_each_index_once() {
    use crate::merge::driver::tests::in_pool;
    for threads in [1, 2, 3] {
        for n in [0, 1, 2, 7, 16] {
            let runs: Vec<AtomicUsize> = (0..n).map(|_| AtomicUsize::new(0)).collect();
            let thens = AtomicUsize::new(0);
            let mut got = in_pool(threads, || {
                let run = |i: usize| {
                    runs[i].fetch_add(1, Relaxed);
                    // Uneven work: later indices cost more.
                    (0..(i as u64 + 1) * 20_000).fold(i as u64, |a, x| a.wrapping_mul(31) ^ x)
                };
                in_turn(n, run, || {
                    thens.fetch_add(1, Relaxed);
                })
            });
            got.sort_unstable_by_key(|r| r.0);
            let want: Vec<(usize, u64)> = (0..n)
                .map(|i| {
                    let v =
                        (0..(i as u64 + 1) * 20_000).fold(i as u64, |a, x| a.wrapping_mul(31) ^ x);
                    (i, v)
                })
                .collect();
            assert_eq!(got, want, "{threads} threads, {n} indices");
            assert!(runs.iter().all(|r| r.load(Relaxed) == 1));
            assert_eq!(thens.load(Relaxed), 1, "{threads} threads, {n} indices");
        }
    }
}

/// Phase 1's parts taken in turn by whichever thread is free give the same groups,
/// part for part, on one thread, two and three, for a part count that does not
/// divide among the threads; so do phase 2's starting clusters.
#[test]
fn parts_merge_alike_on_any_thread_count() {
    use crate::merge::driver::tests::in_pool;
    let mesh = grid_z(24, |i, j| ((i * 7 + j * 13) % 5) as f64 * 0.3);
    let p = crate::params::Params::default();
    crate::merge::driver::tests::with_input(&mesh, &p, |fitter, q, _, pairs| {
        let (o, a) = crate::input::adjacency::neighbour_lists(q.len(), pairs);
        let lists: Lists = (o.into(), a.into());
        let own = FaceData::PerPart {
            tangent_eps: p.fit.tangent_eps,
            lists: &lists,
        };
        let run = |threads| {
            in_pool(threads, || {
                let p1 = merge_parts(fitter, own, (6, 7, false), &|_| true, &|_| {});
                let summary: Vec<_> = p1
                    .parts
                    .iter()
                    .map(|g| {
                        let bits: Vec<u64> = g.volume.iter().map(|v| v.to_bits()).collect();
                        (
                            g.faces.clone(),
                            g.offsets.clone(),
                            g.q.clone(),
                            bits,
                            g.verts.clone(),
                        )
                    })
                    .collect();
                let (merges, fits) = (p1.merges, p1.fits);
                let mut cl = group_clusters(p1, q.len(), &lists, &|_| true).expect("not stopped");
                let roots = cl.roots();
                let starts: Vec<(Vec<u32>, Vec<u32>)> = roots
                    .iter()
                    .map(|&r| (cl.faces(r).collect(), cl.resolved_neighbors(r)))
                    .collect();
                (summary, merges, fits, starts)
            })
        };
        let one = run(1);
        assert_eq!(one.0.len(), 7);
        assert!(one.1 > 0);
        assert_eq!(one, run(2));
        assert_eq!(one, run(3));
    });
}

/// Phase 2 starts from resolved adjacency between groups: every root's list names
/// live roots only, and groups that share an edge name each other (a list resolved
/// before the later groups were merged named their faces instead, which seeding
/// skips: the groups then never merged by adjacency).
#[test]
fn phase_two_lists_name_adjacent_groups() {
    // Bumpy, so that no merge is free and the parts stop at their targets (on a
    // flat grid every merge adds no volume and each part ends as one group).
    let mesh = grid_z(24, |i, j| ((i * 7 + j * 13) % 5) as f64 * 0.3);
    let p = crate::params::Params::default();
    let (mut cl, pairs) =
        crate::merge::driver::tests::with_input(&mesh, &p, |fitter, q, vols, pairs| {
            let given = FaceData::Given {
                q,
                volume: vols,
                pairs,
            };
            let p1 = merge_parts(fitter, given, (4, 4, false), &|_| true, &|_| {});
            (
                {
                    let (o, a) = crate::input::adjacency::neighbour_lists(q.len(), pairs);
                    let lists = (o.into(), a.into());
                    clusters(p1, q.to_vec(), vols.to_vec(), lists, &|_| true).expect("not stopped")
                },
                pairs.to_vec(),
            )
        });
    let roots: Vec<u32> = cl.roots();
    assert!(roots.len() > 4);
    for &r in &roots {
        let n = cl.neighbors(r).to_vec();
        assert!(
            !n.is_empty() && n.iter().all(|&b| cl.is_root(b) && b != r),
            "{n:?}"
        );
    }
    for &(a, b) in &pairs {
        let (ra, rb) = (cl.find(a), cl.find(b));
        if ra != rb {
            assert!(cl.neighbors(ra).contains(&rb), "{ra} and {rb} adjacent");
        }
    }
}

/// Phase 1 computing each part's operators, seed volumes and pairs itself, then
/// phase 2 started from its groups (ids renamed by their lowest faces), holds the
/// clusters that the whole input's arrays and the face-by-face replay make: root
/// for root the same faces in the same list order, operator, volume, points and
/// neighbours (as groups' heads), so the loop after them merges alike.
#[test]
fn groups_start_phase_two_as_faces_do() {
    let mesh = grid_z(24, |i, j| ((i * 7 + j * 13) % 5) as f64 * 0.3);
    let p = crate::params::Params::default();
    crate::merge::driver::tests::with_input(&mesh, &p, |fitter, q, vols, pairs| {
        let (o, a) = crate::input::adjacency::neighbour_lists(q.len(), pairs);
        let lists: Lists = (o.into(), a.into());
        let given = FaceData::Given {
            q,
            volume: vols,
            pairs,
        };
        let own = FaceData::PerPart {
            tangent_eps: p.fit.tangent_eps,
            lists: &lists,
        };
        let p1 = merge_parts(fitter, given, (4, 4, false), &|_| true, &|_| {});
        let old = clusters(p1, q.to_vec(), vols.to_vec(), lists.clone(), &|_| true);
        let mut old = old.expect("not stopped");
        let p1 = merge_parts(fitter, own, (4, 4, false), &|_| true, &|_| {});
        let mut new = group_clusters(p1, q.len(), &lists, &|_| true).expect("not stopped");
        let (ro, rn) = (old.roots(), new.roots());
        assert!(ro.len() > 4);
        assert_eq!(ro, rn.iter().map(|&g| new.head(g)).collect::<Vec<_>>());
        for (&a, &b) in ro.iter().zip(&rn) {
            let faces: Vec<u32> = new.faces(b).collect();
            assert_eq!(old.faces(a).collect::<Vec<_>>(), faces, "root {a}");
            assert_eq!(old.face_count[a as usize] as usize, faces.len());
            assert_eq!(old.q[a as usize], new.q[b as usize]);
            assert_eq!(
                old.volume[a as usize].to_bits(),
                new.volume[b as usize].to_bits()
            );
            assert_eq!(old.verts(a), new.verts(b));
            let heads: Vec<u32> = new.neighbors(b).iter().map(|&g| new.head(g)).collect();
            assert_eq!(old.resolved_neighbors(a), heads, "root {a}");
            assert_eq!(old.neighbor_list(a).1, new.neighbor_list(b).1);
        }
        // Merged groups list their faces as merged faces do (blocks spliced).
        for k in 0..ro.len().min(12) {
            let (a, b) = (old.find(ro[k]), new.find(rn[k]));
            let Some(&n) = new.resolved_neighbors(b).first() else {
                continue;
            };
            let m = old.find(new.head(n));
            let (ra, rb) = (
                old.merge(a, m, Vec::new(), 0.0),
                new.merge(b, n, Vec::new(), 0.0),
            );
            assert_eq!(ra, new.head(rb));
            assert_eq!(
                old.faces(ra).collect::<Vec<_>>(),
                new.faces(rb).collect::<Vec<_>>()
            );
        }
    });
}
