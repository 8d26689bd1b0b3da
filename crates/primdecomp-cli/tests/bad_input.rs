//! Hostile input through the real binary (docs/decisions/hostile-input-limits.md): every case either succeeds
//! with a valid result or fails with exit code 2 and a message naming the file and the
//! line or byte offset, never panics, never hangs (each run has a time limit), and
//! never creates or modifies the output file. Inputs that are not regular files
//! (pipes, symbolic link loops, devices, directories) and glTF buffer URIs that reach
//! outside the glTF's folder are cases too; a second table runs commands whose
//! outputs would overwrite an input or each other, which must be refused before
//! anything is written.
//!
//! Each case also checks key fragments of its message here; the exact messages are the
//! tables in `docs/bad_input.md`, which this test regenerates and compares: a changed
//! message fails the test until the tables are regenerated with
//! `PRIMDECOMP_BLESS=1 cargo test --release --test bad_input`.

// The later tables, in files of their own (not test crates: below tests/bad_input/).
#[path = "bad_input/names.rs"]
mod names;
#[path = "bad_input/results.rs"]
mod results;

use std::collections::BTreeMap;
use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

/// What a case must produce.
enum Want {
    /// Exit 0 and a result file with finite numbers.
    Ok,
    /// Exit 2 and stderr containing each of these fragments (the file name is always
    /// checked too).
    Err(&'static [&'static str]),
}

/// The input of a case, or a file beside it.
enum Input {
    File(Vec<u8>),
    Dir,
    /// A named pipe, made with `mkfifo`.
    Fifo,
    /// A symbolic link to this target.
    Link(&'static str),
}

impl Input {
    fn make(&self, at: &Path) {
        match self {
            Input::File(bytes) => std::fs::write(at, bytes).unwrap(),
            Input::Dir => std::fs::create_dir_all(at).unwrap(),
            Input::Fifo => {
                let ok = Command::new("mkfifo")
                    .arg(at)
                    .status()
                    .expect("mkfifo runs");
                assert!(ok.success(), "mkfifo {at:?}");
            }
            Input::Link(to) => std::os::unix::fs::symlink(to, at).unwrap(),
        }
    }
}

struct Case {
    name: &'static str,
    what: &'static str,
    input: Input,
    /// Files made beside the input first (glTF buffers).
    beside: Vec<(&'static str, Input)>,
    /// Arguments after the usual ones.
    args: &'static [&'static str],
    want: Want,
}

fn case(name: &'static str, what: &'static str, bytes: impl Into<Vec<u8>>, want: Want) -> Case {
    made(name, what, Input::File(bytes.into()), want)
}

fn made(name: &'static str, what: &'static str, input: Input, want: Want) -> Case {
    Case {
        name,
        what,
        input,
        beside: Vec::new(),
        args: &[],
        want,
    }
}

impl Case {
    fn beside(mut self, name: &'static str, input: Input) -> Case {
        self.beside.push((name, input));
        self
    }

    fn args(mut self, args: &'static [&'static str]) -> Case {
        self.args = args;
        self
    }
}

/// The longest any one run may take before the test calls it a hang.
const LIMIT: Duration = Duration::from_secs(120);

/// Runs `cmd` to the end like `Command::output`, but kills it and fails the test if it
/// takes longer than [`LIMIT`] (a read blocked on a pipe would otherwise hang the
/// test too).
fn output_within(mut cmd: Command) -> Output {
    let mut child = cmd
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("runs");
    let drain = |mut r: Box<dyn Read + Send>| {
        std::thread::spawn(move || {
            let mut v = Vec::new();
            let _ = r.read_to_end(&mut v);
            v
        })
    };
    let out = drain(Box::new(child.stdout.take().unwrap()));
    let err = drain(Box::new(child.stderr.take().unwrap()));
    let start = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if start.elapsed() > LIMIT {
            let _ = child.kill();
            let _ = child.wait();
            panic!("{cmd:?} still ran after {LIMIT:?}: it hangs");
        }
        std::thread::sleep(Duration::from_millis(10));
    };
    Output {
        status,
        stdout: out.join().unwrap(),
        stderr: err.join().unwrap(),
    }
}

