//! Shared oracle of the parser targets: `parse_mesh` never panics, an error names
//! the file, and a successful parse is a well-formed mesh (every polygon has ≥ 3
//! corners, every index in range, every coordinate finite, and the re-centred mesh
//! finite too).

use primdecomp::{Mesh, MeshFormat};
use std::path::Path;

#[allow(dead_code)] // gltf_structured calls check_mesh only
pub fn check(data: &[u8], format: MeshFormat, name: &str) {
    // A directory that does not exist: a .gltf naming an external buffer gets an
    // error instead of reading files from the fuzzing machine.
    let path = Path::new("/nonexistent-primdecomp-fuzz").join(name);
    let mesh = match Mesh::parse(data, format, &path) {
        Ok(m) => m,
        Err(e) => {
            let msg = e.to_string();
            assert!(msg.contains(name), "error does not name the file: {msg}");
            assert_eq!(e.exit_code(), 2, "bad input must be exit code 2: {msg}");
            return;
        }
    };
    check_mesh(&mesh);
}

/// A parsed mesh is well formed: polygons of ≥ 3 corners, indices in range, every
/// coordinate (local and world) and the centre finite.
pub fn check_mesh(mesh: &Mesh) {
    let n = mesh.vertex_count();
    for f in 0..mesh.face_count() {
        let face = mesh.face(f);
        assert!(face.len() >= 3, "a face with fewer than 3 corners");
        assert!(face.iter().all(|&i| (i as usize) < n));
    }
    let finite = |p: [f64; 3]| p.iter().all(|c| c.is_finite());
    assert!(finite(mesh.centre()), "{:?}", mesh.centre());
    for v in 0..n as u32 {
        assert!(finite(mesh.pos(v)) && finite(mesh.world_pos(v)));
    }
}
