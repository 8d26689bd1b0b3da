//! Tests of the hull-vertex reduction against brute force (hull planes and random
//! support directions, by proptest too) on degenerate, thin, duplicated, scaled and
//! offset clouds, and with a reused workspace.

use super::*;
use crate::vec3::add;
use proptest::prelude::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

type Cloud = (Vec<f64>, Vec<f64>, Vec<f64>);

fn soa(p: &[V3]) -> Cloud {
    (
        p.iter().map(|q| q[0]).collect(),
        p.iter().map(|q| q[1]).collect(),
        p.iter().map(|q| q[2]).collect(),
    )
}

fn run(p: &[V3], eps: f64) -> Vec<u32> {
    let (x, y, z) = soa(p);
    let (mut ws, mut out) = (HullWorkspace::default(), Vec::new());
    hull_vertices(&x, &y, &z, eps, &mut ws, &mut out);
    assert!(out.windows(2).all(|w| w[0] < w[1]), "not sorted/unique");
    assert!(out.iter().all(|&i| (i as usize) < p.len()));
    out
}

fn diag(p: &[V3]) -> f64 {
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for q in p {
        for k in 0..3 {
            lo[k] = lo[k].min(q[k]);
            hi[k] = hi[k].max(q[k]);
        }
    }
    if p.is_empty() {
        0.0
    } else {
        norm2(sub(hi, lo)).sqrt()
    }
}

fn unit(rng: &mut ChaCha8Rng) -> V3 {
    loop {
        let v = [0; 3].map(|_| rng.gen_range(-1.0..1.0));
        let l = norm2(v);
        if l > 1e-4 && l <= 1.0 {
            return scale(v, 1.0 / l.sqrt());
        }
    }
}

fn ball(rng: &mut ChaCha8Rng) -> V3 {
    scale(unit(rng), rng.gen::<f64>().cbrt())
}

/// For `dirs` random directions, the kept support is within `tol` of the full one.
fn check_support(p: &[V3], kept: &[u32], tol: f64, dirs: usize) {
    let mut rng = ChaCha8Rng::seed_from_u64(p.len() as u64);
    for _ in 0..dirs {
        let d = unit(&mut rng);
        let all = p
            .iter()
            .map(|&q| dot(d, q))
            .fold(f64::NEG_INFINITY, f64::max);
        let k = kept
            .iter()
            .map(|&i| dot(d, p[i as usize]))
            .fold(f64::NEG_INFINITY, f64::max);
        assert!(k >= all - tol, "support gap {} > {tol}", all - k);
    }
}

/// Brute-force facet planes of `conv(q)` (general position): every triple
/// with all points on one side.
fn brute_planes(q: &[V3]) -> Vec<(V3, f64)> {
    let mut planes = Vec::new();
    for i in 0..q.len() {
        for j in i + 1..q.len() {
            for k in j + 1..q.len() {
                let n = cross(sub(q[j], q[i]), sub(q[k], q[i]));
                let n = scale(n, 1.0 / norm2(n).sqrt());
                let o = dot(n, q[i]);
                let ds = q.iter().map(|&p| dot(n, p) - o);
                let (lo, hi) = ds.fold((0.0f64, 0.0f64), |(a, b), d| (a.min(d), b.max(d)));
                if hi <= 1e-12 {
                    planes.push((n, o));
                } else if lo >= -1e-12 {
                    planes.push((scale(n, -1.0), -o));
                }
            }
        }
    }
    planes
}

#[test]
fn cube_corners_only() {
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let mut p: Vec<V3> = (0..8)
        .map(|c| [0, 1, 2].map(|k| ((c >> k) & 1) as f64))
        .collect();
    for _ in 0..500 {
        p.push([0; 3].map(|_| rng.gen_range(0.05..0.95)));
    }
    for _ in 0..300 {
        let mut q = [0; 3].map(|_| rng.gen_range(0.1..0.9));
        q[rng.gen_range(0..3)] = rng.gen_range(0..2) as f64;
        p.push(q);
    }
    let out = run(&p, 1e-12 * 3f64.sqrt());
    assert!((0..8).all(|c| out.contains(&c)), "{out:?}");
    assert!(
        out.iter().all(|&i| !(8..508).contains(&i)),
        "interior kept: {out:?}"
    );
}

#[test]
fn sphere_keeps_all_ball_reduces() {
    let mut rng = ChaCha8Rng::seed_from_u64(2);
    let s: Vec<V3> = (0..300).map(|_| unit(&mut rng)).collect();
    assert_eq!(run(&s, 2e-12).len(), 300);
    let b: Vec<V3> = (0..2000).map(|_| ball(&mut rng)).collect();
    let out = run(&b, 2e-12);
    assert!(out.len() < 400, "{}", out.len());
    check_support(&b, &out, 1e-11, 200);
}

