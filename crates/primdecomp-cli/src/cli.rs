//! Command-line interface: argument parsing (clap), the one-screen summary, progress
//! bar and exit codes (0 ok, 2 bad input or settings, 1 anything else).

use crate::args::{DecomposeArgs, LoadArgs};
use crate::exit::BadArgs;
use crate::exit::{eprintln, print, println};
use crate::manifest::{self, Manifest, Stamp};
use crate::outputs::{check_batch_dir, check_stems, names_dir, Guard, Out};
use crate::paths::{level_labels, output_path_for};
use anyhow::{anyhow, bail};
use clap::{Args, Parser, Subcommand};
use primdecomp::{export, write_atomic, LoadOptions, Stage};
use primdecomp::{Decomposition, Dedup, Kind, Params, Partitions, Reprice, Tolerance};
// `decompose --export` writes through export_cmd.
use primdecomp_sim::{Entry, Geometry, Run as SimRun, Settings as SimSettings};
use std::path::{Path, PathBuf};
use std::time::Instant;

#[derive(Parser, Debug)]
#[command(
    name = "primdecomp",
    version,
    about = "Decompose a mesh into tight convex primitives for collision detection"
)]
struct Cli {
    #[command(subcommand)]
    cmd: Cmd,
}

#[derive(Subcommand, Debug)]
enum Cmd {
    /// Decompose INPUT (OBJ, PLY, STL, OFF, glTF/GLB) into boxes, spheres, capsules,
    /// cylinders, frustums and trapezoidal prisms that enclose every face.
    Decompose(Box<DecomposeArgs>),
    /// Measure colliders against their input mesh: distances, enclosure, bytes.
    Eval(EvalArgs),
    /// Drop balls on the input mesh and on each collider in Rapier, time every frame's
    /// physics step and compare where the balls end (the paper's §4.1 benchmark).
    Sim(SimArgs),
    /// Look at colliders: a self-contained HTML viewer page (-o) and/or a PNG render
    /// of its default view (--png) of results, the input mesh and peers' hulls.
    View(ViewArgs),
    /// Write a result's colliders for an engine: glTF/GLB with physics extensions,
    /// MuJoCo MJCF, URDF, USD (.usda) or a Godot 4 scene (.tscn).
    Export(Box<crate::export_cmd::ExportCmd>),
    /// Write the built-in demo scene (stairs, table, pipes, house, ring, washer) as OBJ.
    DemoScene {
        /// Output file.
        #[arg(short, long, default_value = "datasets/demo_scene.obj")]
        out: PathBuf,
    },
}

/// `primdecomp eval`. The sampling-error figures in the help come from
/// `benches/eval_spread.sh` (see docs/results/eval_sampling.md).
#[derive(Args, Debug)]
#[command(after_help = EVAL_HELP)]
struct EvalArgs {
    /// The input mesh the colliders were made for (OBJ, PLY, STL, OFF, glTF/GLB).
    #[arg(long)]
    input: PathBuf,
    /// Colliders: primdecomp JSON, or OBJ convex hulls (one `o`/`g` per hull).
    #[arg(required = true)]
    colliders: Vec<PathBuf>,
    /// Area-uniform samples per surface (collider surface, input surface).
    #[arg(long, default_value_t = primdecomp_eval::DEFAULT_SAMPLES)]
    samples: usize,
    /// Seed of the samples; results are the same for a seed on any thread count.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Also write the metrics as JSON here (atomically).
    #[arg(long)]
    json: Option<PathBuf>,
    /// Worker threads (default: all cores); results do not depend on it.
    #[arg(long)]
    threads: Option<usize>,
    #[command(flatten)]
    load: LoadArgs,
}

const EVAL_HELP: &str = include_str!("eval_help.txt");

#[derive(Args, Debug)]
struct SimArgs {
    /// The input mesh (the reference, simulated as a triangle mesh).
    #[arg(long)]
    input: PathBuf,
    /// Colliders: primdecomp JSON results, or OBJ files of convex hulls (one per o/g).
    colliders: Vec<PathBuf>,
    /// Balls dropped on each collider.
    #[arg(long, default_value_t = 5000)]
    balls: usize,
    /// Frames simulated (1/60 s each).
    #[arg(long, default_value_t = 1000)]
    frames: usize,
    /// Seed of the release-position jitter.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Threads for Rapier's parallel step (1 is the most repeatable).
    #[arg(long, default_value_t = 1)]
    threads: usize,
    /// Up axis of the input: gravity points along its negative direction.
    #[arg(long, default_value = "y", value_parser = ["x", "y", "z"])]
    up: String,
    /// Write the report (per collider: frame times, similarity, …) as JSON.
    #[arg(long)]
    json: Option<PathBuf>,
    /// Write per-frame physics-step times (`<mesh>_frame_ms.csv`) and every ball's end
    /// point per collider (`<mesh>_ends.csv`) as CSV into this directory.
    #[arg(long)]
    csv: Option<PathBuf>,
    /// Write a PNG plot of frame time against frame number.
    #[arg(long)]
    plot: Option<PathBuf>,
    /// Skip the perturbed copy of the reference (the mesh against itself with every
    /// ball started up to 1e-4 ball radii away: the behaviour measures' noise floor).
    #[arg(long)]
    no_perturbed: bool,
    /// Attribute each collider's step time: Rapier's per-stage times and the contact
    /// pairs per frame by shape kind, in the JSON report (`profile`) and printed.
    #[arg(long)]
    profile: bool,
    /// Give Rapier each collider's parts as one compound shape (one collider with its
    /// own BVH, as Rapier's `ColliderBuilder::convex_decomposition` does) instead of
    /// one collider per part; every collider alike.
    #[arg(long)]
    compound: bool,
    /// `drop`: balls dropped on the object, frame time and behaviour (paper §4.1).
    /// `projectiles`: balls fired at the object from every side at four speeds
    /// (0.1, 0.5, 2, 10 ball diameters per frame), CCD off unless --ccd, counting
    /// the balls that pass through (end inside the input's volume or beyond it).
    #[arg(long, default_value = "drop", value_parser = ["drop", "projectiles"])]
    scenario: String,
    /// Projectiles: shots per collider and speed (Fibonacci-sphere directions).
    #[arg(long, default_value_t = 256)]
    shots: usize,
    /// Projectiles: continuous collision detection on the balls (engines default to off).
    #[arg(long)]
    ccd: bool,
    /// Print nothing but errors.
    #[arg(short, long)]
    quiet: bool,
    #[command(flatten)]
    load: LoadArgs,
}

