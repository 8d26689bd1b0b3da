//! Arbitrary bytes through the memory-mapped loader, `primdecomp::Mesh::load_with` (which
//! holds the crate's one `unsafe` block, `memmap2::Mmap::map`): the bytes are written
//! to a temporary file under each text/binary extension in turn, then mapped and
//! parsed. The parser targets feed `parse_mesh` in-memory slices; this one checks the
//! mapped path under AddressSanitizer (cargo-fuzz's default), and given corpus files
//! as inputs (`load_mmap FILE...`) it maps real meshes. glTF is left out: its external
//! buffer URIs would read other files. Invariants: no panic; an error names the file
//! and has exit code 2 (bad input) or 1 (I/O); a success has at least one face.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let dir = std::env::temp_dir().join(format!("primdecomp-load-mmap-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temporary directory");
    for ext in ["obj", "ply", "stl", "off"] {
        let path = dir.join(format!("input.{ext}"));
        std::fs::write(&path, data).expect("temporary file");
        let options = primdecomp::LoadOptions {
            max_memory: Some(1 << 30),
            ..Default::default()
        };
        match primdecomp::Mesh::load_with(&path, &options) {
            Ok(mesh) => assert!(mesh.face_count() > 0, "a mesh without faces was accepted"),
            Err(e) => {
                let text = e.to_string();
                assert!(text.contains(&*path.to_string_lossy()), "{text}");
                assert!(matches!(e.exit_code(), 1 | 2), "{text}");
            }
        }
    }
});
