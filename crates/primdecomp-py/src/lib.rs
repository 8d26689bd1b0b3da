//! The native half of the `primdecomp` Python package: a thin layer over
//! the core library's public API. The Python half (python/primdecomp/__init__.py)
//! checks shapes and dtypes and turns arrays into the contiguous float64 / uint32
//! buffers read here without a copy; this file runs the decomposition with the GIL
//! released, watches for Ctrl-C and progress from the calling thread, and converts
//! the library's errors into Python exceptions.

use numpy::{
    PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods,
};
use primdecomp::{Decomposition, Error, Mesh, Params, Primitive, Progress, Stage, Target};
use primdecomp_export::{write_export, ExportOptions, Format};
use pyo3::exceptions::{PyKeyboardInterrupt, PyOSError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Mutex;
use std::time::Duration;

mod tiles;

/// A mesh for Python: (vertices (N,3) float64, polygons).
type MeshArrays<'py> = (Bound<'py, PyArray2<f64>>, Vec<Vec<u32>>);

/// How often the waiting Python thread checks for signals and reports progress.
const POLL: Duration = Duration::from_millis(50);

/// The library's errors in Python's vocabulary: the file system's as `OSError` with
/// the errno and the file name, so Python raises its own subclass
/// (`FileNotFoundError`, `PermissionError`, `IsADirectoryError`, …) with its usual
/// message; bad input and settings as `ValueError` with the CLI's one-line message
/// (without the "invalid setting: " prefix the CLI prints after "error: "); a
/// cancellation as `KeyboardInterrupt`.
pub(crate) fn to_py_err(e: Error) -> PyErr {
    let os = |error: &std::io::Error, path: &Path| match error.raw_os_error() {
        Some(code) => PyOSError::new_err((code, reason(error), path.display().to_string())),
        None => PyOSError::new_err(e.to_string()),
    };
    match &e {
        Error::Open { path, error } | Error::Io { path, error } | Error::Write { path, error } => {
            os(error, path)
        }
        Error::NotAFile {
            path,
            kind: primdecomp_files::FileKind::Directory,
        } => PyOSError::new_err((EISDIR, "Is a directory", path.display().to_string())),
        Error::NotAFile { .. } => PyOSError::new_err(e.to_string()),
        Error::Cancelled => PyKeyboardInterrupt::new_err(e.to_string()),
        Error::InvalidParams(m) => PyValueError::new_err(m.clone()),
        _ => PyValueError::new_err(e.to_string()),
    }
}

/// `EISDIR`, the errno Python maps to `IsADirectoryError` (the same on Linux, macOS
/// and the BSDs).
const EISDIR: i32 = 21;

/// The operating system's words for an error, without Rust's " (os error N)" suffix
/// (Python prints the errno itself).
fn reason(error: &std::io::Error) -> String {
    let s = error.to_string();
    match s.rfind(" (os error ") {
        Some(i) => s[..i].to_string(),
        None => s,
    }
}

pub(crate) fn panic_message(p: Box<dyn std::any::Any + Send>) -> String {
    p.downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| p.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "unknown panic".into())
}

/// Loads a mesh file (every format the core reads): vertices (N,3) float64 exactly as
/// the file gives them (not re-centred, so that `decompose(*load(path))` equals the
/// CLI's output byte for byte), and faces: a (F,k) uint32 array when every face has
/// k corners, else a list of polygons.
#[pyfunction]
fn load<'py>(py: Python<'py>, path: &str) -> PyResult<(Bound<'py, PyArray2<f64>>, PyObject)> {
    let options = primdecomp::LoadOptions {
        keep_world_coordinates: true,
        ..Default::default()
    };
    let mesh = py
        .allow_threads(|| catch_unwind(|| primdecomp::Mesh::load_with(Path::new(path), &options)))
        .map_err(|p| PyRuntimeError::new_err(panic_message(p)))?
        .map_err(to_py_err)?;
    let n = mesh.vertex_count();
    let flat: Vec<f64> = (0..n as u32).flat_map(|v| mesh.world_pos(v)).collect();
    let verts = PyArray1::from_vec(py, flat).reshape([n, 3])?;
    let nf = mesh.face_count();
    let k = if nf > 0 { mesh.face(0).len() } else { 3 };
    let faces = if (0..nf).all(|f| mesh.face(f).len() == k) {
        let flat: Vec<u32> = (0..nf).flat_map(|f| mesh.face(f).iter().copied()).collect();
        PyArray1::from_vec(py, flat)
            .reshape([nf, k])?
            .into_any()
            .unbind()
    } else {
        let polys: Vec<Vec<u32>> = (0..nf).map(|f| mesh.face(f).to_vec()).collect();
        polys.into_pyobject(py)?.into_any().unbind()
    };
    Ok((verts, faces))
}

