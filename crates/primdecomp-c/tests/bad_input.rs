//! Bad input across the C ABI, called as a C program calls it: mesh files in every
//! format cut short, bit-flipped and made of random bytes; arrays that lie about their
//! sizes; settings and export options of every wrong type and range; hostile names
//! for models, paths and inputs. Every call must return a status and a message, never
//! `PRIMDECOMP_STATUS_PANIC` (a caught panic is a bug too), and whatever is written
//! must be well formed for its format (the readers of `primdecomp_testkit::exports`).
//! Seeded: the same cases on every run.

use primdecomp_c::export::{primdecomp_bytes_free, primdecomp_result_export_to_memory};
use primdecomp_c::mesh::{
    primdecomp_mesh_free, primdecomp_mesh_from_doubles, primdecomp_mesh_from_floats,
    primdecomp_mesh_parse, primdecomp_mesh_set_path, PrimdecompMesh,
};
use primdecomp_c::result::{
    primdecomp_result_free, primdecomp_result_json, primdecomp_result_level_count,
    primdecomp_result_primitives, primdecomp_string_free, PrimdecompPrimitive, PrimdecompResult,
};
use primdecomp_c::run::primdecomp_decompose;
use primdecomp_c::status::{primdecomp_last_error, PrimdecompStatus};
use primdecomp_testkit::exports;
use primdecomp_testkit::shapes::{cuboid, cylinder, join, obj_text};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::ffi::{CStr, CString};
use std::ptr::{null, null_mut};

fn last_error() -> String {
    // SAFETY: never NULL, valid until the next call on this thread.
    unsafe { CStr::from_ptr(primdecomp_last_error()) }
        .to_string_lossy()
        .into_owned()
}

/// The status, after checking it is no panic and that a failure says why.
#[track_caller]
fn checked(s: PrimdecompStatus, what: &str) -> PrimdecompStatus {
    assert_ne!(s, PrimdecompStatus::Panic, "{what}: {}", last_error());
    if s != PrimdecompStatus::Ok {
        assert!(
            !last_error().is_empty(),
            "{what}: a failure without a message"
        );
    }
    s
}

fn parse(bytes: &[u8], name: &str) -> (PrimdecompStatus, *mut PrimdecompMesh) {
    let name = CString::new(name).unwrap();
    let mut m = null_mut();
    // SAFETY: valid pointers and lengths.
    let s = unsafe { primdecomp_mesh_parse(bytes.as_ptr(), bytes.len(), name.as_ptr(), &mut m) };
    (s, m)
}

fn decompose(
    m: *const PrimdecompMesh,
    settings: &str,
) -> (PrimdecompStatus, *mut PrimdecompResult) {
    let settings = CString::new(settings).unwrap();
    let mut r = null_mut();
    // SAFETY: a live mesh, a NUL-terminated string, an out-pointer.
    let s = unsafe { primdecomp_decompose(m, settings.as_ptr(), None, null_mut(), null(), &mut r) };
    (s, r)
}

/// Reads everything a result hands out, then frees it.
fn drain(r: *mut PrimdecompResult, what: &str) {
    // SAFETY: a live result; out-pointers to locals.
    unsafe {
        for level in 0..primdecomp_result_level_count(r) {
            let mut prims: *const PrimdecompPrimitive = null();
            let mut n = 0;
            checked(
                primdecomp_result_primitives(r, level, &mut prims, &mut n),
                what,
            );
            let mut text = null_mut();
            let mut len = 0;
            checked(primdecomp_result_json(r, level, &mut text, &mut len), what);
            let json = CStr::from_ptr(text).to_str().expect("UTF-8 JSON");
            let doc: serde_json::Value = serde_json::from_str(json)
                .unwrap_or_else(|e| panic!("{what}: the JSON does not parse: {e}"));
            assert_eq!(
                doc["primitives"].as_array().map(Vec::len),
                Some(n),
                "{what}"
            );
            primdecomp_string_free(text);
        }
        primdecomp_result_free(r);
    }
}

