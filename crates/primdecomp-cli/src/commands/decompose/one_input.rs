//! One input's run: load, decompose (whole, or each object with `--per-object`), write
//! the JSON, OBJ, exports and PNG of every level, print the summary.

use super::dest::Dest;
use super::progress::Shown;
use super::settings::{load_options, resolve_targets};
use super::summary::print_summary;
use super::timings::{print_timings, StageMemory};
use crate::args::DecomposeArgs;
use crate::commands::export::{whole, write_level_exports, Source};
use crate::exit::println;
use crate::exit::BadArgs;
use crate::outputs::{write_out, Guard};
use crate::paths::output_path_for;
use anyhow::{anyhow, bail};
use primdecomp::Stage;
use primdecomp::Target;
use primdecomp::{Decomposition, Goal, Params};
use primdecomp_files::write_atomic;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Keeps one input's messages together when several inputs run at once.
pub(super) static PRINT: std::sync::Mutex<()> = std::sync::Mutex::new(());

/// Loads, decomposes and writes one input; `beside_others` (several inputs at once):
/// no progress bar, and the messages printed in one block. Returns the decomposition
/// and the files written.
pub(super) fn run_one(
    a: &DecomposeArgs,
    input: &Path,
    base: &Params,
    targets: &[Target],
    dest: &Dest,
    guard: &Guard,
    beside_others: bool,
) -> anyhow::Result<(Decomposition, Vec<PathBuf>)> {
    // Peaks per stage only for a run alone in the process: the mark is process-wide.
    let memory = (a.timings && !beside_others).then(|| StageMemory::new("load"));
    let now = Instant::now();
    let options = load_options(a, base)?;
    // Read whole, unless the input is to be (or must be) decomposed in tiles.
    let (loaded, why) = load_whole(a, input, &options)?;
    let (mesh, params, mut dec) = match loaded {
        Some(Ok(mesh)) => {
            let load_s = now.elapsed().as_secs_f64();
            let counts = resolve_targets(targets, mesh.face_count());
            let params = Params {
                goal: base.goal.with_targets(counts),
                ..base.clone()
            };
            if a.per_object {
                let (mut dec, written) =
                    run_objects(a, input, &params, targets, &mesh, dest, guard)?;
                dec.timings.insert(0, ("load".into(), load_s));
                return Ok((dec, written));
            }
            let mut dec = decompose_shown(a, &mesh, &params, memory.as_ref(), beside_others)?;
            dec.timings.insert(0, ("load".into(), load_s));
            (mesh, params, dec)
        }
        refused => {
            let why = (why.as_deref().unwrap_or_default(), beside_others);
            let tiled = super::tiled::decompose(a, input, base, targets, dest, &options, why);
            let (dec, params) = tiled.map_err(|t| refusal_first(t, refused))?;
            (primdecomp::Mesh::from_triangles(&[], &[])?, params, dec)
        }
    };
    record_input(&mut dec.input, a, input);
    let now = Instant::now();
    let mut written = write_outputs(&dec, &params, dest, guard, a.obj_detail, a.timings)?;
    let up = dec.input.up.unwrap_or_default();
    written.extend(write_exports(a, &dec, dest, input, &mesh, up)?);
    let write_s = now.elapsed().as_secs_f64();
    let memory = memory.map(StageMemory::finish);
    if let Some(png) = &dest.png {
        let label = dest.labels(&[dec.levels[0].target]).swap_remove(0);
        written.push(decompose_png(&dest.json, &label, &dec, input, &mesh, png)?);
    }
    let _out = PRINT.lock();
    let (why, memory) = (why.as_deref(), memory.as_deref());
    report(a, (&dec, &mesh), &written, why, write_s, memory);
    Ok((dec, written))
}

/// Where not even tiles fit, the refusal of the input read whole, which says why;
/// else the tiled run's error.
fn refusal_first(tiled: anyhow::Error, refused: Option<Loaded>) -> anyhow::Error {
    match (tiled.downcast_ref(), refused) {
        (Some(primdecomp::Error::TooLarge { .. }), Some(Err(e))) => e.into(),
        _ => tiled,
    }
}

