//! `primdecomp decompose`: one input written to `-o`, or a batch of inputs written
//! into a directory with a manifest (`--resume`). The settings come from
//! [`settings`], where each input's files go from [`dest`], the run of one input from
//! [`one_input`]; the screen it prints from [`progress`], [`summary`] and [`timings`].

mod dest;
mod one_input;
mod progress;
mod settings;
mod summary;
mod tiled;
mod timings;

use crate::args::DecomposeArgs;
use crate::commands::export::check_exports;
use crate::commands::set_threads;
use crate::exit::BadArgs;
use crate::exit::{eprintln, println};
use crate::manifest::{self, Manifest, Stamp};
use crate::outputs::{check_batch_dir, check_stems, is_stdout, names_dir, Guard, Out};
use anyhow::{anyhow, bail};
use dest::{default_obj, default_out, default_png, Chain, Dest};
use one_input::{run_one, PRINT};
use primdecomp::Target;
use primdecomp::{Decomposition, Params, Tess};
use settings::{max_memory, params_from};
use std::path::{Path, PathBuf};
use summary::print_table;

/// Checks the settings and the outputs, then runs one input or a batch.
pub fn run(a: DecomposeArgs) -> anyhow::Result<()> {
    let (base, targets) = params_from(&a)?;
    if Chain::of(&base).names_levels() && a.per_object {
        bail!(BadArgs(
            "--per-object takes one --tolerance and one --max-bytes value (a chain of \
             levels names its levels by them)"
                .into()
        ));
    }
    if !(3..=Tess::MAX_DETAIL).contains(&a.obj_detail) {
        bail!(BadArgs(format!(
            "--obj-detail must be from 3 to {}, got {}",
            Tess::MAX_DETAIL,
            a.obj_detail
        )));
    }
    if result_to_stdout(&a, &base, &targets)? {
        // What the run says goes to standard error from here on.
        crate::exit::keep_stdout_for_result();
    }
    let guard = Guard::new(a.inputs.iter().map(PathBuf::as_path));
    let dir = match &a.out {
        Some(o) if !is_stdout(o) && (a.inputs.len() > 1 || names_dir(o)) => o.clone(),
        None if a.inputs.len() > 1 => PathBuf::from("."),
        _ => return decompose_one(&a, &base, &targets, &guard),
    };
    decompose_batch(&a, &base, &targets, &guard, &dir)
}

/// Whether the result goes to standard output (`-o -`); refuses (exit 2) what cannot
/// go there: another output than -o, several inputs or levels (each is a file of its
/// own), and `--png`, which draws the result read back from -o's file.
fn result_to_stdout(a: &DecomposeArgs, base: &Params, targets: &[Target]) -> anyhow::Result<bool> {
    let others = [("--obj", a.obj.as_ref()), ("--png", a.png.as_ref())]
        .into_iter()
        .chain(a.export.iter().map(|e| ("--export", Some(e))));
    for (flag, path) in others {
        if path.is_some_and(|p| is_stdout(p)) {
            bail!(BadArgs(format!(
                "{flag} {}: only the result (-o -) can go to standard output; give {flag} \
                 a file name",
                path.map_or(String::new(), |p| p.display().to_string())
            )));
        }
    }
    let Some(out) = a.out.as_ref().filter(|o| is_stdout(o)) else {
        return Ok(false);
    };
    let why = if a.inputs.len() > 1 {
        "several inputs write a result each: give -o a directory (e.g. -o out/)"
    } else if targets.len() > 1 || Chain::of(base).names_levels() {
        "these settings make several levels, a file each: give -o a file name \
         (-o NAME.json writes NAME_LABEL.json per level)"
    } else if a.png.is_some() {
        "--png draws the result read back from -o's file: give -o a file name"
    } else if a.resume {
        "--resume finishes a batch: give -o a directory (e.g. -o out/)"
    } else {
        return Ok(true);
    };
    bail!(BadArgs(format!("-o {}: {why}", out.display())))
}

