//! Tests of the hierarchy and its kernels against brute force: the point–triangle
//! distance, nearest and containing items, the slots meeting a box, searches from any
//! slot, first ray hits, and a parallel build equal to the one-thread build.

use super::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Brute force over barycentric grid points plus the edges: an upper bound that
/// the exact distance must not exceed and must come within grid resolution of.
fn brute(p: V3, t: &[V3; 3]) -> f64 {
    let n = 200;
    let mut best = f64::INFINITY;
    for i in 0..=n {
        for j in 0..=n - i {
            let (u, v) = (i as f64 / n as f64, j as f64 / n as f64);
            let q = add(
                t[0],
                add(scale(sub(t[1], t[0]), u), scale(sub(t[2], t[0]), v)),
            );
            best = best.min(norm2(sub(p, q)));
        }
    }
    best
}

#[test]
fn triangle_distance_matches_brute_force() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let mut v = || -> V3 { std::array::from_fn(|_| rng.gen_range(-1.0..1.0)) };
    for _ in 0..200 {
        let t = [v(), v(), v()];
        let p = scale(v(), 2.0);
        let exact = point_tri_dist2(p, &t).sqrt();
        let bf = brute(p, &t).sqrt();
        assert!(exact <= bf + 1e-12, "{exact} > {bf}");
        assert!(bf - exact < 0.02, "{exact} vs {bf}");
    }
    let flat = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]];
    assert!((point_tri_dist2([1.0, 1.0, 0.0], &flat) - 1.0).abs() < 1e-15);
}

/// A triangle with two corners at one point is a segment: its distance is the
/// segment's, never NaN. Each edge's parameter divided 0 by 0 there, and a NaN
/// distance passed every comparison: nearest searches visited the whole tree for
/// each point (samurai_monastery's cut took minutes) and error bounds over such
/// triangles came out 0.
#[test]
fn a_triangle_with_coincident_corners_is_its_segment() {
    let (a, b) = ([0.0, 0.0, 0.0], [2.0, 0.0, 0.0]);
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    for _ in 0..200 {
        let p: V3 = std::array::from_fn(|_| rng.gen_range(-3.0..3.0));
        let want = point_segment_dist2(p, a, b);
        for t in [
            [a, a, b],
            [a, b, a],
            [b, a, a],
            [a, b, b],
            [b, b, a],
            [a, a, a],
        ] {
            let want = if t == [a, a, a] { norm2(p) } else { want };
            let got = point_tri_dist2(p, &t);
            assert!(
                (got - want).abs() <= 1e-12 * (1.0 + want),
                "{t:?} {p:?}: {got} vs {want}"
            );
        }
    }
}

#[test]
fn nearest_and_any_at_match_linear_scans() {
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    let tris = small_triangles(&mut rng, 500);
    let boxes: Vec<_> = tris.iter().map(tri_box).collect();
    let bvh = Bvh::build(&boxes);
    for _ in 0..300 {
        let p: V3 = std::array::from_fn(|_| rng.gen_range(-6.0..6.0));
        let (d, i) = bvh.nearest(p, |i| point_tri_dist2(p, &tris[i as usize]));
        let lin = tris
            .iter()
            .map(|t| point_tri_dist2(p, t))
            .fold(f64::INFINITY, f64::min);
        assert_eq!(d, lin);
        assert_eq!(point_tri_dist2(p, &tris[i as usize]), d);
        let near = |i: u32| point_tri_dist2(p, &tris[i as usize]) < 0.01;
        let want = (0..tris.len() as u32).any(near);
        assert_eq!(bvh.any_at(p, 0.1, near), want);
    }
    assert_eq!(Bvh::build(&[]).nearest([0.0; 3], |_| 0.0).1, u32::MAX);
}

/// `n` triangles of corners within 0.3 of a centre in the cube of half-side 5.
fn small_triangles(rng: &mut ChaCha8Rng, n: usize) -> Vec<[V3; 3]> {
    (0..n)
        .map(|_| {
            let c: V3 = std::array::from_fn(|_| rng.gen_range(-5.0..5.0));
            std::array::from_fn(|_| add(c, std::array::from_fn(|_| rng.gen_range(-0.3..0.3))))
        })
        .collect()
}