/// A mesh read whole, or why it was not.
type Loaded = Result<primdecomp::Mesh, primdecomp::Error>;

/// The input read whole (`None` when it is to be decomposed in tiles, `Some(Err)` when
/// read whole it would not fit and tiles may), and why it is decomposed in tiles.
fn load_whole(
    a: &DecomposeArgs,
    input: &Path,
    options: &primdecomp::LoadOptions,
) -> anyhow::Result<(Option<Loaded>, Option<String>)> {
    if let Some(why) = super::tiled::reason(a, input, options) {
        return Ok((None, Some(why)));
    }
    match primdecomp::Mesh::load_with(input, options) {
        Err(e @ primdecomp::Error::TooLarge { needed, limit, .. }) if !a.per_object => {
            Ok((Some(Err(e)), Some(super::tiled::over(needed, limit))))
        }
        m => Ok((Some(Ok(m?)), None)),
    }
}

/// The whole mesh decomposed, with the progress bar and the stages' memory marks.
fn decompose_shown(
    a: &DecomposeArgs,
    mesh: &primdecomp::Mesh,
    params: &Params,
    memory: Option<&StageMemory>,
    beside_others: bool,
) -> anyhow::Result<Decomposition> {
    let shown = Shown::new(params, mesh.face_count(), a, beside_others);
    let dec = primdecomp::decompose_with(mesh, params, &|stage: Stage, f: f64| {
        if let Some(m) = memory {
            m.enter(stage.name());
        }
        shown.update(stage, f);
    })?;
    shown.finish();
    Ok(dec)
}

/// The summary (unless `--quiet`) and the stages' timings (`--verbose`, `--timings`)
/// or the run's time.
fn report(
    a: &DecomposeArgs,
    (dec, mesh): (&Decomposition, &primdecomp::Mesh),
    written: &[PathBuf],
    why_tiled: Option<&str>,
    write_s: f64,
    memory: Option<&[(String, f64, f64)]>,
) {
    if !a.quiet {
        if let Some(why) = why_tiled {
            println!("tiles     {}: {why}", dec.stats.tiles);
        }
        print_summary(dec, mesh, written, a.verbose, None);
    }
    if a.verbose || a.timings {
        print_timings(dec, write_s, a.inputs.len() > 1, a.verbose, memory);
    } else if !a.quiet {
        println!("time      {:.2} s", dec.seconds() + write_s);
    }
}

/// `--export`: each level's file in each format asked for; returns the paths written.
fn write_exports(
    a: &DecomposeArgs,
    dec: &Decomposition,
    dest: &Dest,
    input: &Path,
    mesh: &primdecomp::Mesh,
    up: primdecomp::Up,
) -> anyhow::Result<Vec<PathBuf>> {
    let mut written = Vec::new();
    let counts: Vec<usize> = dec.levels.iter().map(|l| l.target).collect();
    for (level, label) in dec.levels.iter().zip(dest.labels(&counts)) {
        written.extend(write_level_exports(
            &a.export,
            &a.export_opts,
            &whole(level),
            (&label, dec.levels.len()),
            &Source {
                path: input,
                mesh,
                up,
            },
        )?);
    }
    Ok(written)
}