/// One input, written to -o (or the default name) and --obj as files.
fn decompose_one(
    a: &DecomposeArgs,
    base: &Params,
    targets: &[Target],
    guard: &Guard,
) -> anyhow::Result<()> {
    if a.resume {
        bail!(BadArgs(
            "--resume finishes a batch: give -o a directory (e.g. -o out/), where the \
             batch keeps its manifest"
                .into()
        ));
    }
    let input = &a.inputs[0];
    let dest = Dest {
        json: a.out.clone().unwrap_or_else(|| default_out(input)),
        json_flag: if a.out.is_some() {
            "-o"
        } else {
            "the default output"
        },
        obj: a.obj.clone(),
        exports: a.export.clone(),
        png: a.png.clone(),
        batch_input: None,
        chain: Chain::of(base),
    };
    guard.check(&dest.up_front(targets))?;
    // An export whose format or options are wrong fails now, not after the
    // decomposition has written the levels before it.
    check_exports(&a.export, &a.export_opts)?;
    set_threads(a.threads)?;
    run_one(a, input, base, targets, &dest, guard, false).map(|_| ())
}

/// Several inputs (or -o naming a directory): each writes STEM.primdecomp.json in the
/// directory, one manifest line per input finished (`manifest.rs`), `--resume`
/// skipping what an interrupted run finished.
fn decompose_batch(
    a: &DecomposeArgs,
    base: &Params,
    targets: &[Target],
    guard: &Guard,
    dir: &Path,
) -> anyhow::Result<()> {
    let n = a.inputs.len();
    let dests = prepare_batch(a, base, targets, guard, dir)?;
    let settings = batch_settings(a, base, targets)?;
    let manifest = Manifest::open(dir, a.resume)?;
    clear_stale(a, dir);
    let todo = still_to_do(a, &dests, targets, &manifest, &settings, dir);
    let threads = rayon::current_num_threads();
    let jobs = a.jobs.unwrap_or(threads).max(1);
    let paths: Vec<PathBuf> = todo.iter().map(|&i| a.inputs[i].clone()).collect();
    let results = crate::batch::run_all(&paths, jobs, threads, max_memory(a)?, |k| {
        let (input, dest) = (&a.inputs[todo[k]], &dests[todo[k]]);
        let stamp = Stamp::of(input);
        let r = run_one(a, input, base, targets, dest, guard, jobs > 1);
        let recorded = match &r {
            Ok((_, written)) => manifest.done(input, stamp, &settings, written),
            Err(e) => manifest.failed(input, stamp, &settings, &format!("{e:#}")),
        };
        let r = r.and_then(|(dec, _)| recorded.map(|()| dec));
        if let Err(e) = &r {
            let _out = PRINT.lock();
            eprintln!("error: {e:#}");
        }
        r
    });
    let (rows, worst) = tally(results);
    if a.table {
        print_table(&rows);
    }
    match worst {
        Some(e) => Err(e.context(format!("{} of {n} inputs failed", todo.len() - rows.len()))),
        None => Ok(()),
    }
}

/// Refuses what a batch cannot write, checks every output known before the run and
/// creates the output directories; returns each input's destinations.
fn prepare_batch(
    a: &DecomposeArgs,
    base: &Params,
    targets: &[Target],
    guard: &Guard,
    dir: &Path,
) -> anyhow::Result<Vec<Dest>> {
    let n = a.inputs.len();
    if !a.export.is_empty() {
        bail!(BadArgs(
            "--export writes one file per level of one input; with several inputs, \
             decompose them to a directory and run `primdecomp export` on each result"
                .into()
        ));
    }
    check_batch_dir("-o", dir, n, "json", "STEM.primdecomp.json")?;
    if let Some(o) = &a.obj {
        check_batch_dir("--obj", o, n, "obj", "STEM.primdecomp.obj")?;
    }
    check_stems(&a.inputs, |i| dir.join(default_out(i)))?;
    let dests = batch_dests(a, base, dir);
    let known: Vec<Out> = dests.iter().flat_map(|d| d.up_front(targets)).collect();
    guard.check(&known)?;
    set_threads(a.threads)?;
    for d in std::iter::once(dir)
        .chain(a.obj.as_deref())
        .chain(a.png.as_deref())
    {
        std::fs::create_dir_all(d)
            .map_err(|e| anyhow!("cannot create output directory {}: {e}", d.display()))?;
    }
    Ok(dests)
}

