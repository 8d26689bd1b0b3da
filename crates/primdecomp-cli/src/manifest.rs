//! The batch manifest, so that a batch killed halfway (SIGKILL, power loss) can be
//! finished with `--resume` instead of redone.
//!
//! Every batch (several inputs, or `-o` naming a directory) keeps
//! `OUT/.primdecomp-manifest.jsonl`: JSON lines, appended and `fsync`ed one at a
//! time. The first line is `{"format":"primdecomp-manifest","version":1}`; then one
//! line per input finished, in the order they finish:
//!
//! ```text
//! {"input":"in/a.obj","size":1234,"mtime_ns":1764165600123456789,"settings":"9f0c…",
//!  "status":"done","outputs":[{"file":"a.primdecomp.json","bytes":5678}]}
//! {"input":"in/b.obj","size":99,"mtime_ns":…,"settings":"9f0c…","status":"failed",
//!  "error":"in/b.obj:3: face index 9 is out of range (file has 3 vertices so far)"}
//! ```
//!
//! `input` is the path as given on the command line; `size` and `mtime_ns` (the
//! modification time in nanoseconds since 1970) are the input's, taken before it was
//! read; `settings` is [`settings_hash`], the hash of every setting that changes
//! what is written; `outputs` are the files written with their sizes (relative to
//! OUT, or absolute when `--obj` names another directory). An
//! input's outputs are renamed into place (complete) before its line is appended.
//!
//! A run without `--resume` starts a new manifest. `--resume` reads it (a torn last
//! line, from a kill in mid-append, is ignored) and skips an input whose last line
//! says `done` with the same size, mtime and settings hash while each of its outputs
//! exists with the recorded size; everything else (failed, missing, changed, or not
//! recorded) runs again. Outputs are deterministic, so the resumed batch ends with
//! the files a clean run writes.

use anyhow::{anyhow, Context};
use serde::{Deserialize, Serialize};
use std::collections::HashMap;
use std::fs::{File, OpenOptions};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// The manifest's file name inside the output directory.
pub const NAME: &str = ".primdecomp-manifest.jsonl";

const HEADER: &str = r#"{"format":"primdecomp-manifest","version":1}"#;

/// An input's size and modification time when it was read.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Stamp {
    pub size: u64,
    pub mtime_ns: i64,
}

impl Stamp {
    /// The stamp of `path` now; `None` if it cannot be `stat`ed.
    pub fn of(path: &Path) -> Option<Stamp> {
        let m = std::fs::metadata(path).ok()?;
        let t = m.modified().ok()?;
        let ns = match t.duration_since(std::time::UNIX_EPOCH) {
            Ok(d) => i64::try_from(d.as_nanos()).unwrap_or(i64::MAX),
            Err(e) => i64::try_from(e.duration().as_nanos()).map_or(i64::MIN, |n| -n),
        };
        Some(Stamp {
            size: m.len(),
            mtime_ns: ns,
        })
    }
}

/// One output file of an input, named relative to the output directory.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Written {
    pub file: String,
    pub bytes: u64,
}

#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
enum Status {
    Done,
    Failed,
}

/// One line of the manifest.
#[derive(Clone, Debug, Serialize, Deserialize)]
struct Record {
    input: String,
    #[serde(flatten)]
    stamp: Option<Stamp>,
    settings: String,
    status: Status,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    outputs: Vec<Written>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    error: Option<String>,
}

/// The hash that tells whether two runs write the same files for an input: FNV-1a
/// (64 bits) of `settings` serialized as JSON (fields in declaration order, so the
/// text and its hash are the same on every run and machine) after the program's
/// version, in 16 hex digits.
pub fn settings_hash(settings: &impl Serialize) -> anyhow::Result<String> {
    let json = serde_json::to_string(settings).context("cannot serialize the settings")?;
    let text = format!("primdecomp {} {json}", env!("CARGO_PKG_VERSION"));
    Ok(format!("{:016x}", fnv1a(text.as_bytes())))
}

