//! The glTF loader on structurally valid documents with hostile contents, built from
//! the fuzzer's bytes with `arbitrary` (random bytes rarely get past the JSON parser
//! and the crate's validation): node graphs with cycles, shared nodes and chains
//! thousands deep; accessors with extreme counts, offsets, strides, component types
//! and sparse blocks; buffer views overrunning their buffers; buffers with huge
//! `byteLength`s and URIs that are `data:` (valid or not), files beside the document,
//! `..` and %-encoded escapes, absolute paths, `file:` and other URLs, a symbolic link
//! leading out of the folder, a named pipe, a directory and a link to `/dev/zero`;
//! as `.gltf` or as a `.glb` with a binary chunk; with and without
//! `allow_external_uris`.
//!
//! Checked: no panic, no hang (a pipe read would block: libFuzzer's -timeout), no
//! unbounded read (a device read would grow without end: -rss_limit_mb); an error
//! names the glTF (or, for a failed read of an opened buffer file, exit code 1 and
//! that file) and has exit code 2; without `allow_external_uris` a document whose
//! buffers reach outside its folder never loads; a loaded mesh is well formed
//! (`parsed.rs`).
#![no_main]

#[path = "parsed.rs"]
mod parsed;

use arbitrary::Arbitrary;
use primdecomp::{LoadOptions, Mesh, MeshFormat};
use serde_json::{json, Map, Value};
use std::path::PathBuf;
use std::sync::OnceLock;

/// An index: mostly small (valid or just past the end), sometimes huge.
#[derive(Arbitrary, Debug)]
enum Idx {
    Small(u8),
    Huge(u32),
}

impl Idx {
    fn v(&self) -> Value {
        match self {
            Idx::Small(i) => json!(i % 12),
            Idx::Huge(i) => json!(*i),
        }
    }
}

/// A count, length or offset: typical, at a boundary, or enormous.
#[derive(Arbitrary, Debug)]
enum Num {
    Small(u8),
    Mid(u16),
    Big(u32),
    Huge(u64),
    Pow2(u8),
}

impl Num {
    fn get(&self) -> u64 {
        match self {
            Num::Small(n) => u64::from(*n),
            Num::Mid(n) => u64::from(*n),
            Num::Big(n) => u64::from(*n),
            // serde_json writes u64 as is; the crate reads sizes as u64 or usize.
            Num::Huge(n) => *n,
            Num::Pow2(k) => 1u64 << (k % 64),
        }
    }
    fn v(&self) -> Value {
        json!(self.get())
    }
}

/// A float for transforms: finite (JSON has no NaN), possibly extreme.
#[derive(Arbitrary, Debug)]
struct F(f32);

impl F {
    fn v(&self) -> Value {
        json!(if self.0.is_finite() { self.0 } else { 3.0e38 })
    }
}

#[derive(Arbitrary, Debug)]
enum Transform {
    None,
    Matrix([F; 16]),
    Trs {
        t: Option<[F; 3]>,
        r: Option<[F; 4]>,
        s: Option<[F; 3]>,
    },
}

#[derive(Arbitrary, Debug)]
struct Node {
    children: Vec<Idx>,
    mesh: Option<Idx>,
    transform: Transform,
}

#[derive(Arbitrary, Debug)]
struct Prim {
    position: Option<Idx>,
    indices: Option<Idx>,
    /// 0-6 are the spec's modes, others invalid.
    mode: Option<u8>,
}

#[derive(Arbitrary, Debug)]
struct SparseSide {
    view: Idx,
    offset: Option<Num>,
    component: u8,
}

#[derive(Arbitrary, Debug)]
struct Sparse {
    count: Num,
    indices: SparseSide,
    values: SparseSide,
}

#[derive(Arbitrary, Debug)]
struct Accessor {
    view: Option<Idx>,
    offset: Option<Num>,
    component: u8,
    count: Num,
    ty: u8,
    normalized: bool,
    sparse: Option<Sparse>,
}

#[derive(Arbitrary, Debug)]
struct View {
    buffer: Idx,
    offset: Option<Num>,
    length: Num,
    stride: Option<u8>,
}

/// Where a buffer's bytes come from.
#[derive(Arbitrary, Debug)]
enum Uri {
    /// The GLB's binary chunk (no `uri`).
    Bin,
    /// Valid base64 of these bytes.
    Data(Vec<u8>),
    /// `data:` with this (probably invalid) payload.
    DataRaw(String),
    /// A file in the glTF's folder (some are not regular files, some lead out).
    Beside(u8),
    /// A path that leaves the folder, or a URL.
    Outside(u8),
    /// Any string; with `allow_external_uris` only ones without `/` or `\`, so the
    /// run cannot be made to read the machine's files.
    Raw(String),
}