/// The slots meeting a box hold every item whose box meets it, in slot order,
/// each once; more than `most` of them is said so. Against a linear scan, for
/// boxes of every size about 200 small triangles.
#[test]
fn the_slots_meeting_a_box_hold_every_item_meeting_it() {
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    let tris = small_triangles(&mut rng, 200);
    let boxes: Vec<(V3, V3)> = tris.iter().map(tri_box).collect();
    let bvh = Bvh::build(&boxes);
    let slot_box = |k: u32| boxes[bvh.order()[k as usize] as usize];
    let (mut stack, mut out) = (Vec::new(), Vec::new());
    for q in 0..300 {
        let c: V3 = std::array::from_fn(|_| rng.gen_range(-6.0..6.0));
        let r = [0.1, 1.0, 4.0][q % 3];
        let (lo, hi) = (c.map(|x| x - r), c.map(|x| x + r));
        let meets = |(a, b): &(V3, V3)| (0..3).all(|k| a[k] <= hi[k] && lo[k] <= b[k]);
        let want: Vec<u32> = (0..200u32).filter(|&i| meets(&boxes[i as usize])).collect();
        let all = bvh.slots_meeting((lo, hi), usize::MAX, slot_box, &mut stack, &mut out);
        assert!(all);
        assert!(out.windows(2).all(|w| w[0] < w[1]), "{out:?}");
        let ids: Vec<u32> = out.iter().map(|&k| bvh.order()[k as usize]).collect();
        assert!(want.iter().all(|i| ids.contains(i)), "{want:?} {ids:?}");
        let fits = bvh.slots_meeting((lo, hi), want.len(), slot_box, &mut stack, &mut out);
        assert_eq!(fits, ids.len() <= want.len());
        if !want.is_empty() {
            assert!(!bvh.slots_meeting((lo, hi), want.len() - 1, slot_box, &mut stack, &mut out));
        }
    }
}

/// Searched from any slot, the nearest item is the one of least id among all at
/// the least distance: triangles repeated three times over (so every nearest one
/// ties with two others in other leaves) and points on a triangle (distance 0
/// to it and to its copies), against a linear scan.
#[test]
fn a_search_from_any_slot_finds_the_least_id_among_the_nearest() {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let base = small_triangles(&mut rng, 200);
    let tris: Vec<[V3; 3]> = (0..3).flat_map(|_| base.iter().copied()).collect();
    let bvh = Bvh::build(&tris.iter().map(tri_box).collect::<Vec<_>>());
    let by_slot: Vec<[V3; 3]> = bvh.order().iter().map(|&i| tris[i as usize]).collect();
    let mut stack = Vec::new();
    for q in 0..300 {
        let p: V3 = match q % 2 {
            0 => std::array::from_fn(|_| rng.gen_range(-6.0..6.0)),
            _ => base[q % base.len()][0],
        };
        let dist = |t: &[V3; 3]| point_tri_dist2(p, t);
        let least = tris.iter().map(dist).fold(f64::INFINITY, f64::min);
        let first = (0..tris.len()).find(|&i| dist(&tris[i]) == least);
        for start in [0, 7, (q * 13) as u32 % 600, 599, u32::MAX] {
            let (d, k) = bvh.nearest_slot(p, f64::NEG_INFINITY, start, &mut stack, |k| {
                dist(&by_slot[k as usize])
            });
            assert_eq!(d, least, "point {q}, start {start}");
            assert_eq!(Some(bvh.order()[k as usize] as usize), first, "point {q}");
        }
    }
}

/// A hierarchy large enough to build its halves in parallel: each item in one
/// leaf, each box holding its children's (and a leaf's its items'), nearest
/// queries the linear scan's, and the same nodes and items on one thread and two.
#[test]
fn a_parallel_build_is_whole_and_thread_independent() {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let n = 3 * PARALLEL + 5;
    let boxes: Vec<(V3, V3)> = (0..n)
        .map(|_| {
            let lo: V3 = std::array::from_fn(|_| rng.gen_range(-5.0..5.0));
            (lo, lo.map(|x| x + rng.gen_range(0.0..0.2)))
        })
        .collect();
    let on = |threads| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build();
        pool.expect("pool").install(|| Bvh::build(&boxes))
    };
    let (one, bvh) = (on(1), on(2));
    assert_eq!(format!("{one:?}"), format!("{bvh:?}"));
    let mut seen = vec![0; n];
    let holds = |(lo, hi): (V3, V3), n: &Node<Exact>| {
        let (nlo, nhi) = n.b.get();
        (0..3).all(|k| nlo[k] <= lo[k] && hi[k] <= nhi[k])
    };
    for node in &bvh.nodes {
        let span = node.first as usize..(node.first + node.count) as usize;
        for &i in &bvh.items[span] {
            seen[i as usize] += 1;
            assert!(holds(boxes[i as usize], node));
        }
        if node.count == 0 {
            for c in [node.first, node.first + 1] {
                assert!(holds(bvh.nodes[c as usize].b.get(), node));
            }
        }
    }
    assert!(seen.iter().all(|&k| k == 1));
    for _ in 0..200 {
        let p: V3 = std::array::from_fn(|_| rng.gen_range(-6.0..6.0));
        let d2 = |i: u32| box_dist2(p, boxes[i as usize].0, boxes[i as usize].1);
        let lin = (0..n as u32).map(d2).fold(f64::INFINITY, f64::min);
        assert_eq!(bvh.nearest(p, d2).0, lin);
    }
}

