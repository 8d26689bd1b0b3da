//! Inputs the fuzzers (`fuzz/`) found to break an invariant, each reduced to a test
//! that failed before its fix. The comment on each says what must happen and why.

mod common;

use common::check::assert_valid;
use primdecomp::{decompose, Dedup, Mesh, Params};

/// `fuzz/fuzz_targets/decompose.rs`, first run: one triangle at a 1e-30 scale welded
/// with a tolerance of 10 collapsed to one point, and the output sphere was fitted
/// around the welded point only, missing the face's other corner. Output primitives
/// must enclose the faces as given, whatever the weld did to the topology.
#[test]
fn tolerance_weld_does_not_shrink_the_output() {
    let v = [[1e-30, -1e-30, 0.0], [0.0, -1e-30, 2e-30]];
    let mesh = Mesh::from_polygons(&v, &[vec![0, 1, 1]]);
    let params = Params {
        targets: vec![27],
        dedup: Dedup::Tolerance(10.0),
        ..Default::default()
    };
    assert_valid(&mesh, &decompose(&mesh, &params).unwrap(), &params);
}

/// The same at ordinary scale: a strip of triangles 10 long whose vertices are 0.5
/// apart, welded with tolerance 0.6, merges transitively into one vertex group. Every
/// triangle must still lie inside an output primitive.
#[test]
fn transitive_tolerance_weld_keeps_every_face_enclosed() {
    let mut v = Vec::new();
    let mut f = Vec::new();
    for i in 0..=20 {
        v.push([0.5 * i as f64, 0.0, 0.0]);
        v.push([0.5 * i as f64, 0.5, 0.0]);
    }
    for i in 0..20u32 {
        f.push(vec![2 * i, 2 * i + 2, 2 * i + 1]);
        f.push(vec![2 * i + 1, 2 * i + 2, 2 * i + 3]);
    }
    let mesh = Mesh::from_polygons(&v, &f);
    for n in [40, 4, 1] {
        let params = Params {
            targets: vec![n],
            dedup: Dedup::Tolerance(0.6),
            ..Default::default()
        };
        assert_valid(&mesh, &decompose(&mesh, &params).unwrap(), &params);
    }
}
