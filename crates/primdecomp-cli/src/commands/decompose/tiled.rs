//! `decompose` in out-of-core tiles (`primdecomp::Tiled::decompose`): when `--tiles`
//! asks for them or the input would need more than `--max-memory` read whole. The
//! mesh is never held whole, so what needs it is refused: `--per-object`, `--png`,
//! `--export-preview`, and `-n` as a percentage. `one_input` writes the result.

use super::dest::Dest;
use super::progress::Shown;
use crate::args::DecomposeArgs;
use crate::exit::BadArgs;
use anyhow::bail;
use primdecomp::Target;
use primdecomp::{Decomposition, LoadOptions, Params, Stage};
use std::path::Path;

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

/// Decomposes `input` in tiles with `base`'s settings at `targets`; returns the
/// decomposition and its settings. What needs the whole mesh is refused.
pub(super) fn decompose(
    a: &DecomposeArgs,
    input: &Path,
    base: &Params,
    targets: &[Target],
    dest: &Dest,
    options: &LoadOptions,
    (why, beside_others): (&str, bool),
) -> anyhow::Result<(Decomposition, Params)> {
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
        goal: if counts.is_empty() {
            base.goal.clone()
        } else {
            base.goal.with_targets(counts)
        },
        ..base.clone()
    };
    let options = LoadOptions {
        tiles: a.tiles,
        ..options.clone()
    };
    let shown = Shown::new(&params, usize::MAX, a, beside_others);
    let dec = primdecomp::Tiled::decompose(input, &params, &options, &|s: Stage, f: f64| {
        shown.update(s, f)
    })?;
    shown.finish();
    Ok((dec, params))
}