/// Runs the command line; returns the process exit code.
pub fn main() -> i32 {
    let cli = match Cli::try_parse() {
        Ok(c) => c,
        Err(e) => {
            let _ = e.print();
            return if e.use_stderr() { 2 } else { 0 };
        }
    };
    let result = match cli.cmd {
        Cmd::Decompose(a) => decompose(*a),
        Cmd::Eval(a) => eval(a),
        Cmd::Sim(a) => sim(a),
        Cmd::View(a) => view(a),
        Cmd::Export(a) => crate::export_cmd::export(*a),
        Cmd::DemoScene { out } => write_atomic(&out, primdecomp::demo_scene_obj().as_bytes())
            .map_err(anyhow::Error::from)
            .map(|_| println!("wrote {}", out.display())),
    };
    match result {
        Ok(()) => 0,
        Err(e) => crate::exit::report(&e),
    }
}

/// The settings: the defaults, then `--config`, then every flag given.
fn params_from(a: &DecomposeArgs) -> anyhow::Result<Params> {
    let mut p = match &a.config {
        Some(path) => read_config(path)?,
        None => Params::default(),
    };
    let set = |field: &mut f64, v: Option<f64>| {
        if let Some(v) = v {
            *field = v;
        }
    };
    set(&mut p.tangent_eps, a.tangent_eps);
    set(&mut p.min_extent, a.min_extent);
    set(&mut p.open_holes, a.open_holes);
    set(&mut p.min_thickness, a.min_thickness);
    set(&mut p.rim_weight, a.rim_weight);
    if let Some(m) = a.max_excess_volume {
        p.max_excess_volume = Some(m);
        p.reprice = Reprice::Exact;
    }
    if a.remove_thin_boxes.is_some() {
        p.remove_thin_boxes = a.remove_thin_boxes;
    }
    p.remove_nested &= !a.keep_nested;
    p.flush_plates &= !a.no_flush_plates;
    p.join_coplanar &= !a.no_join_coplanar;
    p.solid |= a.solid;
    p.fill |= a.fill;
    p.cut |= a.cut;
    p.greedy |= a.greedy;
    if let Some(t) = &a.tolerance {
        p.tolerance = t
            .iter()
            .map(|t| parse_tolerance(t))
            .collect::<anyhow::Result<_>>()?;
    }
    if let Some(b) = &a.max_bytes {
        p.max_bytes = b
            .iter()
            .map(|b| parse_bytes(b))
            .collect::<anyhow::Result<_>>()?;
    }
    if let Some(k) = &a.partitions {
        p.partitions = match k.as_str() {
            "auto" => Partitions::Auto,
            k => Partitions::Fixed(k.parse().map_err(|_| {
                BadArgs(format!("--partitions: expected auto or a count, got '{k}'"))
            })?),
        };
    }
    for w in &a.weights {
        let (k, v) = w
            .split_once('=')
            .ok_or_else(|| BadArgs(format!("--weights: expected kind=value, got '{w}'")))?;
        let kind = parse_kind(k)?;
        p.weights[kind as usize] = v
            .trim()
            .parse()
            .map_err(|_| BadArgs(format!("--weights: '{v}' is not a number")))?;
    }
    if !a.kinds.is_empty() {
        p.kinds = [false; 6];
        for k in &a.kinds {
            p.kinds[parse_kind(k)? as usize] = true;
        }
    }
    if let Some(d) = &a.dedup {
        p.dedup = parse_dedup(d)?;
    }
    if let Some(r) = &a.reprice {
        p.reprice = parse_reprice(r)?;
    }
    // Targets are resolved per input (percentages); validate with a stand-in.
    let levels = p.tolerance.len().max(p.max_bytes.len()).max(1);
    let check = Params {
        // One -n value is the cap of every level of a chain (`decompose`).
        targets: vec![1; a.targets.as_ref().map_or(1, Vec::len).max(1).max(levels)],
        ..p.clone()
    };
    check.validate().map_err(|e| BadArgs(e.to_string()))?;
    Ok(p)
}

/// `--tolerance`: a distance in input units, or a percentage of the diagonal.
fn parse_tolerance(t: &str) -> anyhow::Result<Tolerance> {
    let t = t.trim();
    let bad = || {
        BadArgs(format!(
            "--tolerance: expected a positive distance (input units) or a percentage of \
             the diagonal like 1%, got '{t}'"
        ))
    };
    let (num, percent) = match t.strip_suffix('%') {
        Some(p) => (p.trim(), true),
        None => (t, false),
    };
    if num.parse::<f64>().is_ok_and(|v| v <= 0.0) {
        return Err(BadArgs(format!(
            "--tolerance: '{t}' is not positive: a tolerance is how far every primitive may \
             stand from the mesh, a distance (input units) or a percentage of the diagonal \
             like 1%, greater than 0"
        ))
        .into());
    }
    match num.parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 && (!percent || v < 100.0) => Ok(match percent {
            true => Tolerance::Diagonal(v / 100.0),
            false => Tolerance::Units(v),
        }),
        _ => Err(bad().into()),
    }
}

/// `--max-bytes`: a positive byte count, optionally with K, M or G.
fn parse_bytes(b: &str) -> anyhow::Result<usize> {
    match crate::paths::parse_size(b.trim()) {
        Some(v) if v > 0 && v <= usize::MAX as u64 => Ok(v as usize),
        _ => Err(BadArgs(format!(
            "--max-bytes: expected a positive byte count such as 4096 or 4K, got '{b}'"
        ))
        .into()),
    }
}

/// `--config FILE`: JSON (a result's settings or settings alone) or TOML settings.
fn read_config(path: &Path) -> anyhow::Result<Params> {
    let text = crate::paths::read_result(path)?;
    let toml = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("toml"));
    let params = if toml {
        let p: Params =
            toml::from_str(&text).map_err(|e| BadArgs(format!("{}: {e}", path.display())))?;
        p.validate().map(|()| p)
    } else {
        Params::from_json(&text)
    };
    params.map_err(|e| BadArgs(format!("{}: {e}", path.display())).into())
}

fn parse_dedup(d: &str) -> anyhow::Result<Dedup> {
    Ok(match d {
        "exact" => Dedup::Exact,
        "off" => Dedup::Off,
        t => Dedup::Tolerance(t.parse().map_err(|_| {
            BadArgs(format!(
                "--dedup: expected exact, off or a distance, got '{t}'"
            ))
        })?),
    })
}

fn parse_reprice(r: &str) -> anyhow::Result<Reprice> {
    Ok(match r {
        "exact" => Reprice::Exact,
        "deferred" => Reprice::Deferred { min_degree: 0 },
        t => Reprice::Deferred {
            min_degree: t.parse().map_err(|_| {
                BadArgs(format!(
                    "--reprice: expected exact, deferred or a neighbour count, got '{t}'"
                ))
            })?,
        },
    })
}

/// How `decompose` reads each input: `--max-memory` (checked against the peak of the
/// run `params` asks for) and `--allow-external-uris`.
fn load_options(a: &DecomposeArgs, params: &Params) -> anyhow::Result<LoadOptions> {
    Ok(LoadOptions {
        max_memory: max_memory(a)?,
        greedy_only: !params.uses_cut(),
        allow_external_uris: a.load.allow_external_uris,
        ..LoadOptions::default()
    })
}

