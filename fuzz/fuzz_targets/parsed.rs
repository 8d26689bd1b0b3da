//! Shared oracle of the parser targets: `parse_bytes` never panics, an error names
//! the file, and a successful parse is a well-formed mesh (CSR offsets consistent,
//! every polygon has ≥ 3 corners, every index in range, every coordinate finite, and
//! the re-centred mesh finite too).

use primdecomp::mesh::io::{parse_bytes, Format};
use primdecomp::mesh::MeshBuilder;
use primdecomp::Mesh;
use std::path::Path;

#[allow(dead_code)] // gltf_structured calls check_builder only
pub fn check(data: &[u8], format: Format, name: &str) {
    // A directory that does not exist: a .gltf naming an external buffer gets an
    // error instead of reading files from the fuzzing machine.
    let path = Path::new("/nonexistent-primdecomp-fuzz").join(name);
    let b = match parse_bytes(data, format, &path) {
        Ok(b) => b,
        Err(e) => {
            let msg = e.to_string();
            assert!(msg.contains(name), "error does not name the file: {msg}");
            assert_eq!(e.exit_code(), 2, "bad input must be exit code 2: {msg}");
            return;
        }
    };
    check_builder(b);
}

/// A parsed mesh is well formed, and so is its re-centred [`Mesh`].
pub fn check_builder(b: MeshBuilder) {
    let n = b.positions.len();
    assert_eq!(b.face_offsets.first(), Some(&0));
    assert_eq!(
        *b.face_offsets.last().unwrap() as usize,
        b.face_indices.len()
    );
    for w in b.face_offsets.windows(2) {
        assert!(w[1] >= w[0] + 3, "a face with fewer than 3 corners");
    }
    assert!(b.face_indices.iter().all(|&i| (i as usize) < n));
    assert!(b.positions.iter().flatten().all(|c| c.is_finite()));
    let mesh = Mesh::from_builder(b);
    assert!(
        mesh.offset.iter().all(|c| c.is_finite()),
        "{:?}",
        mesh.offset
    );
    let finite = |v: &[f64]| v.iter().all(|c| c.is_finite());
    assert!(finite(&mesh.x) && finite(&mesh.y) && finite(&mesh.z));
}