/// Progress shared between the worker thread (writes) and the Python thread (reads).
struct Shared {
    cancel: AtomicBool,
    latest: Mutex<Option<(Stage, f64)>>,
}

impl Progress for Shared {
    fn update(&self, stage: Stage, fraction: f64) {
        if let Ok(mut l) = self.latest.lock() {
            *l = Some((stage, fraction));
        }
    }
    fn cancelled(&self) -> bool {
        self.cancel.load(Ordering::Relaxed)
    }
}

/// The mesh from borrowed arrays: faces are `offsets` into `indices` (polygon lists)
/// or, with no offsets, consecutive runs of `arity` indices (an (F,k) array).
fn build_mesh(
    positions: &[f64],
    offsets: Option<&[u32]>,
    arity: usize,
    indices: &[u32],
) -> Result<Mesh, primdecomp::Error> {
    // SAFETY: [f64; 3] has the alignment of f64 and no padding; the Python side
    // passes a C-contiguous (N,3) array.
    let pos: &[[f64; 3]] =
        unsafe { std::slice::from_raw_parts(positions.as_ptr().cast(), positions.len() / 3) };
    let faces: Vec<&[u32]> = match offsets {
        Some(o) => o
            .windows(2)
            .map(|w| &indices[w[0] as usize..w[1] as usize])
            .collect(),
        None => indices.chunks_exact(arity.max(1)).collect(),
    };
    Mesh::from_polygons(pos, &faces)
}

/// Runs `decompose_with` on a worker thread while this (Python) thread, GIL
/// released, wakes every [`POLL`] to check signals and `stop` and call the progress
/// callback.
fn run_watched(
    py: Python<'_>,
    mesh: &Mesh,
    params: &Params,
    callback: Option<&PyObject>,
    stop: Option<&PyObject>,
) -> PyResult<Decomposition> {
    watched(py, params, callback, stop, |shared| {
        primdecomp::decompose_with(mesh, params, shared)
    })
}

/// Runs `work` on a worker thread while this (Python) thread, GIL released, wakes
/// every [`POLL`] to check signals (Ctrl-C cancels the work) and call the progress
/// callback with the stage, its fraction and the estimate of `params`' run.
///
/// Python runs signal handlers on its main thread only: on any other thread Ctrl-C
/// reaches the main thread, which stops a run here through `stop` (an object with
/// `is_set()`, such as a `threading.Event`): once set, the work is cancelled and the
/// call raises `KeyboardInterrupt`, as Ctrl-C does on the main thread.
///
/// The worker wakes this thread as it finishes, so a short run returns at once
/// rather than at the next poll, and one last look follows its end: the callback
/// gets the final progress (however short the run, every run that reports progress
/// calls it at least once), and a Ctrl-C that came after the previous look still
/// raises `KeyboardInterrupt` here, not in whatever Python runs next.
pub(crate) fn watched<T: Send>(
    py: Python<'_>,
    params: &Params,
    callback: Option<&PyObject>,
    stop: Option<&PyObject>,
    work: impl FnOnce(&dyn Progress) -> Result<T, primdecomp::Error> + Send,
) -> PyResult<T> {
    let shared = Shared {
        cancel: AtomicBool::new(false),
        latest: Mutex::new(None),
    };
    let done = AtomicBool::new(false);
    let caller = std::thread::current();
    let mut watch = Watch {
        params,
        callback,
        stop,
        start: std::time::Instant::now(),
        reported: None,
        raised: None,
    };
    let out = std::thread::scope(|s| {
        let worker = s.spawn(|| {
            let out = catch_unwind(AssertUnwindSafe(|| work(&shared)));
            done.store(true, Ordering::Release);
            caller.unpark();
            out
        });
        loop {
            // Read before the look, so that the last look sees the last update.
            let finished = done.load(Ordering::Acquire);
            watch.look(py, &shared);
            if finished {
                break;
            }
            py.allow_threads(|| std::thread::park_timeout(POLL));
        }
        worker.join()
    });
    if let Some(e) = watch.raised {
        return Err(e);
    }
    match out {
        Ok(Ok(r)) => r.map_err(to_py_err),
        Ok(Err(p)) | Err(p) => Err(PyRuntimeError::new_err(format!(
            "primdecomp panicked (a bug, please report it): {}",
            panic_message(p)
        ))),
    }
}