impl LoadArgs {
    /// The options for `eval` and `sim`, which have no memory limit.
    fn options(&self) -> LoadOptions {
        LoadOptions {
            allow_external_uris: self.allow_external_uris,
            ..LoadOptions::default()
        }
    }
}

/// The memory limit in bytes from `--max-memory`; `None` for no limit.
fn max_memory(a: &DecomposeArgs) -> anyhow::Result<Option<u64>> {
    memory_limit(&a.max_memory)
}

/// A `--max-memory` value in bytes: a size, `available` or `none` (`None`).
fn memory_limit(s: &str) -> anyhow::Result<Option<u64>> {
    Ok(match s.trim() {
        "none" => None,
        "available" => crate::paths::available_memory(),
        s => Some(crate::paths::parse_size(s).ok_or_else(|| {
            BadArgs(format!(
                "--max-memory: expected a size like 8G, 'available' or 'none', got '{s}'"
            ))
        })?),
    })
}

fn parse_kind(k: &str) -> anyhow::Result<Kind> {
    Kind::from_name(k.trim()).ok_or_else(|| {
        BadArgs(format!("unknown primitive kind '{k}': expected box, sphere, capsule, cylinder, frustum or prism")).into()
    })
}

/// A target as given: a count, or a percentage of the input's faces.
#[derive(Clone, Copy, Debug)]
enum Target {
    Count(usize),
    Percent(f64),
}

fn parse_targets(raw: &[String]) -> anyhow::Result<Vec<Target>> {
    raw.iter()
        .map(|t| {
            let t = t.trim();
            let bad = || {
                BadArgs(format!(
                    "-n: expected a positive count or a percentage like 1%, got '{t}'"
                ))
            };
            match t.strip_suffix('%') {
                Some(p) => match p.trim().parse::<f64>() {
                    Ok(v) if v > 0.0 && v <= 100.0 => Ok(Target::Percent(v)),
                    _ => Err(bad().into()),
                },
                None => match t.parse::<usize>() {
                    Ok(v) if v > 0 => Ok(Target::Count(v)),
                    _ => Err(bad().into()),
                },
            }
        })
        .collect()
}

fn resolve_targets(targets: &[Target], faces: usize) -> Vec<usize> {
    targets
        .iter()
        .map(|t| match *t {
            Target::Count(n) => n,
            Target::Percent(p) => ((faces as f64 * p / 100.0).round() as usize).max(1),
        })
        .collect()
}

fn set_threads(threads: Option<usize>) -> anyhow::Result<()> {
    if let Some(t) = threads {
        rayon::ThreadPoolBuilder::new()
            .num_threads(t.max(1))
            .build_global()
            .map_err(|e| anyhow!("cannot start {t} threads: {e}"))?;
    }
    Ok(())
}

/// Loads the input and every collider first (a bad file fails the run before any
/// work), then evaluates them in order.
fn eval(a: EvalArgs) -> anyhow::Result<()> {
    if a.samples == 0 {
        bail!(BadArgs("--samples must be at least 1".into()));
    }
    let guard = Guard::new(
        std::iter::once(&a.input)
            .chain(&a.colliders)
            .map(PathBuf::as_path),
    );
    if let Some(out) = &a.json {
        guard.check(&[Out::flag("--json", out, out.clone())])?;
    }
    set_threads(a.threads)?;
    let mesh = primdecomp::load_with(&a.input, &a.load.options())?;
    let colliders = a
        .colliders
        .iter()
        .map(|p| primdecomp_eval::collider::load(p))
        .collect::<primdecomp::Result<Vec<_>>>()?;
    let input = primdecomp_eval::Input::new(&mesh);
    let rows: Vec<(String, primdecomp_eval::Metrics)> = a
        .colliders
        .iter()
        .zip(&colliders)
        .map(|(p, c)| {
            let m = primdecomp_eval::evaluate(&input, c, a.samples, a.seed);
            (p.display().to_string(), m)
        })
        .collect();
    print!("{}", primdecomp_eval::report::table(&rows));
    if let Some(out) = &a.json {
        let doc = primdecomp_eval::report::to_json(&a.input.display().to_string(), &rows);
        write_atomic(out, doc.as_bytes())?;
        println!("wrote {}", out.display());
    }
    Ok(())
}