/// Runs one case in `dir` (relative paths, so messages do not depend on the temp dir);
/// returns its outcome and message for the table.
fn run_case(dir: &Path, c: &Case) -> (String, String) {
    let name = c.name;
    c.input.make(&dir.join(name));
    for (file, input) in &c.beside {
        input.make(&dir.join(file));
    }
    let out = format!("{name}.json");
    std::fs::write(dir.join(&out), b"previous result").unwrap();
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_primdecomp"));
    cmd.current_dir(dir)
        .args(["decompose", name, "-n", "4", "--quiet", "-o", &out])
        .args(c.args);
    let res = output_within(cmd);
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

/// A glTF document of one indexed triangle in a buffer of 44 bytes ([`tri_bin`])
/// whose source is `uri` (`None`: the GLB's binary chunk).
fn tri_gltf(uri: Option<&str>) -> String {
    let source = uri.map_or(String::new(), |u| format!(r#""uri":"{u}","#));
    format!(
        r#"{{"asset":{{"version":"2.0"}},"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0}}],"meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}},"indices":1}}]}}],"buffers":[{{{source}"byteLength":44}}],"bufferViews":[{{"buffer":0,"byteLength":36}},{{"buffer":0,"byteOffset":36,"byteLength":6}}],"accessors":[{{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"}},{{"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}}]}}"#
    )
}

/// The triangle's buffer: 3 f32 positions, 3 u16 indices, 2 bytes padding.
fn tri_bin() -> Vec<u8> {
    let mut bin: Vec<u8> = [0f32, 0., 0., 1., 0., 0., 0., 1., 0.]
        .iter()
        .flat_map(|c| c.to_le_bytes())
        .collect();
    bin.extend([0u16, 1, 2, 0].iter().flat_map(|i| i.to_le_bytes()));
    bin
}

/// A GLB with one indexed triangle.
fn glb() -> Vec<u8> {
    let mut j = tri_gltf(None).into_bytes();
    j.resize(j.len().div_ceil(4) * 4, b' ');
    let bin = tri_bin();
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
        made("a_directory.obj", "a directory given as the input", Input::Dir, e(&["is a directory, not a regular file"])),
        made("pipe.obj", "a named pipe (FIFO, no writer) given as the input", Input::Fifo, e(&["is a named pipe (FIFO), not a regular file"])),
        made("loop.obj", "a symbolic link to itself", Input::Link("loop.obj"), e(&["cannot open", "symbolic link loop"])),
        made("dangling.obj", "a symbolic link to nothing", Input::Link("nowhere.obj"), e(&["cannot open: no such file"])),
        made("device.obj", "a symbolic link to /dev/zero", Input::Link("/dev/zero"), e(&["is a character device, not a regular file"])),
        case("uri_absolute.gltf", "glTF buffer URI /dev/zero (absolute)", tri_gltf(Some("/dev/zero")), e(&["buffer 0: the URI '/dev/zero' is an absolute path", "--allow-external-uris"])),
        case("uri_absolute_allowed.gltf", "glTF buffer URI /dev/zero, with", tri_gltf(Some("/dev/zero")), e(&["names /dev/zero, which is a character device"])).args(&["--allow-external-uris"]),
        case("uri_parent.gltf", "glTF buffer URI ../tri.bin", tri_gltf(Some("../tri.bin")), e(&["'../tri.bin' climbs out of the glTF's folder with '..'"])),
        case("uri_encoded_parent.gltf", "glTF buffer URI %2E%2E/tri.bin", tri_gltf(Some("%2E%2E/tri.bin")), e(&["climbs out of the glTF's folder"])),
        case("uri_file_url.gltf", "glTF buffer URI file:///etc/passwd", tri_gltf(Some("file:///etc/passwd")), e(&["is a file: URL"])),
        case("uri_http.gltf", "glTF buffer URI https://…", tri_gltf(Some("https://example.com/tri.bin")), e(&["'https:', which is never read"])),
        case("uri_link_out.gltf", "glTF buffer, a symbolic link beside it to /dev/zero", tri_gltf(Some("uri_link_out.bin")), e(&["leads out of the glTF's folder through a symbolic link, to /dev/zero"])).beside("uri_link_out.bin", Input::Link("/dev/zero")),
        case("uri_pipe.gltf", "glTF buffer, a named pipe beside it", tri_gltf(Some("uri_pipe.bin")), e(&["names uri_pipe.bin, which is a named pipe (FIFO), not a regular file"])).beside("uri_pipe.bin", Input::Fifo),
        case("uri_short.gltf", "glTF buffer file of 20 bytes, 44 declared", tri_gltf(Some("uri_short.bin")), e(&["which holds 20 bytes; the buffer declares 44"])).beside("uri_short.bin", Input::File(tri_bin()[..20].to_vec())),
        case("uri_missing.gltf", "glTF buffer file missing", tri_gltf(Some("uri_missing.bin")), e(&["names uri_missing.bin, which cannot be opened: no such file"])),
        case("uri_bad_base64.gltf", "glTF data: URI with bad base64", tri_gltf(Some("data:application/octet-stream;base64,%%%")), e(&["without valid base64"])),
        case("uri_ok.gltf", "glTF buffer file beside it, 1 MB longer than declared", tri_gltf(Some("uri_ok.bin")), Want::Ok).beside("uri_ok.bin", Input::File([tri_bin(), vec![7; 1 << 20]].concat())),
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
        let args = c.args.iter().map(|a| format!(" `{a}`")).collect::<String>();
        table += &format!(
            "| `{}` | {}{args} | {} | {} |\n",
            c.name, c.what, outcome, msg
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
    table += "\n## Outputs that would destroy an input or each other\n\n\
              Each command runs in a directory holding `m.obj` (a triangle), `link.obj` (a\n\
              symbolic link to `m.obj`), `hard.obj` (a hard link to it), `a/x.obj`, `b/x.obj`,\n\
              `b/y.obj`, `pipe.obj` (a named pipe) and `c.json`; \"nothing written\" means every\n\
              file there kept its bytes and no file or directory was added.\n\n\
              | command | what | outcome | exact message (stderr) |\n|---|---|---|---|\n";
    let dir = tempdir("clashes");
    make_clash_dir(&dir);
    for c in clashes() {
        let (outcome, msg) = run_clash(&dir, &c);
        let cmd = format!("primdecomp {}", c.args.join(" "));
        table += &format!("| `{cmd}` | {} | {outcome} | `{}` |\n", c.what, cell(&msg));
    }
    std::fs::remove_dir_all(&dir).unwrap();
    table += "\n## Files that lie, absurd counts, planted links, terminals\n\n\
              Result, evaluation and settings files read back by `export`, `view`, `eval`,\n\
              `sim` and `--config`, a batch's manifest read by `--resume`, counts and sizes\n\
              beyond what a run can use, links planted where an export writes, and names\n\
              with control characters. Each command runs in a fresh directory its case sets\n\
              up (`r.json` a result, `m.obj` a triangle, `a.obj`/`b.obj` a batch already run\n\
              into `out/`); \"nothing written\" means every file there kept its bytes and\n\
              none was added (`tests/bad_input/results.rs`).\n\n";
    let dir = tempdir("results");
    table += &results::table(&dir);
    std::fs::remove_dir_all(&dir).unwrap();
    table += "\n## Object names in the exports\n\n\
              A per-object result whose objects carry these names (each with a prism and a\n\
              sphere), exported as MJCF, URDF, USD, Godot and glTF; every file reads back\n\
              with its format's reader (`primdecomp_testkit::exports`: quick-xml, the glTF\n\
              schema, the USD and `.tscn` grammars) and the columns show the names as read\n\
              (`tests/bad_input/names.rs`). Control characters and the non-characters are\n\
              written as visible escapes, names are made unique (`_2`) and MuJoCo's\n\
              `world` is avoided; identifiers keep `[A-Za-z0-9_]`.\n\n";
    let dir = tempdir("names");
    table += &names::table(&dir);
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

/// A command whose outputs would overwrite an input or each other.
struct Clash {
    args: &'static [&'static str],
    what: &'static str,
    /// Fragments of the message (exit code 2 is always checked).
    want: &'static [&'static str],
    /// What the command may add (a batch's good inputs still run); nothing else may
    /// appear or change.
    writes: &'static [&'static str],
}

/// The heart of the message for an output that is `m.obj`.
const SAME: &str = "is the input m.obj (the same file): refusing to overwrite an input";

#[rustfmt::skip]
fn clashes() -> Vec<Clash> {
    let c = |args, what, want, writes| Clash {
        args,
        what,
        want,
        writes,
    };
    vec![
        c(&["decompose", "m.obj", "-n", "4", "--quiet", "-o", "m.obj"], "-o is the input", &["-o m.obj", SAME], &[]),
        c(&["decompose", "m.obj", "-n", "4", "--quiet", "-o", "./m.obj"], "-o is the input, spelled ./m.obj", &["-o ./m.obj", SAME], &[]),
        c(&["decompose", "m.obj", "-n", "4", "--quiet", "-o", "link.obj"], "-o is a symbolic link to the input", &["-o link.obj", SAME], &[]),
        c(&["decompose", "m.obj", "-n", "4", "--quiet", "-o", "hard.obj"], "-o is a hard link to the input", &["-o hard.obj", SAME], &[]),
        c(&["decompose", "link.obj", "-n", "4", "--quiet", "-o", "m.obj"], "the input is a symbolic link to -o", &["-o m.obj is the input link.obj (the same file)"], &[]),
        c(&["decompose", "m.obj", "-n", "4", "--quiet", "--obj", "m.obj"], "--obj is the input", &["--obj m.obj", SAME], &[]),
        c(&["decompose", "m.obj", "-n", "4,8", "--quiet", "-o", "r.json", "--obj", "r.json"], "-o and --obj are one file once target suffixes are added", &["-o r.json (as r_n8.json) and --obj r.json (as r_n8.json) are the same file"], &[]),
        c(&["decompose", "m.obj", "-n", "4", "--quiet", "-o", "r.json", "--obj", "./r.json"], "-o and --obj are one file", &["-o r.json and --obj ./r.json are the same file"], &[]),
        c(&["decompose", "a/x.obj", "b/x.obj", "-n", "4", "--quiet", "-o", "out/"], "two inputs, one output name", &["a/x.obj and b/x.obj would both write out/x.primdecomp.json"], &[]),
        c(&["decompose", "a/x.obj", "b/y.obj", "-n", "4", "--quiet", "-o", "one.json"], "two inputs, -o a .json file", &["-o one.json: ends in .json, but with 2 inputs -o names a directory"], &[]),
        c(&["decompose", "a/x.obj", "b/y.obj", "-n", "4", "--quiet", "-o", "m.obj"], "two inputs, -o an existing file", &["-o m.obj: exists and is not a directory"], &[]),
        c(&["decompose", "a/x.obj", "b/y.obj", "-n", "4", "--quiet", "-o", "out/", "--obj", "hulls.obj"], "two inputs, --obj a .obj file", &["--obj hulls.obj: ends in .obj, but with 2 inputs --obj names a directory"], &[]),
        c(&["decompose", "m.obj", "-n", "4", "--quiet", "-o", "r.json", "--resume"], "--resume without a batch directory", &["--resume finishes a batch"], &[]),
        c(&["decompose", "a/x.obj", "pipe.obj", "-n", "4", "--quiet", "-o", "out/"], "a batch with a named pipe among its inputs", &["pipe.obj: is a named pipe (FIFO), not a regular file", "1 of 2 inputs failed"], &["out", "out/.primdecomp-manifest.jsonl", "out/x.primdecomp.json"]),
        c(&["eval", "--input", "m.obj", "c.json", "--json", "c.json"], "eval --json is a collider", &["--json c.json is the input c.json (the same file)"], &[]),
        c(&["sim", "--input", "m.obj", "c.json", "--json", "./m.obj"], "sim --json is the input mesh", &["--json ./m.obj", SAME], &[]),
        c(&["view", "c.json", "-o", "c.json"], "view -o is the result it shows", &["-o c.json is the input c.json (the same file)"], &[]),
        c(&["view", "c.json", "--input", "m.obj", "--png", "./m.obj"], "view --png is the input mesh", &["--png ./m.obj", SAME], &[]),
        c(&["export", "c.json", "-o", "./c.json", "--format", "glb"], "export -o is the result", &["-o ./c.json is the input c.json (the same file)"], &[]),
        c(&["decompose", "m.obj", "-n", "4", "--quiet", "--export", "link.obj", "--format", "mjcf"], "--export is a link to the input", &["--export link.obj", SAME], &[]),
        c(&["decompose", "m.obj", "-n", "4", "--quiet", "--png", "hard.obj"], "--png is a hard link to the input", &["--png hard.obj", SAME], &[]),
        c(&["decompose", "a/x.obj", "b/y.obj", "-n", "4", "--quiet", "-o", "out/", "--export", "x.glb"], "--export with several inputs", &["--export writes one file per level of one input"], &[]),
        // Standard output holds one result: what would be several, or another output, is refused.
        c(&["decompose", "m.obj", "-n", "4,8", "--quiet", "-o", "-"], "-o - with two levels", &["-o -: these settings make several levels, a file each: give -o a file name"], &[]),
        c(&["decompose", "a/x.obj", "b/y.obj", "-n", "4", "--quiet", "-o", "-"], "-o - with two inputs", &["-o -: several inputs write a result each: give -o a directory"], &[]),
        c(&["decompose", "m.obj", "-n", "4", "--quiet", "-o", "-", "--png", "m.png"], "-o - with --png (drawn from -o's file)", &["-o -: --png draws the result read back from -o's file"], &[]),
        c(&["decompose", "m.obj", "-n", "4", "--quiet", "-o", "r.json", "--obj", "-"], "--obj -", &["--obj -: only the result (-o -) can go to standard output"], &[]),
        // Refused before the run: no level's JSON or first export written.
        c(&["decompose", "m.obj", "--tolerance", "1%,0.3%", "--quiet", "-o", "r.json", "--export", "r.glb", "--export", "r.xml"], "a second --export of no known format", &["r.xml: cannot tell the export format"], &[]),
        // The library's coupling, said in the flags' words (the library refuses it too).
        c(&["decompose", "m.obj", "--max-excess-volume", "0.1", "--quiet", "-o", "r.json"], "an excess-volume cap with deferred re-pricing", &["--max-excess-volume needs --reprice exact"], &[]),
        c(&["decompose", "m.obj", "--greedy", "--quiet", "-o", "r.json"], "--greedy without counts", &["--greedy needs -n"], &[]),
    ]
}

fn make_clash_dir(dir: &Path) {
    Input::File(format!("{TRI}f 1 2 3\n").into_bytes()).make(&dir.join("m.obj"));
    Input::Link("m.obj").make(&dir.join("link.obj"));
    std::fs::hard_link(dir.join("m.obj"), dir.join("hard.obj")).unwrap();
    for f in ["a/x.obj", "b/x.obj", "b/y.obj"] {
        std::fs::create_dir_all(dir.join(f).parent().unwrap()).unwrap();
        std::fs::copy(dir.join("m.obj"), dir.join(f)).unwrap();
    }
    Input::Fifo.make(&dir.join("pipe.obj"));
    Input::File(b"{}".to_vec()).make(&dir.join("c.json"));
}

/// Every file and directory below `dir` (relative) with its bytes; a pipe is not
/// read (that would block), a link is its target, and a file over 1 MiB its size and
/// modification time (a sparse file of gigabytes is not read).
fn snapshot(dir: &Path) -> BTreeMap<PathBuf, Vec<u8>> {
    let mut out = BTreeMap::new();
    let mut todo = vec![dir.to_path_buf()];
    while let Some(d) = todo.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            let m = std::fs::symlink_metadata(&p).unwrap();
            let t = m.file_type();
            let bytes = if t.is_symlink() {
                std::fs::read_link(&p)
                    .unwrap()
                    .into_os_string()
                    .into_encoded_bytes()
            } else if t.is_dir() {
                todo.push(p.clone());
                b"(directory)".to_vec()
            } else if t.is_file() && m.len() > 1 << 20 {
                format!("({} bytes, {:?})", m.len(), m.modified().unwrap()).into_bytes()
            } else if t.is_file() {
                std::fs::read(&p).unwrap()
            } else {
                b"(other)".to_vec()
            };
            out.insert(p.strip_prefix(dir).unwrap().to_path_buf(), bytes);
        }
    }
    out
}

