//! `primdecomp export` and `decompose --export` / `--per-object`.

use anyhow::bail;
use clap::Args;
use primdecomp::{Body, Frame, Level, ResultFile, Up};
use primdecomp_export::{render, write_export, ExportOptions, Format, Physics};
use std::path::{Path, PathBuf};

use crate::exit::println;
use crate::exit::BadArgs;
use crate::outputs::{is_stdout, write_out, Guard, Out};

/// The options every export takes (`export` and `decompose --export`).
#[derive(Args, Debug, Clone)]
pub struct ExportArgs {
    /// The format of exports whose extension names none: gltf, glb, mjcf, urdf,
    /// usda, tscn.
    ///
    /// MuJoCo's .xml needs --format mjcf. An extension that names a format (.gltf,
    /// .glb, .urdf, .usda, .tscn, .mjcf) always decides.
    #[arg(long = "format", hide_short_help = true)]
    pub format: Option<String>,
    /// Which axis points up in the mesh: y or z (default: what the file format says).
    ///
    /// decompose: glTF is +Y up by its specification; STL files say nothing and are
    /// taken as +Z up (CAD and robot parts mostly are); OBJ, PLY and OFF say nothing
    /// and are taken as +Y up (most modelling tools and scans write them so). The
    /// result records it (input.up), and export and view use it: glTF and Godot are
    /// +Y up and MJCF and URDF +Z up, so a mesh whose up differs is turned; USD
    /// declares it. export: the result's axis (y for results that record none).
    // Listed with the input files: it says how the mesh stands, for decompose too.
    #[arg(long, value_parser = ["y", "z"], ignore_case = true, help_heading = "Input files")]
    pub up: Option<String>,
    /// Multiply every length by this (input units to metres; default 1).
    #[arg(long, default_value_t = 1.0, hide_short_help = true)]
    pub scale: f64,
    /// glTF physics extensions: khr (default) or omi.
    ///
    /// khr: KHR_implicit_shapes and KHR_physics_rigid_bodies (Khronos); omi:
    /// OMI_physics_shape and OMI_physics_body, which Godot 4 imports.
    #[arg(
        long,
        default_value = "khr",
        value_name = "khr|omi",
        hide_short_help = true
    )]
    pub gltf_physics: String,
    /// glTF: also a coloured, half-transparent preview mesh of each collider.
    #[arg(long, hide_short_help = true)]
    pub preview: bool,
    /// URDF: write capsules as <capsule> (not in URDF 1.0) instead of a cylinder and
    /// two spheres.
    #[arg(long, hide_short_help = true)]
    pub urdf_capsule: bool,
    /// Segments around circles of frustums (and of every preview) written as meshes.
    #[arg(long, default_value_t = primdecomp::Tess::DEFAULT_DETAIL, hide_short_help = true)]
    pub export_detail: usize,
}

/// `primdecomp export`.
#[derive(Args, Debug)]
pub struct ExportCmd {
    /// A primdecomp JSON result (from `decompose`, with or without --per-object).
    pub result: PathBuf,
    /// Output file; the format follows its extension (or --format). `-` writes the
    /// export to standard output (with --format; not a URDF that needs mesh files).
    #[arg(short, long)]
    pub out: PathBuf,
    /// glTF: include this input mesh (OBJ, PLY, STL, OFF, glTF/GLB) beside the
    /// colliders, so the file is both the import and a preview.
    #[arg(long)]
    pub input: Option<PathBuf>,
    /// Print nothing but errors.
    #[arg(short, long)]
    pub quiet: bool,
    #[command(flatten)]
    pub opts: ExportArgs,
}

impl ExportArgs {
    /// Options and format for `out`; `up` is the result's up axis, which `--up`
    /// overrides.
    pub fn resolve(
        &self,
        out: &Path,
        model: &str,
        up: Up,
    ) -> anyhow::Result<(Format, ExportOptions)> {
        // The extension decides where it names a format; --format covers the others
        // (MuJoCo's .xml), so `decompose --export a.glb --export b.xml --format mjcf`
        // writes both.
        let named = self
            .format
            .as_deref()
            .map(|f| {
                Format::from_name(f).ok_or_else(|| {
                    BadArgs(format!(
                        "--format: expected gltf, glb, mjcf, urdf, usda or tscn, got '{f}'"
                    ))
                })
            })
            .transpose()?;
        let format = Format::from_path(out).or(named).ok_or_else(|| {
            BadArgs(format!(
                "{}: cannot tell the export format from the extension (.gltf, .glb, .urdf, .usda, .tscn, .mjcf; MuJoCo's .xml needs --format mjcf)",
                out.display()
            ))
        })?;
        let up = match self.up.as_deref() {
            None => up,
            Some(u) => Up::from_axis(u)
                .ok_or_else(|| BadArgs(format!("--up: expected y or z, got '{u}'")))?,
        };
        let physics = match self.gltf_physics.to_ascii_lowercase().as_str() {
            "khr" => Physics::Khr,
            "omi" => Physics::Omi,
            p => bail!(BadArgs(format!(
                "--gltf-physics: expected khr or omi, got '{p}'"
            ))),
        };
        let opts = ExportOptions {
            up,
            scale: self.scale,
            detail: self.export_detail,
            physics,
            preview: self.preview,
            urdf_capsule: self.urdf_capsule,
            model: model.to_string(),
            input_mesh: None,
        };
        opts.validate().map_err(|e| BadArgs(e.to_string()))?;
        Ok((format, opts))
    }
}

