//! Numerically extreme input: degenerate geometry — one quad, a
//! million-quad flat grid, collinear-only and zero-area-only faces, identical faces, a
//! needle of aspect 1e-6 : 1 : 1, coordinates of 1e38 — must give a valid result: finite
//! JSON and every face enclosed (`primdecomp_testkit::check`, the independent oracle). Coordinates
//! so large that volumes would overflow f64 are refused with `Error::Extent`. Under
//! seeded random rotations the demo scene keeps its primitive count and its tightness
//! (a one-way surface distance computed here, see [`tightness`]) within 10%.

use primdecomp::{decompose, Error, Goal, Mesh, Params, Primitive, Reprice};
use primdecomp_testkit::check::assert_valid;
use primdecomp_testkit::shapes::{self, cuboid};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn params(targets: &[usize]) -> Params {
    Params {
        goal: Goal::counts(targets.to_vec()),
        ..Default::default()
    }
}

/// Decomposes at each target and checks validity; returns the primitive counts.
fn valid(v: &[[f64; 3]], f: &[Vec<u32>], targets: &[usize]) -> Vec<usize> {
    let mesh = Mesh::from_polygons(v, f).unwrap();
    let p = params(targets);
    let dec = decompose(&mesh, &p).unwrap_or_else(|e| panic!("{e}"));
    assert_valid(&mesh, &dec, &p);
    dec.levels.iter().map(|l| l.primitives.len()).collect()
}

#[test]
fn one_quad() {
    let v = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
    ];
    assert_eq!(valid(&v, &[vec![0, 1, 2, 3]], &[1, 5]), vec![1, 1]);
}

/// The `n` × `n` flat grid (`shapes::flat_grid`: every merge costs zero) decomposed to
/// N = 100 and N = 1 with `reprice`, checked valid. Returns the seconds taken and the
/// pairs re-priced per merge (at once and when popped).
/// Returns the seconds, the pairs re-priced per merge and the parts merged first.
fn flat_grid(n: u32, reprice: Reprice) -> (f64, f64, usize) {
    let (v, f) = shapes::flat_grid(n);
    let mesh = Mesh::from_polygons(&v, &f).unwrap();
    let p = Params {
        reprice,
        ..params(&[100, 1])
    };
    let t = std::time::Instant::now();
    let dec = decompose(&mesh, &p).unwrap_or_else(|e| panic!("{e}"));
    let secs = t.elapsed().as_secs_f64();
    assert_valid(&mesh, &dec, &p);
    let counts: Vec<usize> = dec.levels.iter().map(|l| l.primitives.len()).collect();
    let per_merge =
        (dec.stats.fits_at_once + dec.stats.fits_when_popped) as f64 / dec.stats.merges as f64;
    eprintln!(
        "flat grid {n}x{n}, {reprice:?}: {counts:?} primitives in {secs:.1} s \
         (decompose only), {per_merge:.2} pairs re-priced per merge"
    );
    assert!(counts[0] <= 100 && counts[1] == 1, "{counts:?}");
    (secs, per_merge, dec.stats.partitions)
}

#[test]
fn flat_grid_of_10_000_quads() {
    flat_grid(100, Params::default().reprice);
}

/// Exact re-pricing re-prices the ~2L quads along a growing strip's sides at every
/// merge (growing with n: docs/decisions/limits-flat-grid.md). The default defers merges of
/// clusters with 64 or more neighbours, so
/// only strips shorter than about 32 quads re-price their sides at once: the pairs
/// re-priced per merge stop growing with the grid's size.
#[test]
fn flat_grid_defers_its_long_strips() {
    let (_, exact, _) = flat_grid(100, Reprice::Exact);
    let (_, at_100, _) = flat_grid(100, Params::default().reprice);
    let (_, at_200, _) = flat_grid(200, Params::default().reprice);
    assert!(exact > 40.0, "exact: {exact:.2} per merge");
    assert!(
        at_100 < exact / 2.0,
        "default {at_100:.2}, exact {exact:.2}"
    );
    assert!(
        at_200 <= at_100,
        "default: {at_100:.2} at 100², {at_200:.2} at 200²"
    );
}

