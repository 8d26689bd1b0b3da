//! What `decompose` prints when an input is done: the input, its up axis, one line
//! per level (what it asked for, what it reached, why it holds fewer primitives than
//! asked), the files written; and `--table`'s markdown rows for a batch.

use crate::commands::export::wrote_lines;
use crate::exit::println;
use crate::outputs::is_stdout;
use primdecomp::{Decomposition, Kind};
use std::path::{Path, PathBuf};

/// The input, its up axis, skipped elements, one line per level and the files
/// written; with `verbose` also the welding and adjacency counts. `objects`: the
/// objects of a `--per-object` run, each held to its own tolerance.
pub(super) fn print_summary(
    dec: &Decomposition,
    mesh: &primdecomp::Mesh,
    written: &[PathBuf],
    verbose: bool,
    objects: Option<&primdecomp::Objects>,
) {
    print_input(dec, verbose);
    print_up(&dec.input);
    let (short_faces, other) = (mesh.skipped_faces(), mesh.skipped_other());
    if short_faces + other > 0 {
        println!(
            "skipped   {short_faces} faces with fewer than 3 vertices or lines, {other} other elements"
        );
    }
    for (level, l) in dec.levels.iter().enumerate() {
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
            match objects {
                Some(objects) => reach_of_objects(l, dec.input.diagonal(), objects, level),
                None => reach(l, dec.input.diagonal()),
            },
            few(l, dec.input.faces)
        );
    }
    let (to_stdout, files): (Vec<&PathBuf>, Vec<&PathBuf>) =
        written.iter().partition(|f| is_stdout(f));
    if !to_stdout.is_empty() {
        println!("wrote     the result to standard output");
    }
    let files: Vec<PathBuf> = files.into_iter().cloned().collect();
    for line in wrote_lines(&files) {
        println!("{line}");
    }
}

/// The input line: its path and size; with `verbose` also the welding and adjacency
/// counts.
fn print_input(dec: &Decomposition, verbose: bool) {
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
}

/// The up axis and where it came from, when known; an assumed axis says how to
/// change it.
fn print_up(i: &primdecomp::InputInfo) {
    let (Some(up), Some(from)) = (i.up, &i.up_from) else {
        return;
    };
    let other = match up {
        primdecomp::Up::Y => "z",
        primdecomp::Up::Z => "y",
    };
    // An assumption says how to change it; a format's own axis does not need to.
    let change = match from.starts_with("assumed") {
        true => format!("; --up {other} if the mesh stands on {other}"),
        false => String::new(),
    };
    println!("up        +{} ({from}{change})", up.axis().to_uppercase());
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
        "; farthest {d:.4} {} ({:.2}% of the diagonal",
        measured_to(l),
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

/// What a level's distance is measured to: the mesh's surface, or with `--solid` on
/// a mesh with an inside its solid (a primitive's points inside it stand at 0,
/// docs/decisions/0056).
fn measured_to(l: &primdecomp::Level) -> &'static str {
    match l.distance_to_solid {
        true => "outside the solid",
        false => "from the mesh",
    }
}

/// [`reach`] for a level of a `--per-object` run: each object is held to its own
/// tolerance (a share of its own diagonal), not the whole mesh's, so the line says how
/// many objects stand within theirs and names those that do not.
fn reach_of_objects(
    l: &primdecomp::Level,
    diagonal: f64,
    objects: &primdecomp::Objects,
    level: usize,
) -> String {
    let Some(d) = l.distance else {
        return String::new();
    };
    if l.tolerance.is_none() {
        return reach(l, diagonal);
    }
    let over: Vec<(&str, Option<primdecomp::Shortfall>)> = (objects.objects.iter())
        .map(|o| (o.name.as_str(), &o.decomposition.levels[level]))
        .filter(|(_, own)| own.distance.zip(own.tolerance).is_some_and(|(d, t)| d > t))
        .map(|(name, own)| (name, own.shortfall))
        .collect();
    let n = objects.objects.len();
    let mut s = format!(
        "; farthest {d:.4} {} ({:.2}% of the whole mesh's diagonal); {} of {n} \
         objects within their own tolerance",
        measured_to(l),
        100.0 * d / diagonal.max(f64::MIN_POSITIVE),
        n - over.len()
    );
    if !over.is_empty() {
        let names: Vec<String> = (over.iter().take(5))
            .map(|(name, _)| format!("{name:?}"))
            .collect();
        let more = if over.len() > 5 {
            format!(" and {} more", over.len() - 5)
        } else {
            String::new()
        };
        // What stopped them nearer, when it is the same for all (a count is each
        // object's share of the level's).
        let why = match over.iter().all(|(_, why)| *why == over[0].1) {
            false => String::new(),
            true => match over[0].1 {
                Some(primdecomp::Shortfall::Count) => format!(
                    ": their share of the cap of {} primitives comes first (-n raises it)",
                    l.target
                ),
                why => {
                    let own = primdecomp::Level {
                        shortfall: why,
                        ..Default::default()
                    };
                    format!(": {}", shortfall(&own))
                }
            },
        };
        s += &format!(", over it: {}{more}{why}", names.join(", "));
    }
    s
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

/// One markdown row per input and target.
pub(super) fn print_table(rows: &[Decomposition]) {
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
                d.seconds()
            );
        }
    }
}