/// The first hit along random rays through random triangles is the brute-force
/// least hit over all triangles, and a ray pointing away from them all meets none.
#[test]
fn first_ray_hits_match_brute_force() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let mut pt = || -> V3 { std::array::from_fn(|_| rng.gen_range(-1.0..1.0)) };
    let tris: Vec<[V3; 3]> = (0..200)
        .map(|_| {
            let c = pt();
            let (a, b) = (pt(), pt());
            [c, add(c, scale(a, 0.2)), add(c, scale(b, 0.2))]
        })
        .collect();
    let bvh = Bvh::build(&tris.iter().map(tri_box).collect::<Vec<_>>());
    let mut stack = Vec::new();
    for k in 0..100 {
        let o = scale(pt(), 3.0);
        let c = scale(add(add(tris[k][0], tris[k][1]), tris[k][2]), 1.0 / 3.0);
        let d = sub(c, o);
        let (t, i) = bvh.ray_first(o, d, 10.0, &mut stack, |i| {
            ray_tri(o, d, &tris[i as usize], 0.0)
        });
        let brute = (0..tris.len() as u32)
            .filter_map(|i| ray_tri(o, d, &tris[i as usize], 0.0).map(|t| (t, i)))
            .fold((10.0, u32::MAX), |b, x| if x.0 < b.0 { x } else { b });
        assert_eq!((t, i), brute, "ray {k}");
        assert!(t <= 1.0 + 1e-9, "ray {k} aims at a centroid: {t}");
    }
    let away = bvh.ray_first([0.0, 0.0, 5.0], [0.0, 0.0, 1.0], 10.0, &mut stack, |i| {
        ray_tri([0.0, 0.0, 5.0], [0.0, 0.0, 1.0], &tris[i as usize], 0.0)
    });
    assert_eq!(away, (10.0, u32::MAX));
}

/// Boxes of unit size along x at `i · 2654435761 mod m`, in 7 rows along y.
fn spread(m: u32) -> impl Fn(u32) -> (V3, V3) + Sync {
    move |i: u32| {
        let x = f64::from(i.wrapping_mul(2_654_435_761) % m);
        let y = f64::from(i % 7);
        ([x, y, 0.0], [x + 1.0, y + 1.0, 1.0])
    }
}

/// How many times a checked build of `n` items asks to go on, asserting it builds
/// what the unchecked build does.
fn asks_building(n: usize, bbox: &(dyn Fn(u32) -> (V3, V3) + Sync)) -> usize {
    use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};
    let asked = AtomicUsize::new(0);
    let go_on = |_: f64| {
        asked.fetch_add(1, Relaxed);
        true
    };
    let checked = Bvh::build_by_checked(n, LEAF, bbox, &go_on).expect("not stopped");
    assert_eq!(
        format!("{checked:?}"),
        format!("{:?}", Bvh::build_by(n, LEAF, bbox))
    );
    asked.into_inner()
}

/// A build told to stop returns nothing, after asking a few times (once per node of
/// `CHECK_AT` items or more, not per item); one told to go on is the unchecked build.
#[test]
fn a_checked_build_stops_when_told_and_is_the_same_when_not() {
    let n = 4 * CHECK_AT + 3;
    let bbox = spread(1000);
    // The nodes of 4, 2 and 1 × CHECK_AT items or more: 1 + 2 + 4.
    assert_eq!(asks_building(n, &bbox), 7);
    let stop = |_: f64| false;
    assert!(Bvh::build_by_checked(n, LEAF, &bbox, &stop).is_none());
    assert!(Bvh::build_coarse(n, 16, &bbox, &stop).is_none());
    // Too few items to ask: built whole.
    assert!(Bvh::build_by_checked(CHECK_AT - 1, LEAF, &bbox, &stop).is_some());
}