/// The model name of an output path: its stem.
fn model_name(out: &Path) -> String {
    out.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "primdecomp".into())
}

/// The model name of an export to standard output, which has no name: the result's
/// stem, without the `.primdecomp` of a result's default name (`bolt.primdecomp.json`
/// → `bolt`).
fn result_model(result: &Path) -> String {
    let stem = model_name(result);
    match stem.strip_suffix(".primdecomp") {
        Some(s) if !s.is_empty() => s.to_string(),
        _ => stem,
    }
}

/// Refuses an output that is one of the inputs (never overwrite an input): the
/// files compared by identity, as every output of the CLI (`outputs.rs`).
pub fn not_an_input(flag: &str, out: &Path, inputs: &[&Path]) -> anyhow::Result<()> {
    let guard = Guard::new(inputs.iter().copied());
    guard.check(&[Out::flag(flag, out, out.to_path_buf())])?;
    Ok(())
}

/// World positions and polygons of a mesh, for `--input` / the decompose run.
pub fn mesh_polygons(mesh: &primdecomp::Mesh) -> (Vec<[f64; 3]>, Vec<Vec<u32>>) {
    let v = (0..mesh.vertex_count() as u32)
        .map(|i| mesh.world_pos(i))
        .collect();
    let f = (0..mesh.face_count())
        .map(|f| mesh.face(f).to_vec())
        .collect();
    (v, f)
}

/// `primdecomp export`: reads a result and writes its colliders in the format `-o`
/// names, turned to the format's up axis.
pub fn run(a: ExportCmd) -> anyhow::Result<()> {
    if a.quiet {
        crate::exit::quiet_from_now();
    }
    let inputs: Vec<&Path> = std::iter::once(a.result.as_path())
        .chain(a.input.as_deref())
        .collect();
    not_an_input("-o", &a.out, &inputs)?;
    let to_stdout = is_stdout(&a.out);
    if to_stdout {
        if a.opts.format.is_none() {
            bail!(BadArgs(format!(
                "-o {}: standard output has no extension to name the format: give \
                 --format (gltf, glb, mjcf, urdf, usda or tscn)",
                a.out.display()
            )));
        }
        // The export alone on standard output; what the run says goes to standard error.
        crate::exit::keep_stdout_for_result();
    }
    let text = crate::paths::read_result(&a.result)?;
    let objects = ResultFile::read(&text, &a.result)
        .map_err(|e| BadArgs(e.to_string()))?
        .objects;
    // The result's up axis (results made before it was recorded: +Y, as then).
    let recorded = serde_json::from_str::<serde_json::Value>(&text)
        .ok()
        .and_then(|d| Up::from_axis(d.get("input")?.get("up")?.as_str()?));
    let up = recorded.unwrap_or(Up::Y);
    let model = match to_stdout {
        true => result_model(&a.result),
        false => model_name(&a.out),
    };
    let (format, mut opts) = a.opts.resolve(&a.out, &model, up)?;
    if let Some(input) = &a.input {
        let mesh = primdecomp::Mesh::load(input)?;
        opts.input_mesh = Some(mesh_polygons(&mesh));
    }
    if to_stdout {
        export_to_stdout(&a.out, &objects, format, &opts)?;
    } else {
        for line in wrote_lines(&write_export(&a.out, &objects, format, &opts)?) {
            println!("{line}");
        }
    }
    if let Some(native) = format.up().filter(|&n| n != opts.up) {
        say_turned(opts.up, native, a.opts.up.is_some(), recorded.is_some());
    }
    Ok(())
}

/// Says that the mesh's `up` (given by `--up`, else `recorded` in the result, else
/// assumed) was turned to the format's `native` axis, and how to say otherwise.
fn say_turned(up: Up, native: Up, given: bool, recorded: bool) {
    println!(
        "up        {} in the result{}, turned to the format's {}{}",
        up.axis(),
        match (given, recorded) {
            (true, _) => " (--up)",
            (false, true) => "",
            (false, false) => " (assumed: the result records none)",
        },
        native.axis(),
        match up {
            Up::Y => " (--up z if the mesh stands on z)",
            Up::Z => " (--up y if the mesh stands on y)",
        }
    );
}

