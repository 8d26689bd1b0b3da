//! Hostile input through the real binary: every case either succeeds or fails with exit
//! code 2 and a message naming the file (and the line or byte offset), and a failing
//! run never creates or modifies its output file.

use std::path::{Path, PathBuf};
use std::process::Command;

/// What a case must produce.
enum Want {
    /// Exit 0 and a result file.
    Ok,
    /// Exit 2, stderr containing each of these fragments (the file name is always checked).
    Err(&'static [&'static str]),
}

fn run_case(dir: &Path, name: &str, bytes: &[u8], want: Want) {
    let input = dir.join(name);
    std::fs::write(&input, bytes).unwrap();
    let out = dir.join(format!("{name}.json"));
    std::fs::write(&out, b"previous result").unwrap();
    let res = Command::new(env!("CARGO_BIN_EXE_primdecomp"))
        .args([
            "decompose",
            input.to_str().unwrap(),
            "-n",
            "4",
            "--quiet",
            "-o",
            out.to_str().unwrap(),
        ])
        .output()
        .expect("runs");
    let stderr = String::from_utf8_lossy(&res.stderr);
    match want {
        Want::Ok => {
            assert_eq!(res.status.code(), Some(0), "{name}: {stderr}");
            let json = std::fs::read_to_string(&out).unwrap();
            assert!(json.contains("\"format\": \"primdecomp\""), "{name}");
            assert!(
                !json.contains("NaN") && !json.contains("null,\n      \"rotation"),
                "{name}"
            );
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
            assert!(!stderr.contains("panicked"), "{name}: {stderr}");
            assert_eq!(
                std::fs::read(&out).unwrap(),
                b"previous result",
                "{name}: output touched"
            );
        }
    }
    let leftovers: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.to_string_lossy().contains(".tmp"))
        .collect();
    assert!(
        leftovers.is_empty(),
        "{name}: temporary files left: {leftovers:?}"
    );
}

fn binary_stl(tris: u32, declared: u32) -> Vec<u8> {
    let mut b = vec![0u8; 80];
    b.extend_from_slice(&declared.to_le_bytes());
    for t in 0..tris {
        b.extend_from_slice(&[0u8; 12]);
        for v in [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, t as f32]] {
            v.iter().for_each(|c| b.extend_from_slice(&c.to_le_bytes()));
        }
        b.extend_from_slice(&[0u8; 2]);
    }
    b
}

fn binary_ply(declared_faces: u32, faces: u32) -> Vec<u8> {
    let mut b = format!(
        "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face {declared_faces}\nproperty list uchar int vertex_indices\nend_header\n"
    )
    .into_bytes();
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

const TRI: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

#[test]
fn hostile_inputs_table() {
    let dir = tempdir();
    let big_ngon: String = {
        let n = 100_000;
        let mut s = String::new();
        for i in 0..n {
            let a = i as f64 / n as f64 * std::f64::consts::TAU;
            s += &format!("v {} {} 0\n", a.cos(), a.sin());
        }
        s += "f";
        for i in 1..=n {
            s += &format!(" {i}");
        }
        s + "\n"
    };
    let cases: Vec<(&str, Vec<u8>, Want)> = vec![
        ("empty.obj", vec![], Want::Err(&["no polygon faces"])),
        (
            "comments.obj",
            b"# nothing\n# here\n".to_vec(),
            Want::Err(&["no polygon faces"]),
        ),
        (
            "vertices_only.obj",
            TRI.as_bytes().to_vec(),
            Want::Err(&["no polygon faces"]),
        ),
        (
            "nan.obj",
            b"v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n".to_vec(),
            Want::Err(&[":1:"]),
        ),
        (
            "inf.obj",
            b"v 0 0 0\nv inf 0 0\nv 0 1 0\nf 1 2 3\n".to_vec(),
            Want::Err(&[":2:"]),
        ),
        (
            "index_range.obj",
            format!("{TRI}f 1 2 9\n").into_bytes(),
            Want::Err(&[":4:", "9"]),
        ),
        (
            "index_zero.obj",
            format!("{TRI}f 0 1 2\n").into_bytes(),
            Want::Err(&[":4:"]),
        ),
        (
            "negative_ok.obj",
            format!("{TRI}f -3 -2 -1\n").into_bytes(),
            Want::Ok,
        ),
        (
            "negative_bad.obj",
            format!("{TRI}f -1 -2 -4\n").into_bytes(),
            Want::Err(&[":4:"]),
        ),
        (
            "short_faces.obj",
            format!("{TRI}f 1 2\nl 1 2 3\n").into_bytes(),
            Want::Err(&["no polygon faces"]),
        ),
        (
            "degenerate.obj",
            format!("{TRI}f 1 1 2\nf 1 2 3\nf 1 2 3\n").into_bytes(),
            Want::Ok,
        ),
        (
            "collinear.obj",
            b"v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n".to_vec(),
            Want::Ok,
        ),
        ("ngon_100k.obj", big_ngon.into_bytes(), Want::Ok),
        (
            "crlf.obj",
            b"v 0 0 0\r\nv 1 0 0\rv 0 1 0\nf 1 2 3\r\n".to_vec(),
            Want::Ok,
        ),
        (
            "latin1.obj",
            b"# caf\xe9\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n".to_vec(),
            Want::Ok,
        ),
        (
            "bad_number.obj",
            b"v 0 0 0\nv 1 \xff 0\nv 0 1 0\nf 1 2 3\n".to_vec(),
            Want::Err(&[":2:"]),
        ),
        (
            "huge.obj",
            b"v 0 0 0\nv 1e38 0 0\nv 0 1e38 0\nf 1 2 3\n".to_vec(),
            Want::Ok,
        ),
        (
            "gzip.obj",
            vec![0x1f, 0x8b, 8, 0, 0, 0, 0, 0],
            Want::Err(&["gzip"]),
        ),
        (
            "mesh.xyz",
            TRI.as_bytes().to_vec(),
            Want::Err(&["unknown extension"]),
        ),
        (
            "truncated.stl",
            binary_stl(3, 3)[..150].to_vec(),
            Want::Err(&["byte"]),
        ),
        ("lying_count.stl", binary_stl(2, 5), Want::Err(&["byte"])),
        ("ok.stl", binary_stl(2, 2), Want::Ok),
        ("lying_count.ply", binary_ply(4, 1), Want::Err(&["byte"])),
        ("ok.ply", binary_ply(1, 1), Want::Ok),
        (
            "truncated.glb",
            b"glTF\x02\x00\x00\x00\x00\x10\x00\x00".to_vec(),
            Want::Err(&[]),
        ),
        (
            "lying.off",
            b"OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n".to_vec(),
            Want::Err(&[":6:", "ends after 1 of 2 faces"]),
        ),
    ];
    for (name, bytes, want) in cases {
        run_case(&dir, name, &bytes, want);
    }
    // A directory given as the input.
    let sub = dir.join("a_directory.obj");
    std::fs::create_dir_all(&sub).unwrap();
    let res = Command::new(env!("CARGO_BIN_EXE_primdecomp"))
        .args([
            "decompose",
            sub.to_str().unwrap(),
            "-o",
            dir.join("d.json").to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert_eq!(res.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&res.stderr).contains("is a directory"));
    assert!(!dir.join("d.json").exists());
}

fn tempdir() -> PathBuf {
    let d = std::env::temp_dir().join(format!("primdecomp-bad-input-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}