/// Files in the glTF's folder, made once: (name, leads outside the folder).
const BESIDE: [(&str, bool); 8] = [
    ("b.bin", false),
    ("short.bin", false),
    ("pipe.bin", false),
    ("dir.bin", false),
    ("missing.bin", false),
    ("zero.bin", true),
    ("up.bin", true),
    ("b%2ebin", false),
];

/// URIs that reach outside the folder (the outside file is `../outside.bin`).
const OUTSIDE: [&str; 9] = [
    "../outside.bin",
    "%2e%2e/outside.bin",
    "sub/../../outside.bin",
    "/dev/zero",
    "/dev/null",
    "/nonexistent-primdecomp/x.bin",
    "file:///dev/zero",
    "file:../outside.bin",
    "http://127.0.0.1:9/x.bin",
];

impl Uri {
    /// The `uri` member (None for the binary chunk) and whether it reaches outside
    /// the glTF's folder.
    fn v(&self, outside_abs: &str) -> (Option<String>, bool) {
        match self {
            Uri::Bin => (None, false),
            Uri::Data(bytes) => (
                Some(format!(
                    "data:application/octet-stream;base64,{}",
                    b64(bytes)
                )),
                false,
            ),
            Uri::DataRaw(s) => (Some(format!("data:;base64,{s}")), false),
            Uri::Beside(i) => {
                let (name, out) = BESIDE[usize::from(*i) % BESIDE.len()];
                (Some(name.into()), out)
            }
            Uri::Outside(i) => match usize::from(*i) % (OUTSIDE.len() + 1) {
                k if k < OUTSIDE.len() => (Some(OUTSIDE[k].into()), true),
                _ => (Some(outside_abs.into()), true),
            },
            Uri::Raw(s) => (Some(s.clone()), false),
        }
    }
}

#[derive(Arbitrary, Debug)]
struct Buffer {
    length: Num,
    uri: Uri,
}

#[derive(Arbitrary, Debug)]
struct Doc {
    nodes: Vec<Node>,
    /// A chain of more nodes, each the child of the one before (deep trees).
    chain: u16,
    /// Where the chain hangs: its first node is a child of this node.
    chain_root: Idx,
    scenes: Vec<Vec<Idx>>,
    scene: Option<Idx>,
    meshes: Vec<Vec<Prim>>,
    accessors: Vec<Accessor>,
    views: Vec<View>,
    buffers: Vec<Buffer>,
    glb: Option<Vec<u8>>,
    allow_external_uris: bool,
}

fn b64(bytes: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::new();
    for c in bytes.chunks(3) {
        let n = c
            .iter()
            .enumerate()
            .fold(0u32, |n, (i, &b)| n | u32::from(b) << (16 - 8 * i));
        for k in 0..=c.len() {
            s.push(A[(n >> (18 - 6 * k) & 63) as usize] as char);
        }
        s.extend(std::iter::repeat_n('=', 3 - c.len()));
    }
    s
}

const COMPONENTS: [u64; 7] = [5120, 5121, 5122, 5123, 5125, 5126, 5124];
const TYPES: [&str; 8] = [
    "SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4", "VEC5",
];

fn component(c: u8) -> Value {
    json!(COMPONENTS
        .get(usize::from(c))
        .copied()
        .unwrap_or(u64::from(c)))
}

fn set(o: &mut Map<String, Value>, key: &str, v: Option<Value>) {
    if let Some(v) = v {
        o.insert(key.into(), v);
    }
}