/// `export -o -`: the export's one file to standard output; refuses (exit 2) a URDF
/// whose frustums or prisms need mesh files beside it, which a stream cannot carry.
fn export_to_stdout(
    out: &Path,
    objects: &[Body],
    format: Format,
    opts: &ExportOptions,
) -> anyhow::Result<()> {
    let files = render(objects, format, opts, Path::new(&opts.model))?;
    if !files.beside.is_empty() {
        bail!(BadArgs(format!(
            "-o {}: this {} export needs {} mesh file{} beside it (for its frustums and \
             prisms), which standard output cannot carry: give -o a file name",
            out.display(),
            format.name(),
            files.beside.len(),
            if files.beside.len() == 1 { "" } else { "s" }
        )));
    }
    write_out(out, &files.main)?;
    println!("wrote     the {} export to standard output", format.name());
    Ok(())
}

/// One unnamed world-frame object of a level.
pub fn whole(level: &Level) -> Vec<Body> {
    vec![Body {
        name: String::new(),
        frame: Frame::IDENTITY,
        primitives: level.primitives.clone(),
    }]
}

/// Each of `exports` names a format with valid options (what
/// [`write_level_exports`] will ask), or the first error.
pub fn check_exports(exports: &[PathBuf], args: &ExportArgs) -> anyhow::Result<()> {
    for e in exports {
        args.resolve(e, &model_name(e), Up::Y)?;
    }
    Ok(())
}

/// The files a run wrote, one line each, except that the collision meshes a URDF
/// writes into its `{stem}_meshes/` folder are counted on the URDF's line:
/// `wrote     robot.urdf and 96 mesh files in robot_meshes/`.
pub fn wrote_lines(written: &[PathBuf]) -> Vec<String> {
    // The URDF whose meshes folder holds `f`, by its index in `written`.
    let owner = |f: &PathBuf| -> Option<usize> {
        let dir = f.parent()?;
        let name = dir.file_name()?.to_str()?;
        written.iter().position(|h| {
            let urdf = h
                .extension()
                .is_some_and(|e| e.eq_ignore_ascii_case("urdf"));
            let stem = h.file_stem().and_then(|s| s.to_str());
            urdf && h.parent() == dir.parent()
                && stem.is_some_and(|s| name == format!("{s}_meshes"))
        })
    };
    let owners: Vec<Option<usize>> = written.iter().map(owner).collect();
    let mut lines = Vec::new();
    for (i, f) in written
        .iter()
        .enumerate()
        .filter(|(i, _)| owners[*i].is_none())
    {
        let meshes: Vec<&PathBuf> = (written.iter().zip(&owners))
            .filter(|(_, o)| **o == Some(i))
            .map(|(m, _)| m)
            .collect();
        lines.push(match meshes.first().and_then(|m| m.parent()) {
            None => format!("wrote     {}", f.display()),
            Some(dir) => format!(
                "wrote     {} and {} mesh file{} in {}/",
                f.display(),
                meshes.len(),
                if meshes.len() == 1 { "" } else { "s" },
                dir.display()
            ),
        });
    }
    lines
}

/// The input `decompose --export` writes a level of: its path (never to be
/// overwritten), its mesh (for `--preview`) and its up axis.
pub struct Source<'a> {
    pub path: &'a Path,
    pub mesh: &'a primdecomp::Mesh,
    pub up: Up,
}

/// Writes `decompose --export` files of one level; returns the paths.
pub fn write_level_exports(
    exports: &[PathBuf],
    args: &ExportArgs,
    objects: &[Body],
    (label, levels): (&str, usize),
    source: &Source,
) -> anyhow::Result<Vec<PathBuf>> {
    let mut written = Vec::new();
    for e in exports {
        let path = crate::paths::output_path_for(e, label, levels);
        let (format, mut opts) = args.resolve(e, &model_name(e), source.up)?;
        if args.preview {
            opts.input_mesh = Some(mesh_polygons(source.mesh));
        }
        not_an_input("--export", &path, &[source.path])?;
        written.extend(write_export(&path, objects, format, &opts)?);
    }
    Ok(written)
}

#[cfg(test)]
mod tests {
    use super::wrote_lines;
    use std::path::PathBuf;

    /// A URDF's mesh files are one count on its line, wherever they stand in the list;
    /// other files (an MJCF of the same stem, the result) keep a line each.
    #[test]
    fn a_urdfs_meshes_are_counted_on_its_line() {
        let p = |s: &str| PathBuf::from(s);
        let written = [
            p("out/r.json"),
            p("out/r.xml"),
            p("out/r_meshes/a.obj"),
            p("out/r_meshes/b.obj"),
            p("out/r.urdf"),
            p("out/other/c.obj"),
        ];
        assert_eq!(
            wrote_lines(&written),
            [
                "wrote     out/r.json",
                "wrote     out/r.xml",
                "wrote     out/r.urdf and 2 mesh files in out/r_meshes/",
                "wrote     out/other/c.obj",
            ]
        );
    }
}