#[test]
fn ball_matches_brute_force() {
    for seed in 0..6 {
        let mut rng = ChaCha8Rng::seed_from_u64(100 + seed);
        let p: Vec<V3> = (0..40).map(|_| ball(&mut rng)).collect();
        let out = run(&p, 2e-12);
        // Exactly the brute-force vertex set of all points.
        let planes = brute_planes(&p);
        let verts: Vec<u32> = (0..40u32)
            .filter(|&i| {
                planes
                    .iter()
                    .any(|&(n, o)| (dot(n, p[i as usize]) - o).abs() < 1e-12)
            })
            .collect();
        assert_eq!(out, verts);
        // Every dropped point is inside conv(kept).
        let kept: Vec<V3> = out.iter().map(|&i| p[i as usize]).collect();
        for (n, o) in brute_planes(&kept) {
            assert!(p.iter().all(|&q| dot(n, q) - o <= 2e-11));
        }
    }
}

#[test]
fn tilted_grid_and_noisy_plane() {
    let (o, u, v) = ([3.0, -2.0, 5.0], [0.6, 0.64, 0.48], [0.0, 0.6, -0.8]);
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    for noise in [0.0, 1e-14] {
        let mut p = Vec::new();
        for i in 0..100 {
            for j in 0..100 {
                let q = [0, 1, 2].map(|k| o[k] + i as f64 * 0.01 * u[k] + j as f64 * 0.01 * v[k]);
                p.push(scale(q, 1.0 + noise * rng.gen_range(-1.0..1.0)));
            }
        }
        let out = run(&p, 1e-12 * diag(&p));
        assert_eq!(out, vec![0, 99, 9900, 9999], "noise {noise}");
        check_support(&p, &out, 1e-11 * diag(&p), 64);
    }
}

#[test]
fn degenerate_small_inputs() {
    let mut rng = ChaCha8Rng::seed_from_u64(4);
    let ts: Vec<f64> = (0..50).map(|_| rng.gen_range(-3.0..7.0)).collect();
    let line: Vec<V3> = ts
        .iter()
        .map(|&t| [1.0 + 0.3 * t, 2.0 - t, 0.5 * t])
        .collect();
    let lo = ts
        .iter()
        .enumerate()
        .min_by(|a, b| a.1.total_cmp(b.1))
        .unwrap()
        .0 as u32;
    let hi = ts
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.total_cmp(b.1))
        .unwrap()
        .0 as u32;
    assert_eq!(run(&line, 1e-11), vec![lo.min(hi), lo.max(hi)]);
    let same = vec![[1.5, -2.0, 1e6]; 20];
    let out = run(&same, 1e-6);
    assert!(out.len() == 1 || out.len() == 20);
    assert_eq!(run(&same[..1], 1e-6), vec![0]);
    assert_eq!(run(&[], 1e-6), Vec::<u32>::new());
    assert_eq!(run(&same[..3], 0.0), vec![0, 1, 2]);
    // Bad eps or non-finite input: everything.
    assert_eq!(run(&line, f64::NAN).len(), 50);
    let mut bad = line.clone();
    bad[7][1] = f64::INFINITY;
    assert_eq!(run(&bad, 1e-11).len(), 50);
}

#[test]
fn thin_slab_and_duplicates() {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    for thick in [1e-13, 1e-11, 1e-9, 1e-6] {
        let mut p: Vec<V3> = (0..500)
            .map(|_| [rng.gen(), rng.gen(), thick * rng.gen::<f64>()])
            .collect();
        p.extend_from_within(100..300);
        let eps = 1e-12 * diag(&p);
        let out = run(&p, eps);
        check_support(&p, &out, 10.0 * eps, 200);
        assert!(out.len() < 300, "thick {thick}: {}", out.len());
    }
}

#[test]
fn scale_and_offset_invariance() {
    let mut rng = ChaCha8Rng::seed_from_u64(6);
    let p: Vec<V3> = (0..300).map(|_| ball(&mut rng)).collect();
    let base = run(&p, 2e-12);
    for s in [1e-6, 1.0, 1e6] {
        for t in [0.0, 1e6 * s] {
            let q: Vec<V3> = p.iter().map(|&a| [0, 1, 2].map(|k| a[k] * s + t)).collect();
            assert_eq!(run(&q, 2e-12 * s), base, "scale {s} offset {t}");
        }
    }
}

#[test]
fn workspace_reuse() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let (mut ws, mut out) = (HullWorkspace::default(), Vec::new());
    for n in [500, 5, 60, 1000, 7] {
        let p: Vec<V3> = (0..n).map(|_| ball(&mut rng)).collect();
        let (x, y, z) = soa(&p);
        hull_vertices(&x, &y, &z, 2e-12, &mut ws, &mut out);
        assert_eq!(out, run(&p, 2e-12));
    }
}

