//! Helpers for the export checks in `tests/exports/` (Python, run by
//! `scripts/test.sh`):
//!
//! - `faces MESH OUT.json`: the input faces as the core loader sees them, in world
//!   coordinates: `{"vertices": [[x, y, z], …], "faces": [[i, j, k, …], …]}`;
//! - `contain SHAPES.json POINTS.json TOL`: for each point, whether some primitive of
//!   a primdecomp JSON document contains it within TOL, by the tests' independent
//!   containment routine (`contain.rs`), printed as a JSON array of booleans; the
//!   Python containment check is tested against it;
//! - `ladder MESH LEVELS OUT.ply` / `city PARTS OUT.ply`: the scale ladder's inputs
//!   (`primdecomp_testkit::ladder`): MESH subdivided LEVELS times, or a city block of
//!   PARTS parts, streamed to a binary PLY file; prints the faces written.
//! - `inputs DIR`: the made-up inputs every consumer check runs on (`inputs.rs`),
//!   one file name per line on stdout.

use primdecomp_testkit::contain::{parse_primitive, shape_contains};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let res = match args.get(1).map(String::as_str) {
        Some("faces") if args.len() == 4 => faces(&args[2], &args[3]),
        Some("contain") if args.len() == 5 => contain(&args[2], &args[3], &args[4]),
        Some("ladder") if args.len() == 5 => ladder(&args[2], &args[3], &args[4]),
        Some("city") if args.len() == 4 => city(&args[2], &args[3]),
        Some("inputs") if args.len() == 3 => inputs(&args[2]),
        _ => Err(
            "usage: primdecomp-testkit faces MESH OUT.json | contain SHAPES.json POINTS.json TOL \
             | ladder MESH LEVELS OUT.ply | city PARTS OUT.ply | inputs DIR"
                .into(),
        ),
    };
    if let Err(e) = res {
        eprintln!("error: {e}");
        std::process::exit(2);
    }
}

fn faces(mesh: &str, out: &str) -> Result<(), String> {
    let m = primdecomp::Mesh::load(mesh.as_ref()).map_err(|e| e.to_string())?;
    let vertices: Vec<[f64; 3]> = (0..m.vertex_count() as u32)
        .map(|v| m.world_pos(v))
        .collect();
    let faces: Vec<&[u32]> = (0..m.face_count()).map(|f| m.face(f)).collect();
    let v = serde_json::json!({"vertices": vertices, "faces": faces});
    std::fs::write(out, v.to_string()).map_err(|e| format!("{out}: {e}"))
}

fn ladder(mesh: &str, levels: &str, out: &str) -> Result<(), String> {
    let m = primdecomp::Mesh::load(mesh.as_ref()).map_err(|e| e.to_string())?;
    let levels: u32 = levels.parse().map_err(|e| format!("LEVELS: {e}"))?;
    let (faces, _) = primdecomp_testkit::ladder::subdivided_ply(&m, levels, 49, out.as_ref())
        .map_err(|e| format!("{out}: {e}"))?;
    println!("{faces}");
    Ok(())
}

fn city(parts: &str, out: &str) -> Result<(), String> {
    let parts: u32 = parts.parse().map_err(|e| format!("PARTS: {e}"))?;
    let (faces, _) = primdecomp_testkit::ladder::city_block_ply(parts, 1, out.as_ref())
        .map_err(|e| format!("{out}: {e}"))?;
    println!("{faces}");
    Ok(())
}

fn contain(shapes: &str, points: &str, tol: &str) -> Result<(), String> {
    let read = |p: &str| -> Result<serde_json::Value, String> {
        let t = std::fs::read_to_string(p).map_err(|e| format!("{p}: {e}"))?;
        serde_json::from_str(&t).map_err(|e| format!("{p}: {e}"))
    };
    let doc = read(shapes)?;
    let pts = read(points)?;
    let tol: f64 = tol.parse().map_err(|e| format!("TOL: {e}"))?;
    let shapes: Vec<_> = doc["primitives"]
        .as_array()
        .ok_or("no primitives array")?
        .iter()
        .map(parse_primitive)
        .collect();
    let out: Vec<bool> = pts
        .as_array()
        .ok_or("points must be an array")?
        .iter()
        .map(|p| {
            let c = |i: usize| p[i].as_f64().unwrap_or(f64::NAN);
            let x = [c(0), c(1), c(2)];
            shapes.iter().any(|s| shape_contains(s, x, tol))
        })
        .collect();
    println!(
        "{}",
        serde_json::to_string(&out).map_err(|e| e.to_string())?
    );
    Ok(())
}

fn inputs(dir: &str) -> Result<(), String> {
    let names =
        primdecomp_testkit::inputs::write_all(dir.as_ref()).map_err(|e| format!("{dir}: {e}"))?;
    for n in names {
        println!("{n}");
    }
    Ok(())
}
