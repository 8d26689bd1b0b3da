//! Fuzzes the OBJ reader through `parse_bytes` (see `parsed.rs` for what is checked).
#![no_main]

#[path = "parsed.rs"]
mod parsed;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    parsed::check(data, primdecomp::MeshFormat::Obj, "fuzz.obj");
});
