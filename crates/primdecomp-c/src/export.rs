//! Writing a level in every format the CLI writes: the JSON result, the OBJ
//! tessellation and the engine exports (glTF/GLB with physics, MJCF, URDF, USD,
//! Godot), to a file or into memory.

use crate::args::{handle, optional_text, put, text, writable};
use crate::result::PrimdecompResult;
use crate::status::{guard, Failure, PrimdecompStatus};
use primdecomp::{Body, Frame, Tess, Up};
use primdecomp_export::{render, write_export, ExportOptions, Format, Physics};
use serde::Deserialize;
use std::ffi::c_char;
use std::path::Path;

/// The export options as JSON, each key the CLI's flag of the same name.
#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields, default)]
struct Options {
    /// `--format`: needed where the extension names none (MuJoCo's `.xml`).
    format: Option<String>,
    /// `--up`: `"y"` (default) or `"z"`.
    up: Option<String>,
    /// `--scale`.
    scale: Option<f64>,
    /// `--gltf-physics`: `"khr"` (default) or `"omi"`.
    gltf_physics: Option<String>,
    /// `--preview`: coloured preview meshes of the colliders (glTF).
    preview: bool,
    /// `--urdf-capsule`.
    urdf_capsule: bool,
    /// `--export-detail` (and `--obj-detail` for `.obj`).
    detail: Option<usize>,
    /// The model's name (MJCF model, URDF robot, USD prim, Godot root); the file's
    /// stem by default, as the CLI names it.
    model: Option<String>,
}

/// What a level can be written as.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Target {
    Json,
    Obj,
    Engine(Format),
}

impl Target {
    fn from_name(s: &str) -> Option<Target> {
        match s.to_ascii_lowercase().as_str() {
            "json" => Some(Target::Json),
            "obj" => Some(Target::Obj),
            _ => Format::from_name(s).map(Target::Engine),
        }
    }
}

fn bad(message: String) -> Failure {
    Failure::new(PrimdecompStatus::InvalidArgument, message)
}

fn options(json: Option<&str>) -> Result<Options, Failure> {
    match json {
        None => Ok(Options::default()),
        Some(j) => serde_json::from_str(j).map_err(|e| bad(format!("options_json: {e}"))),
    }
}

/// The library's export options from the JSON's.
fn export_options(o: &Options, model: &str) -> Result<ExportOptions, Failure> {
    let up = match o.up.as_deref().map(str::to_ascii_lowercase).as_deref() {
        None | Some("y") => Up::Y,
        Some("z") => Up::Z,
        Some(u) => return Err(bad(format!("up: expected \"y\" or \"z\", got \"{u}\""))),
    };
    let physics = match o
        .gltf_physics
        .as_deref()
        .map(str::to_ascii_lowercase)
        .as_deref()
    {
        None | Some("khr") => Physics::Khr,
        Some("omi") => Physics::Omi,
        Some(p) => {
            return Err(bad(format!(
                "gltf_physics: expected \"khr\" or \"omi\", got \"{p}\""
            )))
        }
    };
    let opts = ExportOptions {
        up,
        scale: o.scale.unwrap_or(1.0),
        detail: o.detail.unwrap_or(Tess::DEFAULT_DETAIL),
        physics,
        preview: o.preview,
        urdf_capsule: o.urdf_capsule,
        model: o.model.clone().unwrap_or_else(|| model.to_string()),
        input_mesh: None,
    };
    opts.validate().map_err(|e| bad(e.to_string()))?;
    Ok(opts)
}

/// The level as one world-frame object, as `primdecomp decompose --export` writes it.
fn objects(r: &PrimdecompResult, level: usize) -> Result<Vec<Body>, Failure> {
    Ok(vec![Body {
        name: String::new(),
        frame: Frame::IDENTITY,
        primitives: r.level(level)?.primitives.clone(),
    }])
}

/// The bytes of a single-file format.
fn bytes_of(
    r: &PrimdecompResult,
    level: usize,
    target: Target,
    o: &Options,
) -> Result<Vec<u8>, Failure> {
    let model = "primdecomp";
    Ok(match target {
        Target::Json => r.dec.to_json(level, &r.params).into_bytes(),
        Target::Obj => {
            let opts = export_options(o, model)?;
            r.level(level)?.to_obj(opts.detail).into_bytes()
        }
        Target::Engine(f) => {
            let opts = export_options(o, model)?;
            // In memory the model's name stands for the path (it names files beside).
            let files = render(&objects(r, level)?, f, &opts, Path::new(&opts.model))?;
            if let Some((name, _)) = files.beside.first() {
                return Err(bad(format!(
                    "{} writes files beside the main one ({name}): export it to a path",
                    f.name()
                )));
            }
            files.main
        }
    })
}

