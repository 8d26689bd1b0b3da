//! primdecomp for JavaScript: the core library compiled to WebAssembly
//! (`wasm32-unknown-unknown`, one thread: rayon runs its work on the calling thread)
//! with wasm-bindgen. This is the low-level half; `npm/index.js` is the package's
//! API (`decompose(vertices, indices, settings)`, typed primitives, `toJSON()`,
//! `toGltf()`), and `build.sh` lays both out as an npm package.
//!
//! - [`mesh::WasmMesh`]: a mesh parsed from a file's bytes with the core's readers
//!   (OBJ, PLY, STL, OFF, glTF, GLB) or built from vertex and index arrays;
//! - [`run::decompose`]: the settings as the JSON a result file carries, progress to
//!   a JavaScript callback that may cancel;
//! - [`result::WasmResult`]: the CLI's JSON, every export, and the tessellation the
//!   live page draws.
//!
//! Errors become JavaScript `Error`s with the core's message. A panic (a bug) cannot
//! unwind on this target; the hook installed by [`start`] keeps its message for
//! [`take_panic`], which the JavaScript side reads when a call traps.

pub mod mesh;
pub mod result;
pub mod run;

use std::cell::RefCell;
use wasm_bindgen::prelude::*;

thread_local! {
    static PANIC: RefCell<Option<String>> = const { RefCell::new(None) };
}

/// Installs the panic hook that keeps a panic's message (runs when the module
/// starts).
#[wasm_bindgen(start)]
pub fn start() {
    std::panic::set_hook(Box::new(|info| {
        let message = info.to_string();
        PANIC.with(|p| {
            if let Ok(mut p) = p.try_borrow_mut() {
                *p = Some(message);
            }
        });
    }));
}

/// The message of the panic that made the last call trap, once.
#[wasm_bindgen(js_name = takePanic)]
pub fn take_panic() -> Option<String> {
    PANIC.with(|p| p.try_borrow_mut().ok().and_then(|mut p| p.take()))
}

/// Panics, for the package's own test that a panic comes back to JavaScript as an
/// error with its message and that the engine works after it is reset.
#[wasm_bindgen(js_name = selfTestPanic)]
pub fn self_test_panic() {
    panic!("the self-test panic");
}

/// The built-in demo scene (stairs, a table, pipes, a house, a torus and a washer) as
/// OBJ text: `datasets/demo_scene.obj` of the repository.
#[wasm_bindgen(js_name = demoSceneObj)]
pub fn demo_scene_obj() -> String {
    include_str!(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../datasets/demo_scene.obj"
    ))
    .into()
}

/// The library's version, `"MAJOR.MINOR.PATCH"`.
#[wasm_bindgen]
pub fn version() -> String {
    env!("CARGO_PKG_VERSION").to_string()
}

/// A core error as a JavaScript `Error` with its message.
pub(crate) fn js_error(e: impl std::fmt::Display) -> JsError {
    JsError::new(&e.to_string())
}
