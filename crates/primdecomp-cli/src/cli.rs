//! Command-line interface: argument parsing (clap), the one-screen summary, progress
//! bar and exit codes (0 ok, 2 bad input or settings, 1 anything else).

use anyhow::{anyhow, bail};
use clap::{Args, Parser, Subcommand};
use primdecomp::export::{self, output_path_for, write_atomic};
use primdecomp::{Decomposition, Dedup, Kind, Params, Partitions, Reduction, Reprice};
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
    /// each: merges into plates that add no area still run (see --no-free-merges).
    #[arg(
        short = 'n',
        long = "targets",
        value_delimiter = ',',
        default_value = "64"
    )]
    targets: Vec<String>,
    /// With several inputs: print a markdown table of all results at the end.
    #[arg(long)]
    table: bool,
    /// With several inputs: how many to decompose at once, each on its share of the
    /// threads and within the --max-memory budget together (default: one per thread).
    /// 1 = one after another, each with all threads. Outputs do not depend on it.
    #[arg(long)]
    jobs: Option<usize>,
    /// Refuse merges adding more than this fraction of the input's AABB volume.
    #[arg(long)]
    max_excess_volume: Option<f64>,
    /// Cost weights per kind, e.g. box=1,sphere=1,capsule=1,cylinder=1.05,frustum=2.1,prism=1.4.
    #[arg(long, value_delimiter = ',')]
    weights: Vec<String>,
    /// Kinds allowed, e.g. box,sphere,capsule (default: all six).
    #[arg(long, value_delimiter = ',')]
    kinds: Vec<String>,
    /// Weight ε of the tangent term in Q = area·(nnᵀ + ε·ttᵀ); 0 disables it.
    #[arg(long, default_value_t = 0.01)]
    tangent_eps: f64,
    /// Vertex deduplication: exact, off, or a distance tolerance in input units.
    #[arg(long, default_value = "exact")]
    dedup: String,
    /// Minimum half-extent of a primitive, as a fraction of the input's AABB diagonal.
    #[arg(long, default_value_t = 5e-4)]
    min_extent: f64,
    /// Price merges as if every primitive were at least this thick (half-extent, as a
    /// fraction of the diagonal): coplanar merges across gaps and holes cost more;
    /// output primitives keep --min-extent. Default: the same as --min-extent.
    #[arg(long)]
    merge_min_extent: Option<f64>,
    /// Price merges of coplanar clusters only as if primitives were this thick
    /// (half-extent, as a fraction of the diagonal): a roof's rim does not close into a
    /// lid over a hole; other merges keep their prices. 0 = off (the paper's pricing).
    #[arg(long, default_value_t = 0.01)]
    flat_merge_extent: f64,
    /// When merged clusters' pairs are re-priced: exact (at once, the paper's greedy
    /// order), deferred (each when popped: faster, approximate order), or a neighbour
    /// count N: merges of clusters with N or more neighbours are deferred, others exact.
    #[arg(long, default_value = "64")]
    reprice: String,
    /// Split the faces into K spatial parts merged in parallel (to 16x the largest
    /// target) before the global merge: faster on several cores, merges across parts
    /// wait (docs/results/partitions.md). 1 = one global greedy (the paper); auto = 16
    /// parts (or one per 65,536 faces if more) for inputs of 524,288 faces or more,
    /// else 1.
    #[arg(long, default_value = "auto")]
    partitions: String,
    /// How merged clusters' points are reduced for pricing: hull (exact: the convex
    /// hull's vertices) or extremes (approximate: the extreme points along 13 fixed
    /// axes; faster, different merges; docs/results/reduction.md). Output primitives
    /// are always fitted on all of their faces' vertices.
    #[arg(long, value_enum, default_value = "hull")]
    reduction: ReductionArg,
    /// Keep primitives whose points lie inside another primitive.
    #[arg(long)]
    keep_contained: bool,
    /// Fill each target: when removing nested primitives leaves fewer than N, merge
    /// less (search up to 8N) so the result has as many primitives as fit within N.
    /// Costs up to 4 more merge passes; the JSON's settings.merge_target says where
    /// the merge stopped.
    #[arg(long)]
    fill: bool,
    /// Weight of the outward reach when choosing each output primitive's frame: k·V +
    /// W·(area-weighted distance the primitive reaches past its faces' outer side). 0 =
    /// off (the volume alone, the paper's criterion).
    #[arg(long, default_value_t = 0.0)]
    outward_weight: f64,
    /// Weight of the rim reach when choosing each output primitive's frame and kind:
    /// k·V + W·Σ len·gap², gap how far the primitive reaches past the plane of the
    /// face across each convex boundary edge of its cluster, creases and bends of more
    /// than 2° (a side plate standing past a wall's top as a curb). 0 = off (the
    /// volume alone, the paper's criterion).
    #[arg(long, default_value_t = primdecomp::params::RIM_WEIGHT)]
    rim_weight: f64,
    /// Stop at exactly N clusters (the paper) even where the next merges add nothing;
    /// by default merges of coplanar clusters into a plate of no more area run first,
    /// and plates in one plane the merge left apart are joined where one plate covers
    /// both with no more area, so -n N gives at most N primitives, fewer where faces
    /// merge for free.
    #[arg(long)]
    no_free_merges: bool,
    /// Centre output plates on their faces (half the minimum thickness proud of the
    /// surface) instead of laying them flush, reaching inward from the faces.
    #[arg(long)]
    no_flush_plates: bool,
    /// Price merges by the volume they add outside the input (its interior by ray
    /// parity on a voxel grid) instead of the whole volume: closed parts fill into
    /// solid primitives rather than shells of plates.
    #[arg(long)]
    solid: bool,
    /// Remove boxes thinner than this fraction of the diagonal when others cover them.
    #[arg(long)]
    remove_thin_boxes: Option<f64>,
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
        Cmd::Export(a) => crate::export_cmd::export(*a),
        Cmd::DemoScene { out } => write_atomic(&out, primdecomp::demo::demo_scene_obj().as_bytes())
            .map_err(anyhow::Error::from)
            .map(|_| println!("wrote {}", out.display())),
    };
    match result {
        Ok(()) => 0,
        Err(e) => {
            eprintln!("error: {e:#}");
            match e.downcast_ref::<primdecomp::Error>() {
                Some(pe) => pe.exit_code(),
                None if e.downcast_ref::<BadArgs>().is_some() => 2,
                None => 1,
            }
        }
    }
}