impl Doc {
    /// The document as JSON, and whether a buffer's URI reaches outside the folder.
    fn json(&self, outside_abs: &str) -> (Value, bool) {
        let mut nodes: Vec<Value> = self.nodes.iter().take(64).map(node).collect();
        let first = nodes.len();
        // Up to 255 nodes deep, and 1 time in 16 up to 4095 (slow under the sanitizer).
        let chain = usize::from(match self.chain {
            c if c >= 0xF000 => c % 4096,
            c => c % 256,
        });
        for k in 0..chain {
            let next = (k + 1 < chain).then(|| json!([first + k + 1]));
            let mut o = Map::new();
            set(&mut o, "children", next);
            if k + 1 == chain {
                o.insert("mesh".into(), json!(0));
            }
            nodes.push(Value::Object(o));
        }
        if chain > 0 {
            let root = self.chain_root.v().as_u64().unwrap_or(0) as usize;
            if let Some(Value::Object(o)) = nodes.get_mut(root) {
                let kids = o.entry("children").or_insert_with(|| json!([]));
                if let Value::Array(a) = kids {
                    a.push(json!(first));
                }
            }
        }
        let mut outside = false;
        let buffers: Vec<Value> = self
            .buffers
            .iter()
            .take(8)
            .map(|b| {
                let (uri, out) = b.uri.v(outside_abs);
                outside |= out;
                let mut o = Map::new();
                o.insert("byteLength".into(), b.length.v());
                set(&mut o, "uri", uri.map(Value::from));
                Value::Object(o)
            })
            .collect();
        let mut root = json!({
            "asset": {"version": "2.0"},
            "nodes": nodes,
            "scenes": self.scenes.iter().take(4).map(|s| json!({"nodes": s.iter().take(16).map(Idx::v).collect::<Vec<_>>()})).collect::<Vec<_>>(),
            "meshes": self.meshes.iter().take(8).map(|m| json!({"primitives": m.iter().take(8).map(prim).collect::<Vec<_>>()})).collect::<Vec<_>>(),
            "accessors": self.accessors.iter().take(16).map(accessor).collect::<Vec<_>>(),
            "bufferViews": self.views.iter().take(16).map(view).collect::<Vec<_>>(),
            "buffers": buffers,
        });
        if let (Some(s), Value::Object(o)) = (&self.scene, &mut root) {
            o.insert("scene".into(), s.v());
        }
        (root, outside)
    }
}

fn node(n: &Node) -> Value {
    let mut o = Map::new();
    if !n.children.is_empty() {
        o.insert(
            "children".into(),
            n.children.iter().take(8).map(Idx::v).collect(),
        );
    }
    set(&mut o, "mesh", n.mesh.as_ref().map(Idx::v));
    match &n.transform {
        Transform::None => {}
        Transform::Matrix(m) => {
            o.insert("matrix".into(), m.iter().map(F::v).collect());
        }
        Transform::Trs { t, r, s } => {
            let arr = |a: &[F]| a.iter().map(F::v).collect::<Value>();
            set(&mut o, "translation", t.as_ref().map(|a| arr(a)));
            set(&mut o, "rotation", r.as_ref().map(|a| arr(a)));
            set(&mut o, "scale", s.as_ref().map(|a| arr(a)));
        }
    }
    Value::Object(o)
}

fn prim(p: &Prim) -> Value {
    let mut attrs = Map::new();
    set(&mut attrs, "POSITION", p.position.as_ref().map(Idx::v));
    let mut o = Map::new();
    o.insert("attributes".into(), Value::Object(attrs));
    set(&mut o, "indices", p.indices.as_ref().map(Idx::v));
    set(&mut o, "mode", p.mode.map(|m| json!(m % 9)));
    Value::Object(o)
}

fn accessor(a: &Accessor) -> Value {
    let mut o = Map::new();
    set(&mut o, "bufferView", a.view.as_ref().map(Idx::v));
    set(&mut o, "byteOffset", a.offset.as_ref().map(Num::v));
    o.insert("componentType".into(), component(a.component));
    o.insert("count".into(), a.count.v());
    o.insert("type".into(), json!(TYPES[usize::from(a.ty) % TYPES.len()]));
    if a.normalized {
        o.insert("normalized".into(), json!(true));
    }
    if let Some(s) = &a.sparse {
        let side = |x: &SparseSide, with_type: bool| {
            let mut o = Map::new();
            o.insert("bufferView".into(), x.view.v());
            set(&mut o, "byteOffset", x.offset.as_ref().map(Num::v));
            if with_type {
                o.insert("componentType".into(), component(x.component));
            }
            Value::Object(o)
        };
        o.insert(
            "sparse".into(),
            json!({"count": s.count.v(), "indices": side(&s.indices, true), "values": side(&s.values, false)}),
        );
    }
    Value::Object(o)
}

fn view(v: &View) -> Value {
    let mut o = Map::new();
    o.insert("buffer".into(), v.buffer.v());
    set(&mut o, "byteOffset", v.offset.as_ref().map(Num::v));
    o.insert("byteLength".into(), v.length.v());
    set(&mut o, "byteStride", v.stride.map(|s| json!(s)));
    Value::Object(o)
}

