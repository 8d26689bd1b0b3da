//! Out-of-core tiles (`primdecomp::Tiled::decompose`, src/tiles.rs): a tiled run must
//! enclose every input face (checked by the independent oracle,
//! `primdecomp_testkit::contain`), be the same bytes on 1 and 2 threads, run within a
//! memory limit that refuses the input read whole, and turn bad input into the usual
//! errors. Every input is made here and written as binary PLY (read from the map a
//! tile at a time) or OBJ (parsed whole).

use primdecomp::{Error, Goal, LoadOptions, Mesh, Params, Tiled};
use primdecomp_testkit::check::{assert_counts, assert_valid};
use primdecomp_testkit::on_threads;
use primdecomp_testkit::shapes::{
    cuboid, cylinder, flat_grid, icosphere, join, obj_text, ply_bytes, Polys,
};
use std::path::{Path, PathBuf};

/// A sphere, a cylinder and a box standing apart: three parts, several tiles.
fn scene() -> Polys {
    let moved = |(v, f): Polys, d: [f64; 3]| -> Polys {
        (
            v.iter().map(|p| [0, 1, 2].map(|k| p[k] + d[k])).collect(),
            f,
        )
    };
    join(&[
        icosphere(1.0, 4),
        moved(cylinder(0.5, 3.0, 48), [3.0, 0.2, 0.0]),
        cuboid([-4.0, -1.0, -1.0], [-2.5, 0.5, 2.0]),
    ])
}

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("primdecomp-tiles-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn write(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

fn tiles(k: usize) -> LoadOptions {
    LoadOptions {
        tiles: Some(k),
        ..LoadOptions::default()
    }
}

/// Forced tiles from the map: every face enclosed at every level, at most N
/// primitives, the same JSON on 1 and 2 threads; OBJ (parsed whole, then tiled)
/// encloses too.
#[test]
fn forced_tiles_enclose_and_are_deterministic() {
    let dir = temp_dir("forced");
    let polys = scene();
    let ply = write(&dir, "scene.ply", &ply_bytes(&polys));
    let params = Params {
        goal: Goal::counts([40, 12]),
        ..Params::default()
    };
    let mesh = Mesh::load(&ply).unwrap();
    let runs: Vec<_> = [1, 2]
        .iter()
        .map(|&t| {
            on_threads(t, || {
                Tiled::decompose(&ply, &params, &tiles(3), &|_, _| {}).unwrap()
            })
        })
        .collect();
    assert_eq!(runs[0].stats.tiles, 3);
    assert_eq!(runs[0].input.faces, mesh.face_count());
    for level in 0..params.goal.targets().len() {
        assert_eq!(
            runs[0].to_json(level, &params),
            runs[1].to_json(level, &params),
            "1 vs 2 threads"
        );
    }
    assert_valid(&mesh, &runs[0], &params);
    assert_counts(&runs[0], "tiled");
    // The default run (a tolerance, cut from the merge tree) on tiles encloses too.
    let default = Params::default();
    let dec = Tiled::decompose(&ply, &default, &tiles(4), &|_, _| {}).unwrap();
    assert_valid(&mesh, &dec, &default);
    // Its tolerance is the share of the input's diagonal asked for, not of the boxes'.
    let diagonal = (0..3)
        .map(|d| (dec.input.aabb_max[d] - dec.input.aabb_min[d]).powi(2))
        .sum::<f64>()
        .sqrt();
    let asked = primdecomp::Tolerance::DEFAULT.in_units(diagonal);
    let tolerance = dec.levels[0].tolerance.expect("a tolerance level");
    assert!(
        (tolerance - asked).abs() <= 1e-12 * asked,
        "{tolerance} against {asked}"
    );
    let obj = write(&dir, "scene.obj", obj_text(&polys).as_bytes());
    let dec = Tiled::decompose(&obj, &params, &tiles(2), &|_, _| {}).unwrap();
    assert_valid(&Mesh::load(&obj).unwrap(), &dec, &params);
    std::fs::remove_dir_all(&dir).ok();
}

/// A limit that refuses the input read whole: `load_with` says too large, the tiled
/// run picks more than one tile by itself and still encloses every face.
#[test]
fn a_small_memory_limit_tiles_instead_of_refusing() {
    let dir = temp_dir("limit");
    let ply = write(&dir, "ball.ply", &ply_bytes(&icosphere(1.0, 7)));
    let options = LoadOptions {
        max_memory: Some(115 << 20),
        greedy_only: true,
        ..LoadOptions::default()
    };
    let refused = Mesh::load_with(&ply, &options).unwrap_err();
    assert!(matches!(refused, Error::TooLarge { .. }), "{refused}");
    let params = Params {
        goal: Goal::counts([50]),
        ..Params::default()
    };
    let dec = Tiled::decompose(&ply, &params, &options, &|_, _| {}).unwrap();
    assert!(dec.stats.tiles > 1, "{} tiles", dec.stats.tiles);
    assert_valid(&Mesh::load(&ply).unwrap(), &dec, &params);
    // A limit below what even the most tiles need is refused, naming the file.
    let tiny = LoadOptions {
        max_memory: Some(1 << 20),
        ..options
    };
    let e = Tiled::decompose(&ply, &params, &tiny, &|_, _| {}).unwrap_err();
    assert!(e.to_string().contains("ball.ply"), "{e}");
    assert_eq!(e.exit_code(), 2);
    std::fs::remove_dir_all(&dir).ok();
}

/// Truncated data, a header that claims more than the file holds and an index out
/// of range are the whole parse's errors, naming the file and a byte offset.
#[test]
fn bad_input_fails_with_the_usual_errors() {
    let dir = temp_dir("bad");
    let good = ply_bytes(&scene());
    let params = Params {
        goal: Goal::counts([10]),
        ..Params::default()
    };
    let run = |name: &str, bytes: &[u8]| {
        let path = write(&dir, name, bytes);
        let e = Tiled::decompose(&path, &params, &tiles(2), &|_, _| {}).unwrap_err();
        assert_eq!(e.exit_code(), 2, "{e}");
        assert!(matches!(e, Error::ParseByte { .. }), "{name}: {e}");
        e.to_string()
    };
    // Cut inside the faces, and inside the vertices.
    let e = run("cut.ply", &good[..good.len() - 7]);
    assert!(e.contains("truncated file"), "{e}");
    let header_end = good.windows(11).position(|w| w == b"end_header\n").unwrap() + 11;
    let e = run("cut_vertices.ply", &good[..header_end + 40]);
    assert!(e.contains("ends inside vertex"), "{e}");
    // A header that claims one more face than the data holds.
    let text = String::from_utf8_lossy(&good[..header_end]).to_string();
    let faces: usize = text
        .lines()
        .find_map(|l| l.strip_prefix("element face "))
        .unwrap()
        .parse()
        .unwrap();
    let lying = text.replace(
        &format!("element face {faces}"),
        &format!("element face {}", faces + 1),
    );
    let mut bytes = lying.into_bytes();
    bytes.extend_from_slice(&good[header_end..]);
    let e = run("lying.ply", &bytes);
    assert!(e.contains("truncated file"), "{e}");
    // The last face's last index out of range.
    let mut bytes = good.clone();
    let n = bytes.len();
    bytes[n - 4..].copy_from_slice(&i32::MAX.to_le_bytes());
    let e = run("index.ply", &bytes);
    assert!(e.contains("out of range"), "{e}");
    // A non-finite vertex.
    let mut bytes = good.clone();
    bytes[header_end..header_end + 4].copy_from_slice(&f32::NAN.to_le_bytes());
    let e = run("nan.ply", &bytes);
    assert!(e.contains("not finite"), "{e}");
    std::fs::remove_dir_all(&dir).ok();
}

/// Planned in 3 tiles (the plan's bytes the same twice), read back, run a tile at a
/// time and merged: `Tiled::decompose`'s JSON at every level, byte for byte.
fn apart_equals_whole(ply: &Path, params: &Params) {
    let plan = Tiled::plan(ply, params, &tiles(3)).unwrap();
    let bytes = plan.to_bytes();
    assert_eq!(
        bytes,
        Tiled::plan(ply, params, &tiles(3)).unwrap().to_bytes()
    );
    let plan = Tiled::from_bytes(&bytes).unwrap();
    assert_eq!(plan.tiles(), 3);
    let results: Vec<Vec<u8>> = (0..3)
        .map(|t| plan.run_tile(ply, t, &|_, _| {}).unwrap())
        .collect();
    let merged = plan.merge(&results, &|_, _| {}).unwrap();
    let whole = Tiled::decompose(ply, params, &tiles(3), &|_, _| {}).unwrap();
    for level in 0..whole.levels.len() {
        assert_eq!(merged.to_json(level, params), whole.to_json(level, params));
    }
}

/// `e` is a bad-input error (exit code 2) whose message holds `words`.
fn refused(e: Error, words: &str) {
    let text = e.to_string();
    assert!(text.contains(words), "{text} (expected '{words}')");
    assert_eq!(e.exit_code(), 2, "{text}");
}

/// The three steps apart (plan, each tile, merge), through their bytes, give
/// `Tiled::decompose`'s JSON byte for byte; bytes altered, cut, of another version,
/// another plan, another tile or another file are refused with an error naming what
/// is wrong, never trusted.
#[test]
fn plan_tiles_and_merge_apart_equal_the_tiled_run_and_refuse_bad_bytes() {
    let dir = temp_dir("apart");
    let ply = write(&dir, "scene.ply", &ply_bytes(&scene()));
    for params in [
        Params {
            goal: Goal::counts([30, 8]),
            ..Params::default()
        },
        Params::default(),
    ] {
        apart_equals_whole(&ply, &params);
    }
    let params = Params {
        goal: Goal::counts([20]),
        ..Params::default()
    };
    let plan = Tiled::plan(&ply, &params, &tiles(2)).unwrap();
    let bytes = plan.to_bytes();
    let tile = plan.run_tile(&ply, 1, &|_, _| {}).unwrap();
    plan.check_tile(1, &tile).unwrap();
    // Plans: cut, altered, of another version, not a plan at all.
    refused(
        Tiled::from_bytes(&bytes[..bytes.len() - 3]).unwrap_err(),
        "checksum",
    );
    let mut altered = bytes.clone();
    altered[30] ^= 4;
    refused(Tiled::from_bytes(&altered).unwrap_err(), "checksum");
    let mut v2 = bytes.clone();
    v2[8] = 2;
    refused(Tiled::from_bytes(&v2).unwrap_err(), "version 2");
    refused(
        Tiled::from_bytes(b"{\"format\": 1}").unwrap_err(),
        "not a primdecomp plan",
    );
    refused(
        Tiled::from_bytes(&tile).unwrap_err(),
        "not a primdecomp plan",
    );
    // Tile results: cut, altered, of tile 1 read as tile 0, of another plan.
    refused(
        plan.check_tile(1, &tile[..tile.len() - 9]).unwrap_err(),
        "checksum",
    );
    let mut altered = tile.clone();
    altered[60] ^= 1;
    refused(plan.check_tile(1, &altered).unwrap_err(), "checksum");
    refused(
        plan.check_tile(0, &tile).unwrap_err(),
        "holds tile 1, not tile 0",
    );
    let other = Tiled::plan(&ply, &params, &tiles(3)).unwrap();
    refused(other.check_tile(1, &tile).unwrap_err(), "another plan");
    let results = vec![plan.run_tile(&ply, 0, &|_, _| {}).unwrap(), tile.clone()];
    refused(other.merge(&results, &|_, _| {}).unwrap_err(), "3 tiles, 2");
    refused(
        plan.merge(&[tile.clone(), tile], &|_, _| {}).unwrap_err(),
        "not tile 0",
    );
    // A tile out of range, and a file other than the plan's.
    refused(
        plan.run_tile(&ply, 2, &|_, _| {}).unwrap_err(),
        "out of range",
    );
    let changed = write(&dir, "other.ply", &ply_bytes(&icosphere(1.0, 3)));
    refused(
        plan.run_tile(&changed, 0, &|_, _| {}).unwrap_err(),
        "not the file",
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// The top run holds relative settings to the input's diagonal, not to the tiles'
/// boxes' (which stand beyond the input by their thickness): on a flat grid tiled in
/// two with `min_extent` 2%, the plates come out exactly 2% of the input's diagonal
/// thick (half-extent), where the boxes' diagonal made them about 0.05% thicker.
#[test]
fn the_top_run_holds_relative_settings_to_the_inputs_diagonal() {
    let dir = temp_dir("relative");
    let ply = write(&dir, "grid.ply", &ply_bytes(&flat_grid(24)));
    let params = Params {
        goal: Goal::counts([2]),
        fit: primdecomp::Fit {
            min_extent: 0.02,
            ..primdecomp::Fit::default()
        },
        ..Params::default()
    };
    let dec = Tiled::decompose(&ply, &params, &tiles(2), &|_, _| {}).unwrap();
    assert_valid(&Mesh::load(&ply).unwrap(), &dec, &params);
    let want = 0.02 * dec.input.diagonal();
    for p in &dec.levels[0].primitives {
        let primdecomp::Primitive::Box(b) = p else {
            panic!("a flat grid gives boxes: {p:?}")
        };
        let thin = b.half.iter().copied().fold(f64::INFINITY, f64::min);
        assert!(
            (thin - want).abs() <= 1e-9 * want,
            "half-thickness {thin}, {} of the input's diagonal's 2%",
            thin / want
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}
