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

/// `f` on a rayon pool of `threads` threads.
fn in_pool<R: Send>(threads: usize, f: impl FnOnce() -> R + Send) -> R {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("thread pool")
        .install(f)
}

/// ASCII data read by lines in parallel, in blocks of a few bytes (so that blocks
/// end on every line), gives what the serial reader gives wherever each element is
/// alone on its line, and leaves to the serial reader (`None`) whatever is not: two
/// elements on a line, one across lines, a blank line among them, a line too short
/// or too long, a bad token, an index out of range, data that ends early. Through
/// `parse_ply`, one thread and two give the same result or the same error.
#[test]
fn ascii_by_lines_reads_as_the_serial_reader() {
    let strips = ASCII.replace("element edge 1", "element tristrips 1");
    let regular = [
        ASCII.to_string(),
        ASCII.replace('\n', "\r\n"),
        ASCII.trim_end().to_string(),
        format!("{ASCII}trailing words after the data\n\n"),
        ASCII.replace("3 0 1 2 0.5", "2 0 1 0.5"),
        strips,
    ];
    let irregular = [
        ASCII.replace("0 0 0 0 4\n3 0 1 2 0.5", "0 0 0 0 4 3 0 1 2 0.5\n"),
        ASCII.replace("1 0 0 0 2\n", "1 0 0\n0 2\n"),
        ASCII.replace("1 0 0 0 2\n", "1 0 0 0 2\n\n"),
        ASCII.replace("1 0 0 0 2\n", "1 0 0 0 2 6\n"),
        ASCII.replace("1 0 0 0 2\n", "1 0 x 0 2\n"),
        ASCII.replace("3 0 1 2 0.5", "3 0 1 9 0.5"),
        ASCII.replace("\n3 1 2 3 7\n", "\n"),
        {
            let (head, data) = ASCII.split_at(ASCII.find("end_header\n").unwrap() + 11);
            format!("{head}{}", data.replace('\n', "\r"))
        },
    ];
    for (text, fits) in
        (regular.iter().map(|t| (t, true))).chain(irregular.iter().map(|t| (t, false)))
    {
        let bytes = text.as_bytes();
        let h = parse_header(bytes, Path::new("t.ply")).unwrap();
        for block in [1, 7, 64, 1 << 20] {
            let got = in_pool(2, || {
                ascii_by_lines(bytes, &h, Path::new("t.ply"), (0, block))
            });
            assert_eq!(got.is_some(), fits, "{text:?}, blocks of {block}");
            if let Some(got) = got {
                let want = in_pool(1, || parse(bytes)).unwrap();
                assert_eq!(got.positions, want.positions, "{text:?}");
                assert_eq!(got.face_offsets, want.face_offsets, "{text:?}");
                assert_eq!(got.face_indices, want.face_indices, "{text:?}");
                assert_eq!(got.skipped, want.skipped, "{text:?}");
            }
        }
        // Below the size where it pays, or on one thread, the serial reader reads it.
        assert!(in_pool(2, || ascii_by_lines(
            bytes,
            &h,
            Path::new("t.ply"),
            (1 << 20, 64)
        ))
        .is_none());
        assert!(in_pool(1, || ascii_by_lines(bytes, &h, Path::new("t.ply"), (0, 64))).is_none());
    }
}

/// A mesh large enough for `parse_ply` to read it by lines on two threads loads as on
/// one: the same positions and faces.
#[test]
fn large_ascii_reads_alike_on_one_thread_and_two() {
    let n = 160u32;
    let mut text = format!(
        "ply\nformat ascii 1.0\nelement vertex {}\nproperty float x\nproperty float y\n\
         property float z\nelement face {}\nproperty list uchar int vertex_indices\nend_header\n",
        (n + 1) * (n + 1),
        2 * n * n
    );
    for j in 0..=n {
        for i in 0..=n {
            text += &format!("{}.{} {}.25 -{}e-3\n", i, j % 10, j, (i * j) % 97);
        }
    }
    for j in 0..n {
        for i in 0..n {
            let v = j * (n + 1) + i;
            text += &format!(
                "3 {} {} {}\n3 {} {} {}\n",
                v,
                v + 1,
                v + n + 2,
                v,
                v + n + 2,
                v + n + 1
            );
        }
    }
    assert!(text.len() > BY_LINES_MIN);
    let bytes = text.as_bytes();
    let h = parse_header(bytes, Path::new("t.ply")).unwrap();
    let by_lines = in_pool(2, || {
        ascii_by_lines(bytes, &h, Path::new("t.ply"), (0, 4096))
    });
    assert!(by_lines.is_some());
    let (one, two) = (
        in_pool(1, || parse(bytes)).unwrap(),
        in_pool(2, || parse(bytes)).unwrap(),
    );
    assert_eq!(one.positions.len(), ((n + 1) * (n + 1)) as usize);
    assert_eq!(one.face_count(), (2 * n * n) as usize);
    assert_eq!(one.positions, two.positions);
    assert_eq!(one.face_offsets, two.face_offsets);
    assert_eq!(one.face_indices, two.face_indices);
}