fn decompose(a: DecomposeArgs) -> anyhow::Result<()> {
    let mut base = params_from(&a)?;
    if a.fill && a.targets.is_none() {
        bail!(BadArgs(
            "--fill needs -n: the counts whose levels it fills".into()
        ));
    }
    if a.targets.is_none() {
        // Without -n, the library's run: a tolerance or byte target capped at
        // MAX_PRIMITIVES, or the default tolerance (`Params::resolved`).
        base.validate().map_err(|e| BadArgs(e.to_string()))?;
        base = base.resolved();
    }
    let mut targets = match &a.targets {
        Some(t) => parse_targets(t)?,
        None => base.targets.iter().map(|&n| Target::Count(n)).collect(),
    };
    // A chain of tolerances or byte targets under one cap: one level each.
    let chain = base.tolerance.len().max(base.max_bytes.len());
    if chain > 1 && targets.len() == 1 {
        targets = vec![targets[0]; chain];
    }
    if chain > 1 && a.per_object {
        bail!(BadArgs(
            "--per-object takes one --tolerance and one --max-bytes value (a chain of \
             levels names its levels by them)"
                .into()
        ));
    }
    if !(3..=export::MAX_DETAIL).contains(&a.obj_detail) {
        bail!(BadArgs(format!(
            "--obj-detail must be from 3 to {}, got {}",
            export::MAX_DETAIL,
            a.obj_detail
        )));
    }
    let guard = Guard::new(a.inputs.iter().map(PathBuf::as_path));
    let dir = match &a.out {
        Some(o) if a.inputs.len() > 1 || names_dir(o) => o.clone(),
        None if a.inputs.len() > 1 => PathBuf::from("."),
        _ => return decompose_one(&a, &base, &targets, &guard),
    };
    decompose_batch(&a, &base, &targets, &guard, &dir)
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
    crate::export_cmd::check_exports(&a.export, &a.export_opts)?;
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
    let dests: Vec<Dest> = a
        .inputs
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
        .collect();
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
    let settings = manifest::settings_hash(&serde_json::json!({
        "params": base,
        "targets": targets.iter().map(|t| format!("{t:?}")).collect::<Vec<_>>(),
        "per_object": a.per_object,
        "obj": a.obj,
        "obj_detail": a.obj_detail,
        "timings": a.timings,
        "allow_external_uris": a.load.allow_external_uris,
    }))?;
    let manifest = Manifest::open(dir, a.resume)?;
    clear_stale(a, dir);
    let todo: Vec<usize> = (0..n)
        .filter(|&i| {
            let input = &a.inputs[i];
            !(a.resume && {
                let (expected, could_write) = dests[i].resumable(targets, a.per_object);
                manifest.done_before(
                    input,
                    Stamp::of(input),
                    &settings,
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
    if a.table {
        print_table(&rows);
    }
    match worst {
        Some(e) => Err(e.context(format!("{} of {n} inputs failed", todo.len() - rows.len()))),
        None => Ok(()),
    }
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

/// A run's tolerances and byte targets: several of either name its levels
/// ([`level_labels`]).
#[derive(Clone, Debug, Default)]
struct Chain {
    tolerance: Vec<Tolerance>,
    max_bytes: Vec<usize>,
}

impl Chain {
    fn of(p: &Params) -> Chain {
        Chain {
            tolerance: p.tolerance.clone(),
            max_bytes: p.max_bytes.clone(),
        }
    }

    /// Whether the levels are named by tolerances or byte targets, not counts.
    fn names_levels(&self) -> bool {
        self.tolerance.len() > 1 || self.max_bytes.len() > 1
    }
}

/// Keeps one input's messages together when several inputs run at once.
static PRINT: std::sync::Mutex<()> = std::sync::Mutex::new(());

/// Where one input's files go: the JSON and OBJ names before target suffixes
/// ([`output_path_for`]), and in a batch the input they are named after.
struct Dest {
    json: PathBuf,
    /// How messages name `json`'s origin: "-o", or "the default output".
    json_flag: &'static str,
    obj: Option<PathBuf>,
    /// `--export` files (one input only).
    exports: Vec<PathBuf>,
    /// The `--png` file (in a batch, inside the `--png` directory).
    png: Option<PathBuf>,
    batch_input: Option<PathBuf>,
    /// The tolerances and byte targets that name a chain's levels.
    chain: Chain,
}

impl Dest {
    /// The labels of levels with these counts in output names.
    fn labels(&self, counts: &[usize]) -> Vec<String> {
        level_labels(counts, &self.chain.tolerance, &self.chain.max_bytes)
    }

    /// The files written for `levels`, the targets of the decomposition's levels.
    fn outs(&self, levels: &[usize]) -> Vec<Out> {
        let n = levels.len();
        let mut outs = Vec::new();
        for t in self.labels(levels) {
            let files = std::iter::once((self.json_flag, &self.json))
                .chain(self.obj.iter().map(|o| ("--obj", o)));
            for (flag, base) in files {
                let path = output_path_for(base, &t, n);
                outs.push(match &self.batch_input {
                    Some(input) => Out::of_input(path, input),
                    None => Out::flag(flag, base, path),
                });
            }
        }
        outs
    }

    /// What `--resume` may take as this input's outputs (never what a manifest says):
    /// the files it writes when their names are known before decomposing, else a test
    /// that a file is one of them (`STEM.primdecomp_nCOUNT.json`, the same for --obj,
    /// the --png file).
    #[allow(clippy::type_complexity)]
    fn resumable(
        &self,
        targets: &[Target],
        per_object: bool,
    ) -> (Option<Vec<PathBuf>>, Box<dyn Fn(&Path) -> bool + '_>) {
        // --per-object writes no picture.
        let png = self.png.as_ref().filter(|_| !per_object);
        let known: Vec<PathBuf> = self
            .up_front(targets)
            .into_iter()
            .map(|o| o.path)
            .filter(|p| Some(p) != self.png.as_ref() || png.is_some())
            .collect();
        let abs = |p: &Path| std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf());
        let named = move |p: &Path| {
            let p = abs(p);
            std::iter::once(&self.json)
                .chain(self.obj.as_ref())
                .any(|base| {
                    let base = abs(base);
                    let (Some(stem), Some(name)) = (base.file_stem(), p.file_stem()) else {
                        return false;
                    };
                    let count = name
                        .to_str()
                        .and_then(|n| n.strip_prefix(&format!("{}_n", stem.to_string_lossy())));
                    p.parent() == base.parent()
                        && p.extension() == base.extension()
                        && count
                            .is_some_and(|c| !c.is_empty() && c.bytes().all(|b| b.is_ascii_digit()))
                })
                || png.is_some_and(|g| abs(g) == p)
        };
        let expected = (!known.is_empty()).then_some(known);
        (expected, Box::new(named))
    }

    /// The files whose names are known before decomposing: all of them unless a
    /// percentage target among several makes the suffixes depend on the input.
    fn up_front(&self, targets: &[Target]) -> Vec<Out> {
        let mut counts: Vec<usize> = Vec::new();
        for t in targets {
            match *t {
                Target::Count(c) => counts.push(c),
                // One target, or a chain named by its tolerances: whatever the count.
                Target::Percent(_) if targets.len() == 1 || self.chain.names_levels() => {
                    counts.push(0)
                }
                Target::Percent(_) => return Vec::new(),
            }
        }
        if !self.chain.names_levels() {
            counts.sort_unstable_by(|a, b| b.cmp(a));
            counts.dedup();
        }
        let mut outs = self.outs(&counts);
        for e in &self.exports {
            for t in self.labels(&counts) {
                outs.push(Out::flag(
                    "--export",
                    e,
                    output_path_for(e, &t, counts.len()),
                ));
            }
        }
        if let Some(png) = &self.png {
            outs.push(match &self.batch_input {
                Some(input) => Out::of_input(png.clone(), input),
                None => Out::flag("--png", png, png.clone()),
            });
        }
        outs
    }
}

/// Loads, decomposes and writes one input; `beside_others` (several inputs at once):
/// no progress bar, and the messages printed in one block. Returns the decomposition
/// and the files written.
fn run_one(
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
    let mesh = primdecomp::load_with(input, &load_options(a, base)?)?;
    let load_s = now.elapsed().as_secs_f64();
    let params = Params {
        targets: resolve_targets(targets, mesh.face_count()),
        ..base.clone()
    };
    if a.per_object {
        let (mut dec, written) = run_objects(a, input, &params, targets, &mesh, dest, guard)?;
        dec.timings.stages.insert(0, ("load".into(), load_s));
        return Ok((dec, written));
    }
    let shown = Shown::new(&params, mesh.face_count(), a, beside_others);
    let mut dec = primdecomp::decompose_with(&mesh, &params, &|stage: Stage, f: f64| {
        if let Some(m) = &memory {
            m.enter(stage.name());
        }
        shown.update(stage, f);
    })?;
    shown.finish();
    dec.input.path = Some(input.display().to_string());
    let up = input_up(a, input);
    (dec.input.up, dec.input.up_from) = (Some(up.0), Some(up.1));
    dec.timings.stages.insert(0, ("load".into(), load_s));
    let now = Instant::now();
    let mut written = write_outputs(&dec, &params, dest, guard, a.obj_detail, a.timings)?;
    let counts: Vec<usize> = dec.levels.iter().map(|l| l.target).collect();
    for (level, label) in dec.levels.iter().zip(dest.labels(&counts)) {
        written.extend(crate::export_cmd::write_level_exports(
            &a.export,
            &a.export_opts,
            &crate::export_cmd::whole(level),
            (&label, dec.levels.len()),
            &crate::export_cmd::Source {
                path: input,
                mesh: &mesh,
                up: up.0,
            },
        )?);
    }
    let write_s = now.elapsed().as_secs_f64();
    let memory = memory.map(StageMemory::finish);
    if let Some(png) = &dest.png {
        let label = dest.labels(&[dec.levels[0].target]).swap_remove(0);
        written.push(decompose_png(&dest.json, &label, &dec, input, &mesh, png)?);
    }
    let _out = PRINT.lock();
    if !a.quiet {
        print_summary(&dec, &mesh, &written, a.verbose);
    }
    if a.verbose || a.timings {
        print_timings(
            &dec,
            write_s,
            a.inputs.len() > 1,
            a.verbose,
            memory.as_deref(),
        );
    } else if !a.quiet {
        println!("time      {:.2} s", dec.timings.total() + write_s);
    }
    Ok((dec, written))
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
    use primdecomp::{decompose_objects, ObjectTarget};
    if a.obj_detail < 3 {
        bail!(BadArgs(format!(
            "--obj-detail must be at least 3, got {}",
            a.obj_detail
        )));
    }
    let now = Instant::now();
    let wanted: Vec<ObjectTarget> = targets
        .iter()
        .map(|t| match *t {
            Target::Count(n) => ObjectTarget::Total(n),
            Target::Percent(p) => ObjectTarget::Percent(p),
        })
        .collect();
    let mut objs = decompose_objects(mesh, params, &wanted).map_err(|e| match e {
        primdecomp::Error::InvalidParams(m) => BadArgs(format!("{}: {m}", input.display())).into(),
        e => anyhow::Error::from(e),
    })?;
    objs.input.path = Some(input.display().to_string());
    let up = input_up(a, input);
    (objs.input.up, objs.input.up_from) = (Some(up.0), Some(up.1));
    let n = objs.levels();
    let mut written = Vec::new();
    let sum = |f: fn(&primdecomp::Stats) -> usize| {
        objs.objects.iter().map(|o| f(&o.decomposition.stats)).sum()
    };
    let mut dec = Decomposition {
        input: objs.input.clone(),
        stats: primdecomp::Stats {
            welded_vertices: sum(|s| s.welded_vertices),
            adjacency_edges: sum(|s| s.adjacency_edges),
            ..Default::default()
        },
        ..Default::default()
    };
    dec.timings
        .stages
        .push(("decompose".into(), now.elapsed().as_secs_f64()));
    let mut jsons = Vec::with_capacity(n);
    for i in 0..n {
        let json = export::to_json_objects(&objs, i, params);
        let v: serde_json::Value = serde_json::from_str(&json)?;
        jsons.push((v["settings"]["target"].as_u64().unwrap_or(0) as usize, json));
    }
    // The names are known only now (a percentage's count): check them before writing.
    let outs = dest.outs(&jsons.iter().map(|j| j.0).collect::<Vec<_>>());
    guard.check(&outs)?;
    let per_level = if dest.obj.is_some() { 2 } else { 1 };
    for (i, (target, json)) in jsons.into_iter().enumerate() {
        let level = primdecomp::Level {
            target,
            merged_to: target,
            primitives: objs.world_primitives(i),
            // For the summary line: each object's tolerance is this share of its own
            // diagonal (--per-object takes one value).
            tolerance: params
                .tolerance
                .first()
                .map(|t| t.in_units(mesh.diagonal())),
            max_bytes: params.max_bytes.first().copied(),
            ..Default::default()
        };
        let json_out = &outs[i * per_level];
        write_atomic(&json_out.path, json.as_bytes())?;
        guard.wrote(json_out);
        written.push(json_out.path.clone());
        if dest.obj.is_some() {
            let obj_out = &outs[i * per_level + 1];
            write_atomic(
                &obj_out.path,
                export::to_obj(&level, a.obj_detail).as_bytes(),
            )?;
            guard.wrote(obj_out);
            written.push(obj_out.path.clone());
        }
        written.extend(crate::export_cmd::write_level_exports(
            &a.export,
            &a.export_opts,
            &crate::export_cmd::level_objects(&objs, i),
            (&format!("n{target}"), n),
            &crate::export_cmd::Source {
                path: input,
                mesh,
                up: up.0,
            },
        )?);
        dec.levels.push(level);
    }
    let _out = PRINT.lock();
    if !a.quiet {
        println!(
            "objects   {}: {}",
            objs.objects.len(),
            objs.objects
                .iter()
                .map(|o| format!("{:?} ({} faces)", o.name, o.faces))
                .collect::<Vec<_>>()
                .join(", ")
        );
        print_summary(&dec, mesh, &written, a.verbose);
    }
    Ok((dec, written))
}

/// The input's up axis and where it came from: `--up`, else what its format says
/// (`Up::of_format`).
fn input_up(a: &DecomposeArgs, input: &Path) -> (primdecomp::export::Up, String) {
    use primdecomp::export::Up;
    match a.export_opts.up.as_deref().and_then(Up::from_axis) {
        Some(up) => (up, "given with --up".into()),
        None => primdecomp::Format::from_path(input)
            .map(Up::of_format)
            .map_or((Up::Y, "assumed".into()), |(u, why)| (u, why.into())),
    }
}

/// One markdown row per input and target.
fn print_table(rows: &[Decomposition]) {
    println!("\n| mesh | faces | N | primitives | box | sphere | capsule | cylinder | frustum | prism | bytes | seconds |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for d in rows {
        let name = d
            .input
            .path
            .as_deref()
            .and_then(|p| Path::new(p).file_name()?.to_str())
            .unwrap_or("-");
        for l in &d.levels {
            let c = l.counts();
            println!(
                "| {name} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {:.3} |",
                d.input.faces,
                l.target,
                l.primitives.len(),
                c[0],
                c[1],
                c[2],
                c[3],
                c[4],
                c[5],
                l.bytes(),
                d.timings.total()
            );
        }
    }
}

/// `STEM.primdecomp.json`, STEM the input's file name without its extension.
fn default_out(input: &Path) -> PathBuf {
    named_after(input, "json")
}

/// `STEM.primdecomp.obj`, an input's OBJ in a batch.
fn default_obj(input: &Path) -> PathBuf {
    named_after(input, "obj")
}

/// `STEM.png`, an input's `--png` picture in a batch.
fn default_png(input: &Path) -> PathBuf {
    let stem = input.file_stem().unwrap_or_default().to_string_lossy();
    PathBuf::from(format!("{stem}.png"))
}

fn named_after(input: &Path, ext: &str) -> PathBuf {
    let stem = input
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "out".into());
    PathBuf::from(format!("{stem}.primdecomp.{ext}"))
}

/// A run's progress as the user sees it: a bar on a terminal (stage, percent of the
/// run, time left), lines on stderr every few seconds with `--progress` elsewhere,
/// or nothing (quiet, several inputs at once, a small input, or stderr not a terminal
/// without `--progress`).
struct Shown {
    eta: primdecomp::Eta,
    bar: Option<indicatif::ProgressBar>,
    /// `--progress` off a terminal: when the last line was printed, and its stage.
    lines: Option<std::sync::Mutex<(Instant, Option<Stage>)>>,
}

/// Seconds between `--progress` lines off a terminal.
const PROGRESS_EVERY: f64 = 5.0;

impl Shown {
    fn new(params: &Params, faces: usize, a: &DecomposeArgs, beside_others: bool) -> Shown {
        use std::io::IsTerminal;
        let eta = primdecomp::Eta::new(params);
        let wanted = !a.quiet && !beside_others && (a.progress || faces >= 100_000);
        let terminal = std::io::stderr().is_terminal();
        let bar = (wanted && terminal).then(|| {
            let b = indicatif::ProgressBar::new(1000);
            b.set_style(
                indicatif::ProgressStyle::with_template(
                    "{msg:<24} {bar:30} {percent:>3}% {prefix}",
                )
                .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
            );
            b
        });
        let lines = (wanted && !terminal && a.progress)
            .then(|| std::sync::Mutex::new((Instant::now(), None)));
        Shown { eta, bar, lines }
    }

    fn update(&self, stage: Stage, fraction: f64) {
        if self.bar.is_none() && self.lines.is_none() {
            return;
        }
        let e = self.eta.update(stage, fraction);
        let left = e
            .seconds_left
            .map_or(String::new(), |s| format!("about {} left", duration(s)));
        if let Some(b) = &self.bar {
            b.set_message(format!("{} {:.0}%", stage.name(), 100.0 * e.fraction));
            b.set_prefix(left.clone());
            b.set_position((e.overall * 1000.0) as u64);
        }
        if let Some(last) = &self.lines {
            // A line as each stage starts, and every few seconds within one.
            let mut last = last.lock().unwrap_or_else(|e| e.into_inner());
            if last.1 != Some(stage) || last.0.elapsed().as_secs_f64() >= PROGRESS_EVERY {
                *last = (Instant::now(), Some(stage));
                eprintln!(
                    "progress  {} {:.0}%, run {:.0}%{}",
                    stage.name(),
                    100.0 * e.fraction,
                    100.0 * e.overall,
                    if left.is_empty() {
                        left
                    } else {
                        format!(", {left}")
                    }
                );
            }
        }
    }

    fn finish(self) {
        if let Some(b) = self.bar {
            b.finish_and_clear();
        }
    }
}

/// `s` seconds as `1h02m`, `3m05s` or `42s`.
fn duration(s: f64) -> String {
    let s = s.round() as u64;
    match s {
        0..=59 => format!("{s}s"),
        60..=3599 => format!("{}m{:02}s", s / 60, s % 60),
        _ => format!("{}h{:02}m", s / 3600, s % 3600 / 60),
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
            export::to_obj(level, detail)
        } else if timed {
            export::to_json_timed(dec, i, params)
        } else {
            export::to_json(dec, i, params)
        };
        write_atomic(&out.path, bytes.as_bytes())?;
        guard.wrote(out);
        written.push(out.path.clone());
    }
    Ok(written)
}

fn print_summary(dec: &Decomposition, mesh: &primdecomp::Mesh, written: &[PathBuf], verbose: bool) {
    let i = &dec.input;
    let welded = match verbose {
        true => format!(
            " ({} after welding), {} pairs of faces sharing an edge",
            dec.stats.welded_vertices, dec.stats.adjacency_edges
        ),
        false => String::new(),
    };
    println!(
        "input     {}: {} faces, {} vertices{welded}",
        i.path.as_deref().unwrap_or("-"),
        i.faces,
        i.vertices,
    );
    if let (Some(up), Some(from)) = (i.up, &i.up_from) {
        let other = match up {
            primdecomp::export::Up::Y => "z",
            primdecomp::export::Up::Z => "y",
        };
        // An assumption says how to change it; a format's own axis does not need to.
        let change = match from.starts_with("assumed") {
            true => format!("; --up {other} if the mesh stands on {other}"),
            false => String::new(),
        };
        println!("up        +{} ({from}{change})", up.axis().to_uppercase());
    }
    let skipped = mesh.skipped();
    if skipped.short_faces + skipped.other > 0 {
        println!(
            "skipped   {} faces with fewer than 3 vertices or lines, {} other elements",
            skipped.short_faces, skipped.other
        );
    }
    for l in &dec.levels {
        let c = l.counts();
        let kinds: Vec<String> = Kind::ALL
            .iter()
            .filter(|k| c[**k as usize] > 0)
            .map(|k| format!("{} {}", c[*k as usize], k.name()))
            .collect();
        println!(
            "{} → {} primitives ({}), {} bytes{}{}",
            asked(l, dec.input.diagonal()),
            l.primitives.len(),
            kinds.join(", "),
            l.bytes(),
            reach(l, dec.input.diagonal()),
            few(l, dec.input.faces)
        );
    }
    for line in crate::export_cmd::wrote_lines(written) {
        println!("{line}");
    }
}

/// What a level asked for, for the summary line: its tolerance (a percentage of the
/// diagonal), else its byte target, else its count; a count that only caps is named.
fn asked(l: &primdecomp::Level, diagonal: f64) -> String {
    match (l.tolerance, l.max_bytes) {
        (Some(t), _) => format!(
            "tolerance {:.2}% (at most {})",
            100.0 * t / diagonal.max(f64::MIN_POSITIVE),
            l.target
        ),
        (None, Some(b)) => format!("bytes {b} (at most {})", l.target),
        (None, None) => format!("count {:>5}", l.target),
    }
}

/// A cut's limits and the distance it reached, for the summary line ("" for a
/// greedy snapshot).
fn reach(l: &primdecomp::Level, diagonal: f64) -> String {
    let Some(d) = l.distance else {
        return String::new();
    };
    let pct = |x: f64| 100.0 * x / diagonal.max(f64::MIN_POSITIVE);
    let mut s = format!(
        "; farthest {d:.4} from the mesh ({:.2}% of the diagonal",
        pct(d)
    );
    if let Some(t) = l.tolerance {
        s += &match d <= t {
            true => format!(", within the tolerance {t:.4}"),
            false => format!(", over the tolerance {t:.4}: {}", shortfall(l)),
        };
    }
    if let Some(b) = l.max_bytes {
        s += &match l.bytes() <= b {
            true => format!(", byte target {b}"),
            false => format!(", over the byte target {b}: no cut of the merge tree fits it"),
        };
    }
    s + ")"
}

/// Why a level of a count alone holds fewer primitives than asked, for the summary
/// line ("" otherwise): a greedy snapshot under half of its count, where
/// post-processing removed the clusters inside others and joined coplanar plates
/// (§3.4); a cut short by more than a few (2, or 1/32 of the count: the rule that
/// makes a greedy level a cut, docs/decisions/0054), where no split of the merge tree
/// stands nearer the mesh than the primitives kept.
fn few(l: &primdecomp::Level, faces: usize) -> &'static str {
    let want = l.target.min(faces);
    let n = l.primitives.len();
    let count_alone = l.tolerance.is_none() && l.max_bytes.is_none();
    match (l.distance.is_some(), count_alone) {
        (false, true) if 2 * n < want => {
            "; the other clusters lay inside those kept or were joined to them (without \
            --greedy, counts keep parts apart)"
        }
        (true, true) if n + (want / 32).max(2) < want => {
            "; no more primitives would stand nearer the mesh"
        }
        _ => "",
    }
}

/// What stopped a level short of its tolerance, for the summary line.
fn shortfall(l: &primdecomp::Level) -> String {
    match l.shortfall {
        Some(primdecomp::Shortfall::Count) => format!(
            "the cap of {} primitives comes first (-n raises it)",
            l.target
        ),
        Some(primdecomp::Shortfall::Bytes) => {
            "the bytes run out first (--max-bytes raises them)".into()
        }
        Some(primdecomp::Shortfall::Faces) => "the nearest the merge tree reaches: faces \
            no enabled kind encloses nearer"
            .into(),
        None => "the nearest the merge tree reaches".into(),
    }
}

/// The stage breakdown (load through write) and the process's peak resident memory
/// (with `by_stage`, each stage's own peak, MiB, and the largest of them); with
/// `verbose` also the merge loop's counters.
fn print_timings(
    dec: &Decomposition,
    write_s: f64,
    several: bool,
    verbose: bool,
    by_stage: Option<&[(String, f64, f64)]>,
) {
    let stages: Vec<String> = dec
        .timings
        .stages
        .iter()
        .map(|(s, t)| format!("{s} {t:.3}"))
        .collect();
    println!(
        "seconds   {}, write {write_s:.3} | total {:.3}",
        stages.join(", "),
        dec.timings.total() + write_s
    );
    let st = &dec.stats;
    if verbose {
        println!(
        "fits      {} merges{}; {} seeding, {} re-priced at once, {} when popped ({:.2} per merge); {} merges' points reduced ahead",
        st.merges,
        match st.merges_past {
            0 => String::new(),
            n => format!(" (and {n} past the target by components' loops)"),
        },
        st.fits_seeded,
        st.fits_at_once,
        st.fits_when_popped,
        (st.fits_at_once + st.fits_when_popped) as f64 / st.merges.max(1) as f64,
        st.merges_ahead
    );
    }
    if let Some(stages) = by_stage.filter(|s| !s.is_empty()) {
        let peak = stages.iter().map(|s| s.1).fold(0.0, f64::max);
        let each: Vec<String> = stages
            .iter()
            .map(|(n, m, _)| format!("{n} {m:.1}"))
            .collect();
        let cpu: Vec<String> = stages
            .iter()
            .map(|(n, _, c)| format!("{n} {c:.3}"))
            .collect();
        println!("memory    peak resident {peak:.1} MiB");
        println!("memory    by stage (MiB): {}", each.join(", "));
        println!("cpu       by stage (s): {}", cpu.join(", "));
    } else if let Some(kib) = peak_rss_kib() {
        // The process's peak so far: with several inputs, of all of them up to now.
        let whose = if several {
            " (the process's, all inputs so far)"
        } else {
            ""
        };
        println!(
            "memory    peak resident {:.1} MiB{whose}",
            kib as f64 / 1024.0
        );
    }
}

/// Each stage's peak resident memory (`--timings` on a run alone): as a stage
/// starts, the kernel's high-water mark is read for the stage before and reset
/// (Linux `/proc/self/clear_refs`; where that cannot be written, each figure is the
/// peak so far).
/// Each stage's CPU seconds (every thread of the process) are read at the same
/// moments: what other jobs on the machine cannot add to, for comparing stages
/// between input sizes on a busy machine.
struct StageMemory(std::sync::Mutex<StageMarks>);

/// The stage running, the process's CPU seconds when it started, and per stage
/// before it: (name, peak MiB, CPU seconds).
type StageMarks = (&'static str, f64, Vec<(String, f64, f64)>);

impl StageMemory {
    fn new(first: &'static str) -> StageMemory {
        reset_peak_rss();
        StageMemory(std::sync::Mutex::new((first, cpu_seconds(), Vec::new())))
    }

    /// `stage` runs now (called often, from any thread).
    fn enter(&self, stage: &'static str) {
        let mut s = self.0.lock().unwrap_or_else(|e| e.into_inner());
        if s.0 != stage {
            let mib = peak_rss_kib().unwrap_or(0) as f64 / 1024.0;
            reset_peak_rss();
            let cpu = cpu_seconds();
            let before = std::mem::replace(&mut s.0, stage);
            let spent = cpu - std::mem::replace(&mut s.1, cpu);
            s.2.push((before.to_string(), mib, spent));
        }
    }

    /// The stages' peaks and CPU seconds in order, the last one's (through writing)
    /// included.
    fn finish(self) -> Vec<(String, f64, f64)> {
        self.enter("");
        let s = self.0.into_inner().unwrap_or_else(|e| e.into_inner());
        s.2
    }
}

/// CPU seconds of this process (every thread) so far; 0 where unknown.
fn cpu_seconds() -> f64 {
    #[cfg(unix)]
    {
        let mut ts = libc::timespec {
            tv_sec: 0,
            tv_nsec: 0,
        };
        // SAFETY: `ts` is a valid timespec for the call to fill.
        if unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut ts) } == 0 {
            return ts.tv_sec as f64 + 1e-9 * ts.tv_nsec as f64;
        }
    }
    0.0
}

/// Resets the process's peak resident set size to its current one (Linux 4.0+).
fn reset_peak_rss() {
    let _ = std::fs::write("/proc/self/clear_refs", "5");
}

/// Peak resident set size of this process so far (Linux `VmHWM`), if known.
fn peak_rss_kib() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

fn sim(a: SimArgs) -> anyhow::Result<()> {
    let guard = Guard::new(
        std::iter::once(&a.input)
            .chain(&a.colliders)
            .map(PathBuf::as_path),
    );
    let mut outs = Vec::new();
    for (flag, path) in [("--json", &a.json), ("--plot", &a.plot)] {
        if let Some(p) = path {
            outs.push(Out::flag(flag, p, p.clone()));
        }
    }
    if let Some(dir) = &a.csv {
        for name in csv_names(&a.input) {
            outs.push(Out::flag("--csv", dir, dir.join(name)));
        }
    }
    guard.check(&outs)?;
    let mesh = primdecomp::load_with(&a.input, &a.load.options())?;
    if a.scenario == "projectiles" {
        return projectiles(&a, &mesh);
    }
    let entries = sim_entries(&a.colliders)?;
    let settings = SimSettings {
        balls: a.balls,
        frames: a.frames,
        seed: a.seed,
        threads: a.threads,
        up: ["x", "y", "z"].iter().position(|u| *u == a.up).unwrap_or(1),
        perturbed: !a.no_perturbed,
        profile: a.profile,
        compound: a.compound,
    };
    let bar = (!a.quiet).then(|| {
        let b = indicatif::ProgressBar::new(a.frames as u64);
        b.set_style(
            indicatif::ProgressStyle::with_template(
                "simulating {bar:40} {pos}/{len} frames {elapsed_precise} (eta {eta})",
            )
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
        );
        b
    });
    let input = a.input.display().to_string();
    let run = primdecomp_sim::run(&mesh, &input, &entries, &settings, &|f| {
        if let Some(b) = &bar {
            b.set_position(f as u64);
        }
    })
    .map_err(|e| match e {
        primdecomp::Error::InvalidParams(m) => BadArgs(m).into(),
        e => anyhow::Error::from(e),
    })?;
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    write_sim_outputs(&a, &run, &input, mesh.face_count())?;
    if !a.quiet {
        print_sim_table(&run);
    }
    if a.profile {
        print!("{}", primdecomp_sim::report::profile_table(&run));
    }
    Ok(())
}

/// `primdecomp sim --scenario projectiles`: the pass-through table, and its JSON.
fn projectiles(a: &SimArgs, mesh: &primdecomp::Mesh) -> anyhow::Result<()> {
    let entries = sim_entries(&a.colliders)?;
    let settings = primdecomp_sim::projectiles::Settings {
        shots: a.shots,
        seed: a.seed,
        ccd: a.ccd,
        threads: a.threads,
    };
    let input = a.input.display().to_string();
    let run =
        primdecomp_sim::projectiles::run(mesh, &input, &entries, &settings).map_err(
            |e| match e {
                primdecomp::Error::InvalidParams(m) => BadArgs(m).into(),
                e => anyhow::Error::from(e),
            },
        )?;
    if let Some(p) = &a.json {
        write_atomic(p, run.to_json(&input).as_bytes())?;
    }
    if !a.quiet {
        print!("{}", run.table());
    }
    Ok(())
}

/// The colliders named on the command line, labelled by their paths.
fn sim_entries(paths: &[PathBuf]) -> anyhow::Result<Vec<Entry>> {
    paths
        .iter()
        .map(|p| -> anyhow::Result<Entry> {
            Ok(Entry {
                label: p.display().to_string(),
                geometry: Geometry::Collider(primdecomp_eval::collider::load(p)?),
            })
        })
        .collect()
}

/// JSON, CSV and plot, in that order (the plot needs a font and fails last).
fn write_sim_outputs(a: &SimArgs, run: &SimRun, input: &str, faces: usize) -> anyhow::Result<()> {
    use primdecomp_sim::{plot, report};
    if let Some(p) = &a.json {
        write_atomic(p, report::to_json(run, input, faces).as_bytes())?;
    }
    if let Some(dir) = &a.csv {
        std::fs::create_dir_all(dir)
            .map_err(|e| anyhow!("cannot create CSV directory {}: {e}", dir.display()))?;
        let [frames, ends] = csv_names(&a.input);
        write_atomic(&dir.join(frames), report::frame_csv(run).as_bytes())?;
        write_atomic(&dir.join(ends), report::ends_csv(run).as_bytes())?;
    }
    if let Some(p) = &a.plot {
        let name = a.input.file_name().unwrap_or_default().to_string_lossy();
        let title = format!(
            "{name}: {} balls, physics step per frame",
            run.settings.balls
        );
        plot::write_png(run, &title, p)?;
    }
    Ok(())
}

/// The CSV files `sim --csv DIR` writes for `input`: frame times, then end points.
fn csv_names(input: &Path) -> [String; 2] {
    let stem = input.file_stem().unwrap_or_default().to_string_lossy();
    [format!("{stem}_frame_ms.csv"), format!("{stem}_ends.csv")]
}

fn print_sim_table(run: &SimRun) {
    println!("| collider | kind | shapes | median ms | mean ms | p95 ms | total ms | similarity | set similarity | on object | resting |");
    println!("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for o in &run.outcomes {
        let (s, b) = (&o.stats, &o.behaviour);
        println!(
            "| {} | {} | {} | {:.3} | {:.3} | {:.3} | {:.1} | {:.3} | {:.3} | {:.3} | {:.3} |",
            o.label,
            o.kind,
            o.shapes,
            s.median,
            s.mean,
            s.p95,
            s.total,
            b.similarity,
            b.similarity_set,
            b.on_object,
            b.resting
        );
    }
}

/// `primdecomp view`.
#[derive(Args, Debug)]
struct ViewArgs {
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
    /// Write the viewer page here: one HTML file that works offline from disk.
    #[arg(short, long, value_name = "view.html")]
    out: Option<PathBuf>,
    /// Write a PNG of the page's default view here (software-rendered, no browser).
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
    #[command(flatten)]
    load: LoadArgs,
}

/// Reads every file first (a bad one fails the run before anything is written), then
/// writes the page and the PNG atomically.
fn view(a: ViewArgs) -> anyhow::Result<()> {
    use primdecomp_view::scene;
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
    if !(3..=primdecomp::export::MAX_DETAIL).contains(&a.detail) {
        bail!(BadArgs(format!(
            "--detail must be from 3 to {}, got {}",
            primdecomp::export::MAX_DETAIL,
            a.detail
        )));
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
    let up = view_up(&a);
    let mut opts = scene::Options {
        detail: a.detail,
        display_triangles: a.display_faces.max(1),
        up_axis: if up == primdecomp::export::Up::Z {
            2
        } else {
            1
        },
        load: LoadOptions {
            max_memory: memory_limit(&a.max_memory)?,
            allow_external_uris: a.load.allow_external_uris,
            ..LoadOptions::default()
        },
    };
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
        .collect::<primdecomp::Result<Vec<_>>>()?;
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
    let levels: Vec<_> = docs
        .iter()
        .map(|d| scene::build_level(d, opts.detail))
        .collect();
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
        write_atomic(out, primdecomp_view::html::page(&s, &title).as_bytes())?;
        println!("wrote     {}", out.display());
    }
    if let Some(png) = &a.png {
        let bytes =
            primdecomp_view::render_png(&s, a.png_size).expect("checked: the scene has triangles");
        write_atomic(png, &bytes)?;
        println!("wrote     {}", png.display());
    }
    Ok(())
}

/// `view`'s up axis: `--up`, else the first result's (`input.up`), else what the
/// input's format says (as `decompose`), else +Y.
fn view_up(a: &ViewArgs) -> primdecomp::export::Up {
    use primdecomp::export::Up;
    let recorded = || {
        let first = a.results.first()?;
        let file = scene_first_file(first)?;
        let doc: serde_json::Value =
            serde_json::from_str(&crate::paths::read_result(&file).ok()?).ok()?;
        let doc = doc.get("levels").and_then(|l| l.get(0)).unwrap_or(&doc);
        Up::from_axis(doc.get("input")?.get("up")?.as_str()?)
    };
    let of_input = || Some(Up::of_format(primdecomp::Format::from_path(a.input.as_deref()?)?).0);
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
            Some(primdecomp::export::Up::Z) => 2,
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