fn cloud_strategy() -> impl Strategy<Value = (Vec<V3>, u8)> {
    let pt = (
        -4i32..=4,
        -4i32..=4,
        -4i32..=4,
        0.0f64..1.0,
        0.0f64..1.0,
        0.0f64..1.0,
        0u8..8,
    );
    (prop::collection::vec(pt, 0..300), 0u8..5).prop_map(|(raw, mode)| {
        let mut p: Vec<V3> = Vec::new();
        for (i, j, k, a, b, c, dup) in raw {
            let g = [i as f64, j as f64, k as f64];
            let q = match mode {
                0 => g,
                1 => [a, b, c],
                2 => [g[0], g[1], 0.5 * g[0] - g[1]],
                3 => [g[0], 2.0 * g[0] + 1.0, -g[0]],
                _ => [g[0] + 1e-9 * a, g[1], 1e-10 * c],
            };
            p.push(if dup == 0 && !p.is_empty() {
                p[p.len() - 1]
            } else {
                q
            });
        }
        (p, mode)
    })
}

/// Small clouds that are thin relative to `eps` (slabs of thickness
/// ≈ `k·eps`, needles), grid-snapped or random, with duplicates.
fn small_strategy() -> impl Strategy<Value = Vec<V3>> {
    let pt = (
        -2i32..=2,
        -2i32..=2,
        0.0f64..1.0,
        0.0f64..1.0,
        0.0f64..1.0,
        0u8..6,
    );
    let thick = prop::sample::select(vec![0.0, 0.3, 1.0, 3.0, 30.0, 1e4, 1e12]);
    (prop::collection::vec(pt, 5..36), 0u8..4, thick).prop_map(|(raw, mode, k)| {
        let t = k * 1e-12;
        let mut p: Vec<V3> = Vec::new();
        for (i, j, a, b, c, dup) in raw {
            let q = match mode {
                0 => [i as f64, j as f64, t * (i * j) as f64],
                1 => [a, b, t * c],
                2 => [a, t * b, t * c],
                _ => [a + 0.5 * b, b - 0.5 * t * a, t * (c - a * b)],
            };
            p.push(if dup == 0 && !p.is_empty() {
                p[p.len() / 2]
            } else {
                q
            });
        }
        p
    })
}

