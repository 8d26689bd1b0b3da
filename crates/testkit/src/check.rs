//! One validity check for a decomposition, shared by the extreme-input and regression
//! tests: every level's JSON has no NaN or infinity (serde_json writes them as `null`;
//! the oracle refuses non-finite numbers), and every input face lies inside one output
//! primitive according to the independent oracle in `contain.rs`.
#![allow(dead_code)]

use super::contain::{faces_enclosed, parse_primitive, Shape};

use primdecomp::{Decomposition, Mesh, Params};

/// World-space corners of every face of `mesh`.
pub fn polygons(mesh: &Mesh) -> Vec<Vec<[f64; 3]>> {
    (0..mesh.face_count())
        .map(|f| mesh.face(f).iter().map(|&v| mesh.world_pos(v)).collect())
        .collect()
}

/// The oracle's shapes of level `level`, from the JSON we write.
pub fn shapes(dec: &Decomposition, level: usize, params: &Params) -> Vec<Shape> {
    let text = dec.to_json(level, params);
    let json: serde_json::Value = serde_json::from_str(&text).expect("valid JSON");
    let prims = json["primitives"].as_array().expect("primitives");
    // serde_json writes NaN and infinities as null.
    let body = serde_json::to_string(prims).unwrap();
    assert!(
        !body.contains("null"),
        "non-finite number in the JSON:\n{text}"
    );
    prims.iter().map(parse_primitive).collect()
}

/// Tolerance of the enclosure check: 1e-6 of the diagonal plus the round-off of
/// coordinates of the mesh's magnitude (a 10^6 offset carries 10^-10 of noise).
pub fn tolerance(mesh: &Mesh) -> f64 {
    let mag = (0..mesh.vertex_count() as u32)
        .flat_map(|v| mesh.world_pos(v))
        .fold(0.0f64, |m, c| m.max(c.abs()));
    1e-6 * mesh.diagonal() + 64.0 * f64::EPSILON * mag
}

/// Panics unless every level is finite and encloses every face of `mesh`.
pub fn assert_valid(mesh: &Mesh, dec: &Decomposition, params: &Params) {
    let polys = polygons(mesh);
    let tol = tolerance(mesh);
    for (i, level) in dec.levels.iter().enumerate() {
        let shapes = shapes(dec, i, params);
        let inside = faces_enclosed(&shapes, &polys, tol);
        let missing: Vec<usize> = (0..inside.len()).filter(|&f| !inside[f]).collect();
        assert!(
            missing.is_empty(),
            "target {}: {} of {} faces not enclosed (first: face {} {:?})",
            level.target,
            missing.len(),
            polys.len(),
            missing[0],
            polys[missing[0]]
        );
    }
}

/// Panics unless every level holds at most its target's primitives.
pub fn assert_counts(dec: &Decomposition, what: &str) {
    for l in &dec.levels {
        assert!(
            l.primitives.len() <= l.target,
            "{what}: {} primitives for target {}",
            l.primitives.len(),
            l.target
        );
    }
}

/// Panics unless `params` give the same JSON bytes (as written without `--timings`)
/// at every level on 1, 2 and 8 threads; returns the one-thread run.
pub fn assert_same_on_threads(mesh: &Mesh, params: &Params) -> Decomposition {
    let runs: Vec<Decomposition> = [1, 2, 8]
        .iter()
        .map(|&t| super::on_threads(t, || primdecomp::decompose(mesh, params).unwrap()))
        .collect();
    for level in 0..runs[0].levels.len() {
        let a = runs[0].to_json(level, params);
        assert_eq!(a, runs[1].to_json(level, params), "1 vs 2 threads");
        assert_eq!(a, runs[2].to_json(level, params), "1 vs 8 threads");
    }
    runs.into_iter().next().expect("three runs")
}

/// Panics unless `params` (an option set to its off value) give the default engine's
/// primitives at every level of `params.goal`, met the same way (a test of the
/// greedy pass's pricing compares greedy levels).
pub fn assert_default_output(mesh: &Mesh, params: &Params) {
    let a = primdecomp::decompose(mesh, params).unwrap();
    let default = Params {
        goal: params.goal.clone(),
        ..Default::default()
    };
    let b = primdecomp::decompose(mesh, &default).unwrap();
    for (x, y) in a.levels.iter().zip(&b.levels) {
        assert_eq!(x.primitives, y.primitives);
    }
}

/// Decomposes corpus meshes (one closed scan, one model of many parts that must be
/// bridged) at about 1% of their faces and at 20 under `with(targets)`, and checks
/// every result valid and within its counts; says so loudly and returns when the
/// corpus is absent.
pub fn check_corpus_meshes(with: impl Fn(&[usize]) -> Vec<Params>) {
    let dir = crate::corpus_dir();
    if !dir.is_dir() {
        crate::corpus_absent(&dir);
        return;
    }
    for name in ["stanford_bunny.obj", "peterbilt_truck.obj"] {
        let m = primdecomp::Mesh::load(&dir.join(name)).unwrap_or_else(|e| panic!("{e}"));
        let targets = [(m.face_count() / 100).max(1), 20];
        for p in with(&targets) {
            let dec = primdecomp::decompose(&m, &p).unwrap_or_else(|e| panic!("{name}: {e}"));
            assert_valid(&m, &dec, &p);
            assert_counts(&dec, &format!("{name}, {p:?}"));
        }
    }
}
