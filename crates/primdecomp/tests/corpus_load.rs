//! Loads every mesh of the shared corpus (`../shared/datasets/corpus/`) through
//! `primdecomp::Mesh::load` and checks it against `../shared/datasets/CATALOG.tsv`:
//! the face count (faces of arity ≥ 3 from `faces_by_arity`; `triangles` for glTF),
//! a sane vertex count (at least `vertices_merged`, indices in range, finite
//! coordinates), and no error. When the corpus folder is absent the test says so
//! loudly on stderr and returns.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The catalog figures this test checks.
struct Row {
    format: String,
    faces_by_arity: String,
    triangles: u64,
    vertices_merged: u64,
}

use primdecomp_testkit::{corpus_absent, datasets_dir};

fn read_catalog(path: &Path) -> HashMap<String, Row> {
    let text = std::fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("{}: cannot read the catalog: {e}", path.display()));
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().expect("empty catalog").split('\t').collect();
    let col = |name: &str| {
        header
            .iter()
            .position(|h| *h == name)
            .unwrap_or_else(|| panic!("catalog has no column {name}"))
    };
    let (name, format, arity) = (col("name"), col("format"), col("faces_by_arity"));
    let (tris, verts) = (col("triangles"), col("vertices_merged"));
    let mut rows = HashMap::new();
    for line in lines.filter(|l| !l.trim().is_empty()) {
        let f: Vec<&str> = line.split('\t').collect();
        let num = |i: usize| {
            f[i].trim()
                .parse::<u64>()
                .unwrap_or_else(|e| panic!("{line}: {e}"))
        };
        let row = Row {
            format: f[format].to_string(),
            faces_by_arity: f[arity].to_string(),
            triangles: num(tris),
            vertices_merged: num(verts),
        };
        rows.insert(f[name].to_string(), row);
    }
    rows
}

/// Sum of the counts of arity ≥ 3 in `3:348;4:22117`-style text.
fn polygon_faces(by_arity: &str) -> u64 {
    by_arity
        .split(';')
        .filter(|s| !s.is_empty())
        .map(|pair| {
            let (a, n) = pair.split_once(':').expect("arity:count");
            let (a, n): (u64, u64) = (a.parse().unwrap(), n.parse().unwrap());
            if a >= 3 {
                n
            } else {
                0
            }
        })
        .sum()
}

/// Loads one file and returns a description of what is wrong, if anything.
fn check(path: &Path, row: &Row) -> Result<String, String> {
    let start = Instant::now();
    let mesh = primdecomp::Mesh::load(path).map_err(|e| format!("load failed: {e}"))?;
    let secs = start.elapsed().as_secs_f64();
    let expected = if row.format == "glb" {
        row.triangles
    } else {
        polygon_faces(&row.faces_by_arity)
    };
    let faces = mesh.face_count() as u64;
    if faces != expected {
        return Err(format!("{faces} faces, catalog says {expected}"));
    }
    let nv = mesh.vertex_count() as u64;
    if nv < row.vertices_merged {
        let msg = format!(
            "{nv} vertices, fewer than the catalog's {} merged",
            row.vertices_merged
        );
        return Err(msg);
    }
    if let Some(&bad) = (0..mesh.face_count())
        .flat_map(|f| mesh.face(f))
        .find(|&&v| u64::from(v) >= nv)
    {
        return Err(format!("face index {bad} out of range ({nv} vertices)"));
    }
    let finite =
        (0..mesh.vertex_count()).all(|v| mesh.world_pos(v as u32).iter().all(|c| c.is_finite()));
    if !finite {
        return Err("a vertex coordinate is not finite".into());
    }
    Ok(format!(
        "{faces} faces, {nv} vertices, {:.1} ms",
        secs * 1e3
    ))
}

#[test]
fn corpus_files_load_with_catalog_face_counts() {
    let dir = datasets_dir();
    let corpus = dir.join("corpus");
    if !corpus.is_dir() {
        corpus_absent(&corpus);
        return;
    }
    let catalog = read_catalog(&dir.join("CATALOG.tsv"));
    let mut files: Vec<PathBuf> = std::fs::read_dir(&corpus)
        .expect("read corpus dir")
        .map(|e| e.expect("dir entry").path())
        .filter(|p| p.is_file())
        .collect();
    files.sort();
    assert!(!files.is_empty(), "{} holds no file", corpus.display());
    let mut failures = Vec::new();
    for path in &files {
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let Some(row) = catalog.get(&name) else {
            failures.push(format!("{name}: no row in CATALOG.tsv"));
            continue;
        };
        match check(path, row) {
            Ok(summary) => eprintln!("ok   {name}: {summary}"),
            Err(msg) => {
                eprintln!("FAIL {name}: {msg}");
                failures.push(format!("{name}: {msg}"));
            }
        }
    }
    for name in catalog.keys() {
        if !corpus.join(name).is_file() {
            eprintln!("note: catalog row {name} has no file in the corpus");
        }
    }
    eprintln!("corpus: {} files, {} failures", files.len(), failures.len());
    assert!(
        failures.is_empty(),
        "corpus failures:\n{}",
        failures.join("\n")
    );
}

/// Times the largest corpus file on its own (run with `--nocapture` to see it).
#[test]
fn dragon_load_time() {
    let path = datasets_dir().join("corpus/dragon_vrip_full.ply");
    if !path.is_file() {
        corpus_absent(&path);
        return;
    }
    let start = Instant::now();
    let mesh = primdecomp::Mesh::load(&path).expect("dragon loads");
    let ms = start.elapsed().as_secs_f64() * 1e3;
    eprintln!(
        "dragon_vrip_full.ply: {} faces loaded in {ms:.1} ms",
        mesh.face_count()
    );
    assert_eq!(mesh.face_count(), 871_414);
}