/// A small mesh with a part of two kinds, in every format the readers take.
fn seeds() -> Vec<(&'static str, Vec<u8>)> {
    let polys = join(&[cuboid([0.0; 3], [1.0, 2.0, 0.5]), cylinder(0.4, 1.0, 12)]);
    let (v, f) = &polys;
    let tris: Vec<[u32; 3]> = f
        .iter()
        .flat_map(|p| (1..p.len() - 1).map(move |k| [p[0], p[k], p[k + 1]]))
        .collect();
    let mut stl = vec![0u8; 80];
    stl.extend((tris.len() as u32).to_le_bytes());
    for t in &tris {
        stl.extend([0u8; 12]);
        for &i in t {
            for x in v[i as usize] {
                stl.extend((x as f32).to_le_bytes());
            }
        }
        stl.extend([0u8; 2]);
    }
    let header = |format: &str| {
        format!(
            "ply\nformat {format} 1.0\nelement vertex {}\nproperty float x\nproperty float y\n\
             property float z\nelement face {}\nproperty list uchar int vertex_indices\nend_header\n",
            v.len(),
            f.len()
        )
    };
    let mut ply_ascii = header("ascii");
    let mut ply_binary = header("binary_little_endian").into_bytes();
    let mut off = format!("OFF\n{} {} 0\n", v.len(), f.len());
    for p in v {
        ply_ascii += &format!("{} {} {}\n", p[0], p[1], p[2]);
        off += &format!("{} {} {}\n", p[0], p[1], p[2]);
        for x in p {
            ply_binary.extend((*x as f32).to_le_bytes());
        }
    }
    for face in f {
        let ids: Vec<String> = face.iter().map(u32::to_string).collect();
        ply_ascii += &format!("{} {}\n", face.len(), ids.join(" "));
        off += &format!("{} {}\n", face.len(), ids.join(" "));
        ply_binary.push(face.len() as u8);
        for &i in face {
            ply_binary.extend((i as i32).to_le_bytes());
        }
    }
    let (gltf, glb) = gltf_pair(v, &tris);
    vec![
        ("part.obj", obj_text(&polys).into_bytes()),
        ("part.stl", stl),
        ("part.ply", ply_ascii.into_bytes()),
        ("binary.ply", ply_binary),
        ("part.off", off.into_bytes()),
        ("part.gltf", gltf),
        ("part.glb", glb),
    ]
}

/// The triangles as a glTF (its buffer a `data:` URI) and as a GLB.
fn gltf_pair(v: &[[f64; 3]], tris: &[[u32; 3]]) -> (Vec<u8>, Vec<u8>) {
    let mut bin = Vec::new();
    let (mut lo, mut hi) = ([f32::MAX; 3], [f32::MIN; 3]);
    for p in v {
        for d in 0..3 {
            let x = p[d] as f32;
            lo[d] = lo[d].min(x);
            hi[d] = hi[d].max(x);
            bin.extend(x.to_le_bytes());
        }
    }
    let positions = bin.len();
    for t in tris {
        for &i in t {
            bin.extend(i.to_le_bytes());
        }
    }
    let doc = |uri: Option<String>| {
        let mut buffer = serde_json::json!({ "byteLength": bin.len() });
        if let Some(u) = uri {
            buffer["uri"] = u.into();
        }
        serde_json::json!({
            "asset": { "version": "2.0" },
            "scene": 0,
            "scenes": [{ "nodes": [0] }],
            "nodes": [{ "mesh": 0, "name": "part" }],
            "meshes": [{ "primitives": [{ "attributes": { "POSITION": 0 }, "indices": 1 }] }],
            "buffers": [buffer],
            "bufferViews": [
                { "buffer": 0, "byteOffset": 0, "byteLength": positions },
                { "buffer": 0, "byteOffset": positions, "byteLength": bin.len() - positions }
            ],
            "accessors": [
                { "bufferView": 0, "componentType": 5126, "count": v.len(), "type": "VEC3",
                  "min": lo, "max": hi },
                { "bufferView": 1, "componentType": 5125, "count": tris.len() * 3, "type": "SCALAR" }
            ]
        })
        .to_string()
    };
    let gltf = doc(Some(format!(
        "data:application/octet-stream;base64,{}",
        base64(&bin)
    )));
    let mut json = doc(None).into_bytes();
    while json.len() % 4 != 0 {
        json.push(b' ');
    }
    let mut glb = b"glTF".to_vec();
    glb.extend(2u32.to_le_bytes());
    glb.extend(((12 + 8 + json.len() + 8 + bin.len()) as u32).to_le_bytes());
    glb.extend((json.len() as u32).to_le_bytes());
    glb.extend(b"JSON");
    glb.extend(json);
    glb.extend((bin.len() as u32).to_le_bytes());
    glb.extend(b"BIN\0");
    glb.extend(&bin);
    (gltf.into_bytes(), glb)
}

fn base64(bytes: &[u8]) -> String {
    const A: &[u8] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::new();
    for c in bytes.chunks(3) {
        let n = (c[0] as u32) << 16
            | (*c.get(1).unwrap_or(&0) as u32) << 8
            | *c.get(2).unwrap_or(&0) as u32;
        for k in 0..4 {
            s.push(if k <= c.len() {
                A[(n >> (18 - 6 * k) & 63) as usize] as char
            } else {
                '='
            });
        }
    }
    s
}