/// Each input's files in a batch: `STEM.primdecomp.json` in `dir`, the OBJ and PNG in
/// theirs.
fn batch_dests(a: &DecomposeArgs, base: &Params, dir: &Path) -> Vec<Dest> {
    a.inputs
        .iter()
        .map(|i| Dest {
            json: dir.join(default_out(i)),
            json_flag: "-o",
            obj: a.obj.as_ref().map(|o| o.join(default_obj(i))),
            exports: Vec::new(),
            png: a.png.as_ref().map(|d| d.join(default_png(i))),
            batch_input: Some(i.clone()),
            chain: Chain::of(base),
        })
        .collect()
}

/// The hash of every setting that changes what a batch writes (`manifest.rs`).
fn batch_settings(a: &DecomposeArgs, base: &Params, targets: &[Target]) -> anyhow::Result<String> {
    manifest::settings_hash(&serde_json::json!({
        "params": base,
        "targets": targets.iter().map(|t| format!("{t:?}")).collect::<Vec<_>>(),
        "per_object": a.per_object,
        "obj": a.obj,
        "obj_detail": a.obj_detail,
        "timings": a.timings,
        "allow_external_uris": a.load.allow_external_uris,
    }))
}

/// The inputs still to run: all of them, or with `--resume` those the manifest does not
/// show finished with these settings and files.
fn still_to_do(
    a: &DecomposeArgs,
    dests: &[Dest],
    targets: &[Target],
    manifest: &Manifest,
    settings: &str,
    dir: &Path,
) -> Vec<usize> {
    let n = a.inputs.len();
    let todo: Vec<usize> = (0..n)
        .filter(|&i| {
            let input = &a.inputs[i];
            !(a.resume && {
                let (expected, could_write) = dests[i].resumable(targets, a.per_object);
                manifest.done_before(
                    input,
                    Stamp::of(input),
                    settings,
                    expected.as_deref(),
                    &could_write,
                )
            })
        })
        .collect();
    if a.resume && !a.quiet {
        println!(
            "resume: {} of {n} inputs were done by an earlier run ({}); running the other {}",
            n - todo.len(),
            dir.join(manifest::NAME).display(),
            todo.len()
        );
    }
    todo
}

/// The decompositions that succeeded, and the error to report: the last one, except
/// that a failure that is not the input's fault (exit 1), once seen, is kept.
fn tally(
    results: Vec<anyhow::Result<Decomposition>>,
) -> (Vec<Decomposition>, Option<anyhow::Error>) {
    let mut rows = Vec::new();
    let mut worst: Option<anyhow::Error> = None;
    for r in results {
        match r {
            Ok(dec) => rows.push(dec),
            // A failure that is not the input's fault (exit 1) outranks bad input.
            Err(e) if worst.as_ref().is_some_and(|w| crate::exit::code(w) == 1) => drop(e),
            Err(e) => worst = Some(e),
        }
    }
    (rows, worst)
}

/// Removes what a killed run left half-written in the output directories: the
/// temporary files (`write_atomic`'s `.NAME.tmp.PID.N`) of this batch's outputs
/// (`STEM.primdecomp[_nT].json` or `.obj`), where process PID is gone.
fn clear_stale(a: &DecomposeArgs, dir: &Path) {
    let stems: std::collections::HashSet<String> = a
        .inputs
        .iter()
        .filter_map(|i| Some(i.file_stem()?.to_string_lossy().into_owned()))
        .collect();
    let ours = |name: &str| {
        let ext = name.ends_with(".json") || name.ends_with(".obj");
        ext && name
            .rsplit_once(".primdecomp")
            .is_some_and(|(stem, _)| stems.contains(stem))
    };
    for d in std::iter::once(dir).chain(a.obj.as_deref()) {
        manifest::remove_stale_temporaries(d, &ours);
    }
}
