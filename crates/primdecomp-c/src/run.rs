//! Running a decomposition: settings from JSON, progress reported to the caller's
//! callback on the caller's own thread, cancellation by a flag or by the callback.

use crate::args::{array, handle, optional_text, put, writable};
use crate::mesh::PrimdecompMesh;
use crate::result::PrimdecompResult;
use crate::status::{guard, panic_message, Failure, PrimdecompStatus};
use primdecomp::{Decomposition, Params, Progress, Stage};
use std::ffi::{c_char, c_int, c_void, CStr};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, AtomicI32, Ordering};
use std::sync::Mutex;
use std::time::Duration;

/// Called with the stage running (`"dedup"`, `"adjacency"`, `"quadrics"`, `"seed"`,
/// `"merge"`, `"postprocess"`: a static string) and the fraction of it done (0 to 1).
/// Return 0 to go on, anything else to cancel the run.
pub type PrimdecompProgressFn = Option<
    unsafe extern "C" fn(user_data: *mut c_void, stage: *const c_char, fraction: f64) -> c_int,
>;

/// How often the calling thread passes progress on to the callback.
const POLL: Duration = Duration::from_millis(20);

/// The settings: the JSON of a result file's `settings` object, a whole result file
/// (its settings are used), or NULL / empty for the defaults.
pub(crate) fn settings(json: Option<&str>) -> Result<Params, Failure> {
    Ok(Params::from_json(json.unwrap_or("{}"))?)
}

/// The run's progress: the latest report, and whether to stop.
struct Watch<'a> {
    flag: Option<&'a AtomicI32>,
    stop: AtomicBool,
    latest: Mutex<Option<(Stage, f64)>>,
}

impl Progress for Watch<'_> {
    fn update(&self, stage: Stage, fraction: f64) {
        if let Ok(mut l) = self.latest.lock() {
            *l = Some((stage, fraction));
        }
    }
    fn cancelled(&self) -> bool {
        self.stop.load(Ordering::Relaxed)
            || self.flag.is_some_and(|f| f.load(Ordering::Relaxed) != 0)
    }
}

/// A stage's name as a static C string.
fn stage_name(stage: Stage) -> &'static CStr {
    match stage {
        Stage::Dedup => c"dedup",
        Stage::Adjacency => c"adjacency",
        Stage::Quadrics => c"quadrics",
        Stage::Seed => c"seed",
        Stage::Merge => c"merge",
        Stage::Postprocess => c"postprocess",
    }
}

/// Runs the decomposition on a helper thread while this thread passes progress to
/// `callback` every [`POLL`]; without a callback, runs here.
fn run(
    mesh: &PrimdecompMesh,
    params: &Params,
    watch: &Watch,
    callback: PrimdecompProgressFn,
    user_data: *mut c_void,
) -> Result<Decomposition, Failure> {
    let Some(cb) = callback else {
        return Ok(primdecomp::decompose_with(&mesh.mesh, params, watch)?);
    };
    let mut told = None;
    let outcome = std::thread::scope(|s| {
        let worker = s.spawn(|| {
            catch_unwind(AssertUnwindSafe(|| {
                primdecomp::decompose_with(&mesh.mesh, params, watch)
            }))
        });
        let mut tell = |now: Option<(Stage, f64)>| {
            if let (Some((stage, f)), true) = (now, now != told) {
                // SAFETY: the caller's callback with the caller's user data, on the
                // caller's thread; the stage name is a static C string.
                let stop = unsafe { cb(user_data, stage_name(stage).as_ptr(), f) };
                if stop != 0 {
                    watch.stop.store(true, Ordering::Relaxed);
                }
            }
            told = now;
        };
        while !worker.is_finished() {
            std::thread::park_timeout(POLL);
            tell(*watch.latest.lock().unwrap_or_else(|e| e.into_inner()));
        }
        let out = worker.join();
        // The last report (a finished stage at 1) reaches the caller too.
        tell(*watch.latest.lock().unwrap_or_else(|e| e.into_inner()));
        out
    });
    match outcome {
        Ok(Ok(run)) => Ok(run?),
        Ok(Err(p)) | Err(p) => Err(Failure::new(
            PrimdecompStatus::Panic,
            format!(
                "internal error in primdecomp (a bug, please report it): {}",
                panic_message(p.as_ref())
            ),
        )),
    }
}

/// Decomposes `mesh` with the settings in `settings_json` (the `settings` object of a
/// result file, a whole result file, or NULL for the defaults: the fewest primitives
/// within 2% of the mesh's diagonal). Deterministic: the CLI's JSON for the same file
/// and settings, byte for byte.
///
/// `progress` (may be NULL) is called on this thread, about every 20 ms while the
/// run goes on and once at its end, with `user_data`; returning nonzero cancels.
/// `cancel` (may be NULL) is watched throughout: once the `int32_t` it points to is
/// nonzero (set from any thread, with an atomic store) the run stops and returns
/// `PRIMDECOMP_STATUS_CANCELLED`. On success `*out` holds a new result.
///
/// # Safety
/// `mesh` is a live mesh of this library; `settings_json` is NULL or a NUL-terminated
/// string; `cancel` is NULL or points to a 4-byte-aligned `int32_t` that lives
/// through the call; `out` points to writable storage for a pointer.
#[no_mangle]
pub unsafe extern "C" fn primdecomp_decompose(
    mesh: *const PrimdecompMesh,
    settings_json: *const c_char,
    progress: PrimdecompProgressFn,
    user_data: *mut c_void,
    cancel: *const i32,
    out: *mut *mut PrimdecompResult,
) -> PrimdecompStatus {
    guard(|| {
        writable(out, "out")?;
        let mesh = handle(mesh, "mesh")?;
        let params = settings(optional_text(settings_json, "settings_json")?)?;
        // Checked for NULL and alignment; an atomic view of the caller's flag.
        let flag = array(cancel, usize::from(!cancel.is_null()), "cancel")?
            .first()
            // SAFETY: aligned and live for the call (above); read atomically only.
            .map(|f| unsafe { AtomicI32::from_ptr(f as *const i32 as *mut i32) });
        let watch = Watch {
            flag,
            stop: AtomicBool::new(false),
            latest: Mutex::new(None),
        };
        let mut dec = run(mesh, &params, &watch, progress, user_data)?;
        // As the CLI records the file, so that the JSON is the CLI's byte for byte.
        if let Some(path) = &mesh.path {
            dec.input.record_file(path.as_ref());
        }
        let result = PrimdecompResult::new(dec, params);
        put(out, Box::into_raw(Box::new(result)), "out")
    })
}