/// Runs one command in `dir`: exit 2, the message's fragments, every file there
/// unchanged and nothing added but `writes` (removed again after).
fn run_clash(dir: &Path, c: &Clash) -> (String, String) {
    let before = snapshot(dir);
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_primdecomp"));
    cmd.current_dir(dir).args(c.args);
    let res = output_within(cmd);
    let what = c.args.join(" ");
    let stderr = String::from_utf8_lossy(&res.stderr).trim().to_string();
    assert!(!stderr.contains("panicked"), "{what}: {stderr}");
    assert_eq!(res.status.code(), Some(2), "{what}: {stderr}");
    for f in c.want {
        assert!(stderr.contains(f), "{what}: message lacks '{f}': {stderr}");
    }
    let after = snapshot(dir);
    for (p, bytes) in &before {
        assert_eq!(after.get(p), Some(bytes), "{what}: {p:?} changed or went");
    }
    let added: Vec<&Path> = after
        .keys()
        .filter(|p| !before.contains_key(*p))
        .map(PathBuf::as_path)
        .collect();
    let want: Vec<&Path> = c.writes.iter().map(Path::new).collect();
    assert_eq!(added, want, "{what}: files added");
    for p in c.writes.iter().filter(|p| !p.contains('/')) {
        let p = dir.join(p);
        let _ = std::fs::remove_dir_all(&p).or_else(|_| std::fs::remove_file(&p));
    }
    let outcome = match c.writes {
        [] => "exit 2, nothing written".to_string(),
        w => format!(
            "exit 2, the other input written ({})",
            w.iter()
                .filter(|p| p.ends_with(".json"))
                .map(|p| format!("`{p}`"))
                .collect::<Vec<_>>()
                .join(", ")
        ),
    };
    (outcome, stderr)
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
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_primdecomp"));
    cmd.current_dir(dir).args(args);
    let res = output_within(cmd);
    (
        res.status.code(),
        String::from_utf8_lossy(&res.stderr).trim().to_string(),
    )
}

