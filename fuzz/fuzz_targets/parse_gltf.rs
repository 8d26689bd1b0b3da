//! Fuzzes the glTF/GLB reader through `parse_bytes` (one reader serves both; it
//! tells them apart by the `glTF` magic; see `parsed.rs` for what is checked).
#![no_main]

#[path = "parsed.rs"]
mod parsed;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    parsed::check(data, primdecomp::MeshFormat::Glb, "fuzz.glb");
});
