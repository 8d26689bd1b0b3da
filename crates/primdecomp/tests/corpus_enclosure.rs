//! Enclosure on the real corpus (`../shared/datasets/corpus`): for every mesh up to
//! 200k faces, at a target of about 1% of its faces and at N = 1 (one bottom-up pass
//! serves both), every input face must lie inside one output primitive, checked by
//! `primdecomp_testkit::contain`, which shares no code with the fitting; and the count must not
//! exceed N (bridging makes every N reachable when no excess cap is set).

use primdecomp::{decompose, Goal, Params};
use primdecomp_testkit::contain::{faces_enclosed, parse_primitive};
use rayon::prelude::*;
use std::path::Path;

const MAX_FACES: usize = 200_000;

fn corpus() -> Option<Vec<std::path::PathBuf>> {
    let dir = primdecomp_testkit::corpus_dir();
    let Ok(rd) = std::fs::read_dir(&dir) else {
        primdecomp_testkit::corpus_absent(&dir);
        return None;
    };
    let mut files: Vec<_> = rd.filter_map(|e| e.ok().map(|e| e.path())).collect();
    files.sort();
    Some(files)
}

/// One mesh: its table row, or the failures found.
fn check(path: &Path) -> Option<(String, Vec<String>)> {
    let mesh = primdecomp::Mesh::load(path).unwrap_or_else(|e| panic!("{e}"));
    let faces = mesh.face_count();
    if faces > MAX_FACES {
        return None;
    }
    let n = (faces / 100).max(1);
    let params = Params {
        goal: Goal::counts([n, 1]),
        ..Default::default()
    };
    let t = std::time::Instant::now();
    let dec = decompose(&mesh, &params).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let secs = t.elapsed().as_secs_f64();
    let polys: Vec<Vec<[f64; 3]>> = (0..faces)
        .map(|f| mesh.face(f).iter().map(|&v| mesh.world_pos(v)).collect())
        .collect();
    let tol = 1e-6 * mesh.diagonal().max(1e-300);
    let name = path.file_name().unwrap().to_string_lossy().to_string();
    let mut failures = Vec::new();
    for (i, &target) in params.goal.targets().iter().enumerate() {
        let json: serde_json::Value = serde_json::from_str(&dec.to_json(i, &params)).unwrap();
        let shapes: Vec<_> = json["primitives"]
            .as_array()
            .unwrap()
            .iter()
            .map(parse_primitive)
            .collect();
        let missing = faces_enclosed(&shapes, &polys, tol)
            .iter()
            .filter(|&&b| !b)
            .count();
        if missing > 0 {
            failures.push(format!(
                "{name} N={target}: {missing} of {faces} faces not enclosed"
            ));
        }
        if shapes.len() > target {
            failures.push(format!("{name} N={target}: {} primitives", shapes.len()));
        }
    }
    let row = format!(
        "{name:<34} {faces:>8} {n:>6} {:>6} {:>6} {secs:>8.2}",
        dec.levels[0].primitives.len(),
        dec.levels[1].primitives.len()
    );
    Some((row, failures))
}

#[test]
fn every_corpus_face_is_enclosed_at_one_percent_and_at_one() {
    let Some(files) = corpus() else { return };
    // Meshes in parallel (each run is mostly one sequential merge loop).
    let results: Vec<_> = files.par_iter().filter_map(|p| check(p)).collect();
    println!(
        "{:<34} {:>8} {:>6} {:>6} {:>6} {:>8}",
        "mesh", "faces", "N", "prims", "N=1", "seconds"
    );
    let mut failures = Vec::new();
    for (row, f) in results {
        println!("{row}");
        failures.extend(f);
    }
    assert!(
        failures.is_empty(),
        "enclosure failures:\n{}",
        failures.join("\n")
    );
}
