//! The CLI's JSON for a mesh file and settings from a native build of the library,
//! and the time each decomposition took: `bench/speed.mjs` times the native code on
//! one thread against the WebAssembly package with it (RAYON_NUM_THREADS=1, warm,
//! in one process like the package's calls), and built for
//! `x86_64-unknown-linux-musl` it shows that the package's primitives are the native
//! code's, bit for bit, once both use musl's math library
//! (docs/decisions/limits-wasm-libm.md).
//!
//! `native_json MESH SETTINGS_JSON OUT.json [REPEAT]`: decomposes REPEAT times (1 by
//! default), writes the last result and prints each run's seconds, one a line.

use std::time::Instant;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let (mesh, settings, out, repeat) = match args.as_slice() {
        [_, m, s, o] => (m, s, o, 1),
        [_, m, s, o, r] => (m, s, o, r.parse::<usize>()?.max(1)),
        _ => return Err("usage: native_json MESH SETTINGS_JSON OUT.json [REPEAT]".into()),
    };
    let params = primdecomp::Params::from_json(settings)?;
    let loaded = primdecomp::Mesh::load(mesh.as_ref())?;
    let mut last = None;
    for _ in 0..repeat {
        let start = Instant::now();
        let dec = primdecomp::decompose(&loaded, &params)?;
        println!("{}", start.elapsed().as_secs_f64());
        last = Some(dec);
    }
    let mut dec = last.expect("at least one run");
    dec.input.path = Some(mesh.clone());
    std::fs::write(out, dec.to_json(0, &params))?;
    Ok(())
}