/// `bytes` damaged one of several ways.
fn mutate(bytes: &[u8], rng: &mut ChaCha8Rng) -> Vec<u8> {
    let mut b = bytes.to_vec();
    match rng.gen_range(0..6) {
        0 => b.truncate(rng.gen_range(0..b.len())),
        1 => {
            for _ in 0..rng.gen_range(1..8) {
                let i = rng.gen_range(0..b.len());
                b[i] ^= 1 << rng.gen_range(0..8);
            }
        }
        2 => {
            // A digit or word somewhere replaced by an absurd number.
            let i = rng.gen_range(0..b.len());
            let n = [
                "4294967295",
                "-1",
                "99999999999999999999",
                "1e308",
                "nan",
                "0",
            ];
            b.splice(
                i..(i + 3).min(b.len()),
                n[rng.gen_range(0..n.len())].bytes(),
            );
        }
        3 => {
            // Four bytes of a binary count or offset made huge.
            let i = rng.gen_range(0..b.len().saturating_sub(4).max(1));
            let end = (i + 4).min(b.len());
            b[i..end].fill(0xff);
        }
        4 => {
            let i = rng.gen_range(0..b.len());
            let j = rng.gen_range(i..b.len());
            let piece = b[i..j].to_vec();
            b.splice(i..i, piece);
        }
        _ => b = (0..rng.gen_range(0..512)).map(|_| rng.gen()).collect(),
    }
    b
}

