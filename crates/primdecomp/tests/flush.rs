//! `Plates::flush_plates` (docs/decisions/0026-output-plates-lie-flush.md): an output plate (a
//! primitive at the floor thickness, `min_extent` of the diagonal per half) lies
//! flush on its faces, reaching inward from them, instead of centred on them, so a
//! body resting on it rests where it would on the mesh. Decided by the independent
//! containment oracle (`primdecomp_testkit::contain`) from points a quarter of the floor outside
//! and inside the surface; with the setting off the outside points are inside (so the
//! tests can fail), and every face stays enclosed either way.

use primdecomp::{decompose, Goal, Mesh, Params, Plates};
use primdecomp_testkit::check::{assert_same_on_threads, assert_valid, shapes};
use primdecomp_testkit::contain::shape_contains;
use primdecomp_testkit::shapes::{cuboid, flat_grid, mesh};

fn params(targets: &[usize], flush: bool) -> Params {
    Params {
        goal: Goal::counts(targets.to_vec()),
        plates: Plates {
            flush_plates: flush,
            ..Default::default()
        },
        ..Default::default()
    }
}

/// How many of `points` lie inside some primitive of `dec`'s first level.
fn inside(dec: &primdecomp::Decomposition, p: &Params, points: &[[f64; 3]]) -> usize {
    let shapes = shapes(dec, 0, p);
    points
        .iter()
        .filter(|&&q| shapes.iter().any(|s| shape_contains(s, q, 0.0)))
        .count()
}

/// Points over each side of the 2 × 1 × 0.5 box at `lo = 0`, `d` along its outward
/// normal (negative: inside), away from the edges.
fn around_box(d: f64) -> Vec<[f64; 3]> {
    let hi = [2.0, 1.0, 0.5];
    let mut out = Vec::new();
    for (a, b) in [(0.3, 0.3), (0.5, 0.7), (0.7, 0.4)] {
        for k in 0..3 {
            let (u, v) = ((k + 1) % 3, (k + 2) % 3);
            for (face, sign) in [(0.0, -1.0), (hi[k], 1.0)] {
                let mut q = [0.0; 3];
                q[k] = face + sign * d;
                q[u] = a * hi[u];
                q[v] = b * hi[v];
                out.push(q);
            }
        }
    }
    out
}

/// A closed 2 × 1 × 0.5 box, one plate per side (N = its 6 faces, nested plates
/// kept): every plate reaches inward from its side, none outward.
#[test]
fn a_boxs_side_plates_lie_inside_its_sides() {
    let m = mesh(&cuboid([0.0; 3], [2.0, 1.0, 0.5]));
    let q = 0.25 * Params::default().fit.min_extent * m.diagonal();
    let at = |flush| Params {
        plates: Plates {
            remove_nested: false,
            ..params(&[6], flush).plates
        },
        ..params(&[6], flush)
    };
    let p = at(true);
    let dec = assert_same_on_threads(&m, &p);
    assert_valid(&m, &dec, &p);
    assert_eq!(dec.levels[0].primitives.len(), 6);
    let (outside, under) = (around_box(q), around_box(-q));
    assert_eq!(inside(&dec, &p, &outside), 0, "a plate stands proud");
    assert_eq!(
        inside(&dec, &p, &under),
        under.len(),
        "a plate left its side"
    );
    let centred = decompose(&m, &at(false)).unwrap();
    assert_eq!(
        inside(&centred, &at(false), &outside),
        outside.len(),
        "centred plates stand proud: the test would pass vacuously"
    );
}

/// An open flat 4 × 4 grid (one plate): the plate hangs on the side its faces turn
/// away from — below for faces wound to face +z, above when every face is reversed.
#[test]
fn an_open_sheets_plate_hangs_behind_its_faces() {
    let (v, f) = flat_grid(4);
    let flipped: Vec<Vec<u32>> = f
        .iter()
        .map(|p| p.iter().rev().copied().collect())
        .collect();
    for (faces, up) in [(f.clone(), 1.0), (flipped, -1.0)] {
        let m = Mesh::from_polygons(&v, &faces).unwrap();
        let q = 0.25 * Params::default().fit.min_extent * m.diagonal();
        let p = params(&[m.face_count()], true);
        let dec = assert_same_on_threads(&m, &p);
        assert_valid(&m, &dec, &p);
        let front = [[1.3, 2.1, up * q], [2.9, 0.4, up * q]];
        let back = [[1.3, 2.1, -up * q], [2.9, 0.4, -up * q]];
        assert_eq!(
            inside(&dec, &p, &front),
            0,
            "faces toward {up}: stands proud"
        );
        assert_eq!(
            inside(&dec, &p, &back),
            2,
            "faces toward {up}: left the sheet"
        );
        let c = params(&[m.face_count()], false);
        let centred = decompose(&m, &c).unwrap();
        assert_eq!(
            inside(&centred, &c, &front),
            2,
            "centred: the test would pass vacuously"
        );
    }
}
