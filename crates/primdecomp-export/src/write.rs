//! Writing an export: renders a result in the chosen format with that
//! format's writer, then puts the files in place through temporary files and renames.
//! Shared conventions live in [`super::engine`]; each writer in its own module.
//!
//! Files beside the main one (URDF meshes) go into a folder the export makes
//! (`NAME_meshes`); a folder of that name that is a symbolic link is refused, never
//! written through, and a folder the export made is removed again when the export
//! fails, so a failed export leaves nothing behind.

use super::engine::{check_options, ExportOptions, Files, Format};
use primdecomp::Body;
use primdecomp::Error;
use std::path::{Component, Path, PathBuf};

/// Results with the library's one error type.
type Result<T> = std::result::Result<T, Error>;

/// Writes `objects` as `format` to `path` (each file through a temporary file and a
/// rename; files beside it first, the main file last). Refuses with
/// [`Error::Format`] (exit code 2) options out of range, a result the format cannot
/// hold ([`render`]) and a folder for the files beside it that is a symbolic link or
/// not a folder.
///
/// ```
/// use primdecomp::{Frame, Primitive, Body, Sphere};
/// use primdecomp_export::{write_export, ExportOptions, Format};
///
/// let ball = Primitive::Sphere(Sphere { center: [0.0, 1.0, 0.0], radius: 0.5 });
/// let objects = [Body { name: "ball".into(), frame: Frame::IDENTITY, primitives: vec![ball] }];
/// let path = std::env::temp_dir().join(format!("primdecomp-doc-{}.tscn", std::process::id()));
/// let written = write_export(&path, &objects, Format::Tscn, &ExportOptions::default())?;
/// assert_eq!(written, [path.clone()]);
/// assert!(std::fs::read_to_string(&path)?.contains("SphereShape3D"));
/// # std::fs::remove_file(&path)?;
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_export(
    path: &Path,
    objects: &[Body],
    format: Format,
    opts: &ExportOptions,
) -> Result<Vec<PathBuf>> {
    check_options(opts).map_err(|m| Error::format(path, m))?;
    let files = render(objects, format, opts, path)?;
    let dir = path.parent().unwrap_or(Path::new(""));
    let mut made = Vec::new();
    let mut written = Vec::new();
    let result = place(dir, path, &files, &mut made, &mut written);
    if result.is_err() {
        // Undo what this export added: the folders it made, with what it wrote there.
        for d in made.iter().rev() {
            let _ = std::fs::remove_dir_all(d);
        }
    }
    result.map(|()| written)
}

fn place(
    dir: &Path,
    path: &Path,
    files: &Files,
    made: &mut Vec<PathBuf>,
    written: &mut Vec<PathBuf>,
) -> Result<()> {
    for (rel, bytes) in &files.beside {
        let p = dir.join(rel);
        folders(dir, Path::new(rel), made)?;
        primdecomp_files::write_atomic(&p, bytes)?;
        written.push(p);
    }
    primdecomp_files::write_atomic(path, &files.main)?;
    written.push(path.to_path_buf());
    Ok(())
}

/// Makes the folders of `rel` (relative, no `..`) below `dir`, one at a time;
/// refuses one that exists as a symbolic link or as something other than a folder.
/// Records the folders it made in `made`.
fn folders(dir: &Path, rel: &Path, made: &mut Vec<PathBuf>) -> Result<()> {
    let mut at = dir.to_path_buf();
    let parts: Vec<Component> = rel
        .parent()
        .map(|p| p.components().collect())
        .unwrap_or_default();
    for c in parts {
        let Component::Normal(name) = c else {
            return Err(Error::format(
                &at.join(c),
                "an export's file must lie below its folder",
            ));
        };
        at.push(name);
        match std::fs::symlink_metadata(&at) {
            Ok(m) if m.file_type().is_symlink() => {
                let to = std::fs::read_link(&at).unwrap_or_default();
                return Err(Error::format(
                    &at,
                    format!(
                        "is a symbolic link (to {}); the export's files are never written \
                         through a link in the output folder: remove it, or choose another \
                         output name",
                        primdecomp_files::visible(&to.to_string_lossy())
                    ),
                ));
            }
            Ok(m) if m.is_dir() => {}
            Ok(_) => {
                return Err(Error::format(
                    &at,
                    "exists and is not a folder; the export writes its files beside the main \
                     one in this folder: remove it, or choose another output name",
                ))
            }
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                std::fs::create_dir(&at).map_err(|error| Error::Write {
                    path: at.clone(),
                    error,
                })?;
                made.push(at.clone());
            }
            Err(error) => {
                return Err(Error::Write {
                    path: at.clone(),
                    error,
                })
            }
        }
    }
    Ok(())
}

/// The bytes of an export to `path` (whose file stem names the files beside the
/// main one), or [`Error::Format`] naming `path` when the result holds a shape the
/// format's readers could not load (a number beyond the range of 32-bit floats, a
/// mesh MuJoCo refuses as too small).
///
/// ```
/// use primdecomp::{Frame, Obb, Primitive, Body};
/// use primdecomp_export::{render, ExportOptions, Format};
///
/// let axes = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
/// let crate_box = Primitive::Box(Obb { center: [0.0; 3], axes, half: [1.0, 0.5, 0.25] });
/// let objects = [Body { name: "crate".into(), frame: Frame::IDENTITY, primitives: vec![crate_box] }];
/// let files = render(&objects, Format::Glb, &ExportOptions::default(), "crate.glb".as_ref())?;
/// assert_eq!(&files.main[..4], b"glTF");
/// assert!(files.beside.is_empty());
/// # Ok::<(), primdecomp::Error>(())
/// ```
pub fn render(
    objects: &[Body],
    format: Format,
    opts: &ExportOptions,
    path: &Path,
) -> Result<Files> {
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "export".into());
    let one = |main: std::result::Result<Vec<u8>, String>| {
        main.map(|main| Files {
            main,
            beside: Vec::new(),
        })
    };
    let files = match format {
        Format::Gltf | Format::Glb => {
            one(super::gltf::to_gltf(objects, opts, format == Format::Glb))
        }
        Format::Mjcf => one(super::mjcf::to_mjcf(objects, opts).map(String::into_bytes)),
        Format::Urdf => super::urdf::to_urdf(objects, opts, &stem),
        Format::Usda => one(super::usd::to_usda(objects, opts).map(String::into_bytes)),
        Format::Tscn => one(super::godot::to_tscn(objects, opts).map(String::into_bytes)),
    };
    files.map_err(|m| Error::format(path, format!("cannot be written as {}: {m}", format.name())))
}