#[test]
fn damaged_files_in_every_format_are_refused_or_read() {
    let mut rng = ChaCha8Rng::seed_from_u64(0x0c_ab1);
    let mut read = 0;
    for (name, bytes) in seeds() {
        let (s, m) = parse(&bytes, name);
        assert_eq!(
            s,
            PrimdecompStatus::Ok,
            "{name}, undamaged: {}",
            last_error()
        );
        let (s, r) = decompose(m, r#"{"targets": [3]}"#);
        assert_eq!(s, PrimdecompStatus::Ok, "{name}: {}", last_error());
        drain(r, name);
        // SAFETY: made above, freed once.
        unsafe { primdecomp_mesh_free(m) };
        for case in 0..150 {
            let bad = mutate(&bytes, &mut rng);
            let what = format!("{name}, case {case}");
            let (s, m) = parse(&bad, name);
            match checked(s, &what) {
                PrimdecompStatus::Ok => {
                    read += 1;
                    let (s, r) = decompose(m, r#"{"targets": [4]}"#);
                    if checked(s, &what) == PrimdecompStatus::Ok {
                        drain(r, &what);
                    }
                    // SAFETY: made above, freed once.
                    unsafe { primdecomp_mesh_free(m) };
                }
                PrimdecompStatus::InvalidInput => assert!(m.is_null(), "{what}"),
                other => panic!("{what}: {other:?} {}", last_error()),
            }
        }
    }
    eprintln!("{read} of 1050 damaged files read and decomposed, the rest refused");
    // Some damage leaves a readable mesh (a flipped bit in a coordinate): both paths run.
    assert!(read > 20, "only {read} damaged files read");
}

#[test]
fn arrays_that_lie_are_refused() {
    let v = [
        0.0f64, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0,
    ];
    let vf: Vec<f32> = v.iter().map(|&x| x as f32).collect();
    let tris = [0u32, 1, 2, 0, 1, 3, 0, 2, 3, 1, 2, 3];
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let mut made = 0;
    for case in 0..400 {
        // At most the 4 vertices there are, or a count whose byte size no array can
        // have (refused before anything is read).
        let vertex_count = if rng.gen_bool(0.85) {
            [0, 1, 3, 4][rng.gen_range(0..4)]
        } else {
            [usize::MAX / 3 + 1, usize::MAX, isize::MAX as usize / 3][rng.gen_range(0..3)]
        };
        let mut idx = tris.to_vec();
        if rng.gen_bool(0.3) {
            let k = rng.gen_range(0..idx.len());
            idx[k] = [0, 3, 4, u32::MAX, 1 << 31][rng.gen_range(0..5)];
        }
        let index_count = if rng.gen_bool(0.6) {
            idx.len()
        } else {
            rng.gen_range(0..=idx.len())
        };
        let sizes: Vec<u32> = (0..[0, 0, 1, 2, 4][rng.gen_range(0..5)])
            .map(|_| [0, 1, 2, 3, 4, u32::MAX][rng.gen_range(0..6)])
            .collect();
        let mut positions = v;
        if rng.gen_bool(0.2) {
            positions[rng.gen_range(0..12)] =
                [f64::NAN, f64::INFINITY, -f64::INFINITY, 1e308][rng.gen_range(0..4)];
        }
        let vf_case: Vec<f32> = positions.iter().map(|&x| x as f32).collect();
        let what =
            format!("case {case}: {vertex_count} vertices, {index_count} indices, sizes {sizes:?}");
        let mut m = null_mut();
        // SAFETY: every pointer is valid for the length passed, or the length is one
        // no array can have and is refused before any read.
        let s = unsafe {
            if rng.gen_bool(0.5) {
                primdecomp_mesh_from_doubles(
                    positions.as_ptr(),
                    vertex_count,
                    idx.as_ptr(),
                    index_count,
                    if sizes.is_empty() {
                        null()
                    } else {
                        sizes.as_ptr()
                    },
                    sizes.len(),
                    &mut m,
                )
            } else {
                primdecomp_mesh_from_floats(
                    if rng.gen_bool(0.9) {
                        vf_case.as_ptr()
                    } else {
                        // Misaligned: refused before anything is read.
                        vf.as_ptr().cast::<u8>().wrapping_add(1).cast()
                    },
                    vertex_count,
                    idx.as_ptr(),
                    index_count,
                    if sizes.is_empty() {
                        null()
                    } else {
                        sizes.as_ptr()
                    },
                    sizes.len(),
                    &mut m,
                )
            }
        };
        if checked(s, &what) == PrimdecompStatus::Ok {
            made += 1;
            let (s, r) = decompose(m, "{}");
            if checked(s, &what) == PrimdecompStatus::Ok {
                drain(r, &what);
            }
            // SAFETY: made above, freed once.
            unsafe { primdecomp_mesh_free(m) };
        } else {
            assert!(m.is_null(), "{what}");
        }
    }
    eprintln!("{made} of 400 array cases made a mesh, the rest refused");
    assert!(
        made > 10 && made < 390,
        "{made} of 400 array cases made a mesh"
    );
}

/// A cube to decompose, from doubles.
fn cube() -> *mut PrimdecompMesh {
    let bytes = obj_text(&cuboid([0.0; 3], [1.0, 2.0, 3.0])).into_bytes();
    let (s, m) = parse(&bytes, "cube.obj");
    assert_eq!(s, PrimdecompStatus::Ok, "{}", last_error());
    m
}

#[test]
fn settings_of_every_wrong_type_and_range_are_refused_or_run() {
    let m = cube();
    let keys: Vec<String> = {
        let v: serde_json::Value =
            serde_json::to_value(primdecomp::Params::default()).expect("settings as JSON");
        v.as_object().expect("an object").keys().cloned().collect()
    };
    let values = [
        "null",
        "true",
        "-1",
        "0",
        "1",
        "3",
        "0.5",
        "1e308",
        "-1e308",
        "1e-320",
        "18446744073709551616",
        "\"\"",
        "\"x\"",
        "[]",
        "[0]",
        "[1e9]",
        "[-1]",
        "[{\"diagonal\": 2}]",
        "[{\"diagonal\": -0.1}]",
        "[{\"absolute\": 1e300}]",
        "{}",
        "[[1]]",
        "\"</script>\"",
    ];
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let mut ran = 0;
    for case in 0..300 {
        let mut fields = Vec::new();
        for _ in 0..rng.gen_range(1..3) {
            let k = &keys[rng.gen_range(0..keys.len())];
            fields.push(format!(
                "\"{k}\": {}",
                values[rng.gen_range(0..values.len())]
            ));
        }
        // Small runs only: the cube has 6 faces, but a huge count target is fine.
        let text = format!("{{{}}}", fields.join(", "));
        let (s, r) = decompose(m, &text);
        match checked(s, &text) {
            PrimdecompStatus::Ok => {
                ran += 1;
                drain(r, &text);
            }
            PrimdecompStatus::InvalidSettings => assert!(r.is_null(), "{text}"),
            other => panic!("case {case}, {text}: {other:?} {}", last_error()),
        }
    }
    for text in [
        "",
        "[",
        "{\"format\": \"primdecomp-result\"}",
        "{\"format\": 1, \"version\": 99}",
        "\u{1b}[31m",
        "{\"targets\": [3]} trailing",
    ] {
        let (s, _) = decompose(m, text);
        assert!(
            matches!(
                checked(s, text),
                PrimdecompStatus::InvalidSettings | PrimdecompStatus::Ok
            ),
            "{text:?}: {s:?}"
        );
    }
    eprintln!("{ran} of 300 random settings ran, the rest refused");
    assert!(ran > 10, "only {ran} random settings ran");
    // SAFETY: made above, freed once.
    unsafe { primdecomp_mesh_free(m) };
}

const HOSTILE: &[&str] = &[
    "</script><script>alert(1)</script>",
    "<!--",
    "a\"b'c<d>&e]]>",
    "\u{1}\u{8}\u{1b}[31mred\u{7f}",
    "line\nbreak\r\ttab",
    "../../../etc/passwd",
    "con",
    "",
    " ",
    "\u{fffe}\u{ffff}\u{d7ff}\u{e000}",
    "\u{2028}\u{2029}",
    "名前 🚀",
    "$(rm -rf ~)`x`",
];

#[test]
fn hostile_names_make_well_formed_exports_and_json() {
    let mut prims = cube();
    // A cylinder beside the box, so that curved kinds are written too.
    let polys = join(&[cuboid([0.0; 3], [1.0, 2.0, 0.5]), cylinder(0.4, 1.0, 16)]);
    let (s, m2) = parse(obj_text(&polys).as_bytes(), "parts.obj");
    assert_eq!(s, PrimdecompStatus::Ok);
    // SAFETY: made above, freed once.
    unsafe { primdecomp_mesh_free(prims) };
    prims = m2;
    let long = "x".repeat(5000);
    for name in HOSTILE.iter().copied().chain([long.as_str()]) {
        let path = CString::new(name.replace('\0', "")).unwrap();
        // SAFETY: a live mesh and a NUL-terminated string.
        checked(
            unsafe { primdecomp_mesh_set_path(prims, path.as_ptr()) },
            name,
        );
        let (s, r) = decompose(prims, r#"{"targets": [2]}"#);
        assert_eq!(checked(s, name), PrimdecompStatus::Ok);
        // The JSON records the path: it parses and gives it back.
        let mut text = null_mut();
        // SAFETY: a live result and an out-pointer.
        unsafe { checked(primdecomp_result_json(r, 0, &mut text, null_mut()), name) };
        // SAFETY: a string from the library, freed once.
        let json = unsafe { CStr::from_ptr(text) }
            .to_str()
            .unwrap()
            .to_string();
        unsafe { primdecomp_string_free(text) };
        let doc: serde_json::Value = serde_json::from_str(&json).unwrap();
        if !name.is_empty() {
            assert_eq!(doc["input"]["path"].as_str(), Some(name), "{json}");
        }
        for format in ["gltf", "glb", "mjcf", "urdf", "usda", "tscn", "obj", "json"] {
            let options = serde_json::json!({ "model": name, "preview": true }).to_string();
            let options = CString::new(options).unwrap();
            let f = CString::new(format).unwrap();
            let (mut out, mut len) = (null_mut(), 0);
            // SAFETY: a live result, NUL-terminated strings, out-pointers.
            let s = unsafe {
                primdecomp_result_export_to_memory(
                    r,
                    0,
                    f.as_ptr(),
                    options.as_ptr(),
                    &mut out,
                    &mut len,
                )
            };
            let what = format!("{format} of a model named {name:?}");
            if checked(s, &what) != PrimdecompStatus::Ok {
                // Only a URDF needing files beside it is refused in memory.
                assert!(
                    format == "urdf" && last_error().contains("export it to a path"),
                    "{what}: {}",
                    last_error()
                );
                continue;
            }
            // SAFETY: `len` bytes handed out by the library, freed once below.
            let bytes = unsafe { std::slice::from_raw_parts(out, len) }.to_vec();
            unsafe { primdecomp_bytes_free(out, len) };
            let text = || String::from_utf8(bytes.clone()).expect("UTF-8");
            let well_formed = match format {
                "gltf" | "glb" => exports::gltf(&bytes).map(drop),
                "mjcf" => exports::mjcf(&text()).map(drop),
                "urdf" => exports::urdf(&text()).map(drop),
                "usda" => exports::usda(&text()).map(drop),
                "tscn" => exports::tscn(&text()).map(drop),
                "json" => serde_json::from_str::<serde_json::Value>(&text())
                    .map(drop)
                    .map_err(|e| e.to_string()),
                // OBJ: text with a vertex.
                _ if text().contains("\nv ") => Ok(()),
                _ => Err("no vertex".into()),
            };
            if let Err(e) = well_formed {
                panic!("{what} is not well formed: {e}");
            }
        }
        // SAFETY: made above, freed once.
        unsafe { primdecomp_result_free(r) };
    }
    // SAFETY: made above, freed once.
    unsafe { primdecomp_mesh_free(prims) };
}
