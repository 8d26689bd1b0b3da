//! Running a decomposition from JavaScript: the settings as JSON, progress to a
//! callback that may cancel the run by returning `false`.

use crate::js_error;
use crate::mesh::WasmMesh;
use crate::result::WasmResult;
use primdecomp::{Params, Progress, Stage};
use std::cell::Cell;
use wasm_bindgen::prelude::*;

/// Reports to a JavaScript function when the stage changes or a further 1% of it is
/// done (the merge loop reports far more often than that); a `false` back cancels.
struct Callback {
    f: js_sys::Function,
    told: Cell<Option<(Stage, f64)>>,
    stop: Cell<bool>,
    /// What the callback threw: the run stops and the call throws it.
    thrown: Cell<Option<JsValue>>,
}

// SAFETY: wasm32-unknown-unknown (without the atomics feature, as built here) runs
// one thread, so the callback is only ever touched from the thread that made it.
// Natively this crate is compiled for lints and never called.
unsafe impl Sync for Callback {}

impl Progress for Callback {
    fn update(&self, stage: Stage, fraction: f64) {
        let due = match self.told.get() {
            Some((s, f)) => s != stage || fraction >= f + 0.01 || (fraction == 1.0 && f < 1.0),
            None => true,
        };
        if !due {
            return;
        }
        self.told.set(Some((stage, fraction)));
        let back = self.f.call2(
            &JsValue::NULL,
            &JsValue::from_str(stage.name()),
            &JsValue::from_f64(fraction),
        );
        match back {
            Ok(v) if v.as_bool() == Some(false) => self.stop.set(true),
            Ok(_) => {}
            Err(e) => {
                self.thrown.set(Some(e));
                self.stop.set(true);
            }
        }
    }
    fn cancelled(&self) -> bool {
        self.stop.get()
    }
}

/// Decomposes `mesh` with `settings_json` (a result file's `settings` object, a whole
/// result file, or `"{}"` for the defaults); `progress(stage, fraction)` is called as
/// the run goes and cancels it by returning `false` (what it throws stops the run and
/// is thrown again). The same primitives as the CLI on the same file and settings.
#[wasm_bindgen]
pub fn decompose(
    mesh: &WasmMesh,
    settings_json: &str,
    progress: Option<js_sys::Function>,
) -> Result<WasmResult, JsValue> {
    let params = Params::from_json(settings_json).map_err(js_error)?;
    let run = match progress {
        Some(f) => {
            let cb = Callback {
                f,
                told: Cell::new(None),
                stop: Cell::new(false),
                thrown: Cell::new(None),
            };
            let run = primdecomp::decompose_with(&mesh.mesh, &params, &cb);
            if let Some(thrown) = cb.thrown.take() {
                return Err(thrown);
            }
            run
        }
        None => primdecomp::decompose(&mesh.mesh, &params),
    };
    let mut dec = run.map_err(js_error)?;
    // As the CLI records the file, so that the JSON is the CLI's byte for byte.
    if let Some(path) = &mesh.path {
        dec.input.record_file(path.as_ref());
    }
    Ok(WasmResult::new(dec, params, mesh.mesh.centre()))
}
