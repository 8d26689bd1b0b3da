//! Output file names and the memory limit's settings: command-line policy, not the
//! library's.

use crate::exit::BadArgs;
use primdecomp::Tolerance;
use std::path::{Path, PathBuf};

/// The output file for the level labelled `label` when a run has `n_targets` levels:
/// `base` itself for a single level, otherwise `_{label}` inserted before the
/// extension (`n500`: `out.json` → `out_n500.json`, `out` → `out_n500`; see
/// [`level_labels`]).
pub fn output_path_for(base: &Path, label: &str, n_targets: usize) -> PathBuf {
    if n_targets <= 1 {
        return base.to_path_buf();
    }
    let Some(stem) = base.file_stem() else {
        let mut s = base.as_os_str().to_os_string();
        s.push(format!("_{label}"));
        return PathBuf::from(s);
    };
    let mut name = stem.to_os_string();
    name.push(format!("_{label}"));
    if let Some(ext) = base.extension() {
        name.push(".");
        name.push(ext);
    }
    base.with_file_name(name)
}

/// The labels of a run's levels in output names: `n{count}` for each target, or, for
/// a chain of tolerances or byte targets, `t{tolerance}` (a percentage of the diagonal
/// as `t2pct`, a distance as `t0.5`) or `b{bytes}`, which tell levels of one count cap
/// apart.
pub fn level_labels(counts: &[usize], tolerance: &[Tolerance], bytes: &[usize]) -> Vec<String> {
    // The short decimal a value was parsed from (0.07 * 100 is 7.000000000000001).
    let short = |x: f64| format!("{}", (x * 1e10).round() / 1e10);
    (0..counts.len())
        .map(|i| match (tolerance.len() > 1, bytes.len() > 1) {
            (true, _) => match tolerance[i] {
                Tolerance::Diagonal(f) => format!("t{}pct", short(100.0 * f)),
                Tolerance::Units(u) => format!("t{}", short(u)),
            },
            (false, true) => format!("b{}", bytes[i]),
            (false, false) => format!("n{}", counts[i]),
        })
        .collect()
}

/// The text of a result or settings file (JSON or TOML): a regular file of at most
/// [`primdecomp::ResultFile::MAX_BYTES`] (a pipe or device is refused before
/// reading, a larger file from its size), in UTF-8.
pub fn read_result(path: &Path) -> anyhow::Result<String> {
    let bytes = primdecomp_files::read_regular(path, primdecomp::ResultFile::MAX_BYTES)?;
    String::from_utf8(bytes).map_err(|e| {
        primdecomp::Error::ParseByte {
            path: path.to_path_buf(),
            offset: e.utf8_error().valid_up_to() as u64,
            msg: "the file is not UTF-8 text".into(),
        }
        .into()
    })
}

/// `MemAvailable` from `/proc/meminfo`, in bytes; `None` where it cannot be read.
pub fn available_memory() -> Option<u64> {
    let info = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = info.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    kib.checked_mul(1024)
}

/// A `--max-memory` value in bytes: a size, `available` or `none` (`None`).
pub fn memory_limit(s: &str) -> anyhow::Result<Option<u64>> {
    Ok(match s.trim() {
        "none" => None,
        "available" => available_memory(),
        s => Some(primdecomp::Goal::parse_bytes(s).map_err(|_| {
            BadArgs(format!(
                "--max-memory: expected a size like 8G, 'available' or 'none', got '{s}'"
            ))
        })?),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Chains of tolerances or byte targets name their levels by them.
    #[test]
    fn labels_tell_chained_levels_apart() {
        let s = |v: &[&str]| v.iter().map(|x| x.to_string()).collect::<Vec<_>>();
        let (pct, units) = (Tolerance::Diagonal(0.07), Tolerance::Units(0.5));
        assert_eq!(level_labels(&[64, 8], &[], &[]), s(&["n64", "n8"]));
        assert_eq!(level_labels(&[64], &[pct], &[4096]), s(&["n64"]));
        assert_eq!(
            level_labels(&[1024, 1024], &[pct, units], &[]),
            s(&["t7pct", "t0.5"])
        );
        assert_eq!(
            level_labels(&[1024, 1024], &[pct], &[4096, 800]),
            s(&["b4096", "b800"])
        );
    }

    #[test]
    fn output_paths_per_target() {
        let p = |s: &str, t: usize, n| output_path_for(Path::new(s), &format!("n{t}"), n);
        assert_eq!(p("out.json", 500, 1), PathBuf::from("out.json"));
        assert_eq!(p("out.json", 500, 3), PathBuf::from("out_n500.json"));
        assert_eq!(p("dir/out.obj", 40, 2), PathBuf::from("dir/out_n40.obj"));
        assert_eq!(p("dir/out", 40, 2), PathBuf::from("dir/out_n40"));
        assert_eq!(
            p("a.b/out.tar.json", 7, 2),
            PathBuf::from("a.b/out.tar_n7.json")
        );
        assert_eq!(p(".hidden", 7, 2), PathBuf::from(".hidden_n7"));
    }
}
