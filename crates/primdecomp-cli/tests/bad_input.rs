//! Hostile input through the real binary (issue 6, item 1): every case either succeeds
//! with a valid result or fails with exit code 2 and a message naming the file and the
//! line or byte offset, never panics, and never creates or modifies the output file.
//!
//! Each case also checks key fragments of its message here; the exact messages are the
//! table in `docs/bad_input.md`, which this test regenerates and compares: a changed
//! message fails the test until the table is regenerated with
//! `PRIMDECOMP_BLESS=1 cargo test --release --test bad_input`.

use std::path::{Path, PathBuf};
use std::process::Command;

/// What a case must produce.
enum Want {
    /// Exit 0 and a result file with finite numbers.
    Ok,
    /// Exit 2 and stderr containing each of these fragments (the file name is always
    /// checked too).
    Err(&'static [&'static str]),
}

/// The input of a case.
enum Input {
    File(Vec<u8>),
    Dir,
}

struct Case {
    name: &'static str,
    what: &'static str,
    input: Input,
    want: Want,
}

fn case(name: &'static str, what: &'static str, bytes: impl Into<Vec<u8>>, want: Want) -> Case {
    Case {
        name,
        what,
        input: Input::File(bytes.into()),
        want,
    }
}

/// Runs one case in `dir` (relative paths, so messages do not depend on the temp dir);
/// returns its outcome and message for the table.
fn run_case(dir: &Path, c: &Case) -> (String, String) {
    let name = c.name;
    match &c.input {
        Input::File(bytes) => std::fs::write(dir.join(name), bytes).unwrap(),
        Input::Dir => std::fs::create_dir_all(dir.join(name)).unwrap(),
    }
    let out = format!("{name}.json");
    std::fs::write(dir.join(&out), b"previous result").unwrap();
    let res = Command::new(env!("CARGO_BIN_EXE_primdecomp"))
        .current_dir(dir)
        .args(["decompose", name, "-n", "4", "--quiet", "-o", &out])
        .output()
        .expect("runs");
    let stderr = String::from_utf8_lossy(&res.stderr).trim().to_string();
    assert!(!stderr.contains("panicked"), "{name}: {stderr}");
    let row = match c.want {
        Want::Ok => {
            assert_eq!(res.status.code(), Some(0), "{name}: {stderr}");
            let json = std::fs::read_to_string(dir.join(&out)).unwrap();
            let v: serde_json::Value = serde_json::from_str(&json).unwrap();
            let prims = v["primitives"].as_array().unwrap();
            let body = serde_json::to_string(prims).unwrap();
            assert!(!body.contains("null"), "{name}: non-finite number: {json}");
            let faces = &v["input"]["faces"];
            let n = prims.len();
            (format!("exit 0: {faces} faces → {n} primitives"), stderr)
        }
        Want::Err(frags) => {
            assert_eq!(res.status.code(), Some(2), "{name}: {stderr}");
            assert!(
                stderr.contains(name),
                "{name}: message does not name the file: {stderr}"
            );
            for f in frags {
                assert!(stderr.contains(f), "{name}: message lacks '{f}': {stderr}");
            }
            let kept = std::fs::read(dir.join(&out)).unwrap();
            assert_eq!(kept, b"previous result", "{name}: output touched");
            ("exit 2, output untouched".to_string(), stderr)
        }
    };
    let leftovers: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.to_string_lossy().contains(".tmp"))
        .collect();
    assert!(
        leftovers.is_empty(),
        "{name}: temporary files left: {leftovers:?}"
    );
    row
}

fn binary_stl(tris: u32, declared: u32, corner: f32) -> Vec<u8> {
    let mut b = vec![0u8; 80];
    b.extend_from_slice(&declared.to_le_bytes());
    for t in 0..tris {
        b.extend_from_slice(&[0u8; 12]);
        for v in [
            [0.0f32, 0.0, 0.0],
            [corner, 0.0, 0.0],
            [0.0, corner, t as f32],
        ] {
            v.iter().for_each(|c| b.extend_from_slice(&c.to_le_bytes()));
        }
        b.extend_from_slice(&[0u8; 2]);
    }
    b
}

