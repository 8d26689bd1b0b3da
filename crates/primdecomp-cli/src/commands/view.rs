//! `primdecomp view`: a self-contained HTML viewer page and/or a PNG of its default
//! view, showing results, the input mesh and peers' hulls.

use crate::args::LoadArgs;
use crate::exit::println;
use crate::exit::BadArgs;
use crate::outputs::{is_stdout, write_out, Guard, Out};
use crate::paths::memory_limit;
use anyhow::bail;
use clap::Args;
use primdecomp::LoadOptions;
use primdecomp_view::scene;
use std::path::{Path, PathBuf};

/// `primdecomp view`.
#[derive(Args, Debug)]
pub struct ViewArgs {
    /// Result JSON files of `primdecomp decompose`, one level each (or a document with
    /// a `levels` array). A multi-target run's `-o` name (out.json) stands for the
    /// files it wrote (out_n200.json, out_n50.json): every level, largest first.
    results: Vec<PathBuf>,
    /// The input mesh (OBJ, PLY, STL, OFF, glTF/GLB), shown semi-transparent; large
    /// meshes are simplified for display (--display-faces). Default: the first
    /// result's `input.path` when that file exists (--no-input: none).
    #[arg(long)]
    input: Option<PathBuf>,
    /// Show no input mesh.
    #[arg(long, conflicts_with = "input")]
    no_input: bool,
    /// Peers' convex hulls as OBJ (one `o`/`g` per hull, as CoACD and V-HACD write),
    /// shown beside ours.
    #[arg(long, num_args = 1.., value_name = "HULLS.obj")]
    compare: Vec<PathBuf>,
    /// An evaluation of these colliders (`primdecomp eval ... --json E.json`): its
    /// distances go into the panel.
    #[arg(long, value_name = "E.json")]
    eval: Option<PathBuf>,
    /// Write the viewer page here: one HTML file that works offline from disk (`-`:
    /// to standard output).
    #[arg(short, long, value_name = "view.html")]
    out: Option<PathBuf>,
    /// Write a PNG of the page's default view here (software-rendered, no browser;
    /// `-`: to standard output).
    #[arg(long, value_name = "OUT.png")]
    png: Option<PathBuf>,
    /// Width and height in pixels of each pane of the PNG (side by side when peers are
    /// shown).
    #[arg(long, default_value_t = primdecomp_view::PNG_SIZE)]
    png_size: usize,
    /// Which axis points up in the mesh: y or z (default: what the first result
    /// records, else what the input's file format says, as `decompose --up`).
    ///
    /// The default view looks from the front right, above.
    #[arg(long, value_parser = ["y", "z"], ignore_case = true)]
    up: Option<String>,
    /// Most input triangles shown; larger inputs are simplified (meshoptimizer) to this.
    #[arg(long, default_value_t = primdecomp_view::simplify::DISPLAY_TRIANGLES)]
    display_faces: usize,
    /// Segments around circles in the primitives' shown tessellation (fewer where the
    /// page would otherwise hold over 2 million triangles of parts).
    #[arg(long, default_value_t = 24)]
    detail: usize,
    /// Refuse an input mesh (--input, or the result's input.path) whose reading needs
    /// more memory than this, as decompose's --max-memory: a size like 8G, 'available'
    /// (the memory available now) or 'none'.
    #[arg(long, default_value = "available")]
    max_memory: String,
    /// Print nothing but errors.
    #[arg(short, long)]
    quiet: bool,
    #[command(flatten)]
    load: LoadArgs,
}