/// The 1000 × 1000 grid (a million quads). With exact re-pricing it grew as
/// F^1.5 (about 1.5 hours extrapolated) and was ignored; with deferred re-pricing for
/// clusters with 64 or more neighbours the whole test took 13.9 s here (decompose
/// 13.3 s, 3.76 pairs re-priced per merge, peak RSS 741 MB:
/// `cargo test --release --test extremes flat_grid_of_a_million -- --nocapture`).
/// It is above `AUTO_MIN_FACES`, so by default it is now merged in `AUTO_PARTS` lazy
/// parts first (docs/decisions/0019-large-inputs-merged-in-parts.md): the default's large-input
/// path, enclosing and within N;
/// decompose 3.4 s, 2.00 pairs re-priced per merge (same command, machine shared).
#[test]
fn flat_grid_of_a_million_quads() {
    let (_, _, parts) = flat_grid(1000, Params::default().reprice);
    assert_eq!(parts, primdecomp::internals::AUTO_PARTS);
}

/// Growth of the flat grid's time with its size, printed (no assertion: timings are
/// noisy here; this is the measurement behind the known limit).
/// `cargo test --release --test extremes grid_growth -- --ignored --nocapture`
#[test]
#[ignore]
fn grid_growth() {
    for n in [100, 200] {
        flat_grid(n, Reprice::Exact);
    }
    for n in [100, 200, 400, 1000] {
        flat_grid(n, Params::default().reprice);
    }
}

#[test]
fn collinear_only() {
    let v: Vec<[f64; 3]> = (0..12)
        .map(|i| [i as f64, 2.0 * i as f64, -(i as f64)])
        .collect();
    let f: Vec<Vec<u32>> = (0..10).map(|i| vec![i, i + 1, i + 2]).collect();
    let counts = valid(&v, &f, &[4, 1]);
    assert!(counts[0] <= 4 && counts[1] == 1, "{counts:?}");
}

/// Every face has a repeated corner (zero area), and some are single points.
#[test]
fn zero_area_only() {
    let v: Vec<[f64; 3]> = (0..8)
        .map(|i| [(i % 2) as f64, (i / 2 % 2) as f64, (i / 4) as f64])
        .collect();
    let f: Vec<Vec<u32>> = (0..8u32)
        .map(|i| vec![i, (i + 1) % 8, i])
        .chain([vec![3, 3, 3], vec![5, 5, 5, 5]])
        .collect();
    let counts = valid(&v, &f, &[3, 1]);
    assert!(counts[0] <= 3 && counts[1] == 1, "{counts:?}");
}

#[test]
fn all_faces_identical() {
    let v = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 1.0, 0.5]];
    let f = vec![vec![0, 1, 2]; 500];
    assert_eq!(valid(&v, &f, &[10, 1]), vec![1, 1]);
}

/// A slab of 1e-6 × 1 × 1 and a needle of 1e-6 × 1e-6 × 1 (each along every axis):
/// thinner than the minimum extent (5e-4 of the diagonal) by orders of magnitude.
#[test]
fn needle_of_aspect_1e_minus_6() {
    for axis in 0..3 {
        let mut slab = [1.0; 3];
        slab[axis] = 1e-6;
        let mut needle = [1e-6; 3];
        needle[axis] = 1.0;
        for size in [slab, needle] {
            let (v, f) = cuboid([0.0; 3], size);
            assert_eq!(valid(&v, &f, &[6, 1])[1], 1, "{size:?}");
        }
    }
}

/// ±1e38 (near f32's largest value, which binary STL and GLB can carry) is fine.
#[test]
fn coordinates_of_1e38() {
    let v = [
        [-1e38, 0.0, 0.0],
        [1e38, 0.0, 0.0],
        [0.0, 1e38, 0.0],
        [0.0, 0.0, 1e38],
    ];
    let f = vec![vec![0, 1, 2], vec![0, 1, 3], vec![1, 2, 3], vec![0, 2, 3]];
    assert_eq!(valid(&v, &f, &[4, 1])[1], 1);
}