fn binary_ply(declared_verts: u32, declared_faces: u32, faces: u32, eol: &str) -> Vec<u8> {
    let header = format!(
        "ply\nformat binary_little_endian 1.0\nelement vertex {declared_verts}\nproperty float x\nproperty float y\nproperty float z\nelement face {declared_faces}\nproperty list uchar int vertex_indices\nend_header\n"
    );
    let mut b = header.replace('\n', eol).into_bytes();
    for v in [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]] {
        v.iter().for_each(|c| b.extend_from_slice(&c.to_le_bytes()));
    }
    for _ in 0..faces {
        b.extend_from_slice(&[3u8]); // list length
        [0i32, 1, 2]
            .iter()
            .for_each(|i| b.extend_from_slice(&i.to_le_bytes()));
    }
    b
}

/// A GLB with one indexed triangle (3 f32 positions, 3 u16 indices, 2 bytes padding).
fn glb() -> Vec<u8> {
    let json = r#"{"asset":{"version":"2.0"},"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],"meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],"buffers":[{"byteLength":44}],"bufferViews":[{"buffer":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":6}],"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"},{"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}]}"#;
    let mut j = json.as_bytes().to_vec();
    j.resize(j.len().div_ceil(4) * 4, b' ');
    let mut bin: Vec<u8> = [0f32, 0., 0., 1., 0., 0., 0., 1., 0.]
        .iter()
        .flat_map(|c| c.to_le_bytes())
        .collect();
    bin.extend([0u16, 1, 2, 0].iter().flat_map(|i| i.to_le_bytes()));
    let total = (12 + 8 + j.len() + 8 + bin.len()) as u32;
    let mut v = b"glTF".to_vec();
    v.extend(2u32.to_le_bytes().iter().chain(&total.to_le_bytes()));
    v.extend(
        (j.len() as u32)
            .to_le_bytes()
            .iter()
            .chain(b"JSON")
            .chain(&j),
    );
    v.extend(
        (bin.len() as u32)
            .to_le_bytes()
            .iter()
            .chain(b"BIN\0")
            .chain(&bin),
    );
    v
}

const TRI: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

fn ngon(n: usize) -> Vec<u8> {
    let mut s = String::new();
    for i in 0..n {
        let a = i as f64 / n as f64 * std::f64::consts::TAU;
        s += &format!("v {} {} 0\n", a.cos(), a.sin());
    }
    s += "f";
    for i in 1..=n {
        s += &format!(" {i}");
    }
    (s + "\n").into_bytes()
}