/// Reads every file first (a bad one fails the run before anything is written), then
/// writes the page and the PNG atomically.
pub fn run(a: ViewArgs) -> anyhow::Result<()> {
    check_args(&a)?;
    if a.quiet {
        crate::exit::quiet_from_now();
    }
    // Nothing the page or the PNG is made from may be overwritten by them.
    let read: Vec<PathBuf> = a
        .results
        .iter()
        .flat_map(|r| scene::result_files(r))
        .chain(a.input.iter().chain(&a.compare).chain(&a.eval).cloned())
        .collect();
    let guard = Guard::new(read.iter().map(PathBuf::as_path));
    let outs: Vec<Out> = [("-o", &a.out), ("--png", &a.png)]
        .into_iter()
        .filter_map(|(flag, p)| p.as_ref().map(|p| Out::flag(flag, p, p.clone())))
        .collect();
    guard.check(&outs)?;
    if outs.iter().any(|o| is_stdout(&o.path)) {
        // The page or the picture alone on standard output; what the run says goes
        // to standard error.
        crate::exit::keep_stdout_for_result();
    }
    let (s, title) = scene_of(&a)?;
    check_extent(&s)?;
    if let Some(i) = &s.input {
        if i.display.simplified {
            println!(
                "input     {}: {} triangles shown of {} (simplified for display)",
                i.file,
                i.display.triangles.len(),
                i.display.source_triangles
            );
        }
    }
    if let Some(out) = &a.out {
        write_out(out, primdecomp_view::html::page(&s, &title).as_bytes())?;
        println!("wrote     {}", shown(out, "the page"));
    }
    if let Some(png) = &a.png {
        let bytes =
            primdecomp_view::render_png(&s, a.png_size).expect("checked: the scene has triangles");
        write_out(png, &bytes)?;
        println!("wrote     {}", shown(png, "the picture"));
    }
    Ok(())
}

/// How the summary names an output: its path, or `what` went to standard output.
fn shown(path: &Path, what: &str) -> String {
    match is_stdout(path) {
        true => format!("{what} to standard output"),
        false => path.display().to_string(),
    }
}

/// The flags' own checks: something to write, something to show, sizes in range.
fn check_args(a: &ViewArgs) -> anyhow::Result<()> {
    if a.out.is_none() && a.png.is_none() {
        bail!(BadArgs(
            "view: nothing to write: give -o view.html and/or --png OUT.png".into()
        ));
    }
    if a.results.is_empty() && a.input.is_none() && a.compare.is_empty() {
        bail!(BadArgs(
            "view: nothing to show: give a result JSON, --input or --compare".into()
        ));
    }
    if !(16..=8192).contains(&a.png_size) {
        bail!(BadArgs(format!(
            "--png-size must be 16 to 8192, got {}",
            a.png_size
        )));
    }
    if !(3..=primdecomp::Tess::MAX_DETAIL).contains(&a.detail) {
        bail!(BadArgs(format!(
            "--detail must be from 3 to {}, got {}",
            primdecomp::Tess::MAX_DETAIL,
            a.detail
        )));
    }
    Ok(())
}

/// The scene to draw, every file read, and the page's title.
fn scene_of(a: &ViewArgs) -> anyhow::Result<(scene::Scene, String)> {
    let up = view_up(a);
    let mut opts = scene::Options {
        detail: a.detail,
        display_triangles: a.display_faces.max(1),
        up_axis: if up == primdecomp::Up::Z { 2 } else { 1 },
        load: LoadOptions {
            max_memory: memory_limit(&a.max_memory)?,
            allow_external_uris: a.load.allow_external_uris,
            ..LoadOptions::default()
        },
    };
    let (levels, peers) = levels_and_peers(a, &mut opts)?;
    let input_path = match (&a.input, a.no_input) {
        (Some(p), _) => Some(p.clone()),
        (None, true) => None,
        (None, false) => a
            .results
            .first()
            .and_then(|r| scene::result_files(r).into_iter().next())
            .and_then(|f| recorded_input(&f)),
    };
    let input = input_path
        .as_deref()
        .map(|p| scene::load_input(p, &opts))
        .transpose()?;
    let eval = match &a.eval {
        Some(e) => scene::load_eval(e, &levels, &peers)?,
        None => Vec::new(),
    };
    let title = a
        .results
        .first()
        .or(input_path.as_ref())
        .or(a.compare.first())
        .and_then(|p| p.file_name())
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let s = scene::Scene {
        input,
        levels,
        peers,
        eval,
        up_axis: opts.up_axis,
    };
    Ok((s, title))
}