/// `--max-memory`: an input whose estimated need exceeds the limit is refused before
/// parsing (OBJ counts come from a byte scan) and before decomposing (glTF, counted
/// once parsed), with exit 2, a message giving both sizes and the flag, and no output.
/// The need is the run's: a count's greedy run fits where the default's cut does not.
#[test]
fn memory_limit_refuses_up_front() {
    let dir = tempdir("memory");
    // 2,000 triangles: 3 × 2,000 vertices. Estimate (`memory::estimate`), the cut:
    // 1.25 × (112 MiB + 32·6,000 + 128·2,000) = 140.5 MiB; the greedy run:
    // 1.25 × (64 MiB + 32·6,000 + 92·2,000) = 80.4 MiB.
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
            "100M",
        ],
    );
    assert_eq!(code, Some(2), "{err}");
    assert_eq!(
        err,
        "error: big.obj: decomposing this mesh (2000 faces, 6000 vertices) needs about 141 MiB, \
         more than the memory limit of 100 MiB (default: the memory available now); raise \
         the limit with --max-memory SIZE, e.g. --max-memory 64G (in the library: the \
         max_memory of primdecomp::LoadOptions)"
    );
    assert!(!dir.join("big.json").exists());
    // A count's greedy run: fits under 100M, refused under 80M.
    let greedy = |limit: &str| {
        let args = ["decompose", "big.obj", "-n", "2", "-o", "small.json"];
        run_in(
            &dir,
            &[&args[..], &["--max-memory", limit, "--quiet"]].concat(),
        )
    };
    let (code, err) = greedy("100M");
    assert_eq!(code, Some(0), "{err}");
    std::fs::remove_file(dir.join("small.json")).unwrap();
    let (code, err) = greedy("80M");
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("needs about 80.4 MiB"), "{err}");
    assert!(!dir.join("small.json").exists());
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
        err.contains("t.glb: decomposing this mesh (1 faces, 3 vertices) needs about 140 MiB"),
        "{err}"
    );
    assert!(!dir.join("t.json").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// An input the user may not read is bad input too: exit 2, one sentence naming the
/// file. Root reads everything, so as root the binary runs as user 65534 through
/// `setpriv` (util-linux).
#[test]
fn unreadable_input_is_exit_2() {
    let dir = tempdir("permission");
    let input = dir.join("secret.obj");
    std::fs::write(&input, format!("{TRI}f 1 2 3\n")).unwrap();
    let mode = |p: &Path, m| {
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(p, std::fs::Permissions::from_mode(m)).unwrap();
    };
    mode(&input, 0o000);
    mode(&dir, 0o777);
    let uid = Command::new("id").arg("-u").output().expect("id runs");
    let root = String::from_utf8_lossy(&uid.stdout).trim() == "0";
    let bin = env!("CARGO_BIN_EXE_primdecomp");
    let mut cmd = if root {
        let mut c = Command::new("setpriv");
        c.args(["--reuid=65534", "--regid=65534", "--clear-groups", bin]);
        c
    } else {
        Command::new(bin)
    };
    cmd.current_dir(&dir)
        .args(["decompose", "secret.obj", "-o", "out.json", "--quiet"]);
    let res = output_within(cmd);
    let stderr = String::from_utf8_lossy(&res.stderr).trim().to_string();
    assert_eq!(
        (res.status.code(), stderr.as_str()),
        (Some(2), "error: secret.obj: cannot open: permission denied")
    );
    assert!(!dir.join("out.json").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}
