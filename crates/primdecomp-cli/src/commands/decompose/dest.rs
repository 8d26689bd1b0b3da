//! Where one input's files go: the JSON, OBJ, export and PNG names before and after
//! the level suffixes ([`output_path_for`]), which of them are known before
//! decomposing, and what `--resume` may take as an input's outputs.

use crate::outputs::Out;
use crate::paths::{level_labels, output_path_for};
use primdecomp::Target;
use primdecomp::{Goal, Params, Tolerance};
use std::path::{Path, PathBuf};

/// A run's tolerances and byte targets: several of either name its levels
/// ([`level_labels`]).
#[derive(Clone, Debug, Default)]
pub(super) struct Chain {
    tolerance: Vec<Tolerance>,
    max_bytes: Vec<usize>,
}

impl Chain {
    pub(super) fn of(p: &Params) -> Chain {
        match &p.goal {
            Goal::Within {
                tolerance,
                max_bytes,
                ..
            } => Chain {
                tolerance: tolerance.clone(),
                max_bytes: max_bytes.clone(),
            },
            _ => Chain::default(),
        }
    }

    /// Whether the levels are named by tolerances or byte targets, not counts.
    pub(super) fn names_levels(&self) -> bool {
        self.tolerance.len() > 1 || self.max_bytes.len() > 1
    }
}

/// Where one input's files go: the JSON and OBJ names before target suffixes
/// ([`output_path_for`]), and in a batch the input they are named after.
pub(super) struct Dest {
    pub(super) json: PathBuf,
    /// How messages name `json`'s origin: "-o", or "the default output".
    pub(super) json_flag: &'static str,
    pub(super) obj: Option<PathBuf>,
    /// `--export` files (one input only).
    pub(super) exports: Vec<PathBuf>,
    /// The `--png` file (in a batch, inside the `--png` directory).
    pub(super) png: Option<PathBuf>,
    pub(super) batch_input: Option<PathBuf>,
    /// The tolerances and byte targets that name a chain's levels.
    pub(super) chain: Chain,
}

impl Dest {
    /// The labels of levels with these counts in output names.
    pub(super) fn labels(&self, counts: &[usize]) -> Vec<String> {
        level_labels(counts, &self.chain.tolerance, &self.chain.max_bytes)
    }

    /// The files written for `levels`, the targets of the decomposition's levels.
    pub(super) fn outs(&self, levels: &[usize]) -> Vec<Out> {
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
    pub(super) fn resumable(
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
    pub(super) fn up_front(&self, targets: &[Target]) -> Vec<Out> {
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

/// `STEM.primdecomp.json`, STEM the input's file name without its extension.
pub(super) fn default_out(input: &Path) -> PathBuf {
    named_after(input, "json")
}

/// `STEM.primdecomp.obj`, an input's OBJ in a batch.
pub(super) fn default_obj(input: &Path) -> PathBuf {
    named_after(input, "obj")
}

/// `STEM.png`, an input's `--png` picture in a batch.
pub(super) fn default_png(input: &Path) -> PathBuf {
    let stem = input.file_stem().unwrap_or_default().to_string_lossy();
    PathBuf::from(format!("{stem}.png"))
}

/// `STEM.primdecomp.EXT` (`out` for an input without a stem).
fn named_after(input: &Path, ext: &str) -> PathBuf {
    let stem = input
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "out".into());
    PathBuf::from(format!("{stem}.primdecomp.{ext}"))
}