/// The results' levels and the peers' hulls, with circles coarse enough that the page
/// stays within its triangles (`opts.detail`).
fn levels_and_peers(
    a: &ViewArgs,
    opts: &mut scene::Options,
) -> anyhow::Result<(Vec<scene::Collider>, Vec<scene::Collider>)> {
    let mut docs = Vec::new();
    for r in &a.results {
        for f in scene::result_files(r) {
            docs.extend(scene::read_levels(&f)?);
        }
    }
    let peers = a
        .compare
        .iter()
        .map(|p| scene::load_peer(p, None))
        .collect::<Result<Vec<_>, primdecomp::Error>>()?;
    // A page shows a bounded number of parts and triangles: coarser circles first.
    let hulls = peers.iter().map(|c| c.parts.len()).sum();
    let hull_triangles = peers.iter().map(|c| c.parts.triangles.len()).sum();
    opts.detail = scene::fit_detail(&docs, hulls, hull_triangles, a.detail)
        .map_err(|m| BadArgs(format!("view: {m}")))?;
    if opts.detail < a.detail && !docs.is_empty() {
        println!(
            "levels    shown with {} segments around circles (of --detail {}), so the parts \
             stay within {} triangles",
            opts.detail,
            a.detail,
            scene::MAX_PART_TRIANGLES
        );
    }
    let levels: Vec<scene::Collider> = docs
        .iter()
        .map(|d| scene::build_level(d, opts.detail))
        .collect();
    Ok((levels, peers))
}

/// Refuses a scene with nothing to draw, or wider than the page draws.
fn check_extent(s: &scene::Scene) -> anyhow::Result<()> {
    let Some((lo, hi)) = s.aabb() else {
        bail!(BadArgs(
            "view: the files hold nothing to draw (no triangles)".into()
        ));
    };
    // The page draws in 32-bit floats relative to the scene's centre.
    let span = (0..3).fold(0.0f64, |m, k| m.max(hi[k] - lo[k]));
    if span.is_nan() || span > primdecomp_view::MAX_SPAN {
        bail!(BadArgs(format!(
            "view: the scene spans {span:e}, more than the {:e} a page draws in 32-bit floats",
            primdecomp_view::MAX_SPAN
        )));
    }
    Ok(())
}

/// `view`'s up axis: `--up`, else the first result's (`input.up`), else what the
/// input's format says (as `decompose`), else +Y.
fn view_up(a: &ViewArgs) -> primdecomp::Up {
    use primdecomp::Up;
    let recorded = || {
        let first = a.results.first()?;
        let file = scene_first_file(first)?;
        let doc: serde_json::Value =
            serde_json::from_str(&crate::paths::read_result(&file).ok()?).ok()?;
        let doc = doc.get("levels").and_then(|l| l.get(0)).unwrap_or(&doc);
        Up::from_axis(doc.get("input")?.get("up")?.as_str()?)
    };
    let of_input =
        || Some(Up::of_format(primdecomp::MeshFormat::from_path(a.input.as_deref()?)?).0);
    a.up.as_deref()
        .and_then(Up::from_axis)
        .or_else(recorded)
        .or_else(of_input)
        .unwrap_or(Up::Y)
}

/// The first file a result argument stands for (`out.json` → `out_n200.json`).
fn scene_first_file(r: &Path) -> Option<PathBuf> {
    primdecomp_view::scene::result_files(r).into_iter().next()
}

/// The input a result document names (`input.path`), if that file exists here.
fn recorded_input(result: &Path) -> Option<PathBuf> {
    let text = crate::paths::read_result(result).ok()?;
    let doc: serde_json::Value = serde_json::from_str(&text).ok()?;
    let doc = doc.get("levels").and_then(|l| l.get(0)).unwrap_or(&doc);
    let p = PathBuf::from(doc.get("input")?.get("path")?.as_str()?);
    p.is_file().then_some(p)
}
