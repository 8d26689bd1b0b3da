//! `primdecomp eval`'s metrics on cases with known answers: a box collider on a box
//! mesh (zero distances, full enclosure), a shrunken box (a known gap, no
//! enclosure), a cube as a hull OBJ, a sphere around a cube (a reverse Chamfer
//! distance computed by quadrature, approached as samples grow), and the same
//! numbers on one and on several threads.

use primdecomp::{Mesh, Primitive};
use primdecomp::{Obb, Sphere};
use primdecomp_eval::collider::{self, Collider};
use primdecomp_eval::shape::box_triangles;
use primdecomp_eval::{evaluate, Input, Metrics};

const I3: [[f64; 3]; 3] = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

fn cube_prim(h: f64, c: [f64; 3]) -> Primitive {
    Primitive::Box(Obb {
        center: c,
        axes: I3,
        half: [h; 3],
    })
}

/// The surface of the cube [−h, h]³ + c as 12 triangles.
fn cube_mesh(h: f64, c: [f64; 3]) -> Mesh {
    let Primitive::Box(b) = cube_prim(h, c) else {
        unreachable!()
    };
    let v: Vec<[f64; 3]> = box_triangles(&b).into_iter().flatten().collect();
    let f: Vec<Vec<u32>> = (0..12).map(|i| vec![3 * i, 3 * i + 1, 3 * i + 2]).collect();
    Mesh::from_polygons(&v, &f).unwrap()
}

fn cube_box(h: f64, c: [f64; 3]) -> Collider {
    Collider::Primitives(vec![cube_prim(h, c)])
}

fn diag(h: f64) -> f64 {
    2.0 * h * 3f64.sqrt()
}

#[test]
fn box_on_box_has_zero_distance_and_full_enclosure() {
    // Far from the origin, so the re-centring is exercised too.
    let c = [1e3, -2e3, 5e2];
    let input = Input::new(&cube_mesh(1.0, c));
    let m = evaluate(&input, &cube_box(1.0, c), 50_000, 3);
    for d in [
        m.hausdorff,
        m.chamfer,
        m.hausdorff_all,
        m.chamfer_all,
        m.reverse_hausdorff,
        m.reverse_chamfer,
    ] {
        assert!(d < 1e-12, "{m:?}");
    }
    assert_eq!(m.enclosure, 1.0);
    assert_eq!(m.bytes, 40);
    assert_eq!(m.counts[0], ("box", 1));
}

/// Mean over the face x = 1 of the cube [−1, 1]³ of f(y, z), midpoint rule.
fn face_mean(f: impl Fn(f64, f64) -> f64) -> f64 {
    let n = 2000;
    let mut sum = 0.0;
    for i in 0..n {
        for j in 0..n {
            let y = -1.0 + (i as f64 + 0.5) * 2.0 / n as f64;
            let z = -1.0 + (j as f64 + 0.5) * 2.0 / n as f64;
            sum += f(y, z);
        }
    }
    sum / (n * n) as f64
}

#[test]
fn shrunken_box_has_the_known_gap() {
    let s = 0.9;
    let input = Input::new(&cube_mesh(1.0, [0.0; 3]));
    let m = evaluate(&input, &cube_box(s, [0.0; 3]), 100_000, 1);
    let d = diag(1.0);
    // Every point of the inner box's face x = s is 1 − s from the face x = 1 and at
    // least that from the others: the one-way distance is 1 − s everywhere.
    assert!((m.hausdorff - (1.0 - s) / d).abs() < 1e-12, "{m:?}");
    assert!((m.chamfer - (1.0 - s) / d).abs() < 1e-12, "{m:?}");
    // Reverse: a point (1, y, z) is √((1−s)² + (|y|−s)₊² + (|z|−s)₊²) from the inner
    // box; the corners are farthest, (1 − s)·√3.
    let gap = |y: f64, z: f64| {
        let (a, b) = ((y.abs() - s).max(0.0), (z.abs() - s).max(0.0));
        ((1.0 - s).powi(2) + a * a + b * b).sqrt()
    };
    let mean = face_mean(gap) / d;
    let max = (1.0 - s) * 3f64.sqrt() / d;
    assert!(m.reverse_hausdorff <= max + 1e-12, "{m:?} vs {max}");
    assert!(m.reverse_hausdorff > 0.97 * max, "{m:?} vs {max}");
    assert!(
        (m.reverse_chamfer - mean).abs() < 0.005 * mean,
        "{m:?} vs {mean}"
    );
    assert_eq!(m.enclosure, 0.0, "the input lies wholly outside");
}

#[test]
fn cube_hull_obj_matches_the_cube() {
    let dir = std::env::temp_dir().join(format!("eval-metrics-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("cube_hull.obj");
    let mut text = String::from("o hull_0\n");
    for i in 0..8 {
        let s = |b: usize| if i & b != 0 { 1 } else { -1 };
        text.push_str(&format!("v {} {} {}\n", s(4), s(2), s(1)));
    }
    for f in [
        "1 2 4", "1 4 3", "5 7 8", "5 8 6", "1 5 6", "1 6 2", "3 4 8", "3 8 7", "1 3 7", "1 7 5",
        "2 6 8", "2 8 4",
    ] {
        text.push_str(&format!("f {f}\n"));
    }
    std::fs::write(&path, text).unwrap();
    let c = collider::load(&path).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    let input = Input::new(&cube_mesh(1.0, [0.0; 3]));
    let m = evaluate(&input, &c, 50_000, 2);
    assert!(m.hausdorff < 1e-12 && m.reverse_hausdorff < 1e-12, "{m:?}");
    assert_eq!(m.enclosure, 1.0);
    assert_eq!(m.bytes, 8 * 12 + 12 * 6);
    assert_eq!(m.counts.last(), Some(&("hull", 1)));
}

fn sphere_around_cube() -> Collider {
    Collider::Primitives(vec![Primitive::Sphere(Sphere {
        center: [0.0; 3],
        radius: 3f64.sqrt(),
    })])
}

#[test]
fn sample_counts_converge() {
    // Reverse Chamfer of the circumscribed sphere over the cube: a point (1, y, z)
    // is √3 − √(1 + y² + z²) from the sphere.
    let input = Input::new(&cube_mesh(1.0, [0.0; 3]));
    let exact = face_mean(|y, z| 3f64.sqrt() - (1.0 + y * y + z * z).sqrt()) / diag(1.0);
    let err = |n: usize| -> f64 {
        // The worst of three seeds, so one lucky draw cannot pass the test.
        (0..3)
            .map(|seed| {
                let m = evaluate(&input, &sphere_around_cube(), n, seed);
                assert_eq!(m.enclosure, 1.0);
                (m.reverse_chamfer - exact).abs() / exact
            })
            .fold(0.0, f64::max)
    };
    let (e_small, e_large) = (err(1_000), err(200_000));
    assert!(e_large < 0.003, "relative error {e_large} at 200k samples");
    assert!(
        e_large < e_small / 3.0,
        "{e_small} at 1k vs {e_large} at 200k"
    );
}

#[test]
fn same_metrics_on_any_thread_count() {
    let input = Input::new(&cube_mesh(1.0, [0.5, 0.0, 0.0]));
    let run = |threads: usize| -> Metrics {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| evaluate(&input, &sphere_around_cube(), 30_000, 11))
    };
    let one = run(1);
    assert_eq!(one, run(3));
    assert_ne!(
        one,
        rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap()
            .install(|| evaluate(&input, &sphere_around_cube(), 30_000, 12)),
        "another seed draws other samples"
    );
}
