//! `primdecomp eval`: measures colliders against their input mesh (distances both
//! ways, enclosure, bytes) and prints the table, optionally its JSON.

use crate::args::LoadArgs;
use crate::commands::set_threads;
use crate::exit::BadArgs;
use crate::exit::{print, println};
use crate::outputs::{is_stdout, write_out, Guard, Out};
use anyhow::bail;
use clap::Args;
use std::path::PathBuf;

/// `primdecomp eval`. The sampling-error figures in the help come from
/// `benches/eval_spread.sh` (see docs/results/eval_sampling.md).
#[derive(Args, Debug)]
#[command(after_help = EVAL_HELP)]
pub struct EvalArgs {
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
    /// Also write the metrics as JSON here (atomically); `-` writes them to standard
    /// output and the table to standard error.
    #[arg(long)]
    json: Option<PathBuf>,
    /// Measure the colliders' distances to the input's solid, not its surface: a
    /// sample inside the (closed) input stands at 0, as `decompose --solid` bounds it.
    #[arg(long)]
    solid: bool,
    /// Worker threads (default: all cores); results do not depend on it.
    #[arg(long)]
    threads: Option<usize>,
    /// Print nothing but errors (the table too: needs --json).
    #[arg(short, long)]
    quiet: bool,
    #[command(flatten)]
    load: LoadArgs,
}

const EVAL_HELP: &str = include_str!("eval_help.txt");

/// Loads the input and every collider first (a bad file fails the run before any
/// work), then evaluates them in order.
pub fn run(a: EvalArgs) -> anyhow::Result<()> {
    if a.samples == 0 {
        bail!(BadArgs("--samples must be at least 1".into()));
    }
    if a.quiet {
        if a.json.is_none() {
            bail!(BadArgs(
                "--quiet prints no table, and without --json nothing else keeps the \
                 metrics: give --json FILE (or --json - for standard output)"
                    .into()
            ));
        }
        crate::exit::quiet_from_now();
    }
    let guard = Guard::new(
        std::iter::once(&a.input)
            .chain(&a.colliders)
            .map(PathBuf::as_path),
    );
    if let Some(out) = &a.json {
        guard.check(&[Out::flag("--json", out, out.clone())])?;
        if is_stdout(out) {
            // The JSON alone on standard output; the table goes to standard error.
            crate::exit::keep_stdout_for_result();
        }
    }
    set_threads(a.threads)?;
    let mesh = primdecomp::Mesh::load_with(&a.input, &a.load.options())?;
    let colliders = a
        .colliders
        .iter()
        .map(|p| primdecomp_eval::collider::load(p))
        .collect::<Result<Vec<_>, primdecomp::Error>>()?;
    let input = primdecomp_eval::Input::new(&mesh).to_solid(a.solid);
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
        write_out(out, doc.as_bytes())?;
        match is_stdout(out) {
            true => println!("wrote the metrics to standard output"),
            false => println!("wrote {}", out.display()),
        }
    }
    Ok(())
}