/// A node's median selection over millions of items asks too (unless the build
/// cannot unwind), the hierarchy the same as unchecked; told to stop inside the
/// root's selection, the build stops there.
#[test]
#[cfg(panic = "unwind")]
fn a_large_selection_asks_as_it_goes_and_builds_the_same() {
    use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};
    let n = 3 << 20;
    let bbox = spread(100_003);
    let asked = asks_building(n, &bbox);
    // Asks before splits (nodes of CHECK_AT items or more) and between blocks:
    // fewer than were made.
    fn splits(count: usize) -> usize {
        match count >= CHECK_AT {
            true => 1 + splits(count / 2) + splits(count - count / 2),
            false => 0,
        }
    }
    // Asks between the blocks of nodes written and of centroids.
    let nodes = Sizes::new(n, LEAF).nodes(n);
    let blocks = nodes.div_ceil(CHECK_AT << 4) - 1 + n.div_ceil(CHECK_AT << 4) - 1;
    assert!(asked > splits(n) + blocks, "{asked}");
    // Stopped at the first ask after the root's own: inside its selection.
    let after = AtomicUsize::new(0);
    let once = |_: f64| after.fetch_add(1, Relaxed) <= blocks;
    assert!(Bvh::build_by_checked(n, LEAF, &bbox, &once).is_none());
    assert_eq!(after.load(Relaxed), blocks + 2);
}

/// A hierarchy with [`Compact`] boxes is the exact one's tree (items in the same
/// slots) with boxes that hold the exact ones, and answers every query alike: the
/// nearest item and its distance from any slot, with and without an early exit's
/// bound, the slots meeting a box and the first ray hit. Triangles far from the
/// origin and a hair apart, so that f32 boxes round off many of their gaps.
#[test]
fn compact_boxes_answer_as_exact_ones() {
    let mut rng = ChaCha8Rng::seed_from_u64(13);
    let far = [1000.0, -2000.0, 500.0];
    let tris: Vec<[V3; 3]> = (0..3000)
        .map(|_| {
            let c: V3 = std::array::from_fn(|k| far[k] + rng.gen_range(-0.01..0.01));
            std::array::from_fn(|_| add(c, std::array::from_fn(|_| rng.gen_range(-1e-4..1e-4))))
        })
        .collect();
    let bbox = |i: u32| tri_box(&tris[i as usize]);
    let go_on = |_: f64| true;
    let exact = Bvh::build_by_checked(tris.len(), LEAF, &bbox, &go_on).expect("built");
    let compact = Bvh::build_compact(tris.len(), LEAF, &bbox, &go_on).expect("built");
    assert_eq!(exact.order(), compact.order());
    assert_eq!(exact.nodes.len(), compact.nodes.len());
    let mut looser = 0;
    for (e, c) in exact.nodes.iter().zip(&compact.nodes) {
        assert_eq!((e.first, e.count), (c.first, c.count));
        let ((elo, ehi), (clo, chi)) = (e.b.get(), c.b.get());
        assert!((0..3).all(|k| clo[k] <= elo[k] && ehi[k] <= chi[k]));
        looser += usize::from(clo != elo || chi != ehi);
    }
    assert!(looser > exact.nodes.len() / 2, "{looser} boxes rounded");
    let (mut met, mut hits) = (0, 0);
    let slot_tri = |k: u32| tris[exact.order()[k as usize] as usize];
    let slot_box = |k: u32| tri_box(&slot_tri(k));
    let (mut stack, mut pairs) = (Vec::new(), Vec::new());
    let (mut out_e, mut out_c) = (Vec::new(), Vec::new());
    for q in 0..400 {
        let p: V3 = std::array::from_fn(|k| far[k] + rng.gen_range(-0.012..0.012));
        let dist = |k: u32| point_tri_dist2(p, &slot_tri(k));
        for (enough, start) in [
            (f64::NEG_INFINITY, u32::MAX),
            (f64::NEG_INFINITY, q),
            (1e-6, 7),
        ] {
            let e = exact.nearest_slot(p, enough, start, &mut pairs, dist);
            let c = compact.nearest_slot(p, enough, start, &mut pairs, dist);
            match enough > 0.0 {
                true => assert_eq!(e.0.max(enough), c.0.max(enough), "point {q}"),
                false => assert_eq!(e, c, "point {q}"),
            }
        }
        let r = [1e-5, 1e-4, 1e-3][q as usize % 3];
        let query = (p.map(|x| x - r), p.map(|x| x + r));
        let most = [usize::MAX, 40][q as usize % 2];
        let a = exact.slots_meeting(query, most, slot_box, &mut stack, &mut out_e);
        let b = compact.slots_meeting(query, most, slot_box, &mut stack, &mut out_c);
        assert_eq!((a, &out_e), (b, &out_c), "box {q}");
        met += usize::from(a && !out_e.is_empty());
        // Aimed at a triangle's centre from a little way off.
        let t = slot_tri(q * 7 % tris.len() as u32);
        let centre = scale(add(add(t[0], t[1]), t[2]), 1.0 / 3.0);
        let d: V3 = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
        let o = sub(centre, scale(d, 0.02));
        let hit = |k: u32| ray_tri(o, d, &slot_tri(k), 0.0);
        let e = exact.ray_slot_first(o, d, 1.0, &mut stack, hit);
        assert_eq!(
            e,
            compact.ray_slot_first(o, d, 1.0, &mut stack, hit),
            "ray {q}"
        );
        hits += usize::from(e.1 != u32::MAX);
    }
    assert!(met > 50 && hits > 20, "{met} boxes met, {hits} rays hit");
}