/// What [`watched`]'s thread keeps between its looks at the run.
struct Watch<'a> {
    params: &'a Params,
    callback: Option<&'a PyObject>,
    stop: Option<&'a PyObject>,
    start: std::time::Instant,
    /// The progress the callback was last called with.
    reported: Option<(Stage, f64)>,
    /// The first error a look raised (Ctrl-C, `stop` set, the callback's own).
    raised: Option<PyErr>,
}

impl Watch<'_> {
    /// One look: until an error was raised, checks signals and `stop` and reports
    /// new progress; an error cancels the work and is kept for the caller.
    fn look(&mut self, py: Python<'_>, shared: &Shared) {
        if self.raised.is_some() {
            return;
        }
        let now = *shared.latest.lock().unwrap_or_else(|e| e.into_inner());
        if let Err(e) = self.step(py, now) {
            self.raised = Some(e);
            shared.cancel.store(true, Ordering::Relaxed);
        }
        self.reported = now;
    }

    fn step(&self, py: Python<'_>, now: Option<(Stage, f64)>) -> PyResult<()> {
        py.check_signals()?;
        if let Some(stop) = self.stop {
            if stop.bind(py).call_method0("is_set")?.is_truthy()? {
                return Err(PyKeyboardInterrupt::new_err("stopped"));
            }
        }
        if let (Some(cb), Some((stage, f))) = (self.callback, now) {
            if self.reported != now {
                // The Python side passes a callback of three arguments (it wraps
                // one of two): stage, its fraction, seconds left.
                let spent = self.start.elapsed().as_secs_f64();
                let left = stage.seconds_left(f, self.params, spent);
                cb.call1(py, (stage.name(), f, left))?;
            }
        }
        Ok(())
    }
}

/// Decomposes vertices ((N,3) C-contiguous float64) and faces: an (F,k) C-contiguous
/// uint32 array `faces`, or polygons as `offsets` into `indices` (uint32); settings
/// given as the JSON of `Params`. The arrays are read in place, without a copy.
#[pyfunction]
#[pyo3(signature = (vertices, faces, offsets, indices, settings_json, progress=None))]
fn decompose(
    py: Python<'_>,
    vertices: PyReadonlyArray2<'_, f64>,
    faces: Option<PyReadonlyArray2<'_, u32>>,
    offsets: Option<PyReadonlyArray1<'_, u32>>,
    indices: Option<PyReadonlyArray1<'_, u32>>,
    settings_json: &str,
    progress: Option<PyObject>,
) -> PyResult<NativeResult> {
    // The other settings are checked before the mesh is built, as without percentages.
    Params::from_json(&counted(settings_json, None)?).map_err(to_py_err)?;
    let v = vertices.as_slice()?;
    let (o, k, i) = match (&faces, &offsets, &indices) {
        (Some(f), _, _) => (None, f.shape()[1], f.as_slice()?),
        (None, Some(o), Some(i)) => (Some(o.as_slice()?), 0, i.as_slice()?),
        _ => return Err(PyValueError::new_err("faces missing")),
    };
    let mesh = py
        .allow_threads(|| catch_unwind(|| build_mesh(v, o, k, i)))
        .map_err(|p| PyRuntimeError::new_err(panic_message(p)))?
        .map_err(to_py_err)?;
    let params =
        Params::from_json(&counted(settings_json, Some(mesh.face_count()))?).map_err(to_py_err)?;
    params.validate().map_err(to_py_err)?;
    let dec = run_watched(py, &mesh, &params, progress.as_ref(), None)?;
    Ok(NativeResult { dec, params })
}