/// `--per-object`: decomposes each object on its own and writes the JSON (with
/// `objects`), the OBJ (world primitives) and the exports per level. Returns a
/// decomposition of the world primitives for the summary and the table.
fn run_objects(
    a: &DecomposeArgs,
    input: &Path,
    params: &Params,
    targets: &[Target],
    mesh: &primdecomp::Mesh,
    dest: &Dest,
    guard: &Guard,
) -> anyhow::Result<(Decomposition, Vec<PathBuf>)> {
    if a.obj_detail < 3 {
        bail!(BadArgs(format!(
            "--obj-detail must be at least 3, got {}",
            a.obj_detail
        )));
    }
    let now = Instant::now();
    let mut objs = decompose_objects(mesh, params, targets, input)?;
    record_input(&mut objs.input, a, input);
    let (mut written, mut dec) = (Vec::new(), totals(&objs));
    dec.timings
        .push(("decompose".into(), now.elapsed().as_secs_f64()));
    let jsons = level_jsons(&objs, params)?;
    // The names are known only now (a percentage's count): check them before writing.
    let outs = dest.outs(&jsons.iter().map(|j| j.0).collect::<Vec<_>>());
    guard.check(&outs)?;
    let per_level = if dest.obj.is_some() { 2 } else { 1 };
    let source = Source {
        path: input,
        mesh,
        up: objs.input.up.unwrap_or_default(),
    };
    for (i, (target, json)) in jsons.into_iter().enumerate() {
        let level = world_level(&objs, i, target, params, mesh.diagonal());
        let files = &outs[i * per_level..(i + 1) * per_level];
        written.extend(write_object_level(
            files,
            &json,
            &level,
            a.obj_detail,
            guard,
        )?);
        written.extend(write_level_exports(
            &a.export,
            &a.export_opts,
            &objs.bodies(i),
            (&format!("n{target}"), objs.levels()),
            &source,
        )?);
        dec.levels.push(level);
    }
    let _out = PRINT.lock();
    if !a.quiet {
        print_objects(&objs);
        print_summary(&dec, mesh, &written, a.verbose, Some(&objs));
    }
    Ok((dec, written))
}

/// Each object decomposed; settings an object cannot take are the user's to change
/// (a usage error naming the input).
fn decompose_objects(
    mesh: &primdecomp::Mesh,
    params: &Params,
    targets: &[Target],
    input: &Path,
) -> anyhow::Result<primdecomp::Objects> {
    primdecomp::Objects::decompose(mesh, params, targets).map_err(|e| match e {
        primdecomp::Error::InvalidParams(m) => BadArgs(format!("{}: {m}", input.display())).into(),
        e => anyhow::Error::from(e),
    })
}

/// One level of a per-object run: its JSON to `files[0]` and, when asked for, its
/// world primitives as OBJ to `files[1]`; returns the paths written.
fn write_object_level(
    files: &[crate::outputs::Out],
    json: &str,
    level: &primdecomp::Level,
    detail: usize,
    guard: &Guard,
) -> anyhow::Result<Vec<PathBuf>> {
    let mut written = Vec::new();
    for (k, out) in files.iter().enumerate() {
        let bytes = match k {
            0 => json.to_owned(),
            _ => level.to_obj(detail),
        };
        write_out(&out.path, bytes.as_bytes())?;
        guard.wrote(out);
        written.push(out.path.clone());
    }
    Ok(written)
}

/// A decomposition standing for all of `objs` in the summary: their input and the sums
/// of their welding and adjacency counts; no levels yet.
fn totals(objs: &primdecomp::Objects) -> Decomposition {
    let sum = |f: fn(&primdecomp::Stats) -> usize| {
        objs.objects.iter().map(|o| f(&o.decomposition.stats)).sum()
    };
    Decomposition {
        input: objs.input.clone(),
        stats: primdecomp::Stats {
            welded_vertices: sum(|s| s.welded_vertices),
            adjacency_edges: sum(|s| s.adjacency_edges),
            ..Default::default()
        },
        ..Default::default()
    }
}

/// Each level's JSON with its target, read back from the JSON (a percentage's count
/// is known only once decomposed).
fn level_jsons(
    objs: &primdecomp::Objects,
    params: &Params,
) -> anyhow::Result<Vec<(usize, String)>> {
    let n = objs.levels();
    let mut jsons = Vec::with_capacity(n);
    for i in 0..n {
        let json = objs.to_json(i, params);
        let v: serde_json::Value = serde_json::from_str(&json)?;
        jsons.push((v["settings"]["target"].as_u64().unwrap_or(0) as usize, json));
    }
    Ok(jsons)
}