/// 64-bit FNV-1a: a fixed function of the bytes, unlike `std`'s seeded hasher.
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    })
}

/// The manifest of one batch: the records an earlier run left (for `--resume`) and
/// the file this run appends to.
pub struct Manifest {
    path: PathBuf,
    dir: PathBuf,
    earlier: HashMap<String, Record>,
    file: Mutex<File>,
}

impl Manifest {
    /// Opens the manifest of output directory `dir`: with `resume`, reads the records
    /// there (none if there is no manifest) and appends after them; without, starts a
    /// new one (replacing any, atomically).
    pub fn open(dir: &Path, resume: bool) -> anyhow::Result<Manifest> {
        let path = dir.join(NAME);
        let mut earlier = HashMap::new();
        let existing = if resume {
            match std::fs::read_to_string(&path) {
                Ok(text) => Some(text),
                Err(e) if e.kind() == std::io::ErrorKind::NotFound => None,
                Err(e) => return Err(anyhow!("{}: cannot read the manifest: {e}", path.display())),
            }
        } else {
            None
        };
        match &existing {
            Some(text) => {
                let mut lines = text.lines();
                if lines.next() != Some(HEADER) {
                    return Err(anyhow!(
                        "{}: not a primdecomp manifest (its first line is not {HEADER}); \
                         remove it, or run without --resume",
                        path.display()
                    ));
                }
                // A line cut by a kill in mid-append does not parse and is skipped.
                for r in lines.filter_map(|l| serde_json::from_str::<Record>(l).ok()) {
                    earlier.insert(r.input.clone(), r);
                }
            }
            None => primdecomp::export::write_atomic(&path, format!("{HEADER}\n").as_bytes())?,
        }
        let mut file = OpenOptions::new()
            .append(true)
            .open(&path)
            .with_context(|| format!("{}: cannot open the manifest", path.display()))?;
        // A torn last line gets a line end, so the next record starts a line of its own.
        if existing.is_some_and(|t| !t.is_empty() && !t.ends_with('\n')) {
            file.write_all(b"\n")
                .with_context(|| format!("{}: cannot append to the manifest", path.display()))?;
        }
        Ok(Manifest {
            path,
            dir: dir.to_path_buf(),
            earlier,
            file: Mutex::new(file),
        })
    }

    /// Whether an earlier run finished `input` as this one would: its last record
    /// is `done` with the same stamp and settings, and every output it lists is in
    /// the directory with its recorded size.
    pub fn done_before(&self, input: &Path, stamp: Option<Stamp>, settings: &str) -> bool {
        let Some(r) = self.earlier.get(&key(input)) else {
            return false;
        };
        r.status == Status::Done
            && stamp.is_some()
            && r.stamp == stamp
            && r.settings == settings
            && !r.outputs.is_empty()
            && r.outputs.iter().all(|o| {
                let p = self.dir.join(&o.file);
                std::fs::symlink_metadata(p).is_ok_and(|m| m.is_file() && m.len() == o.bytes)
            })
    }

    /// Appends that `input` is done with `outputs` (paths inside the directory).
    pub fn done(
        &self,
        input: &Path,
        stamp: Option<Stamp>,
        settings: &str,
        outputs: &[PathBuf],
    ) -> anyhow::Result<()> {
        let outputs = outputs
            .iter()
            .map(|p| {
                let bytes = std::fs::metadata(p)
                    .with_context(|| {
                        format!("{}: cannot stat an output just written", p.display())
                    })?
                    .len();
                // Relative to the directory; elsewhere (--obj DIR2/) absolute.
                let file = match p.strip_prefix(&self.dir) {
                    Ok(inside) => inside.to_path_buf(),
                    Err(_) => std::path::absolute(p)?,
                };
                Ok(Written {
                    file: file.to_string_lossy().into_owned(),
                    bytes,
                })
            })
            .collect::<anyhow::Result<Vec<_>>>()?;
        self.append(&Record {
            input: key(input),
            stamp,
            settings: settings.into(),
            status: Status::Done,
            outputs,
            error: None,
        })
    }