/// Decomposes the mesh in a file exactly as `primdecomp decompose` does (same
/// loader, so the same primitives byte for byte); `stop` as [`watched`] takes it (the
/// batch's thread pool stops its running inputs with it).
#[pyfunction]
#[pyo3(signature = (path, settings_json, progress=None, stop=None))]
fn decompose_path(
    py: Python<'_>,
    path: &str,
    settings_json: &str,
    progress: Option<PyObject>,
    stop: Option<PyObject>,
) -> PyResult<NativeResult> {
    Params::from_json(&counted(settings_json, None)?).map_err(to_py_err)?;
    let mesh = py
        .allow_threads(|| catch_unwind(|| primdecomp::Mesh::load(Path::new(path))))
        .map_err(|p| PyRuntimeError::new_err(panic_message(p)))?
        .map_err(to_py_err)?;
    let params =
        Params::from_json(&counted(settings_json, Some(mesh.face_count()))?).map_err(to_py_err)?;
    params.validate().map_err(to_py_err)?;
    let mut dec = run_watched(py, &mesh, &params, progress.as_ref(), stop.as_ref())?;
    // As the CLI records them, so that to_json() is the CLI's file byte for byte.
    dec.input.record_file(Path::new(path));
    Ok(NativeResult { dec, params })
}

/// The settings with each target given as a percentage of the faces (`"1%"`, as
/// [`spelled`] leaves it) made the count it stands for on a mesh of `faces` faces
/// ([`Target::count`], as the CLI's `-n 1%`); with `faces` unknown, a placeholder
/// count, so that the other settings can be checked first. Settings without one are
/// given back as they are.
fn counted(settings_json: &str, faces: Option<usize>) -> PyResult<String> {
    let mut value: serde_json::Value = match serde_json::from_str(settings_json) {
        Ok(v) => v,
        Err(_) => return Ok(settings_json.to_string()),
    };
    let Some(targets) = value.get_mut("targets").and_then(|t| t.as_array_mut()) else {
        return Ok(settings_json.to_string());
    };
    if !targets.iter().any(|t| t.is_string()) {
        return Ok(settings_json.to_string());
    }
    for t in targets.iter_mut() {
        if let Some(text) = t.as_str() {
            let target: Target = text
                .parse()
                .map_err(|e: Error| PyValueError::new_err(format!("targets: {}", bare(e))))?;
            *t = faces.map_or(1, |f| target.count(f)).into();
        }
    }
    Ok(value.to_string())
}

/// An invalid setting's message without the error's "invalid setting: " prefix.
fn bare(e: Error) -> String {
    match e {
        Error::InvalidParams(m) => m,
        e => e.to_string(),
    }
}

/// A finished decomposition and the settings that made it.
#[pyclass(frozen, module = "primdecomp._native")]
pub(crate) struct NativeResult {
    pub(crate) dec: Decomposition,
    pub(crate) params: Params,
}