/// A GLB container of `json` and a binary chunk.
fn glb(json: &[u8], bin: &[u8]) -> Vec<u8> {
    let mut j = json.to_vec();
    j.resize(j.len().div_ceil(4) * 4, b' ');
    let mut b = bin.to_vec();
    b.resize(b.len().div_ceil(4) * 4, 0);
    let total = (12 + 8 + j.len() + 8 + b.len()) as u32;
    let mut v = b"glTF".to_vec();
    for word in [2, total, j.len() as u32] {
        v.extend(word.to_le_bytes());
    }
    v.extend(b"JSON".iter().chain(&j));
    v.extend(
        (b.len() as u32)
            .to_le_bytes()
            .iter()
            .chain(b"BIN\0")
            .chain(&b),
    );
    v
}

/// The scratch folder: `g/` holds the glTF's neighbours, `outside.bin` lies beside it.
fn scratch() -> &'static PathBuf {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let d = std::env::temp_dir().join(format!("primdecomp-fuzz-gltf-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        let g = d.join("g");
        std::fs::create_dir_all(g.join("dir.bin")).unwrap();
        std::fs::create_dir_all(g.join("sub")).unwrap();
        let pattern: Vec<u8> = (0..4096u32).map(|i| (i * 7 + 3) as u8).collect();
        std::fs::write(d.join("outside.bin"), &pattern).unwrap();
        std::fs::write(g.join("b.bin"), &pattern).unwrap();
        std::fs::write(g.join("b.bin.bin"), &pattern).unwrap();
        std::fs::write(g.join("short.bin"), &pattern[..5]).unwrap();
        std::fs::write(g.join("b.bin".replace('.', "%2e")), &pattern[..64]).unwrap();
        std::os::unix::fs::symlink("/dev/zero", g.join("zero.bin")).unwrap();
        std::os::unix::fs::symlink("../outside.bin", g.join("up.bin")).unwrap();
        let ok = std::process::Command::new("mkfifo")
            .arg(g.join("pipe.bin"))
            .status();
        assert!(ok.is_ok_and(|s| s.success()), "mkfifo");
        d
    })
}

libfuzzer_sys::fuzz_target!(|doc: Doc| {
    let dir = scratch();
    let outside_abs = dir.join("outside.bin").to_string_lossy().into_owned();
    let (mut value, outside) = doc.json(&outside_abs);
    if doc.allow_external_uris {
        // Raw strings only as plain names, so they stay in the scratch folder.
        if let Some(Value::Array(bufs)) = value.get_mut("buffers") {
            for b in bufs.iter_mut() {
                if let Some(Value::String(u)) = b.get_mut("uri") {
                    if !u.starts_with("data:")
                        && !OUTSIDE.contains(&u.as_str())
                        && *u != outside_abs
                    {
                        u.retain(|c| c != '/' && c != '\\' && c != ':' && c != '%');
                    }
                }
            }
        }
    }
    let json = serde_json::to_vec(&value).unwrap();
    if std::env::var_os("PD_FUZZ_PRINT").is_some() {
        // How regression tests are written: the document and the options.
        eprintln!(
            "allow_external_uris: {}, glb: {}",
            doc.allow_external_uris,
            doc.glb.is_some()
        );
        eprintln!("{}", String::from_utf8_lossy(&json));
    }
    let (bytes, name, format) = match &doc.glb {
        Some(bin) => (glb(&json, bin), "t.glb", MeshFormat::Glb),
        None => (json, "t.gltf", MeshFormat::Gltf),
    };
    let path = dir.join("g").join(name);
    let options = LoadOptions {
        allow_external_uris: doc.allow_external_uris,
        ..LoadOptions::default()
    };
    match Mesh::parse_with(&bytes, format, &path, &options) {
        Ok(b) => {
            assert!(
                doc.allow_external_uris || !outside,
                "a buffer outside the folder was read without allow_external_uris"
            );
            parsed::check_mesh(&b);
        }
        Err(e) => {
            let msg = e.to_string();
            if let primdecomp::Error::Io { path: p, .. } = &e {
                // A failed read of an opened buffer file: not the input's fault.
                assert!(p.starts_with(dir), "{msg}");
                assert_eq!(e.exit_code(), 1, "{msg}");
            } else {
                assert!(msg.contains(name), "error does not name the file: {msg}");
                assert_eq!(e.exit_code(), 2, "bad input must be exit code 2: {msg}");
            }
        }
    }
});