/// Boxes whose centres the f32 rounding ties, or nearly: `kind` picks the family.
/// 0: a few hundred distinct centres a hair apart (closer than f32's spacing), each
/// shared by many items; 1: every centre the same point; 2: coordinates beyond f32's
/// range (rounded to ±inf) and near it; 3: around zero, with signed zeros and values
/// below f32's least (rounded to ±0); 4: far from the origin, jittered below f32's
/// spacing there, on one axis only (the others spread), so extents tie too.
fn adversarial(kind: u32, n: usize, seed: u64) -> Vec<(V3, V3)> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..n)
        .map(|i| {
            let c: V3 = match kind {
                0 => {
                    let base = [0.1, -0.3, 0.7];
                    let j = f64::from(rng.gen_range(0..300u32));
                    std::array::from_fn(|k| base[k] + j * 1e-12 * (k as f64 + 1.0))
                }
                1 => [0.25, 0.25, -0.5],
                2 => std::array::from_fn(|_| {
                    let s = if rng.gen_bool(0.5) { 1.0 } else { -1.0 };
                    s * [1e39, 3.4e38, 3.5e38, 1e60, 1e300][rng.gen_range(0..5)]
                        * (1.0 + f64::from(rng.gen_range(0..4u32)) * 1e-15)
                }),
                3 => std::array::from_fn(|_| {
                    [0.0, -0.0, 1e-50, -1e-50, 1e-46, -1e-46, 1e-300, 1e-40][rng.gen_range(0..8)]
                }),
                _ => [
                    1e7 + f64::from(rng.gen_range(0..50u32)) * 1e-9,
                    f64::from(rng.gen_range(0..1000u32)) * 1e-3,
                    1e7 + f64::from(rng.gen_range(0..50u32)) * 1e-9,
                ],
            };
            // Boxes of varying size about the centre: lo + hi is 2c exactly for the
            // even sizes, and off by rounding for the others.
            let h = [0.0, 0.5, 1e-20, 0.125][i % 4];
            (c.map(|x| x - h), c.map(|x| x + h))
        })
        .collect()
}