/// A settings error found by the CLI itself (exit code 2).
#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct BadArgs(pub String);

/// `--reduction` (mirrors `primdecomp::Reduction`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
enum ReductionArg {
    Hull,
    Extremes,
}

fn params_from(a: &DecomposeArgs) -> anyhow::Result<Params> {
    let mut p = Params {
        targets: vec![1],
        max_excess_volume: a.max_excess_volume,
        tangent_eps: a.tangent_eps,
        min_extent_rel: a.min_extent,
        merge_min_extent_rel: a.merge_min_extent,
        flat_merge_extent_rel: a.flat_merge_extent,
        remove_contained: !a.keep_contained,
        fill: a.fill,
        outward_weight: a.outward_weight,
        solid: a.solid,
        rim_weight: a.rim_weight,
        free_merges: !a.no_free_merges,
        flush_plates: !a.no_flush_plates,
        remove_thin_boxes: a.remove_thin_boxes,
        partitions: match a.partitions.as_str() {
            "auto" => Partitions::Auto,
            k => Partitions::Fixed(k.parse().map_err(|_| {
                BadArgs(format!("--partitions: expected auto or a count, got '{k}'"))
            })?),
        },
        reduction: match a.reduction {
            ReductionArg::Hull => Reduction::Hull,
            ReductionArg::Extremes => Reduction::Extremes,
        },
        ..Default::default()
    };
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
    p.dedup = match a.dedup.as_str() {
        "exact" => Dedup::Exact,
        "off" => Dedup::Off,
        t => Dedup::Tolerance(t.parse().map_err(|_| {
            BadArgs(format!(
                "--dedup: expected exact, off or a distance, got '{t}'"
            ))
        })?),
    };
    p.reprice = match a.reprice.as_str() {
        "exact" => Reprice::Exact,
        "deferred" => Reprice::Deferred { min_degree: 0 },
        t => Reprice::Deferred {
            min_degree: t.parse().map_err(|_| {
                BadArgs(format!(
                    "--reprice: expected exact, deferred or a neighbour count, got '{t}'"
                ))
            })?,
        },
    };
    p.validate().map_err(|e| BadArgs(e.to_string()))?;
    Ok(p)
}