    /// Appends that `input` failed with `error`.
    pub fn failed(
        &self,
        input: &Path,
        stamp: Option<Stamp>,
        settings: &str,
        error: &str,
    ) -> anyhow::Result<()> {
        self.append(&Record {
            input: key(input),
            stamp,
            settings: settings.into(),
            status: Status::Failed,
            outputs: Vec::new(),
            error: Some(error.into()),
        })
    }

    /// One line, written whole and synced before returning.
    fn append(&self, r: &Record) -> anyhow::Result<()> {
        let mut line = serde_json::to_string(r).context("cannot serialize a manifest record")?;
        line.push('\n');
        let mut f = self.file.lock().unwrap_or_else(|e| e.into_inner());
        f.write_all(line.as_bytes())
            .and_then(|()| f.sync_data())
            .with_context(|| format!("{}: cannot append to the manifest", self.path.display()))
    }
}

/// How the manifest names an input: its path as given.
fn key(input: &Path) -> String {
    input.to_string_lossy().into_owned()
}

/// Removes temporary files that a killed run left in `dir` for outputs whose names
/// `ours` accepts (`.NAME.tmp.PID.N`, the names `write_atomic` uses), when no process
/// with that PID is alive any more (Linux: no `/proc/PID`). Returns how many were
/// removed.
pub fn remove_stale_temporaries(dir: &Path, ours: &dyn Fn(&str) -> bool) -> usize {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return 0;
    };
    let mine = std::process::id();
    let mut removed = 0;
    for e in entries.flatten() {
        let file = e.file_name();
        let Some(rest) = file.to_str().and_then(|f| f.strip_prefix('.')) else {
            continue;
        };
        let Some((name, tail)) = rest.rsplit_once(".tmp.") else {
            continue;
        };
        let Some((pid, n)) = tail.split_once('.') else {
            continue;
        };
        let Ok(pid) = pid.parse::<u32>() else {
            continue;
        };
        let alive = pid == mine || Path::new(&format!("/proc/{pid}")).exists();
        if ours(name)
            && n.parse::<u64>().is_ok()
            && !alive
            && std::fs::remove_file(e.path()).is_ok()
        {
            removed += 1;
        }
    }
    removed
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(tag: &str) -> PathBuf {
        crate::scratch_dir(&format!("manifest-{tag}"))
    }

    #[test]
    fn settings_hash_is_stable_and_tells_settings_apart() {
        // FNV-1a's published test vectors: the hash is a fixed function of the text.
        assert_eq!(fnv1a(b""), 0xcbf29ce484222325);
        assert_eq!(fnv1a(b"a"), 0xaf63dc4c8601ec8c);
        assert_eq!(fnv1a(b"foobar"), 0x85944171f73967e8);
        let a = settings_hash(&serde_json::json!({"targets": ["8"], "obj": false})).unwrap();
        let again = settings_hash(&serde_json::json!({"targets": ["8"], "obj": false})).unwrap();
        assert_eq!((a.len(), &a), (16, &again));
        let b = settings_hash(&serde_json::json!({"targets": ["9"], "obj": false})).unwrap();
        assert_ne!(a, b);
    }

    /// Done records are trusted only with the same stamp, settings and outputs; a
    /// torn last line is skipped; a later record replaces an earlier one.
    #[test]
    fn resume_trusts_only_matching_complete_records() {
        let d = scratch("records");
        let input = d.join("a.obj");
        std::fs::write(&input, "v 0 0 0\n").unwrap();
        let stamp = Stamp::of(&input);
        let out = d.join("a.primdecomp.json");
        std::fs::write(&out, "{}").unwrap();
        let m = Manifest::open(&d, false).unwrap();
        m.done(&input, stamp, "h1", std::slice::from_ref(&out))
            .unwrap();
        m.failed(Path::new("b.obj"), None, "h1", "b.obj: bad")
            .unwrap();
        drop(m);
        // A kill in mid-append leaves half a line.
        let mut f = OpenOptions::new().append(true).open(d.join(NAME)).unwrap();
        f.write_all(br#"{"input":"c.obj","si"#).unwrap();
        drop(f);
        let m = Manifest::open(&d, true).unwrap();
        assert!(m.done_before(&input, stamp, "h1"));
        assert!(!m.done_before(&input, stamp, "h2"), "other settings");
        let touched = stamp.map(|s| Stamp {
            mtime_ns: s.mtime_ns + 1,
            ..s
        });
        assert!(!m.done_before(&input, touched, "h1"), "input changed");
        assert!(!m.done_before(Path::new("b.obj"), None, "h1"), "failed");
        assert!(!m.done_before(Path::new("c.obj"), None, "h1"), "torn line");
        std::fs::write(&out, "{ }").unwrap();
        assert!(
            !m.done_before(&input, stamp, "h1"),
            "output of another size"
        );
        std::fs::remove_file(&out).unwrap();
        assert!(!m.done_before(&input, stamp, "h1"), "output missing");
        // The torn line was closed: the record appended after it reads back.
        m.failed(&input, stamp, "h1", "later").unwrap();
        drop(m);
        let text = std::fs::read_to_string(d.join(NAME)).unwrap();
        assert!(text.lines().last().unwrap().contains("\"later\""), "{text}");
        let m = Manifest::open(&d, true).unwrap();
        std::fs::write(&out, "{}").unwrap();
        assert!(!m.done_before(&input, stamp, "h1"), "the last record wins");
        // An output in another directory (--obj DIR2/) is recorded by its absolute
        // path and found again.
        let other = crate::scratch_dir("manifest-elsewhere");
        let elsewhere = other.join("a.primdecomp.obj");
        std::fs::write(&elsewhere, "o a\n").unwrap();
        m.done(&input, stamp, "h3", &[out.clone(), elsewhere.clone()])
            .unwrap();
        drop(m);
        let m = Manifest::open(&d, true).unwrap();
        assert!(m.done_before(&input, stamp, "h3"));
        std::fs::remove_dir_all(&other).unwrap();
        assert!(!m.done_before(&input, stamp, "h3"));
        // Without --resume the manifest starts again.
        drop(m);
        let m = Manifest::open(&d, false).unwrap();
        assert!(m.earlier.is_empty());
        assert_eq!(
            std::fs::read_to_string(d.join(NAME)).unwrap(),
            format!("{HEADER}\n")
        );
        std::fs::remove_dir_all(&d).unwrap();
    }

    #[test]
    fn a_foreign_file_is_not_taken_for_a_manifest() {
        let d = scratch("foreign");
        std::fs::write(d.join(NAME), "hello\n").unwrap();
        let e = Manifest::open(&d, true).err().unwrap().to_string();
        assert!(e.contains("not a primdecomp manifest"), "{e}");
        std::fs::remove_dir_all(&d).unwrap();
    }

    #[test]
    fn stale_temporaries_of_dead_processes_are_removed() {
        let d = scratch("stale");
        // PID 0 is never a user process (and has no /proc entry).
        let stale = d.join(".a.primdecomp.json.tmp.0.3");
        let live = d.join(format!(".a.primdecomp.json.tmp.{}.4", std::process::id()));
        let foreign = d.join(".notes.txt.tmp.0.1");
        for p in [&stale, &live, &foreign] {
            std::fs::write(p, "x").unwrap();
        }
        let n = remove_stale_temporaries(&d, &|name| name == "a.primdecomp.json");
        assert_eq!(n, 1);
        assert!(!stale.exists() && live.exists() && foreign.exists());
        std::fs::remove_dir_all(&d).unwrap();
    }
}
