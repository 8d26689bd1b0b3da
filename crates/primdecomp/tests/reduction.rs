//! `Params::reduction` (`math/extremes.rs`): under `Reduction::Extremes` merges are
//! priced on each cluster's extreme points along 13 fixed axes instead of its hull
//! vertices. The merge order changes, but the output is fitted on all faces' vertices,
//! so it must still enclose every input face (checked by the independent oracle,
//! `primdecomp_testkit::contain`), hold at most N primitives and be the same bytes on any thread
//! count; the default (`Hull`) must not be named in the JSON (default output unchanged).

use primdecomp::export::json::to_json;
use primdecomp::{decompose, Mesh, Params, Reduction};
use primdecomp_testkit::check::{
    assert_counts, assert_same_on_threads, assert_valid, check_corpus_meshes,
};
use primdecomp_testkit::shapes::{cuboid, cylinder, join, mesh, uv_sphere};

/// A sphere and a cylinder (many points per cluster: the hull and the 26 extremes
/// differ) beside two boxes: ~5,000 faces, three components to bridge.
fn scene() -> Mesh {
    mesh(&join(&[
        uv_sphere(3.0, 40, 60),
        cylinder(1.0, 8.0, 64),
        cuboid([-20.0, 12.0, 0.0], [-14.0, 14.0, 9.0]),
        cuboid([15.0, 15.0, 1.0], [16.0, 25.0, 2.0]),
    ]))
}

fn params(targets: &[usize], reduction: Reduction) -> Params {
    Params {
        targets: targets.to_vec(),
        reduction,
        ..Default::default()
    }
}

/// Enclosing and at most N at three targets; and not a no-op: the merges differ from
/// the exact reduction's somewhere (else the setting would not be tested at all).
#[test]
fn extremes_output_encloses_and_differs_from_the_hull() {
    let m = scene();
    let targets = [200, 40, 8];
    let p = params(&targets, Reduction::Extremes);
    let dec = decompose(&m, &p).unwrap();
    assert_valid(&m, &dec, &p);
    assert_counts(&dec, "scene");
    let exact = decompose(&m, &params(&targets, Reduction::Hull)).unwrap();
    let differ = (0..targets.len()).any(|l| {
        format!("{:?}", dec.levels[l].primitives) != format!("{:?}", exact.levels[l].primitives)
    });
    assert!(
        differ,
        "extremes gave the hull's primitives at every target"
    );
}

/// Same bytes (the JSON as written without `--timings`) on 1, 2 and 8 threads.
#[test]
fn extremes_output_is_identical_on_any_thread_count() {
    let p = params(&[60, 12], Reduction::Extremes);
    let one = assert_same_on_threads(&scene(), &p);
    assert!(
        to_json(&one, 0, &p).contains("\"reduction\": \"extremes\""),
        "setting not recorded"
    );
}

/// The default is the exact reduction, and its JSON does not name the setting.
#[test]
fn hull_is_the_default_and_unnamed() {
    assert_eq!(Params::default().reduction, Reduction::Hull);
    let m = scene();
    let p = params(&[12], Reduction::Hull);
    let text = to_json(&decompose(&m, &p).unwrap(), 0, &p);
    assert!(
        !text.contains("reduction"),
        "default JSON names the setting"
    );
}

/// Corpus meshes (a closed scan; a model of many parts that must be bridged) at about
/// 1% of their faces and at 20: enclosing and at most N.
#[test]
fn extremes_output_encloses_corpus_meshes() {
    check_corpus_meshes(|t| vec![params(t, Reduction::Extremes)]);
}
