//! `decompose` in out-of-core tiles (`primdecomp::decompose_tiled`): when `--tiles`
//! asks for them or the input would need more than `--max-memory` read whole. The
//! mesh is never held whole, so what needs it is refused: `--per-object`, `--png`,
//! `--export-preview`, and `-n` as a percentage.

use super::dest::Dest;
use super::one_input::{input_up, write_exports, write_outputs, PRINT};
use super::progress::Shown;
use super::settings::Target;
use super::summary::print_summary;
use super::timings::print_timings;
use crate::args::DecomposeArgs;
use crate::exit::{println, BadArgs};
use crate::outputs::Guard;
use anyhow::bail;
use primdecomp::{Decomposition, LoadOptions, Params, Stage};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Why `input` is decomposed in tiles, or `None` when it is read whole: `--tiles`,
/// or a file larger than the memory limit (reading it whole maps it whole).
pub(super) fn reason(a: &DecomposeArgs, input: &Path, options: &LoadOptions) -> Option<String> {
    if let Some(k) = a.tiles {
        return Some(format!("{k} asked for with --tiles"));
    }
    // Only binary PLY is read a tile at a time: other files over the limit are
    // refused as they are read whole.
    let ply = input.extension()?.eq_ignore_ascii_case("ply");
    let size = std::fs::metadata(input).ok().filter(|_| ply)?.len();
    let limit = options.max_memory?;
    (size > limit).then(|| {
        format!(
            "the file holds {}, more than --max-memory {}",
            bytes(size),
            bytes(limit)
        )
    })
}

/// Why, for an input the memory model says needs `needed` bytes against `limit`.
pub(super) fn over(needed: u64, limit: u64) -> String {
    format!(
        "read whole it would need about {}, more than --max-memory {}",
        bytes(needed),
        bytes(limit)
    )
}

fn bytes(b: u64) -> String {
    match b {
        b if b >= 1 << 30 => format!("{:.1} GiB", b as f64 / (1u64 << 30) as f64),
        b => format!("{:.0} MiB", b as f64 / (1u64 << 20) as f64),
    }
}

/// Decomposes `input` in tiles and writes what a whole run writes.
#[allow(clippy::too_many_arguments)]
pub(super) fn run(
    a: &DecomposeArgs,
    input: &Path,
    base: &Params,
    targets: &[Target],
    dest: &Dest,
    guard: &Guard,
    options: &LoadOptions,
    why: &str,
) -> anyhow::Result<(Decomposition, Vec<PathBuf>)> {
    let refuse = |what: &str| -> anyhow::Result<()> {
        bail!(BadArgs(format!(
            "{}: {what} needs the whole mesh in memory, and this input is decomposed in tiles ({why})",
            input.display()
        )))
    };
    if a.per_object {
        refuse("--per-object")?;
    }
    if dest.png.is_some() {
        refuse("--png")?;
    }
    if a.export_opts.preview {
        refuse("--export-preview")?;
    }
    let mut counts = Vec::new();
    for t in targets {
        match *t {
            Target::Count(n) => counts.push(n),
            Target::Percent(_) => refuse("-n as a percentage of the faces")?,
        }
    }
    let params = Params {
        targets: if counts.is_empty() {
            base.targets.clone()
        } else {
            counts
        },
        ..base.clone()
    };
    let options = LoadOptions {
        tiles: a.tiles,
        ..options.clone()
    };
    let now = Instant::now();
    let shown = Shown::new(&params, usize::MAX, a, false);
    let mut dec = primdecomp::decompose_tiled(input, &params, &options, &|s: Stage, f: f64| {
        shown.update(s, f)
    })?;
    shown.finish();
    let run_s = now.elapsed().as_secs_f64();
    dec.input.path = Some(input.display().to_string());
    let up = input_up(a, input);
    (dec.input.up, dec.input.up_from) = (Some(up.0), Some(up.1));
    let now = Instant::now();
    let empty = primdecomp::Mesh::from_triangles(&[], &[])?;
    let mut written = write_outputs(&dec, &params, dest, guard, a.obj_detail, a.timings)?;
    written.extend(write_exports(a, &dec, dest, input, &empty, up.0)?);
    let write_s = now.elapsed().as_secs_f64();
    let _out = PRINT.lock();
    if !a.quiet {
        println!("tiles     {}: {why}", dec.stats.tiles);
        print_summary(&dec, &empty, &written, a.verbose);
    }
    if a.verbose || a.timings {
        print_timings(&dec, write_s, a.inputs.len() > 1, a.verbose, None);
    } else if !a.quiet {
        println!("time      {:.2} s", run_s + write_s);
    }
    Ok((dec, written))
}