/// Brute-force containment: every point is within `tol` of every supporting
/// plane of the kept subset (plane tests allow `eps` slack for rounding).
fn check_brute(p: &[V3], kept: &[u32], eps: f64, tol: f64) {
    let q: Vec<V3> = kept.iter().map(|&i| p[i as usize]).collect();
    let d2 = diag(p).powi(2);
    for i in 0..q.len() {
        for j in i + 1..q.len() {
            for k in j + 1..q.len() {
                let n = cross(sub(q[j], q[i]), sub(q[k], q[i]));
                if norm2(n) <= (1e-9 * d2).powi(2) {
                    continue;
                }
                let n = scale(n, 1.0 / norm2(n).sqrt());
                let o = dot(n, q[i]);
                for sgn in [1.0, -1.0] {
                    if q.iter().all(|&a| sgn * (dot(n, a) - o) <= eps) {
                        let worst = p.iter().map(|&a| sgn * (dot(n, a) - o)).fold(0.0, f64::max);
                        assert!(worst <= tol + eps, "point {worst} outside conv(kept)");
                    }
                }
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]
    #[test]
    fn prop_small_brute_force(p in small_strategy()) {
        let eps = 1e-12 * diag(&p);
        let out = run(&p, eps);
        check_brute(&p, &out, eps, 10.0 * eps);
        check_support(&p, &out, 10.0 * eps, 64);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]
    #[test]
    fn prop_support_preserved((p, _mode) in cloud_strategy(), s in 0usize..3) {
        let sc = [1e-6, 1.0, 1e6][s];
        let p: Vec<V3> = p.iter().map(|&q| [q[0] * sc + 1e3 * sc, q[1] * sc, q[2] * sc]).collect();
        let eps = 1e-12 * diag(&p);
        let out = run(&p, eps);
        check_support(&p, &out, 10.0 * eps, 64);
    }
}

/// A cloud of a hundred thousand points asks between its passes and in Quickhull's
/// loop, and gives the indices the unchecked reduction gives; told to stop at any
/// of its asks, it stops there and says so.
#[test]
fn a_large_reduction_asks_as_it_goes_and_stops_when_told() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let p: Vec<V3> = (0..100_000).map(|_| ball(&mut rng)).collect();
    let (x, y, z) = soa(&p);
    let want = run(&p, 1e-12);
    let (mut ws, mut out) = (HullWorkspace::default(), Vec::new());
    let asked = std::cell::Cell::new(0usize);
    let count = || {
        asked.set(asked.get() + 1);
        true
    };
    assert!(hull_vertices_checked(
        &x, &y, &z, 1e-12, &mut ws, &mut out, &count
    ));
    assert_eq!(out, want);
    let asks = asked.get();
    assert!(asks >= 8, "{asks} asks");
    for stop_at in [1, 2, asks / 2, asks] {
        asked.set(0);
        let until = || {
            asked.set(asked.get() + 1);
            asked.get() < stop_at
        };
        assert!(!hull_vertices_checked(
            &x, &y, &z, 1e-12, &mut ws, &mut out, &until
        ));
        assert_eq!(asked.get(), stop_at, "asked on after a stop");
    }
    // A small cloud is never asked.
    let (fx, fy, fz) = soa(&p[..1000]);
    let never = || -> bool { panic!("asked") };
    assert!(hull_vertices_checked(
        &fx, &fy, &fz, 1e-12, &mut ws, &mut out, &never
    ));
}

/// Clouds of every shape the merge loop and the cut hand in (balls, spheres, the union
/// of two hulls' vertices, grids, lines, duplicates, huge offsets, thin slabs) at
/// several tolerances, in one reused workspace.
fn pinned_clouds() -> Vec<(Vec<V3>, f64)> {
    let mut rng = ChaCha8Rng::seed_from_u64(49);
    // The unit ball by rejection (`ball` takes a cube root, which libm may round
    // differently from platform to platform).
    let cube = |rng: &mut ChaCha8Rng| loop {
        let v = [0; 3].map(|_| rng.gen_range(-1.0..1.0));
        if norm2(v) <= 1.0 {
            return v;
        }
    };
    let mut clouds = Vec::new();
    for k in 0..240 {
        let n = rng.gen_range(5..300);
        let mut p: Vec<V3> = match k % 8 {
            0 => (0..n).map(|_| cube(&mut rng)).collect(),
            1 => (0..n)
                .map(|_| scale(unit(&mut rng), 1.0 + 1e-7 * rng.gen::<f64>()))
                .collect(),
            2 => {
                // Two clusters' hull vertices, as a merge gathers them.
                let a: Vec<V3> = (0..n).map(|_| cube(&mut rng)).collect();
                let b: Vec<V3> = (0..n)
                    .map(|_| add(cube(&mut rng), [1.2, 0.3, 0.0]))
                    .collect();
                let mut u: Vec<V3> = run(&a, 1e-9).iter().map(|&i| a[i as usize]).collect();
                u.extend(run(&b, 1e-9).iter().map(|&i| b[i as usize]));
                u
            }
            3 => (0..n)
                .map(|_| {
                    let (i, j) = (rng.gen_range(0..12) as f64, rng.gen_range(0..9) as f64);
                    [0.1 * i, 0.1 * j + 0.01 * i, 1.0]
                })
                .collect(),
            4 => (0..n)
                .map(|_| scale([1.0, 2.0, -0.5], rng.gen_range(-3.0..3.0)))
                .collect(),
            5 => (0..n / 2)
                .map(|_| cube(&mut rng))
                .flat_map(|q| [q, q])
                .collect(),
            6 => (0..n)
                .map(|_| add(scale(cube(&mut rng), 1e3), [1e9, -2e9, 5e8]))
                .collect(),
            _ => (0..n)
                .map(|_| cube(&mut rng))
                .map(|q| [q[0], q[1], 1e-9 * q[2]])
                .collect(),
        };
        if k % 5 == 0 {
            p.reverse();
        }
        let eps = [0.0, 1e-12, 1e-6, 1e-3, 0.05][k % 5] * if k % 8 == 6 { 1e3 } else { 1.0 };
        clouds.push((p, eps));
    }
    clouds
}

/// The reduction's exact output (which points, in which order) on [`pinned_clouds`],
/// as a hash: the merge loop and the cut keep what it returns, so any change to the
/// kernel that is meant to be only faster must leave this value as it is. Computed
/// with the kernel before the faces kept their visibility marks and the plane was
/// inlined.
#[test]
fn the_same_points_as_before() {
    let (mut ws, mut out) = (HullWorkspace::default(), Vec::new());
    let (mut h, mut kept) = (0xcbf2_9ce4_8422_2325u64, 0usize);
    for (p, eps) in pinned_clouds() {
        let (x, y, z) = soa(&p);
        hull_vertices(&x, &y, &z, eps, &mut ws, &mut out);
        kept += out.len();
        for &v in out.iter().chain([&u32::MAX]) {
            h = (h ^ v as u64).wrapping_mul(0x100_0000_01b3);
        }
    }
    println!("kept {kept} hash {h:#018x}");
    assert_eq!((kept, h), (10_672, 0x0000_f6ce_e6f1_ff3e));
}