/// The memory limit in bytes from `--max-memory`; `None` for no limit.
fn max_memory(a: &DecomposeArgs) -> anyhow::Result<Option<u64>> {
    Ok(match a.max_memory.trim() {
        "none" => None,
        "available" => primdecomp::memory::available(),
        s => Some(primdecomp::memory::parse_size(s).ok_or_else(|| {
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
    let mesh = primdecomp::mesh::io::load(&a.input)?;
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
    let targets = parse_targets(&a.targets)?;
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
    let mesh = primdecomp::mesh::io::load_limited(input, max_memory(a)?)?;
    let load_s = now.elapsed().as_secs_f64();
    let params = Params {
        targets: resolve_targets(targets, mesh.face_count()),
        ..base.clone()
    };
    if a.per_object {
        return run_objects(a, input, &params, targets, &mesh, out, load_s);
    }
    let bar = progress_bar(mesh.face_count(), a.quiet || beside_others);
    let mut dec = primdecomp::decompose::decompose_with_progress(&mesh, &params, &|f| {
        if let Some(b) = &bar {
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
    use primdecomp::objects::{decompose_objects, ObjectTarget};
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
    let sum =
        |f: fn(&Decomposition) -> usize| objs.objects.iter().map(|o| f(&o.decomposition)).sum();
    let mut dec = Decomposition {
        input: objs.input.clone(),
        welded_vertices: sum(|d| d.welded_vertices),
        adjacency_edges: sum(|d| d.adjacency_edges),
        ..Default::default()
    };
    dec.timings.stages.push(("load".into(), load_s));
    dec.timings.push("decompose", now);
    for i in 0..n {
        let json = export::json::to_json_objects(&objs, i, params);
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
            write_atomic(&path, export::obj::to_obj(&level, a.obj_detail).as_bytes())?;
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
            export::json::to_json_timed(dec, i, params)
        } else {
            export::json::to_json(dec, i, params)
        };
        write_atomic(&path, json.as_bytes())?;
        written.push(path);
        if let Some(o) = obj {
            let path = output_path_for(o, level.target, n);
            write_atomic(&path, export::obj::to_obj(level, detail).as_bytes())?;
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
        dec.welded_vertices,
        dec.adjacency_edges
    );
    if mesh.skipped.short_faces + mesh.skipped.other > 0 {
        println!(
            "skipped   {} faces with fewer than 3 vertices or lines, {} other elements",
            mesh.skipped.short_faces, mesh.skipped.other
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
    let f = dec.fits;
    println!(
        "fits      {} merges{}; {} seeding, {} re-priced at once, {} when popped ({:.2} per merge); {} merges' points reduced ahead",
        dec.merges,
        match dec.merges_past {
            0 => String::new(),
            n => format!(" (and {n} past the target by components' loops)"),
        },
        f.seed,
        f.eager,
        f.lazy,
        (f.eager + f.lazy) as f64 / dec.merges.max(1) as f64,
        dec.merges_ahead
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
    let mesh = primdecomp::mesh::io::load(&a.input)?;
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
