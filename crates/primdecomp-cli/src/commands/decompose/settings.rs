//! `decompose`'s settings from its flags: the library's [`Params`] (defaults, then
//! `--config`, then each flag), its [`Goal`] with the targets as given (counts or
//! percentages, resolved per input), how inputs are read. Every value a user can
//! mistype fails with a message naming the flag (exit code 2).

use crate::args::DecomposeArgs;
use crate::exit::BadArgs;
use crate::paths::memory_limit;
use primdecomp::LoadOptions;
use primdecomp::{Goal, Kind, Params, Reprice, Target, Tolerance};
use std::path::Path;
use std::str::FromStr;

/// The settings (the defaults, then `--config`, then every flag given) and the goal's
/// targets as given, one per level; the goal's counts are set per input
/// ([`resolve_targets`], [`Goal::with_targets`]).
pub(super) fn params_from(a: &DecomposeArgs) -> anyhow::Result<(Params, Vec<Target>)> {
    let mut p = match &a.config {
        Some(path) => read_config(path)?,
        None => Params::default(),
    };
    set_plain(&mut p, a);
    set_parsed(&mut p, a)?;
    let (goal, targets) = goal_from(a, &p.goal)?;
    p.goal = goal;
    if a.max_excess_volume.is_some() && p.reprice != Reprice::Exact {
        return Err(BadArgs(
            "--max-excess-volume needs --reprice exact: a merge over the cap has no queue \
             entry whose re-pricing could be deferred"
                .into(),
        )
        .into());
    }
    // Percentages are resolved per input; validate with a stand-in count.
    let check = Params {
        goal: p.goal.with_targets(vec![1; targets.len()]),
        ..p.clone()
    };
    check.validate().map_err(|e| BadArgs(e.to_string()))?;
    Ok((p, targets))
}

/// The goal the flags ask for, or the settings file's when they ask for none: -n,
/// --tolerance and --max-bytes replace the file's goal; --cut, --greedy and --fill
/// apply to the counts of -n, or of the file. Its targets: one per level (one -n
/// value caps every level of a chain of tolerances or byte budgets).
fn goal_from(a: &DecomposeArgs, file: &Goal) -> anyhow::Result<(Goal, Vec<Target>)> {
    let given = a.targets.is_some() || a.tolerance.is_some() || a.max_bytes.is_some();
    if !(given || a.cut || a.greedy || a.fill) {
        let targets = file.targets().into_iter().map(Target::Count).collect();
        return Ok((file.clone(), targets));
    }
    let (tolerance, max_bytes) = limits_from(a)?;
    let targets = match (&a.targets, file) {
        (Some(t), _) => Some(parse_targets(t)?),
        (
            None,
            Goal::Counts { counts }
            | Goal::Greedy { counts }
            | Goal::Cut { counts }
            | Goal::Fill { counts },
        ) if !given => Some(counts.iter().map(|&n| Target::Count(n)).collect()),
        _ => None,
    };
    let within = !tolerance.is_empty() || !max_bytes.is_empty();
    refuse_couplings(a, within, targets.is_some())?;
    // Placeholder counts, one per target: the counts are set per input.
    let counts = vec![1; targets.as_ref().map_or(0, Vec::len)];
    let goal = match &targets {
        _ if within => Goal::Within {
            caps: counts,
            tolerance,
            max_bytes,
        },
        // --cut alone: the file's tolerance or byte goal, or the default (a cut).
        None => file.clone(),
        Some(_) if a.fill => Goal::Fill { counts },
        Some(_) if a.greedy => Goal::Greedy { counts },
        Some(_) if a.cut => Goal::Cut { counts },
        Some(_) => Goal::Counts { counts },
    };
    let levels = goal.levels().max(1);
    let targets = match targets {
        // A chain of tolerances or byte budgets under one cap: one level each.
        Some(t) if t.len() == 1 => vec![t[0]; levels],
        Some(t) => t,
        None => goal.targets().into_iter().map(Target::Count).collect(),
    };
    Ok((goal, targets))
}

/// `--tolerance` and `--max-bytes` as given (empty when not).
fn limits_from(a: &DecomposeArgs) -> anyhow::Result<(Vec<Tolerance>, Vec<usize>)> {
    let tolerance = (a.tolerance.iter().flatten())
        .map(|t| spelled("--tolerance", t))
        .collect::<anyhow::Result<_>>()?;
    let max_bytes = (a.max_bytes.iter().flatten())
        .map(|b| parse_bytes(b))
        .collect::<anyhow::Result<_>>()?;
    Ok((tolerance, max_bytes))
}