/// The build over f32 centres, ties decided on the exact ones, is the build over
/// the exact (f64) centres bit for bit: every node's box, first and count, and the
/// items' order, on inputs made for the rounding to tie (equal, near-equal, huge,
/// tiny and signed-zero centres), on one thread and on several, with exact and
/// compact boxes; while the rounded centres alone ([`Bvh::build_coarse`]) build
/// another tree on the same inputs (so the ties are there and matter).
#[test]
fn f32_centres_with_exact_ties_build_the_f64_tree() {
    let go_on = |_: f64| true;
    let mut coarse_differs = 0;
    for kind in 0..5 {
        for (n, seed) in [(5, 1), (37, 2), (1000, 3), (9000, 4)] {
            let boxes = adversarial(kind, n, seed + 10 * u64::from(kind));
            let bbox = |i: u32| boxes[i as usize];
            let exact = Bvh::build_f64(n, LEAF, &bbox);
            let tied = Bvh::build_by(n, LEAF, &bbox);
            assert_eq!(
                format!("{exact:?}"),
                format!("{tied:?}"),
                "kind {kind}, {n}"
            );
            let one = rayon::ThreadPoolBuilder::new().num_threads(1).build();
            let single = one.expect("pool").install(|| Bvh::build_by(n, LEAF, &bbox));
            assert_eq!(
                format!("{exact:?}"),
                format!("{single:?}"),
                "kind {kind}, {n}"
            );
            let compact = Bvh::build_compact(n, LEAF, &bbox, &go_on).expect("built");
            assert_eq!(exact.order(), compact.order(), "kind {kind}, {n}");
            for (e, c) in exact.nodes.iter().zip(&compact.nodes) {
                assert_eq!((e.first, e.count), (c.first, c.count), "kind {kind}, {n}");
            }
            let coarse = Bvh::build_coarse(n, LEAF, &bbox, &go_on).expect("built");
            coarse_differs += usize::from(coarse.order() != exact.order());
        }
    }
    assert!(
        coarse_differs >= 10,
        "{coarse_differs} of 20 differ without exact ties"
    );
}

/// The same on random triangles (the cut's own input) at a scale with a parallel
/// build and a checked one, the rounded centres spread as a scan's are.
#[test]
fn f32_centres_with_exact_ties_build_the_f64_tree_on_triangles() {
    let mut rng = ChaCha8Rng::seed_from_u64(21);
    let tris: Vec<[V3; 3]> = (0..50_000)
        .map(|_| {
            let c: V3 = std::array::from_fn(|_| rng.gen_range(-0.1..0.1));
            std::array::from_fn(|_| add(c, std::array::from_fn(|_| rng.gen_range(-1e-4..1e-4))))
        })
        .collect();
    let bbox = |i: u32| tri_box(&tris[i as usize]);
    let exact = Bvh::build_f64(tris.len(), LEAF, &bbox);
    let tied = Bvh::build_by_checked(tris.len(), LEAF, &bbox, &|_| true).expect("built");
    assert_eq!(format!("{exact:?}"), format!("{tied:?}"));
}

/// Triangles said to be apart are: every point of one (on a barycentric grid) stands
/// farther than the margin from the other. Triangles that share a point, or cross,
/// are never said to be apart; and most pairs with a clear gap are found apart.
#[test]
fn triangles_said_apart_are_apart() {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let tri = |rng: &mut ChaCha8Rng, at: f64| -> [V3; 3] {
        std::array::from_fn(|_| {
            std::array::from_fn(|k| rng.gen_range(-1.0..1.0) + at * (k == 0) as u8 as f64)
        })
    };
    let margin = 1e-6;
    let (mut apart, mut clear) = (0, 0);
    for i in 0..4000 {
        let a = tri(&mut rng, 0.0);
        let b = tri(&mut rng, (i % 4) as f64);
        let near = (0..=10)
            .flat_map(|i| (0..=10 - i).map(move |j| (i, j)))
            .map(|(i, j)| {
                let (u, v) = (i as f64 / 10.0, j as f64 / 10.0);
                let p = add(
                    a[0],
                    add(scale(sub(a[1], a[0]), u), scale(sub(a[2], a[0]), v)),
                );
                point_tri_dist2(p, &b).sqrt()
            })
            .fold(f64::INFINITY, f64::min);
        let said = tris_apart(&a, &b, margin);
        assert!(
            !said || near > margin,
            "{a:?} {b:?} said apart, {near} near"
        );
        if near > 0.1 {
            clear += 1;
            apart += usize::from(said);
        }
        // In one plane, apart by a clear gap: found.
        let flat = |t: [V3; 3]| t.map(|v| [v[0], v[1], 0.0]);
        let (fa, fb) = (flat(a), flat(b.map(|v| add(v, [2.5, 0.0, 0.0]))));
        let spans = |t: &[V3; 3]| {
            t.iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
                    (l.min(v[0]), h.max(v[0]))
                })
        };
        if spans(&fb).0 - spans(&fa).1 > 0.1 {
            assert!(tris_apart(&fa, &fb, margin), "{fa:?} {fb:?}");
        }
        // Sharing a corner, they meet.
        let touching = [a[0], b[1], b[2]];
        assert!(!tris_apart(&a, &touching, margin));
    }
    assert!(clear > 1000 && apart * 10 > clear * 9, "{apart} of {clear}");
}
