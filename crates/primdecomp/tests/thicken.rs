//! `Plates::min_thickness` (docs/decisions/0033-plates-thickened-inward.md): plates
//! reach inward to a minimum thickness where the input is closed behind them. Off must
//! be the default output exactly; on must keep the enclosure and thread independence,
//! never move a plate's outer side out, never poke through a thin part's far side,
//! and leave open sheets and holes as they are.

use primdecomp::{decompose, demo_scene, Goal, Level, Params, Plates, Primitive};
use primdecomp_testkit::check::{assert_default_output, assert_same_on_threads, assert_valid};
use primdecomp_testkit::shapes::{cuboid, flat_grid, mesh, plate_with_hole};

fn params(targets: &[usize], min_thickness: f64) -> Params {
    Params {
        goal: Goal::counts(targets.to_vec()),
        plates: Plates {
            min_thickness,
            ..Default::default()
        },
        ..Default::default()
    }
}

fn level(m: &primdecomp::Mesh, n: usize, t: f64) -> Level {
    decompose(m, &params(&[n], t)).unwrap().levels.remove(0)
}

/// The thinnest full extent of a box or prism (other kinds: infinity).
fn thinnest(p: &Primitive) -> f64 {
    match p {
        Primitive::Box(b) => 2.0 * b.half.iter().copied().fold(f64::INFINITY, f64::min),
        Primitive::Prism(q) => 2.0 * q.hx,
        _ => f64::INFINITY,
    }
}

/// Whether every primitive's bounding box lies within `lo`–`hi` (± `tol`).
fn within(l: &Level, lo: [f64; 3], hi: [f64; 3], tol: f64) -> bool {
    l.primitives.iter().all(|p| {
        let (a, b) = p.aabb();
        (0..3).all(|k| a[k] >= lo[k] - tol && b[k] <= hi[k] + tol)
    })
}

/// Off is the default engine, primitive for primitive.
#[test]
fn off_is_the_default_output() {
    assert_default_output(&demo_scene(), &params(&[150, 20], 0.0));
}

/// On, every face stays enclosed (the independent oracle) and the output is the same
/// on 1, 2 and 8 threads.
#[test]
fn thickened_plates_enclose_and_ignore_threads() {
    let m = demo_scene();
    let p = params(&[150, 40, 8], 0.05);
    let dec = assert_same_on_threads(&m, &p);
    assert_valid(&m, &dec, &p);
}

/// A closed 3 × 1 × 2 box (D = √14) at N = 12 is six plates 0.001·D thick; with a
/// minimum of 0.2·D each reaches inward to 0.2·D = 0.748, or 0.6 of the depth behind
/// it where that is less (the y plates: 0.6 of 1), and none stands outside the box.
#[test]
fn closed_box_plates_reach_inward_to_the_minimum() {
    let (lo, hi) = ([0.0; 3], [3.0, 1.0, 2.0]);
    let m = mesh(&cuboid(lo, hi));
    let d = 14f64.sqrt();
    let shell = level(&m, 12, 0.0);
    assert_eq!(shell.primitives.len(), 6, "{:?}", shell.primitives);
    assert!(shell.primitives.iter().all(|p| thinnest(p) < 0.002 * d));
    let thick = level(&m, 12, 0.2);
    assert_eq!(thick.primitives.len(), 6, "{:?}", thick.primitives);
    let mut t: Vec<f64> = thick.primitives.iter().map(thinnest).collect();
    t.sort_by(f64::total_cmp);
    for (i, want) in [0.6, 0.6, 0.2 * d, 0.2 * d, 0.2 * d, 0.2 * d]
        .into_iter()
        .enumerate()
    {
        assert!((t[i] - want).abs() < 1e-9, "{t:?}");
    }
    assert!(within(&thick, lo, hi, 1e-9), "{:?}", thick.primitives);
}

/// An open sheet has nothing behind it: unchanged. A plate 0.05 thick with a square
/// hole: its plates reach at most 0.6 of the 0.05 behind them (never through the far
/// side), and the hole stays open wherever the default output leaves it open.
#[test]
fn open_sheets_and_holes_stay_open() {
    let sheet = mesh(&flat_grid(4));
    for n in [1, 4] {
        assert_eq!(
            level(&sheet, n, 0.1).primitives,
            level(&sheet, n, 0.0).primitives
        );
    }
    let m = mesh(&plate_with_hole(4.0, 0.05, 8, 2));
    let mut open = 0;
    for n in [8, 16, 64] {
        let l = level(&m, n, 0.1);
        assert!(
            within(&l, [0.0; 3], [4.0, 4.0, 0.05], 1e-9),
            "N = {n}: {:?}",
            l.primitives
        );
        assert!(
            l.primitives.iter().any(|p| thinnest(p) > 0.01),
            "N = {n}: nothing thickened"
        );
        let hole = [2.0, 2.0, 0.025];
        let covers = |l: &Level| l.primitives.iter().any(|p| p.contains(hole, 0.0));
        assert_eq!(covers(&l), covers(&level(&m, n, 0.0)), "N = {n}");
        open += usize::from(!covers(&l));
    }
    assert!(open > 0, "the hole is open at some N");
}