fn frame(z: [f64; 3]) -> [[f64; 3]; 3] {
    let n = (z[0] * z[0] + z[1] * z[1] + z[2] * z[2]).sqrt();
    let z = if n > 0.0 {
        z.map(|c| c / n)
    } else {
        [0.0, 0.0, 1.0]
    };
    let t = if z[0].abs() < 0.9 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let cr = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let x = cr(t, z);
    let xn = (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt();
    let x = x.map(|c| c / xn);
    [x, cr(z, x), z]
}

/// Rotation (columns = local axes) and translation of a primitive's local frame:
/// axis kinds have local z along p0→p1 and their origin at its midpoint.
fn transform(p: &Primitive) -> [[f64; 4]; 4] {
    let mid = |a: [f64; 3], b: [f64; 3]| std::array::from_fn(|k| 0.5 * (a[k] + b[k]));
    let dir = |a: [f64; 3], b: [f64; 3]| std::array::from_fn(|k| b[k] - a[k]);
    let (c, axes) = match *p {
        Primitive::Box(b) => (b.center, b.axes),
        Primitive::Prism(b) => (b.center, b.axes),
        Primitive::Sphere(s) => (
            s.center,
            [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        ),
        Primitive::Capsule(k) => (mid(k.p0, k.p1), frame(dir(k.p0, k.p1))),
        Primitive::Cylinder(k) => (mid(k.p0, k.p1), frame(dir(k.p0, k.p1))),
        Primitive::Frustum(k) => (mid(k.p0, k.p1), frame(dir(k.p0, k.p1))),
    };
    let mut m = [[0.0; 4]; 4];
    for r in 0..3 {
        for (col, a) in axes.iter().enumerate() {
            m[r][col] = a[r];
        }
        m[r][3] = c[r];
    }
    m[3][3] = 1.0;
    m
}

impl NativeResult {
    fn level(&self, level: usize) -> PyResult<&primdecomp::Level> {
        self.dec.levels.get(level).ok_or_else(|| {
            PyValueError::new_err(format!(
                "level {level} out of range: the result has {} levels",
                self.dec.levels.len()
            ))
        })
    }
    fn primitive(&self, level: usize, i: usize) -> PyResult<&Primitive> {
        let lv = self.level(level)?;
        lv.primitives.get(i).ok_or_else(|| {
            PyValueError::new_err(format!(
                "primitive {i} out of range ({})",
                lv.primitives.len()
            ))
        })
    }
}

#[pymethods]
impl NativeResult {
    /// The number of levels (one per target).
    fn level_count(&self) -> usize {
        self.dec.levels.len()
    }
    /// The CLI's JSON document of one level.
    fn to_json(&self, level: usize) -> PyResult<String> {
        self.level(level)?;
        Ok(self.dec.to_json(level, &self.params))
    }
    /// Volumes of a level's primitives.
    fn volumes(&self, level: usize) -> PyResult<Vec<f64>> {
        Ok(self
            .level(level)?
            .primitives
            .iter()
            .map(|p| p.volume())
            .collect())
    }
    /// 4x4 transforms of a level's primitives (row-major nested lists).
    fn transforms(&self, level: usize) -> PyResult<Vec<[[f64; 4]; 4]>> {
        Ok(self
            .level(level)?
            .primitives
            .iter()
            .map(transform)
            .collect())
    }
    /// Conservative tessellation of one primitive: (vertices (V,3), polygons).
    fn tessellate<'py>(
        &self,
        py: Python<'py>,
        level: usize,
        i: usize,
        detail: usize,
    ) -> PyResult<MeshArrays<'py>> {
        let t = self.primitive(level, i)?.tessellate(detail);
        let v: Vec<Vec<f64>> = t.vertices.iter().map(|p| p.to_vec()).collect();
        Ok((PyArray2::from_vec2(py, &v)?, t.faces))
    }
    /// Writes one level in the format named by `path`'s extension (`.json`, `.obj`,
    /// or an engine format: `.gltf`, `.glb`, `.urdf`, `.usda`, `.tscn`; `.xml` = MJCF).
    fn export(&self, path: &str, level: usize) -> PyResult<Vec<String>> {
        let p = Path::new(path);
        let json = self.to_json(level)?;
        let ext = p
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        let written = match ext.as_deref() {
            Some("json") => primdecomp_files::write_atomic(p, json.as_bytes())
                .map(|_| vec![p.into()])
                .map_err(Error::from),
            Some("obj") => {
                let obj = self.level(level)?.to_obj(primdecomp::Tess::DEFAULT_DETAIL);
                primdecomp_files::write_atomic(p, obj.as_bytes())
                    .map(|_| vec![p.into()])
                    .map_err(Error::from)
            }
            _ => {
                let format = match ext.as_deref() {
                    Some("xml") => Format::Mjcf,
                    _ => Format::from_path(p).ok_or_else(|| {
                        PyValueError::new_err(format!(
                            "{path}: unknown export format (use .json, .obj, .gltf, .glb, .urdf, .usda, .tscn or .xml for MJCF)"
                        ))
                    })?,
                };
                let objs = primdecomp::ResultFile::read(&json, "result.json".as_ref())
                    .map_err(|e| match e {
                        primdecomp::Error::Format { msg, .. } => PyValueError::new_err(msg),
                        e => PyValueError::new_err(e.to_string()),
                    })?
                    .objects;
                // The input's up axis where the result records it (+Y otherwise).
                let opts = ExportOptions {
                    up: self.dec.input.up.unwrap_or_default(),
                    ..ExportOptions::default()
                };
                write_export(p, &objs, format, &opts)
            }
        }
        .map_err(to_py_err)?;
        Ok(written.iter().map(|w| w.display().to_string()).collect())
    }
}

