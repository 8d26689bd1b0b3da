//! `decompose`'s settings from its flags: the library's [`Params`] (defaults, then
//! `--config`, then each flag), the targets as given (counts or percentages), how
//! inputs are read. Every value a user can mistype fails with a message naming the
//! flag (exit code 2).

use crate::args::DecomposeArgs;
use crate::exit::BadArgs;
use crate::paths::memory_limit;
use primdecomp::LoadOptions;
use primdecomp::{Dedup, Kind, Params, Partitions, Reprice, Tolerance};
use std::path::Path;

/// The settings: the defaults, then `--config`, then every flag given.
pub(super) fn params_from(a: &DecomposeArgs) -> anyhow::Result<Params> {
    let mut p = match &a.config {
        Some(path) => read_config(path)?,
        None => Params::default(),
    };
    set_plain(&mut p, a);
    set_parsed(&mut p, a)?;
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

/// The flags taken as they are: numbers and switches.
fn set_plain(p: &mut Params, a: &DecomposeArgs) {
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
}

/// The flags a user spells (a tolerance, a size, a kind, `auto`…), each parsed with
/// a message naming the flag.
fn set_parsed(p: &mut Params, a: &DecomposeArgs) -> anyhow::Result<()> {
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
    Ok(())
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

/// `--dedup`: exact, off or a welding distance.
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

/// `--reprice`: exact, deferred or the neighbour count from which re-pricing waits.
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
pub(super) fn load_options(a: &DecomposeArgs, params: &Params) -> anyhow::Result<LoadOptions> {
    Ok(LoadOptions {
        max_memory: max_memory(a)?,
        greedy_only: !params.uses_cut(),
        allow_external_uris: a.load.allow_external_uris,
        ..LoadOptions::default()
    })
}

/// The memory limit in bytes from `--max-memory`; `None` for no limit.
pub(super) fn max_memory(a: &DecomposeArgs) -> anyhow::Result<Option<u64>> {
    memory_limit(&a.max_memory)
}

/// A primitive kind by name (`--weights`, `--kinds`).
fn parse_kind(k: &str) -> anyhow::Result<Kind> {
    Kind::from_name(k.trim()).ok_or_else(|| {
        BadArgs(format!("unknown primitive kind '{k}': expected box, sphere, capsule, cylinder, frustum or prism")).into()
    })
}

/// A target as given: a count, or a percentage of the input's faces.
#[derive(Clone, Copy, Debug)]
pub(super) enum Target {
    Count(usize),
    Percent(f64),
}

/// `-n`: each value a positive count or a percentage of the faces.
pub(super) fn parse_targets(raw: &[String]) -> anyhow::Result<Vec<Target>> {
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

/// The counts of `targets` for an input of `faces` faces (a percentage's at least 1).
pub(super) fn resolve_targets(targets: &[Target], faces: usize) -> Vec<usize> {
    targets
        .iter()
        .map(|t| match *t {
            Target::Count(n) => n,
            Target::Percent(p) => ((faces as f64 * p / 100.0).round() as usize).max(1),
        })
        .collect()
}