/// Level `i` of `objs` as one level of world primitives (for the OBJ and the summary).
fn world_level(
    objs: &primdecomp::Objects,
    i: usize,
    target: usize,
    params: &Params,
    diagonal: f64,
) -> primdecomp::Level {
    primdecomp::Level {
        target,
        merged_to: target,
        primitives: objs.world_primitives(i),
        // For the summary line: each object's tolerance is this share of its own
        // diagonal (--per-object takes one value).
        tolerance: match &params.goal {
            Goal::Within { tolerance, .. } => tolerance.first().map(|t| t.in_units(diagonal)),
            _ => None,
        },
        max_bytes: match &params.goal {
            Goal::Within { max_bytes, .. } => max_bytes.first().copied(),
            _ => None,
        },
        // The farthest object's distance, and what stopped that object nearer;
        // to the solid where an object's was (one without an inside is its surface).
        distance: objs.distance(i),
        distance_to_solid: (objs.objects.iter())
            .any(|o| o.decomposition.levels[i].distance_to_solid),
        shortfall: objs
            .objects
            .iter()
            .map(|o| &o.decomposition.levels[i])
            .filter(|l| l.distance.is_some())
            .max_by(|a, b| {
                a.distance
                    .unwrap_or(0.0)
                    .total_cmp(&b.distance.unwrap_or(0.0))
            })
            .and_then(|l| l.shortfall),
        ..Default::default()
    }
}

/// The objects line of the summary: each object's name and faces.
fn print_objects(objs: &primdecomp::Objects) {
    println!(
        "objects   {}: {}",
        objs.objects.len(),
        objs.objects
            .iter()
            .map(|o| format!("{:?} ({} faces)", o.name, o.faces))
            .collect::<Vec<_>>()
            .join(", ")
    );
}

/// Records the input file and its up axis in the result: `--up`, else what its format
/// says (`InputInfo::record_file`).
fn record_input(info: &mut primdecomp::InputInfo, a: &DecomposeArgs, input: &Path) {
    info.record_file(input);
    if let Some(up) = a
        .export_opts
        .up
        .as_deref()
        .and_then(primdecomp::Up::from_axis)
    {
        (info.up, info.up_from) = (Some(up), Some("given with --up".into()));
    }
}

/// Writes JSON (and OBJ) per level atomically, after checking that none of the files
/// is an input or another output of the run ([`Guard`]); returns the paths written.
/// With `timed` (`--timings`) the JSON holds the stage timings, which stop before
/// writing (the file cannot time its own write); without, it is byte-identical across
/// runs.
fn write_outputs(
    dec: &Decomposition,
    params: &Params,
    dest: &Dest,
    guard: &Guard,
    detail: usize,
    timed: bool,
) -> anyhow::Result<Vec<PathBuf>> {
    let levels: Vec<usize> = dec.levels.iter().map(|l| l.target).collect();
    let outs = dest.outs(&levels);
    guard.check(&outs)?;
    let per_level = if dest.obj.is_some() { 2 } else { 1 };
    let mut written = Vec::new();
    for (out, k) in outs.iter().zip(0..) {
        let (i, is_obj) = (k / per_level, k % per_level == 1);
        let level = &dec.levels[i];
        let bytes = if is_obj {
            level.to_obj(detail)
        } else if timed {
            dec.to_json_timed(i, params)
        } else {
            dec.to_json(i, params)
        };
        write_out(&out.path, bytes.as_bytes())?;
        guard.wrote(out);
        written.push(out.path.clone());
    }
    Ok(written)
}

/// `decompose --png`: the first level, read back from the JSON just written, over
/// the input; with several inputs `png` is a directory. Returns the file written.
fn decompose_png(
    out: &Path,
    label: &str,
    dec: &Decomposition,
    input: &Path,
    mesh: &primdecomp::Mesh,
    png: &Path,
) -> anyhow::Result<PathBuf> {
    use primdecomp_view::{scene, source};
    let json = output_path_for(out, label, dec.levels.len());
    let opts = scene::Options {
        up_axis: match dec.input.up {
            Some(primdecomp::Up::Z) => 2,
            _ => 1,
        },
        ..scene::Options::default()
    };
    let s = scene::Scene {
        input: Some(scene::input_from(
            input,
            &source::from_core_mesh(mesh),
            &opts,
        )),
        levels: scene::load_levels(&json, &opts)?,
        peers: Vec::new(),
        eval: Vec::new(),
        up_axis: opts.up_axis,
    };
    let bytes = primdecomp_view::render_png(&s, primdecomp_view::PNG_SIZE)
        .ok_or_else(|| anyhow!("{}: nothing to draw", input.display()))?;
    write_atomic(png, &bytes)?;
    Ok(png.to_path_buf())
}
