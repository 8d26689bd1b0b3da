//! Tests of the glTF reader: JSON with data URIs and node transforms, GLB and its
//! corruptions, scenes and node cycles, external buffers and the folder rule, sparse
//! accessors, and malformed files as errors naming the file.

use super::*;

/// 4 vertices (f32 xyz) then 6 u16 indices (two triangles).
fn bin() -> Vec<u8> {
    let pos = [0f32, 0., 0., 1., 0., 0., 1., 1., 0., 0., 1., 0.];
    let mut v: Vec<u8> = pos.iter().flat_map(|c| c.to_le_bytes()).collect();
    v.extend([0u16, 1, 2, 0, 2, 3].iter().flat_map(|i| i.to_le_bytes()));
    v
}

/// base64 of `bin()`, as a buffer `uri` member.
const DATA_URI: &str = r#""uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAACAPwAAgD8AAAAAAAAAAAAAgD8AAAAAAAABAAIAAAACAAMA","#;
const SCENE: &str = r#""scenes":[{"nodes":[0]}],"#;

/// A document over `bin()`: node 0 translates, node 1 scales and holds the mesh
/// (indexed triangles, points, strip, fan). `uri` is empty for GLB.
fn json(uri: &str, extra_nodes: &str, scene: &str) -> String {
    format!(
        r#"{{"asset":{{"version":"2.0"}},{scene}
        "nodes":[{{"translation":[10,0,0],"children":[1]}},{{"scale":[2,2,2],"mesh":0}}{extra_nodes}],
        "meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}},"indices":1}},
            {{"attributes":{{"POSITION":0}},"mode":0}},
            {{"attributes":{{"POSITION":0}},"mode":5}},
            {{"attributes":{{"POSITION":0}},"mode":6}}]}}],
        "buffers":[{{{uri}"byteLength":60}}],
        "bufferViews":[{{"buffer":0,"byteLength":48}},{{"buffer":0,"byteOffset":48,"byteLength":12}}],
        "accessors":[{{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3"}},
            {{"bufferView":1,"componentType":5123,"count":6,"type":"SCALAR"}}]}}"#
    )
}

fn glb(json: &str, bin: &[u8]) -> Vec<u8> {
    let mut j = json.as_bytes().to_vec();
    j.resize(j.len().div_ceil(4) * 4, b' ');
    let total = (28 + j.len() + bin.len()) as u32;
    let mut v = b"glTF".to_vec();
    for part in [
        &2u32.to_le_bytes(),
        &total.to_le_bytes(),
        &(j.len() as u32).to_le_bytes(),
    ] {
        v.extend_from_slice(part);
    }
    v.extend(
        b"JSON"
            .iter()
            .chain(&j)
            .chain(&(bin.len() as u32).to_le_bytes()),
    );
    v.extend(b"BIN\0".iter().chain(bin));
    v
}

fn parse(b: &[u8]) -> Result<MeshBuilder> {
    parse_gltf(b, Path::new("dir/t.gltf"))
}

fn err(b: &[u8]) -> String {
    parse(b).unwrap_err().to_string()
}

fn check_scene(b: &MeshBuilder) {
    // 3 triangle primitives × 4 vertices; the points primitive is skipped.
    assert_eq!((b.skipped.other, b.positions.len()), (1, 12));
    assert_eq!(b.positions[2], [12.0, 2.0, 0.0]);
    // 2 indexed triangles + 2 strip + 2 fan.
    let want = [0, 1, 2, 0, 2, 3, 4, 5, 6, 5, 7, 6, 8, 9, 10, 8, 10, 11];
    assert_eq!(b.face_indices, want);
}