/// Coordinates of 1e300 made volumes infinite and the frustum fit panicked
/// (`clamp` on NaN). Now `decompose` refuses them with `Error::Extent` naming the
/// vertex, and 1e59 (inside the limit) is decomposed normally.
#[test]
fn coordinates_beyond_the_extent_limit_are_refused() {
    let tri = |s: f64| {
        Mesh::from_polygons(&[[0.0; 3], [s, 0.0, 0.0], [0.0, s, s]], &[vec![0, 1, 2]]).unwrap()
    };
    match decompose(&tri(1e300), &params(&[1])) {
        Err(Error::Extent {
            vertex,
            distance,
            limit,
            ..
        }) => {
            assert_eq!((vertex, distance, limit), (1, 5e299, 1e60));
        }
        other => panic!("expected Error::Extent, got {other:?}"),
    }
    let mesh = tri(1e59);
    let dec = decompose(&mesh, &params(&[1])).unwrap();
    assert_valid(&mesh, &dec, &params(&[1]));
}

/// Rotation by a unit quaternion (x, y, z, w).
fn rotate(q: [f64; 4], p: [f64; 3]) -> [f64; 3] {
    let [x, y, z, w] = q;
    let t = [
        2.0 * (y * p[2] - z * p[1]),
        2.0 * (z * p[0] - x * p[2]),
        2.0 * (x * p[1] - y * p[0]),
    ];
    [
        p[0] + w * t[0] + (y * t[2] - z * t[1]),
        p[1] + w * t[1] + (z * t[0] - x * t[2]),
        p[2] + w * t[2] + (x * t[1] - y * t[0]),
    ]
}

