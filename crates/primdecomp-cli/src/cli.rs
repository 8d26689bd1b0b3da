//! Command-line interface: argument parsing (clap), the one-screen summary, progress
//! bar and exit codes (0 ok, 2 bad input or settings, 1 anything else).

use crate::exit::BadArgs;
use crate::paths::output_path_for;
use anyhow::{anyhow, bail};
use clap::{Args, Parser, Subcommand};
use primdecomp::{export, write_atomic, Stage};
use primdecomp::{Decomposition, Dedup, Kind, Params, Partitions, Reprice};
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
    /// Write the built-in demo scene (stairs, table, pipes, house, ring) as OBJ.
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
}

const EVAL_HELP: &str = include_str!("eval_help.txt");

#[derive(Args, Debug)]
struct DecomposeArgs {
    /// Input meshes; with several, -o names a directory and a table can be printed.
    #[arg(required = true)]
    inputs: Vec<PathBuf>,
    /// Target primitive counts, comma-separated (a count, or a percentage of the input's
    /// faces such as 1%); one result per target from one bottom-up pass. At most N
    /// each: fewer where nested primitives are removed and coplanar faces merge for
    /// free (see --no-join-coplanar). Default: 64.
    #[arg(short = 'n', long = "targets", value_delimiter = ',')]
    targets: Option<Vec<String>>,
    /// Start from the settings of a file: a primdecomp JSON result (its `settings`:
    /// the same settings give the same primitives), or a JSON or TOML file of settings
    /// (keys as in the JSON's `settings`; absent keys keep their defaults). Flags
    /// given here override it.
    #[arg(long, value_name = "FILE")]
    config: Option<PathBuf>,
    /// With several inputs: print a markdown table of all results at the end.
    #[arg(long)]
    table: bool,
    /// With several inputs: how many to decompose at once, each on its share of the
    /// threads and within the --max-memory budget together (default: one per thread).
    /// 1 = one after another, each with all threads. Outputs do not depend on it.
    #[arg(long)]
    jobs: Option<usize>,
    /// Refuse merges adding more than this fraction of the input's bounding-box volume
    /// (§3.3); re-prices every merge at once (--reprice exact) unless --reprice says
    /// otherwise.
    #[arg(long)]
    max_excess_volume: Option<f64>,
    /// Cost weights per kind, e.g. box=1,sphere=1,capsule=1,cylinder=1.05,frustum=2.1,prism=1.4
    /// (the defaults): a heavier kind is chosen less often.
    #[arg(long, value_delimiter = ',')]
    weights: Vec<String>,
    /// Kinds allowed, e.g. box,sphere,capsule (default: all six).
    #[arg(long, value_delimiter = ',')]
    kinds: Vec<String>,
    /// Weight ε of the tangent term in Q = area·(nnᵀ + ε·ttᵀ); 0 disables it. Default 0.01.
    #[arg(long)]
    tangent_eps: Option<f64>,
    /// Vertex deduplication: exact (default), off, or a distance tolerance in input units.
    #[arg(long)]
    dedup: Option<String>,
    /// Minimum half-extent of a primitive, as a fraction of the input's bounding-box
    /// diagonal. Default 0.0005.
    #[arg(long)]
    min_extent: Option<f64>,
    /// Keep primitives whose faces all lie inside another primitive.
    #[arg(long)]
    keep_nested: bool,
    /// Also remove boxes thinner than this fraction of the diagonal when others cover
    /// them.
    #[arg(long)]
    remove_thin_boxes: Option<f64>,
    /// Keep holes and gaps in flat surfaces open: coplanar merges are priced as if the
    /// primitive were this thick (half-extent, fraction of the diagonal), so a roof's
    /// rim does not close into a lid. 0 = the paper's pricing. Default 0.01.
    #[arg(long)]
    open_holes: Option<f64>,
    /// How strongly output primitives keep off the faces beside them (a plate standing
    /// past a wall's top as a curb): k·V + W·Σ len·gap² over the convex boundary edges.
    /// 0 = the volume alone, the paper's criterion. Default 1.
    #[arg(long)]
    rim_weight: Option<f64>,
    /// Centre output plates on their faces (half the minimum thickness proud of the
    /// surface) instead of laying them flush, reaching inward from the faces.
    #[arg(long)]
    no_flush_plates: bool,
    /// Stop at exactly N clusters (the paper) even where the next merges add nothing;
    /// by default coplanar faces merge into plates of no more area first, and plates in
    /// one plane are joined where one covers both with no more area.
    #[arg(long)]
    no_join_coplanar: bool,
    /// Price merges by the volume they add outside the input (its interior by ray
    /// parity on a voxel grid) instead of the whole volume: closed parts fill into
    /// solid primitives rather than shells of plates; slower.
    #[arg(long)]
    solid: bool,
    /// Fill each target: when removing nested primitives leaves fewer than N, merge
    /// less (search up to 8N) so the result has as many primitives as fit within N.
    /// Costs up to 4 more merge passes; the JSON's settings.merge_target says where
    /// the merge stopped.
    #[arg(long)]
    fill: bool,
    /// Cut the merge tree where the error is: split the primitive farthest from the
    /// input until N remain, instead of the greedy pass's N clusters (docs/decisions/0032).
    #[arg(long)]
    cut: bool,
    /// When merged clusters' pairs are re-priced: exact (at once, the paper's greedy
    /// order), deferred (each when popped: faster, approximate order), or a neighbour
    /// count N: merges of clusters with N or more neighbours are deferred, others
    /// exact. Default 64.
    #[arg(long)]
    reprice: Option<String>,
    /// Split the faces into K spatial parts merged in parallel (to 16x the largest
    /// target) before the global merge: faster on several cores, merges across parts
    /// wait. 1 = one global greedy (the paper); auto (default) = 16 parts (or one per
    /// 65,536 faces if more) for inputs of 524,288 faces or more, else 1.
    #[arg(long)]
    partitions: Option<String>,
    /// JSON output file; with several inputs, an output directory (default: INPUT's
    /// stem + .primdecomp.json in the current directory).
    #[arg(short, long)]
    out: Option<PathBuf>,
    /// Also write the primitives as a conservative OBJ tessellation.
    #[arg(long)]
    obj: Option<PathBuf>,
    /// Decompose each object on its own, keeping its name: each glTF node with a mesh
    /// (in the node's frame, its transform kept) and each OBJ o/g group. A total
    /// count -n N is shared: one primitive each, the other N - k (k objects) in
    /// proportion to surface area, largest remainder (ties to the earlier object);
    /// with N < k each object still gets one. A percentage applies per object. The
    /// JSON gains an `objects` list.
    #[arg(long)]
    per_object: bool,
    /// Also export the colliders for an engine (repeatable): .gltf/.glb (Khronos or
    /// OMI physics), .urdf, .usda, .tscn, or MuJoCo's .xml with --format mjcf.
    #[arg(long, value_name = "OUT.EXT")]
    export: Vec<PathBuf>,
    #[command(flatten)]
    export_opts: crate::export_cmd::ExportArgs,
    /// Segments around circles in the OBJ tessellation.
    #[arg(long, default_value_t = 16)]
    obj_detail: usize,
    /// Also render the first level over the input as PNG (`primdecomp view --png`);
    /// with several inputs, a directory: one INPUT-stem.png each.
    #[arg(long, value_name = "OUT.png")]
    png: Option<PathBuf>,
    /// Refuse inputs whose decomposition is estimated to need more memory than this:
    /// a size such as 512M, 8G or 1.5T, "available" (the memory available at start,
    /// from /proc/meminfo) or "none".
    #[arg(long, default_value = "available", value_name = "SIZE")]
    max_memory: String,
    /// Worker threads (default: all cores); results do not depend on it.
    #[arg(long)]
    threads: Option<usize>,
    /// Print nothing but errors.
    #[arg(short, long)]
    quiet: bool,
    /// Print the per-stage seconds and the peak memory even with --quiet, and write the
    /// seconds into the JSON (`stats.seconds`; without this flag the JSON is
    /// byte-identical across runs).
    #[arg(long)]
    timings: bool,
}

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
    /// Print nothing but errors.
    #[arg(short, long)]
    quiet: bool,
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
    let check = Params {
        targets: vec![1],
        ..p.clone()
    };
    check.validate().map_err(|e| BadArgs(e.to_string()))?;
    Ok(p)
}