/// Writes a level to `path` (through a temporary file and a rename, as the CLI
/// does): the format follows the extension (`.json`, `.obj`, `.gltf`, `.glb`,
/// `.urdf`, `.usda`, `.tscn`, `.mjcf`) or `"format"` in `options_json` (`"mjcf"` for
/// MuJoCo's `.xml`). `options_json` (NULL for the defaults) holds the CLI's export
/// flags: `{"format": "mjcf", "up": "z", "scale": 0.01, "gltf_physics": "omi",
/// "preview": true, "urdf_capsule": true, "detail": 32, "model": "robot"}`. URDF
/// writes the meshes of frustums and prisms beside the file.
///
/// # Safety
/// `result` is a live result of this library; `path` a NUL-terminated string;
/// `options_json` NULL or a NUL-terminated string.
#[no_mangle]
pub unsafe extern "C" fn primdecomp_result_export(
    result: *const PrimdecompResult,
    level: usize,
    path: *const c_char,
    options_json: *const c_char,
) -> PrimdecompStatus {
    guard(|| {
        let r = handle(result, "result")?;
        let path = Path::new(text(path, "path")?);
        let o = options(optional_text(options_json, "options_json")?)?;
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .unwrap_or_default();
        let target = match (Target::from_name(ext), o.format.as_deref()) {
            // The extension decides where it names a format, as in the CLI.
            (Some(t), _) => t,
            (None, Some(f)) => Target::from_name(f)
                .ok_or_else(|| bad(format!("format: unknown format \"{f}\"")))?,
            (None, None) => {
                return Err(bad(format!(
                    "{}: cannot tell the format from the extension (.json, .obj, .gltf, .glb, \
                     .urdf, .usda, .tscn, .mjcf; MuJoCo's .xml needs \"format\": \"mjcf\")",
                    path.display()
                )))
            }
        };
        let stem = path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| "primdecomp".into());
        match target {
            Target::Engine(f) => {
                write_export(path, &objects(r, level)?, f, &export_options(&o, &stem)?)?;
            }
            _ => primdecomp_files::write_atomic(path, &bytes_of(r, level, target, &o)?)
                .map_err(primdecomp::Error::from)?,
        }
        Ok(())
    })
}

/// A level in `format` (`"json"`, `"obj"`, `"gltf"`, `"glb"`, `"mjcf"`, `"urdf"`,
/// `"usda"`, `"tscn"`) in memory: `*out` is a new buffer of `*len` bytes (free it
/// with `primdecomp_bytes_free`). `options_json` as for `primdecomp_result_export`;
/// the model is named `"primdecomp"` unless it says otherwise. A URDF whose
/// frustums or prisms need mesh files beside it is refused: export it to a path.
///
/// # Safety
/// `result` is a live result of this library; `format` a NUL-terminated string;
/// `options_json` NULL or a NUL-terminated string; `out` and `len` point to writable
/// storage.
#[no_mangle]
pub unsafe extern "C" fn primdecomp_result_export_to_memory(
    result: *const PrimdecompResult,
    level: usize,
    format: *const c_char,
    options_json: *const c_char,
    out: *mut *mut u8,
    len: *mut usize,
) -> PrimdecompStatus {
    guard(|| {
        writable(out, "out")?;
        writable(len, "len")?;
        let r = handle(result, "result")?;
        let name = text(format, "format")?;
        let target = Target::from_name(name).ok_or_else(|| {
            bad(format!(
                "format: expected json, obj, gltf, glb, mjcf, urdf, usda or tscn, got \"{name}\""
            ))
        })?;
        let o = options(optional_text(options_json, "options_json")?)?;
        let bytes = bytes_of(r, level, target, &o)?.into_boxed_slice();
        put(len, bytes.len(), "len")?;
        put(out, Box::into_raw(bytes).cast::<u8>(), "out")
    })
}

/// Frees a buffer of `len` bytes this library returned (NULL is ignored).
///
/// # Safety
/// `bytes` is NULL or a buffer from `primdecomp_result_export_to_memory` with the
/// `len` it gave, freed only once.
#[no_mangle]
pub unsafe extern "C" fn primdecomp_bytes_free(bytes: *mut u8, len: usize) {
    if !bytes.is_null() {
        // SAFETY: a boxed slice of `len` bytes from Box::into_raw, freed once.
        drop(unsafe { Box::from_raw(std::ptr::slice_from_raw_parts_mut(bytes, len)) });
    }
}