/// Closest point of triangle abc to p (Ericson, Real-Time Collision Detection 5.1.5).
fn closest_on_triangle(p: [f64; 3], a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> [f64; 3] {
    let sub = |u: [f64; 3], v: [f64; 3]| [u[0] - v[0], u[1] - v[1], u[2] - v[2]];
    let dot = |u: [f64; 3], v: [f64; 3]| u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
    let along =
        |o: [f64; 3], d: [f64; 3], t: f64| [o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2]];
    let (ab, ac, ap) = (sub(b, a), sub(c, a), sub(p, a));
    let (d1, d2) = (dot(ab, ap), dot(ac, ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = sub(p, b);
    let (d3, d4) = (dot(ab, bp), dot(ac, bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return along(a, ab, d1 / (d1 - d3));
    }
    let cp = sub(p, c);
    let (d5, d6) = (dot(ab, cp), dot(ac, cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return along(a, ac, d2 / (d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 {
        return along(b, sub(c, b), (d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    let denom = 1.0 / (va + vb + vc);
    let (v, w) = (vb * denom, vc * denom);
    [0, 1, 2].map(|k| a[k] + ab[k] * v + ac[k] * w)
}

/// Tightness: the mean distance from points sampled uniformly (seeded, 20,000 by area)
/// on the primitives' surfaces — the faces of their OBJ tessellation at 24 segments —
/// to the nearest input triangle, by brute force. A one-way Chamfer distance, written
/// here so this test shares no code with an evaluation module.
fn tightness(prims: &[Primitive], mesh_tris: &[[[f64; 3]; 3]]) -> f64 {
    let mut tris = Vec::new();
    for p in prims {
        let t = p.tessellate(24);
        tris.extend(primdecomp_testkit::fan_triangles(&t.vertices, &t.faces));
    }
    let area = |t: &[[f64; 3]; 3]| {
        let (u, v) = (
            [0, 1, 2].map(|k| t[1][k] - t[0][k]),
            [0, 1, 2].map(|k| t[2][k] - t[0][k]),
        );
        let c = [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ];
        0.5 * (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt()
    };
    let mut cum = Vec::with_capacity(tris.len());
    let mut total = 0.0;
    for t in &tris {
        total += area(t);
        cum.push(total);
    }
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let samples = 20_000;
    let mut sum = 0.0;
    for _ in 0..samples {
        let r = rng.gen::<f64>() * total;
        let t = tris[cum.partition_point(|&c| c < r).min(tris.len() - 1)];
        let (mut a, mut b) = (rng.gen::<f64>(), rng.gen::<f64>());
        if a + b > 1.0 {
            (a, b) = (1.0 - a, 1.0 - b);
        }
        let p = [0, 1, 2].map(|k| t[0][k] + a * (t[1][k] - t[0][k]) + b * (t[2][k] - t[0][k]));
        let d2 = mesh_tris
            .iter()
            .map(|m| {
                let c = closest_on_triangle(p, m[0], m[1], m[2]);
                (0..3).map(|k| (p[k] - c[k]).powi(2)).sum::<f64>()
            })
            .fold(f64::INFINITY, f64::min);
        sum += d2.sqrt();
    }
    sum / samples as f64
}

/// The demo scene under 4 seeded random rotations, at N = 40 and 120: the primitive
/// count stays within 10% of the unrotated run's and the tightness (a one-way mean
/// surface distance, see [`tightness`]) within 10% (docs/decisions/limits-rotations.md). Measured with
/// `cargo test --release --test extremes random -- --nocapture`: counts identical (120
/// and 39); tightness 0.01797 → 0.01861, 0.01750, 0.01793, 0.01864 at N = 120 and
/// 0.02352 → 0.02385, 0.02362, 0.02369, 0.02354 at N = 40 (−2.6% … +3.7%). Before the
/// degenerate-frame fit (`primitive::frame`: coplanar clusters' in-plane axes were
/// whatever round-off made of the tangent term) it moved by −38% … +52%.
///
/// These are the greedy levels (`greedy`), which the bounds were set for. The demo
/// scene has several parts, so its counts are cuts by default (docs/decisions/0054):
/// under the same rotations each such level must hold its count within 10% and stand
/// no farther on the mean than the greedy level of the same rotation.
#[test]
fn random_rotations_keep_count_and_tightness() {
    let (base, faces) = primdecomp_testkit::shapes::demo_polys();
    let greedy = Params {
        goal: Goal::Greedy {
            counts: vec![120, 40],
        },
        ..params(&[120, 40])
    };
    let cut = params(&[120, 40]);
    let run = |v: &[[f64; 3]], p: &Params| {
        let mesh = Mesh::from_polygons(v, &faces).unwrap();
        let dec = decompose(&mesh, p).unwrap();
        assert_valid(&mesh, &dec, p);
        let tris = primdecomp_testkit::fan_triangles(v, &faces);
        dec.levels
            .iter()
            .map(|l| (l.primitives.len(), tightness(&l.primitives, &tris)))
            .collect::<Vec<_>>()
    };
    let reference = run(&base, &greedy);
    let cut_reference = run(&base, &cut);
    let mut rng = ChaCha8Rng::seed_from_u64(2026);
    for r in 0..4 {
        // A uniform random rotation: a normalised 4D Gaussian-ish vector (Box–Muller).
        let g = |rng: &mut ChaCha8Rng| {
            let (u, v): (f64, f64) = (rng.gen::<f64>().max(1e-300), rng.gen());
            (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
        };
        let q = [g(&mut rng), g(&mut rng), g(&mut rng), g(&mut rng)];
        let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
        let q = q.map(|x| x / n);
        let v: Vec<[f64; 3]> = base.iter().map(|&x| rotate(q, x)).collect();
        let greedy_now = run(&v, &greedy);
        for ((g, (n0, _)), (n1, t1)) in greedy_now.iter().zip(&cut_reference).zip(run(&v, &cut)) {
            eprintln!(
                "rotation {r}, cut: {n0} → {n1} primitives, tightness {t1:.5} (greedy {:.5})",
                g.1
            );
            assert!(
                (n1 as f64 - *n0 as f64).abs() <= 0.10 * *n0 as f64,
                "rotation {r}: cut count {n0} → {n1}"
            );
            assert!(
                t1 <= g.1,
                "rotation {r}: the cut {t1} farther than the greedy level {}",
                g.1
            );
        }
        for ((n0, t0), (n1, t1)) in reference.iter().zip(greedy_now) {
            eprintln!("rotation {r} {q:.3?}: {n0} → {n1} primitives, tightness {t0:.5} → {t1:.5}");
            let dn = (n1 as f64 - *n0 as f64).abs() / *n0 as f64;
            assert!(dn <= 0.10, "rotation {r}: count {n0} → {n1}");
            assert!(
                (t1 / t0 - 1.0).abs() <= 0.10,
                "rotation {r}: tightness {t0} → {t1}"
            );
        }
    }
}
