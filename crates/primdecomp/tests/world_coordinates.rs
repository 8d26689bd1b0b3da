//! `LoadOptions::keep_world_coordinates`: `world_pos` returns the file's coordinates
//! bit for bit, so that a mesh rebuilt from them with `Mesh::from_polygons` decomposes
//! exactly as the file does (what the Python package's `load` relies on).

use primdecomp::{decompose, Goal, LoadOptions, Mesh, Params};

/// Coordinates whose re-centred value plus the centre is not the value read.
const OBJ: &str = "v 0.1 0.7 1e-17\nv 3.3 0.2 0.3\nv 0.30000000000000004 2.9 0.01\nv 1.1 1.3 2.7\n\
f 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n";

fn world(mesh: &Mesh) -> Vec<[f64; 3]> {
    (0..mesh.vertex_count() as u32)
        .map(|v| mesh.world_pos(v))
        .collect()
}

#[test]
fn kept_coordinates_are_the_files_and_decompose_like_the_file() {
    let dir = std::env::temp_dir().join(format!("primdecomp-world-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("t.obj");
    std::fs::write(&path, OBJ).unwrap();
    let read: Vec<[f64; 3]> = OBJ
        .lines()
        .filter(|l| l.starts_with("v "))
        .map(|l| {
            let c: Vec<f64> = l[2..].split(' ').map(|t| t.parse().unwrap()).collect();
            [c[0], c[1], c[2]]
        })
        .collect();
    let options = LoadOptions {
        keep_world_coordinates: true,
        ..LoadOptions::default()
    };
    let kept = Mesh::load_with(&path, &options).unwrap();
    let centred = Mesh::load(&path).unwrap();
    assert_eq!(kept.centre(), [0.0; 3]);
    assert_eq!(world(&kept), read);
    // Why the option exists: re-centring and adding the centre back is not exact here.
    assert_ne!(world(&centred), read);
    let faces: Vec<&[u32]> = (0..kept.face_count()).map(|f| kept.face(f)).collect();
    let rebuilt = Mesh::from_polygons(&world(&kept), &faces).unwrap();
    let params = Params {
        goal: Goal::counts([2]),
        ..Params::default()
    };
    let a = decompose(&centred, &params).unwrap().to_json(0, &params);
    let b = decompose(&rebuilt, &params).unwrap().to_json(0, &params);
    let prims = |s: &str| s[s.find("\"primitives\"").unwrap()..].to_string();
    assert_eq!(prims(&a), prims(&b));
    std::fs::remove_dir_all(&dir).ok();
}