#[test]
fn gltf_with_data_uri_and_transforms() {
    let j = json(DATA_URI, "", r#""scene":0,"scenes":[{"nodes":[0]}],"#);
    check_scene(&parse(j.as_bytes()).unwrap());
}

#[test]
fn glb_and_its_corruptions() {
    let g = glb(&json("", "", SCENE), &bin());
    check_scene(&parse(&g).unwrap());
    for cut in [1, 3, 11, 12, 19, 20, 40, g.len() - 1] {
        assert!(parse(&g[..cut]).is_err(), "cut {cut}");
    }
    let mut x: u32 = 7;
    for n in 0..3000 {
        let mut v = g.clone();
        x = x.wrapping_mul(1_103_515_245).wrapping_add(12345);
        let i = (x as usize >> 3) % v.len();
        v[i] = (x >> 23) as u8;
        if n % 3 == 0 {
            v[(x as usize >> 11) % 20] = (x >> 5) as u8;
        }
        let _ = parse(&v);
    }
}

#[test]
fn out_of_range_index_errors() {
    let mut b = bin();
    b[48 + 10] = 4;
    let e = err(&glb(&json("", "", ""), &b));
    assert!(
        e.contains("mesh 0 primitive 0: index 4 is out of range"),
        "{e}"
    );
}

#[test]
fn no_scene_adds_each_mesh_once() {
    let b = parse(json(DATA_URI, "", "").as_bytes()).unwrap();
    assert_eq!((b.positions[2], b.face_count()), ([1.0, 1.0, 0.0], 6));
}

#[test]
fn cycles_and_shared_nodes_error() {
    let cyc = json(
        DATA_URI,
        r#",{"children":[2]}"#,
        r#""scenes":[{"nodes":[0,2]}],"#,
    );
    assert!(err(cyc.as_bytes()).contains("node 2 is reached twice"));
    let shared = json(DATA_URI, "", r#""scenes":[{"nodes":[0,1]}],"#);
    assert!(err(shared.as_bytes()).contains("node 1"));
}

#[test]
fn external_buffer_relative_to_file() {
    let dir = std::env::temp_dir().join(format!("primdecomp-gltf-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("my data.bin"), bin()).unwrap();
    let j = json(r#""uri":"my%20data.bin","#, "", SCENE);
    let b = parse_gltf(j.as_bytes(), &dir.join("t.gltf"));
    std::fs::remove_dir_all(&dir).unwrap();
    check_scene(&b.unwrap());
    assert!(err(j.as_bytes()).contains("dir/my data.bin"));
}

/// A scratch folder holding `bin()` as `b.bin`, removed on drop.
struct Scratch(PathBuf);

impl Scratch {
    fn new(tag: &str) -> Scratch {
        let d = std::env::temp_dir().join(format!("primdecomp-gltf-{tag}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(d.join("sub")).unwrap();
        std::fs::write(d.join("b.bin"), bin()).unwrap();
        Scratch(d)
    }

    /// Parses the test document with buffer URI `uri`, as `sub/t.gltf`.
    fn parse(&self, uri: &str, allow: bool) -> Result<MeshBuilder> {
        let j = json(&format!(r#""uri":"{uri}","#), "", SCENE);
        let options = LoadOptions {
            allow_external_uris: allow,
            ..LoadOptions::default()
        };
        parse_gltf_with(j.as_bytes(), &self.0.join("sub/t.gltf"), &options)
    }

    fn err(&self, uri: &str, allow: bool) -> String {
        let e = self.parse(uri, allow).unwrap_err();
        assert_eq!(e.exit_code(), 2, "{e}");
        e.to_string()
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// By default only files inside the glTF's folder are read: absolute paths, `..`
/// (also %-encoded), symbolic links leading out and file: URLs are refused, each
/// naming the URI; with the option they are read. Other schemes never are.
#[cfg(unix)]
#[test]
fn uris_outside_the_folder_need_the_option() {
    let s = Scratch::new("outside");
    let abs = s.0.join("b.bin");
    let abs = abs.to_str().unwrap();
    std::os::unix::fs::symlink("../b.bin", s.0.join("sub/up.bin")).unwrap();
    std::fs::write(s.0.join("sub/in.bin"), bin()).unwrap();
    let url = format!("file://{abs}");
    let cases = [
        (abs, "is an absolute path"),
        ("../b.bin", "climbs out of the glTF's folder with '..'"),
        ("%2e%2e/b.bin", "climbs out of the glTF's folder with '..'"),
        (
            "up.bin",
            "leads out of the glTF's folder through a symbolic link",
        ),
        (url.as_str(), "is a file: URL"),
    ];
    for (uri, why) in cases {
        let e = s.err(uri, false);
        assert!(
            e.contains(&format!("buffer 0: the URI '{uri}' {why}")),
            "{e}"
        );
        assert!(e.contains("--allow-external-uris"), "{e}");
        check_scene(&s.parse(uri, true).unwrap());
    }
    check_scene(&s.parse("in.bin", false).unwrap());
    check_scene(&s.parse("./in.bin", false).unwrap());
    for uri in ["http://example.com/b.bin", "C:b.bin"] {
        for allow in [false, true] {
            assert!(s.err(uri, allow).contains("which is never read"), "{uri}");
        }
    }
    let e = s.err("data:application/octet-stream;base64,@@@", false);
    assert!(e.contains("is a data URI without valid base64 data"), "{e}");
}

/// A buffer file must be a regular file holding its declared length; only that
/// many bytes are read; a pipe or device is refused before any read (a read of
/// either would block or never end).
#[cfg(unix)]
#[test]
fn buffer_files_are_regular_and_no_longer_than_declared() {
    let s = Scratch::new("regular");
    let sub = s.0.join("sub");
    std::fs::write(sub.join("short.bin"), &bin()[..40]).unwrap();
    let e = s.err("short.bin", false);
    assert!(
        e.contains("which holds 40 bytes; the buffer declares 60"),
        "{e}"
    );
    let mut long = bin();
    long.extend([0xAB; 1000]);
    std::fs::write(sub.join("long.bin"), long).unwrap();
    check_scene(&s.parse("long.bin", false).unwrap());
    let fifo = std::ffi::CString::new(sub.join("pipe.bin").to_str().unwrap()).unwrap();
    assert_eq!(unsafe { libc::mkfifo(fifo.as_ptr(), 0o644) }, 0);
    std::fs::create_dir(sub.join("dir.bin")).unwrap();
    std::os::unix::fs::symlink("/dev/zero", sub.join("zero.bin")).unwrap();
    let kinds = [
        (
            "pipe.bin",
            false,
            "is a named pipe (FIFO), not a regular file",
        ),
        ("dir.bin", false, "is a directory, not a regular file"),
        (
            "zero.bin",
            true,
            "is a character device, not a regular file",
        ),
        (
            "/dev/zero",
            true,
            "is a character device, not a regular file",
        ),
    ];
    for (uri, allow, want) in kinds {
        let e = s.err(uri, allow);
        assert!(
            e.contains(&format!("the URI '{uri}' names ")) && e.contains(want),
            "{e}"
        );
    }
    let e = s.err("missing.bin", false);
    assert!(
        e.contains("missing.bin, which cannot be opened: no such file"),
        "{e}"
    );
}

#[test]
fn uris_in_messages_are_escaped_and_cut() {
    assert_eq!(show_uri("a\nb"), "a\\nb");
    let long = "x".repeat(100);
    assert_eq!(show_uri(&long), format!("{}…", "x".repeat(80)));
    assert_eq!(uri_scheme("HTTP://x"), Some("HTTP"));
    assert_eq!(uri_scheme("1:x"), None);
    assert_eq!(uri_scheme("a/b:c"), None);
}

#[test]
fn sparse_and_short_buffers() {
    // Sparse: vertex 2 becomes (5,5,5); index view holds u16 2, value view 3 f32.
    let mut b = bin();
    b.extend(
        [2u8, 0, 0, 0]
            .iter()
            .chain(&[5f32; 3].map(f32::to_le_bytes).concat()),
    );
    let j = json("", "", "")
        .replace(r#""byteLength":60}]"#, r#""byteLength":76}]"#)
        .replace(r#""byteLength":12}]"#, r#""byteLength":12},{"buffer":0,"byteOffset":60,"byteLength":2},{"buffer":0,"byteOffset":64,"byteLength":12}]"#)
        .replace(r#""count":4,"type":"VEC3"}"#, r#""count":4,"type":"VEC3","sparse":{"count":1,"indices":{"bufferView":2,"componentType":5123},"values":{"bufferView":3}}}"#);
    assert_eq!(parse(&glb(&j, &b)).unwrap().positions[2], [5.0, 5.0, 5.0]);
    let e = err(&glb(&json("", "", ""), &b[..40]));
    assert!(e.contains("buffer 0 declares 60 bytes"), "{e}");
}

#[test]
fn empty_and_invalid() {
    assert_eq!(parse(b"").unwrap().face_count(), 0);
    assert!(err(b"{not json").contains("invalid glTF JSON"));
    assert_eq!(
        parse(br#"{"asset":{"version":"2.0"}}"#)
            .unwrap()
            .face_count(),
        0
    );
    let base = json(DATA_URI, "", "");
    let f32_idx = base.replace(r#""componentType":5123"#, r#""componentType":5126"#);
    assert!(err(f32_idx.as_bytes()).contains("indices must be"));
    let ext = r#""extensionsRequired":["KHR_draco_mesh_compression"],"asset""#;
    assert!(err(base.replace("\"asset\"", ext).as_bytes()).contains("draco"));
    let dangling = base.replace(r#"{"POSITION":0},"mode":6"#, r#"{"POSITION":9},"mode":6"#);
    assert!(err(dangling.as_bytes()).contains("accessor 9 does not exist"));
}