/// The goal's flags that cannot go together: --fill with a cut, --greedy with a
/// tolerance or byte budget, --fill or --greedy without counts.
fn refuse_couplings(a: &DecomposeArgs, within: bool, counts: bool) -> anyhow::Result<()> {
    let bad = |m: &str| Err(BadArgs(m.into()).into());
    if a.fill && (within || a.cut) {
        return bad(
            "--fill refines the greedy pass's levels; --cut, --tolerance and --max-bytes \
             already fill each target from the merge tree",
        );
    }
    if a.greedy && within {
        return bad("--greedy takes the greedy pass's levels: not with --tolerance or --max-bytes");
    }
    if !counts && a.fill {
        return bad("--fill needs -n: the counts whose levels it fills");
    }
    if !counts && a.greedy {
        return bad("--greedy needs -n: the counts whose levels it takes");
    }
    Ok(())
}

/// The flags taken as they are: numbers and switches.
fn set_plain(p: &mut Params, a: &DecomposeArgs) {
    let set = |field: &mut f64, v: Option<f64>| {
        if let Some(v) = v {
            *field = v;
        }
    };
    set(&mut p.fit.tangent_eps, a.tangent_eps);
    set(&mut p.fit.min_extent, a.min_extent);
    set(&mut p.plates.open_holes, a.open_holes);
    set(&mut p.plates.min_thickness, a.min_thickness);
    set(&mut p.plates.rim_weight, a.rim_weight);
    if let Some(m) = a.max_excess_volume {
        p.fit.max_excess_volume = Some(m);
    }
    if a.remove_thin_boxes.is_some() {
        p.plates.remove_thin_boxes = a.remove_thin_boxes;
    }
    p.plates.remove_nested &= !a.keep_nested;
    p.plates.flush_plates &= !a.no_flush_plates;
    p.plates.join_coplanar &= !a.no_join_coplanar;
    p.plates.solid |= a.solid;
}

/// The flags a user spells (a tolerance, a size, a kind, `auto`…), each parsed with
/// a message naming the flag.
fn set_parsed(p: &mut Params, a: &DecomposeArgs) -> anyhow::Result<()> {
    if let Some(k) = &a.partitions {
        p.partitions = spelled("--partitions", k)?;
    }
    for w in &a.weights {
        p.fit.set_weights(w).map_err(|e| flagged("--weights", e))?;
    }
    if !a.kinds.is_empty() {
        p.fit.kinds = [false; 6];
        for k in &a.kinds {
            p.fit.kinds[spelled::<Kind>("", k)? as usize] = true;
        }
    }
    if let Some(d) = &a.dedup {
        p.fit.dedup = spelled("--dedup", d)?;
    }
    if let Some(r) = &a.reprice {
        p.reprice = spelled("--reprice", r)?;
    }
    Ok(())
}

/// A value as the library spells it (its `FromStr`), a wrong one refused with the
/// library's words after the flag's name (`flag` empty: the words alone).
pub(crate) fn spelled<T: FromStr<Err = primdecomp::Error>>(
    flag: &str,
    s: &str,
) -> anyhow::Result<T> {
    s.parse().map_err(|e| flagged(flag, e))
}

/// The library's words for a wrong value after the flag's name (`flag` empty: the
/// words alone).
fn flagged(flag: &str, e: primdecomp::Error) -> anyhow::Error {
    let words = match e {
        primdecomp::Error::InvalidParams(m) => m,
        e => e.to_string(),
    };
    match flag {
        "" => BadArgs(words).into(),
        flag => BadArgs(format!("{flag}: {words}")).into(),
    }
}

/// `--max-bytes`: a positive byte count, optionally with K, M or G.
fn parse_bytes(b: &str) -> anyhow::Result<usize> {
    match Goal::parse_bytes(b) {
        Ok(v) if v > 0 && v <= usize::MAX as u64 => Ok(v as usize),
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

/// `-n`: each value a positive count or a percentage of the faces ([`Target`]'s
/// spelling).
pub(super) fn parse_targets(raw: &[String]) -> anyhow::Result<Vec<Target>> {
    raw.iter().map(|t| spelled("-n", t)).collect()
}

/// The counts of `targets` for an input of `faces` faces (a percentage's at least 1).
pub(super) fn resolve_targets(targets: &[Target], faces: usize) -> Vec<usize> {
    targets.iter().map(|t| t.count(faces)).collect()
}