/// `--config FILE`: JSON (a result's settings or settings alone) or TOML settings.
fn read_config(path: &Path) -> anyhow::Result<Params> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| BadArgs(format!("{}: cannot read the settings: {e}", path.display())))?;
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

/// The memory limit in bytes from `--max-memory`; `None` for no limit.
fn max_memory(a: &DecomposeArgs) -> anyhow::Result<Option<u64>> {
    Ok(match a.max_memory.trim() {
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
    set_threads(a.threads)?;
    let mesh = primdecomp::load(&a.input)?;
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
    let base = params_from(&a)?;
    let targets = match &a.targets {
        Some(t) => parse_targets(t)?,
        None => base.targets.iter().map(|&n| Target::Count(n)).collect(),
    };
    set_threads(a.threads)?;
    if a.inputs.len() == 1 {
        let out = a.out.clone().unwrap_or_else(|| default_out(&a.inputs[0]));
        return run_one(&a, &a.inputs[0], &base, &targets, &out, false).map(|_| ());
    }
    let dir = a.out.clone().unwrap_or_else(|| PathBuf::from("."));
    std::fs::create_dir_all(&dir)
        .map_err(|e| anyhow!("cannot create output directory {}: {e}", dir.display()))?;
    let threads = rayon::current_num_threads();
    let jobs = a.jobs.unwrap_or(threads).max(1);
    let results = crate::batch::run_all(&a.inputs, jobs, threads, max_memory(&a)?, |i| {
        let input = &a.inputs[i];
        let r = run_one(
            &a,
            input,
            &base,
            &targets,
            &dir.join(default_out(input)),
            jobs > 1,
        );
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
            Err(e) => worst = Some(e),
        }
    }
    if a.table {
        print_table(&rows);
    }
    match worst {
        Some(e) => Err(e.context(format!(
            "{} of {} inputs failed",
            a.inputs.len() - rows.len(),
            a.inputs.len()
        ))),
        None => Ok(()),
    }
}

/// Keeps one input's messages together when several inputs run at once.
static PRINT: std::sync::Mutex<()> = std::sync::Mutex::new(());

/// Loads, decomposes and writes one input; `beside_others` (several inputs at once):
/// no progress bar, and the messages printed in one block.
fn run_one(
    a: &DecomposeArgs,
    input: &Path,
    base: &Params,
    targets: &[Target],
    out: &Path,
    beside_others: bool,
) -> anyhow::Result<Decomposition> {
    let now = Instant::now();
    let mesh = primdecomp::load_limited(input, max_memory(a)?)?;
    let load_s = now.elapsed().as_secs_f64();
    let params = Params {
        targets: resolve_targets(targets, mesh.face_count()),
        ..base.clone()
    };
    if a.per_object {
        return run_objects(a, input, &params, targets, &mesh, out, load_s);
    }
    let bar = progress_bar(mesh.face_count(), a.quiet || beside_others);
    let mut dec = primdecomp::decompose_with(&mesh, &params, &|stage: Stage, f: f64| {
        if let (Some(b), Stage::Merge) = (&bar, stage) {
            b.set_position((f * 1000.0) as u64);
        }
    })?;
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    dec.input.path = Some(input.display().to_string());
    dec.timings.stages.insert(0, ("load".into(), load_s));
    let now = Instant::now();
    let mut written = write_outputs(
        &dec,
        &params,
        out,
        a.obj.as_deref(),
        a.obj_detail,
        a.timings,
    )?;
    for level in &dec.levels {
        written.extend(crate::export_cmd::write_level_exports(
            &a.export,
            &a.export_opts,
            &crate::export_cmd::whole(level),
            level.target,
            dec.levels.len(),
            &[input],
            Some(&mesh),
        )?);
    }
    let write_s = now.elapsed().as_secs_f64();
    if let Some(png) = &a.png {
        written.push(decompose_png(a, out, &dec, input, &mesh, png)?);
    }
    let _out = PRINT.lock();
    if !a.quiet {
        print_summary(&dec, &mesh, &written);
    }
    if !a.quiet || a.timings {
        print_timings(&dec, write_s, a.inputs.len() > 1);
    }
    Ok(dec)
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
    out: &Path,
    load_s: f64,
) -> anyhow::Result<Decomposition> {
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
    let mut objs = decompose_objects(mesh, params, &wanted)?;
    objs.input.path = Some(input.display().to_string());
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
    dec.timings.stages.push(("load".into(), load_s));
    dec.timings
        .stages
        .push(("decompose".into(), now.elapsed().as_secs_f64()));
    for i in 0..n {
        let json = export::to_json_objects(&objs, i, params);
        let v: serde_json::Value = serde_json::from_str(&json)?;
        let target = v["settings"]["target"].as_u64().unwrap_or(0) as usize;
        let level = primdecomp::Level {
            target,
            merged_to: target,
            primitives: objs.world_primitives(i),
            faces: Vec::new(),
        };
        let path = output_path_for(out, target, n);
        write_atomic(&path, json.as_bytes())?;
        written.push(path);
        if let Some(o) = &a.obj {
            let path = output_path_for(o, target, n);
            write_atomic(&path, export::to_obj(&level, a.obj_detail).as_bytes())?;
            written.push(path);
        }
        written.extend(crate::export_cmd::write_level_exports(
            &a.export,
            &a.export_opts,
            &crate::export_cmd::level_objects(&objs, i),
            target,
            n,
            &[input],
            Some(mesh),
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
        print_summary(&dec, mesh, &written);
    }
    Ok(dec)
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

fn default_out(input: &Path) -> PathBuf {
    let stem = input
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "out".into());
    PathBuf::from(format!("{stem}.primdecomp.json"))
}

fn progress_bar(faces: usize, quiet: bool) -> Option<indicatif::ProgressBar> {
    if quiet || faces < 100_000 {
        return None;
    }
    let b = indicatif::ProgressBar::new(1000);
    b.set_style(
        indicatif::ProgressStyle::with_template("merging {bar:40} {percent:>3}% {elapsed_precise}")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    Some(b)
}

/// Writes JSON (and OBJ) per level atomically; returns the paths written. With
/// `timed` (`--timings`) the JSON holds the stage timings, which stop before writing
/// (the file cannot time its own write); without, it is byte-identical across runs.
fn write_outputs(
    dec: &Decomposition,
    params: &Params,
    out: &Path,
    obj: Option<&Path>,
    detail: usize,
    timed: bool,
) -> anyhow::Result<Vec<PathBuf>> {
    if detail < 3 {
        bail!(BadArgs(format!(
            "--obj-detail must be at least 3, got {detail}"
        )));
    }
    let n = dec.levels.len();
    let mut written = Vec::new();
    for (i, level) in dec.levels.iter().enumerate() {
        let path = output_path_for(out, level.target, n);
        let json = if timed {
            export::to_json_timed(dec, i, params)
        } else {
            export::to_json(dec, i, params)
        };
        write_atomic(&path, json.as_bytes())?;
        written.push(path);
        if let Some(o) = obj {
            let path = output_path_for(o, level.target, n);
            write_atomic(&path, export::to_obj(level, detail).as_bytes())?;
            written.push(path);
        }
    }
    Ok(written)
}

fn print_summary(dec: &Decomposition, mesh: &primdecomp::Mesh, written: &[PathBuf]) {
    let i = &dec.input;
    println!(
        "input     {}: {} faces, {} vertices ({} after dedup), {} adjacent pairs",
        i.path.as_deref().unwrap_or("-"),
        i.faces,
        i.vertices,
        dec.stats.welded_vertices,
        dec.stats.adjacency_edges
    );
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
            "target {:>5} → {} primitives ({}), {} bytes",
            l.target,
            l.primitives.len(),
            kinds.join(", "),
            l.bytes()
        );
    }
    for w in written {
        println!("wrote     {}", w.display());
    }
}

/// The stage breakdown (load through write) and the process's peak resident memory.
fn print_timings(dec: &Decomposition, write_s: f64, several: bool) {
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
    if let Some(kib) = peak_rss_kib() {
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

/// Peak resident set size of this process so far (Linux `VmHWM`), if known.
fn peak_rss_kib() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

fn sim(a: SimArgs) -> anyhow::Result<()> {
    let mesh = primdecomp::load(&a.input)?;
    let entries = a
        .colliders
        .iter()
        .map(|p| -> anyhow::Result<Entry> {
            Ok(Entry {
                label: p.display().to_string(),
                geometry: Geometry::Collider(primdecomp_eval::collider::load(p)?),
            })
        })
        .collect::<anyhow::Result<Vec<_>>>()?;
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

/// JSON, CSV and plot, in that order (the plot needs a font and fails last).
fn write_sim_outputs(a: &SimArgs, run: &SimRun, input: &str, faces: usize) -> anyhow::Result<()> {
    use primdecomp_sim::{plot, report};
    if let Some(p) = &a.json {
        write_atomic(p, report::to_json(run, input, faces).as_bytes())?;
    }
    if let Some(dir) = &a.csv {
        std::fs::create_dir_all(dir)
            .map_err(|e| anyhow!("cannot create CSV directory {}: {e}", dir.display()))?;
        let stem = a.input.file_stem().unwrap_or_default().to_string_lossy();
        write_atomic(
            &dir.join(format!("{stem}_frame_ms.csv")),
            report::frame_csv(run).as_bytes(),
        )?;
        write_atomic(
            &dir.join(format!("{stem}_ends.csv")),
            report::ends_csv(run).as_bytes(),
        )?;
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
    /// The input's up axis (the default view looks from the front right, above).
    #[arg(long, default_value = "y", value_parser = ["y", "z"])]
    up: String,
    /// Most input triangles shown; larger inputs are simplified (meshoptimizer) to this.
    #[arg(long, default_value_t = primdecomp_view::simplify::DISPLAY_TRIANGLES)]
    display_faces: usize,
    /// Segments around circles in the primitives' shown tessellation.
    #[arg(long, default_value_t = 24)]
    detail: usize,
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
    if a.detail < 3 {
        bail!(BadArgs(format!(
            "--detail must be at least 3, got {}",
            a.detail
        )));
    }
    let opts = scene::Options {
        detail: a.detail,
        display_triangles: a.display_faces.max(1),
        up_axis: if a.up == "z" { 2 } else { 1 },
    };
    let mut levels = Vec::new();
    for r in &a.results {
        for f in scene::result_files(r) {
            levels.extend(scene::load_levels(&f, &opts)?);
        }
    }
    let peers = a
        .compare
        .iter()
        .map(|p| scene::load_peer(p, None))
        .collect::<primdecomp::Result<Vec<_>>>()?;
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
    if s.aabb().is_none() {
        bail!(BadArgs(
            "view: the files hold nothing to draw (no triangles)".into()
        ));
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

/// The input a result document names (`input.path`), if that file exists here.
fn recorded_input(result: &Path) -> Option<PathBuf> {
    let text = std::fs::read_to_string(result).ok()?;
    let doc: serde_json::Value = serde_json::from_str(&text).ok()?;
    let doc = doc.get("levels").and_then(|l| l.get(0)).unwrap_or(&doc);
    let p = PathBuf::from(doc.get("input")?.get("path")?.as_str()?);
    p.is_file().then_some(p)
}

/// `decompose --png`: the first level, read back from the JSON just written, over
/// the input; with several inputs `png` is a directory. Returns the file written.
fn decompose_png(
    a: &DecomposeArgs,
    out: &Path,
    dec: &Decomposition,
    input: &Path,
    mesh: &primdecomp::Mesh,
    png: &Path,
) -> anyhow::Result<PathBuf> {
    use primdecomp_view::{scene, source};
    let png = match a.inputs.len() {
        1 => png.to_path_buf(),
        _ => {
            std::fs::create_dir_all(png)
                .map_err(|e| anyhow!("cannot create PNG directory {}: {e}", png.display()))?;
            let stem = input.file_stem().unwrap_or_default().to_string_lossy();
            png.join(format!("{stem}.png"))
        }
    };
    let json = output_path_for(out, dec.levels[0].target, dec.levels.len());
    let opts = scene::Options::default();
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
    write_atomic(&png, &bytes)?;
    Ok(png)
}
