//! Writing an export (issue 28): renders a result in the chosen format with that
//! format's writer, then puts the files in place through temporary files and renames.
//! Shared conventions live in [`super::engine`]; each writer in its own module.

use super::engine::{check_options, ExportOptions, Files, Format};
use super::json::ResultObject;
use std::path::Path;

/// Writes `objects` as `format` to `path` (each file through a temporary file and a
/// rename; files beside it first, the main file last).
pub fn write_export(
    path: &Path,
    objects: &[ResultObject],
    format: Format,
    opts: &ExportOptions,
) -> crate::Result<Vec<std::path::PathBuf>> {
    check_options(opts).map_err(|m| crate::Error::format(path, m))?;
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "export".into());
    let files = render(objects, format, opts, &stem);
    let dir = path.parent().unwrap_or(Path::new(""));
    let mut written = Vec::new();
    for (rel, bytes) in &files.beside {
        let p = dir.join(rel);
        if let Some(parent) = p.parent() {
            std::fs::create_dir_all(parent).map_err(|error| crate::Error::Write {
                path: p.clone(),
                error,
            })?;
        }
        super::write_atomic(&p, bytes)?;
        written.push(p);
    }
    super::write_atomic(path, &files.main)?;
    written.push(path.to_path_buf());
    Ok(written)
}

/// The bytes of an export; `stem` names the files beside the main one.
pub fn render(objects: &[ResultObject], format: Format, opts: &ExportOptions, stem: &str) -> Files {
    match format {
        Format::Gltf | Format::Glb => Files {
            main: super::gltf::to_gltf(objects, opts, format == Format::Glb),
            beside: Vec::new(),
        },
        Format::Mjcf => Files {
            main: super::mjcf::to_mjcf(objects, opts).into_bytes(),
            beside: Vec::new(),
        },
        Format::Urdf => super::urdf::to_urdf(objects, opts, stem),
        Format::Usda => Files {
            main: super::usd::to_usda(objects, opts).into_bytes(),
            beside: Vec::new(),
        },
        Format::Tscn => Files {
            main: super::godot::to_tscn(objects, opts).into_bytes(),
            beside: Vec::new(),
        },
    }
}
