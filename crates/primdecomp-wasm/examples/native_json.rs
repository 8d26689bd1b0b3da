//! The CLI's JSON for a mesh file and settings, from a native build: built for
//! `x86_64-unknown-linux-musl` it shows that the WebAssembly package's primitives are
//! the native code's, bit for bit, once both use musl's math library
//! (docs/decisions/limits-wasm-libm.md; `bench/speed.mjs --musl`).
//!
//! `native_json MESH SETTINGS_JSON OUT.json`

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let [_, mesh, settings, out] = args.as_slice() else {
        return Err("usage: native_json MESH SETTINGS_JSON OUT.json".into());
    };
    let params = primdecomp::Params::from_json(settings)?;
    let mut dec = primdecomp::decompose(&primdecomp::load(mesh.as_ref())?, &params)?;
    dec.input.path = Some(mesh.clone());
    std::fs::write(out, primdecomp::to_json(&dec, 0, &params))?;
    Ok(())
}
