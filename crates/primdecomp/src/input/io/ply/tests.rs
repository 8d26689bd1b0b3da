use super::*;

fn parse(s: &[u8]) -> Result<MeshBuilder> {
    parse_ply(s, Path::new("t.ply"))
}

fn err(s: &[u8]) -> String {
    parse(s).unwrap_err().to_string()
}

const ASCII: &str = "ply\nformat ascii 1.0\ncomment hi\nobj_info x\n\
    element vertex 4\nproperty float x\nproperty list uchar int junk\nproperty double y\n\
    property int z\nproperty uchar red\n\
    element face 2\nproperty list uchar int vertex_indices\nproperty float q\n\
    element edge 1\nproperty list int int stuff\nproperty int v1\n\
    end_header\n\
    0 2 7 7 0 1 9\n1 0 0 0 2\n1 1 5 1 1 3\n0 0 0 0 4\n\
    3 0 1 2 0.5\n4 0 1 2 3 0.25\n3 1 2 3 7\n";

#[test]
fn ascii_with_skipped_lists_and_elements() {
    let b = parse(ASCII.as_bytes()).unwrap();
    assert_eq!(
        b.positions,
        vec![
            [0.0, 0.0, 1.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 1.0],
            [0.0, 0.0, 0.0]
        ]
    );
    assert_eq!(b.face_count(), 2);
    assert_eq!(b.face_indices, vec![0, 1, 2, 0, 1, 2, 3]);
    let crlf = ASCII.replace('\n', "\r\n");
    assert_eq!(parse(crlf.as_bytes()).unwrap().face_indices, b.face_indices);
}

#[test]
fn ascii_errors_name_lines() {
    let lying = ASCII.replace("element edge 1", "element edge 2");
    let e = err(lying.as_bytes());
    assert!(e.contains("edge 1 of 2") && e.contains("t.ply:25:"), "{e}");
    let bad = ASCII.replace("3 0 1 2 0.5", "3 0 1 4 0.5");
    let e = err(bad.as_bytes());
    assert!(
        e.contains("t.ply:22:") && e.contains("face index 4 is out of range (file has 4 vertices)"),
        "{e}"
    );
    let bad = ASCII.replace("1 0 0 0 2", "1 0 zz 0 2");
    let e = err(bad.as_bytes());
    assert!(e.contains("t.ply:19:") && e.contains("'zz'"), "{e}");
    let bad = ASCII.replace("1 0 0 0 2", "1 0 nan 0 2");
    assert!(err(bad.as_bytes()).contains("not finite"));
    let bad = ASCII.replace("property int z", "property int w");
    assert!(err(bad.as_bytes()).contains("no 'z' property"));
    let bad = ASCII.replace("property float q", "property flot q");
    assert!(err(bad.as_bytes()).contains("t.ply:13:"));
}

/// A binary PLY with every scalar type on the vertex and a skipped list.
fn binary(be: bool, faces: u64, idx: &[i32]) -> Vec<u8> {
    let fmt = if be {
        "binary_big_endian"
    } else {
        "binary_little_endian"
    };
    let mut s = format!(
        "ply\nformat {fmt} 1.0\nelement vertex 3\nproperty int8 a\nproperty uint16 b\n\
         property float32 x\nproperty float64 y\nproperty short z\nproperty list ushort char n\n\
         property uint c\nelement face {faces}\nproperty list int uint vertex_index\nend_header\n"
    )
    .into_bytes();
    macro_rules! put {
        ($v:expr) => {
            s.extend_from_slice(&if be {
                $v.to_be_bytes()
            } else {
                $v.to_le_bytes()
            })
        };
    }
    for v in 0..3i16 {
        put!(-1i8);
        put!(7u16);
        put!(v as f32 + 0.5);
        put!(-(v as f64));
        put!(v * 100);
        put!(2u16);
        put!(1i8);
        put!(2i8);
        put!(9u32);
    }
    put!(idx.len() as i32);
    for &i in idx {
        put!(i as u32);
    }
    s
}

#[test]
fn binary_both_endians() {
    for be in [false, true] {
        let b = parse(&binary(be, 1, &[0, 1, 2])).unwrap();
        assert_eq!(b.positions[2], [2.5, -2.0, 200.0]);
        assert_eq!(b.face_indices, vec![0, 1, 2]);
    }
}

#[test]
fn binary_errors_carry_offsets() {
    let e = err(&binary(false, 2, &[0, 1, 2]));
    assert!(e.contains("at byte") && e.contains("face 1 of 2"), "{e}");
    let e = err(&binary(true, 1, &[0, 1, 3]));
    assert!(e.contains("face index 3 is out of range"), "{e}");
    let full = binary(false, 1, &[0, 1, 2]);
    let cut = &full[..full.len() - 2];
    let e = err(cut);
    let off = full.len() - 4;
    assert!(e.contains(&format!("at byte {off}:")), "{e}");
}

#[test]
fn short_faces_and_empty() {
    let s = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n3 0 1 2\n";
    let b = parse(s.as_bytes()).unwrap();
    assert_eq!((b.face_count(), b.skipped.short_faces), (1, 1));
    let verts_only = s.replace("element face 2", "element face 0");
    assert_eq!(parse(verts_only.as_bytes()).unwrap().face_count(), 0);
    assert_eq!(parse(b"").unwrap().face_count(), 0);
    assert!(err(b"plx\n").contains("not a PLY"));
    assert!(err(b"ply\nformat ascii 1.0\n").contains("end_header"));
    let no_props = "ply\nformat ascii 1.0\nelement x 999999999999999999\nend_header\n";
    assert_eq!(parse(no_props.as_bytes()).unwrap().face_count(), 0);
}

#[test]
fn garbage_never_panics() {
    let base = binary(false, 1, &[0, 1, 2]);
    let mut x: u32 = 12345;
    for n in 0..2000 {
        let mut v = base.clone();
        for _ in 0..(1 + n % 4) {
            x = x.wrapping_mul(1_103_515_245).wrapping_add(12345);
            let i = (x as usize >> 4) % v.len();
            v[i] = (x >> 24) as u8;
        }
        v.truncate(v.len() - (n % 7));
        let _ = parse(&v);
        let _ = parse(&ASCII.as_bytes()[..n % ASCII.len()]);
    }
}