fn cases() -> Vec<Case> {
    let e = Want::Err;
    let g = glb();
    let ply = binary_ply(3, 1, 1, "\n"); // 36 bytes of vertices, 13 of face
    vec![
        case("empty.obj", "empty file", "", e(&["no polygon faces"])),
        case("comments.obj", "comments only", "# nothing\n# here\n", e(&["no polygon faces"])),
        case("vertices_only.obj", "vertices, no faces", TRI, e(&["no polygon faces"])),
        case("nan.obj", "NaN coordinate", "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", e(&[":1:", "'nan' is not finite"])),
        case("inf.obj", "Inf coordinate", "v 0 0 0\nv inf 0 0\nv 0 1 0\nf 1 2 3\n", e(&[":2:", "not finite"])),
        case("nan.ply", "NaN in ASCII PLY", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 NaN 0\n0 1 0\n3 0 1 2\n", e(&[":11:", "not finite"])),
        case("nan.stl", "NaN in binary STL", binary_stl(1, 1, f32::NAN), e(&["at byte 108", "non-finite"])),
        case("inf.off", "Inf in OFF", "OFF\n3 1 0\n0 0 0\n1 0 -inf\n0 1 0\n3 0 1 2\n", e(&[":4:"])),
        case("index_range.obj", "OBJ index past the end", format!("{TRI}f 1 2 9\n"), e(&[":4:", "9"])),
        case("index_zero.obj", "OBJ index 0", format!("{TRI}f 0 1 2\n"), e(&[":4:", "index 0"])),
        case("negative_ok.obj", "valid negative (relative) indices", format!("{TRI}f -3 -2 -1\n"), Want::Ok),
        case("negative_bad.obj", "negative index before the first vertex", format!("{TRI}f -1 -2 -4\n"), e(&[":4:", "-4"])),
        case("short_faces.obj", "faces with < 3 vertices and lines only", format!("{TRI}f 1 2\nl 1 2 3\n"), e(&["no polygon faces"])),
        case("zero_area.obj", "zero-area (collinear) face", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n", Want::Ok),
        case("repeated_vertex.obj", "faces repeating a vertex", format!("{TRI}f 1 1 2\nf 3 3 3\nf 1 2 3\n"), Want::Ok),
        case("duplicate_faces.obj", "the same face 3 times, and reversed", format!("{TRI}f 1 2 3\nf 1 2 3\nf 2 3 1\nf 3 2 1\n"), Want::Ok),
        case("ngon_100k.obj", "one 100,000-gon", ngon(100_000), Want::Ok),
        case("truncated.stl", "binary STL cut mid-triangle", binary_stl(3, 3, 1.0)[..150].to_vec(), e(&["at byte 134", "truncated"])),
        case("truncated.ply", "binary PLY cut mid-vertex", ply[..ply.len() - 31].to_vec(), e(&["at byte"])),
        case("truncated.glb", "GLB cut inside the BIN chunk", g[..g.len() - 10].to_vec(), e(&["at byte 8", "truncated"])),
        case("header_only.glb", "GLB header declaring 4096 bytes, 12 present", b"glTF\x02\x00\x00\x00\x00\x10\x00\x00".to_vec(), e(&["at byte 8"])),
        case("lying_count.stl", "binary STL declaring 5 triangles, holding 2", binary_stl(2, 5, 1.0), e(&["at byte 184", "declares 5"])),
        case("short_count.stl", "binary STL declaring 1 triangle, holding 2", binary_stl(2, 1, 1.0), Want::Ok),
        case("lying_faces.ply", "binary PLY declaring 4 faces, holding 1", binary_ply(3, 4, 1, "\n"), e(&["at byte"])),
        case("lying_vertices.ply", "binary PLY declaring 9 vertices, holding 3", binary_ply(9, 1, 1, "\n"), e(&["at byte"])),
        case("lying.off", "OFF declaring 2 faces, holding 1", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", e(&[":6:", "ends after 1 of 2 faces"])),
        case("latin1.obj", "non-UTF-8 byte in a comment", b"# caf\xe9\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n".to_vec(), Want::Ok),
        case("bad_number.obj", "non-UTF-8 byte as a coordinate", b"v 0 0 0\nv 1 \xff 0\nv 0 1 0\nf 1 2 3\n".to_vec(), e(&[":2:", "not a number"])),
        case("crlf.obj", "CRLF line ends", "v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 3\r\n", Want::Ok),
        case("mixed_endings.obj", "CRLF, LF and CR mixed", "v 0 0 0\r\nv 1 0 0\rv 0 1 0\nf 1 2 3\r\n", Want::Ok),
        case("mixed_error.obj", "mixed line ends, error on line 4", "v 0 0 0\r\nv 1 0 0\rv 0 1 0\nf 1 2 x\r\n", e(&[":4:"])),
        case("crlf_header.ply", "binary PLY with a CRLF header", binary_ply(3, 1, 1, "\r\n"), Want::Ok),
        case("huge_1e38.obj", "coordinates of 1e38", "v 0 0 0\nv 1e38 0 0\nv 0 1e38 0\nf 1 2 3\n", Want::Ok),
        case("huge_3e38.stl", "binary STL at f32's largest values", binary_stl(1, 1, 3.4e38), Want::Ok),
        case("huge_1e300.obj", "coordinates of 1e300", "v 0 0 0\nv 1e300 0 0\nv 0 1e300 1e300\nf 1 2 3\n", e(&["vertex 1", "1e60", "rescale"])),
        case("far_1e100.obj", "a unit triangle at 1e100 from the origin", "v 1e100 0 0\nv 1e100 1 0\nv 1e100 0 1\nf 1 2 3\n", e(&["vertex 1", "1e100", "1e70", "nearer the origin"])),
        case("gzip.obj", "gzip data behind .obj", vec![0x1f, 0x8b, 8, 0, 0, 0, 0, 0], e(&["gzip"])),
        case("mesh.xyz", "unknown extension", TRI, e(&["unknown extension"])),
        case("no_extension", "no extension", TRI, e(&["unknown extension"])),
        Case { name: "a_directory.obj", what: "a directory given as the input", input: Input::Dir, want: e(&["is a directory"]) },
    ]
}

/// Markdown cell: pipes escaped, newlines as <br>.
fn cell(s: &str) -> String {
    s.replace('|', "\\|").replace('\n', "<br>")
}

#[test]
fn hostile_inputs_table() {
    let dir = tempdir("table");
    let mut table = String::from(
        "# Hostile input: what each case produces\n\n\
         Generated by `PRIMDECOMP_BLESS=1 cargo test --release --test bad_input`\n\
         (`tests/bad_input.rs`, which fails when a message here changes). Each case runs\n\
         `primdecomp decompose CASE -n 4 --quiet -o CASE.json` in a directory holding\n\
         CASE and a previous CASE.json; \"output untouched\" means that file kept its\n\
         bytes and no temporary file was left.\n\n\
         | case | input | outcome | exact message (stderr) |\n|---|---|---|---|\n",
    );
    for c in cases() {
        let (outcome, msg) = run_case(&dir, &c);
        let msg = if msg.is_empty() {
            "—".to_string()
        } else {
            format!("`{}`", cell(&msg))
        };
        table += &format!("| `{}` | {} | {} | {} |\n", c.name, c.what, outcome, msg);
    }
    std::fs::remove_dir_all(&dir).unwrap();
    let doc = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/bad_input.md");
    if std::env::var_os("PRIMDECOMP_BLESS").is_some() {
        std::fs::write(&doc, &table).unwrap();
    }
    let committed = std::fs::read_to_string(&doc).unwrap_or_default();
    assert!(
        committed == table,
        "docs/bad_input.md differs from what the binary now says; regenerate it with \
         PRIMDECOMP_BLESS=1 cargo test --release --test bad_input\n{table}"
    );
}

/// A fresh directory per test (`name`): the tests of this file run in parallel and
/// each removes its own directory at the end.
fn tempdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!(
        "primdecomp-bad-input-{}-{name}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Runs the binary in `dir` with `args`; returns (exit code, stderr).
fn run_in(dir: &Path, args: &[&str]) -> (Option<i32>, String) {
    let res = Command::new(env!("CARGO_BIN_EXE_primdecomp"))
        .current_dir(dir)
        .args(args)
        .output()
        .expect("runs");
    (
        res.status.code(),
        String::from_utf8_lossy(&res.stderr).trim().to_string(),
    )
}

/// `--max-memory`: an input whose estimated need exceeds the limit is refused before
/// parsing (OBJ counts come from a byte scan) and before decomposing (glTF, counted
/// once parsed), with exit 2, a message giving both sizes and the flag, and no output.
#[test]
fn memory_limit_refuses_up_front() {
    let dir = tempdir("memory");
    // 2,000 triangles: 3 × 2,000 vertices. Estimate: 1.25 × (32 MiB + 100·6,000 +
    // 150·2,000 + 40·6,000) = 41.4 MiB.
    let mut obj = String::new();
    for t in 0..2000 {
        let z = t as f64;
        obj += &format!("v 0 0 {z}\nv 1 0 {z}\nv 0 1 {z}\n");
        obj += &format!("f {} {} {}\n", 3 * t + 1, 3 * t + 2, 3 * t + 3);
    }
    std::fs::write(dir.join("big.obj"), obj).unwrap();
    let (code, err) = run_in(
        &dir,
        &[
            "decompose",
            "big.obj",
            "-o",
            "big.json",
            "--max-memory",
            "40M",
        ],
    );
    assert_eq!(code, Some(2), "{err}");
    assert_eq!(
        err,
        "error: big.obj: decomposing this mesh (2000 faces, 6000 vertices) needs about 41.4 MiB, \
         more than the memory limit of 40.0 MiB (default: the memory available now); raise \
         the limit with --max-memory SIZE, e.g. --max-memory 64G (in the library: the \
         max_memory of primdecomp::load_limited)"
    );
    assert!(!dir.join("big.json").exists());
    let (code, err) = run_in(
        &dir,
        &[
            "decompose",
            "big.obj",
            "-n",
            "2",
            "-o",
            "big.json",
            "--max-memory",
            "43M",
            "--quiet",
        ],
    );
    assert_eq!(code, Some(0), "{err}");
    let (code, err) = run_in(
        &dir,
        &[
            "decompose",
            "big.obj",
            "-o",
            "x.json",
            "--max-memory",
            "lots",
        ],
    );
    assert_eq!(code, Some(2));
    assert_eq!(
        err,
        "error: --max-memory: expected a size like 8G, 'available' or 'none', got 'lots'"
    );
    // glTF: no counts before parsing; refused once parsed.
    std::fs::write(dir.join("t.glb"), glb()).unwrap();
    let (code, err) = run_in(
        &dir,
        &["decompose", "t.glb", "-o", "t.json", "--max-memory", "1M"],
    );
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains("t.glb: decomposing this mesh (1 faces, 3 vertices) needs about 40.0 MiB"),
        "{err}"
    );
    assert!(!dir.join("t.json").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}
