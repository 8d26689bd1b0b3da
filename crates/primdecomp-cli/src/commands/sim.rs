//! `primdecomp sim`: the paper's ball-drop benchmark (§4.1) and the projectile
//! scenario in Rapier, over the input mesh and each collider; prints the table and
//! writes the JSON, CSV and plot asked for.

use crate::args::LoadArgs;
use crate::exit::BadArgs;
use crate::exit::{print, println};
use crate::outputs::{Guard, Out};
use anyhow::anyhow;
use clap::Args;
use primdecomp_files::write_atomic;
use primdecomp_sim::{Entry, Geometry, Run as SimRun, Settings as SimSettings};
use std::path::{Path, PathBuf};

#[derive(Args, Debug)]
pub struct SimArgs {
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

/// Checks the outputs, loads the input and the colliders, runs the scenario and
/// reports it.
pub fn run(a: SimArgs) -> anyhow::Result<()> {
    check_outputs(&a)?;
    let mesh = primdecomp::Mesh::load_with(&a.input, &a.load.options())?;
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

/// Refuses outputs (`--json`, `--plot`, the `--csv` files) that are an input or one
/// another.
fn check_outputs(a: &SimArgs) -> anyhow::Result<()> {
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