/// The weights `text` spells (`kind=w,…`, none for empty) over the defaults, as the
/// settings' JSON writes them: `{"box": 1.0, …}`.
fn weights(text: &str) -> Result<String, Error> {
    let mut fit = primdecomp::Fit::default();
    if !text.is_empty() {
        fit.set_weights(text)?;
    }
    let by_kind: serde_json::Map<String, serde_json::Value> = (primdecomp::Kind::ALL.iter())
        .map(|&k| (k.name().to_string(), fit.weights[k as usize].into()))
        .collect();
    Ok(serde_json::Value::Object(by_kind).to_string())
}

/// The native module; the public API is in python/primdecomp/__init__.py.
/// A setting's value as a user spells it ("1%", "4K", "exact", "auto", "box"), read
/// by the library's own `FromStr` (as the CLI reads its flags), given back as the JSON
/// of the settings; a wrong word is a `ValueError` naming `key`.
#[pyfunction]
fn spelled(key: &str, text: &str) -> PyResult<String> {
    fn json<T: std::str::FromStr<Err = Error> + serde::Serialize>(
        s: &str,
    ) -> Result<String, Error> {
        let value: T = s.parse()?;
        Ok(serde_json::to_string(&value).expect("settings serialize"))
    }
    let value = match key {
        // A count as a number; a percentage as its spelling, made a count by
        // `counted` once the mesh's faces are known.
        "targets" => text.parse::<Target>().map(|t| match t {
            Target::Count(n) => n.to_string(),
            Target::Percent(_) => serde_json::Value::from(t.to_string()).to_string(),
        }),
        "tolerance" => json::<primdecomp::Tolerance>(text),
        "dedup" => json::<primdecomp::Dedup>(text),
        "reprice" => json::<primdecomp::Reprice>(text),
        "partitions" => json::<primdecomp::Partitions>(text),
        "kind" => text.parse::<primdecomp::Kind>().map(|k| format!("\"{k}\"")),
        // A dict's `kind=w` pairs over the defaults: every kind's weight by name.
        "weights" => weights(text),
        "max_bytes" => match primdecomp::Goal::parse_bytes(text) {
            Ok(b) if b > 0 && b <= usize::MAX as u64 => Ok(b.to_string()),
            _ => Err(Error::InvalidParams(format!(
                "expected a positive byte count such as 4096 or 4K, got '{text}'"
            ))),
        },
        _ => {
            return Err(PyValueError::new_err(format!(
                "{key}: not a spelled setting"
            )))
        }
    };
    value.map_err(|e| match e {
        // The kind names itself ("unknown primitive kind …").
        Error::InvalidParams(m) if key == "kind" => PyValueError::new_err(m),
        Error::InvalidParams(m) => PyValueError::new_err(format!("{key}: {m}")),
        e => to_py_err(e),
    })
}

#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(spelled, m)?)?;
    m.add_function(wrap_pyfunction!(load, m)?)?;
    m.add_function(wrap_pyfunction!(decompose, m)?)?;
    m.add_function(wrap_pyfunction!(decompose_path, m)?)?;
    m.add_class::<NativeResult>()?;
    tiles::add(m)?;
    Ok(())
}
