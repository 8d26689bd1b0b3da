//! Deferred re-pricing (`Params::reprice`, `merge/lazy.rs`): the merge order changes,
//! the guarantees do not. Every face stays enclosed, the output does not depend on the
//! thread count, a threshold no cluster reaches is the exact order, and an excess-volume
//! cap keeps the exact order (a pair over the cap has no queue entry to defer).

use primdecomp::{decompose, demo_scene, Decomposition, Fit, Goal, Mesh, Params, Reprice};
use primdecomp_testkit::check::assert_valid;
use primdecomp_testkit::shapes::{self, join, mesh, Polys};

const ALL: Reprice = Reprice::Deferred { min_degree: 0 };

fn params(targets: &[usize], reprice: Reprice) -> Params {
    Params {
        goal: Goal::counts(targets.to_vec()),
        reprice,
        ..Default::default()
    }
}

/// Flat regions (a grid, a plate with a hole) next to curved ones (a cylinder, a sphere).
fn mixed() -> Polys {
    let mut grid = shapes::flat_grid(30);
    grid.0.iter_mut().for_each(|p| p[2] -= 2.0);
    join(&[
        grid,
        shapes::plate_with_hole(10.0, 0.5, 12, 4),
        shapes::cylinder(2.0, 6.0, 24),
        shapes::uv_sphere(3.0, 10, 16),
    ])
}

/// The JSON of every level as written without `--timings` (compared byte for byte).
fn stable(d: &Decomposition, p: &Params) -> Vec<String> {
    (0..d.levels.len()).map(|i| d.to_json(i, p)).collect()
}

fn run(m: &Mesh, p: &Params) -> Vec<String> {
    stable(&decompose(m, p).unwrap_or_else(|e| panic!("{e}")), p)
}

/// Full and hybrid deferral enclose every face at every target, on the demo scene and
/// on flat and curved parts side by side.
#[test]
fn deferred_encloses_every_face() {
    let meshes = [demo_scene(), mesh(&mixed())];
    for m in &meshes {
        for reprice in [ALL, Reprice::Deferred { min_degree: 8 }] {
            let p = params(&[300, 60, 12, 1], reprice);
            let dec = decompose(m, &p).unwrap_or_else(|e| panic!("{e}"));
            assert!(
                dec.stats.fits_when_popped > 0,
                "{reprice:?}: nothing was deferred"
            );
            assert_valid(m, &dec, &p);
        }
    }
}

/// Re-pricing when popped is sequential, so 1 and 2 threads give the same bytes.
#[test]
fn deferred_is_identical_on_1_and_2_threads() {
    let m = mesh(&mixed());
    for reprice in [ALL, Reprice::Deferred { min_degree: 8 }] {
        let p = params(&[200, 20], reprice);
        let runs: Vec<Vec<String>> = [1, 2]
            .iter()
            .map(|&t| primdecomp_testkit::on_threads(t, || run(&m, &p)))
            .collect();
        assert_eq!(runs[0], runs[1], "{reprice:?}");
    }
}

/// A threshold above every cluster's degree defers nothing: the exact order, and the
/// setting's only other effect is its entry in the JSON's settings.
#[test]
fn unreachable_threshold_is_exact() {
    let m = demo_scene();
    let never = Reprice::Deferred {
        min_degree: 1_000_000,
    };
    let prims = |reprice| -> Vec<serde_json::Value> {
        run(&m, &params(&[150, 20], reprice))
            .iter()
            .map(|s| serde_json::from_str::<serde_json::Value>(s).unwrap()["primitives"].clone())
            .collect()
    };
    assert_eq!(prims(Reprice::Exact), prims(never));
    assert_ne!(
        prims(Reprice::Exact),
        prims(ALL),
        "deferral changed nothing"
    );
}

/// An excess-volume cap needs every merge re-priced at once (a capped merge has no
/// queue entry to defer): asked with deferral, the settings are refused up front with a
/// message saying so; with exact re-pricing no fit is deferred.
#[test]
fn excess_cap_keeps_the_exact_order() {
    let m = demo_scene();
    let capped = |reprice| Params {
        fit: Fit {
            max_excess_volume: Some(0.05),
            ..params(&[100], reprice).fit
        },
        ..params(&[100], reprice)
    };
    let exact = decompose(&m, &capped(Reprice::Exact)).unwrap();
    assert_eq!(exact.stats.fits_when_popped, 0);
    match decompose(&m, &capped(ALL)) {
        Err(primdecomp::Error::InvalidParams(msg)) => {
            assert!(msg.contains("reprice: exact"), "{msg}")
        }
        other => panic!("a cap with deferred re-pricing was not refused: {other:?}"),
    }
}
