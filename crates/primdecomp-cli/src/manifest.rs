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
//! what is written; `outputs` are the files written with their sizes and a hash of
//! their bytes (`fnv1a`; named relative to OUT, or absolute when `--obj` names
//! another directory). An input's outputs are renamed into place (complete) before
//! its line is appended.
//!
//! A run without `--resume` starts a new manifest. `--resume` reads it (a torn last
//! line, from a kill in mid-append, is ignored) as a hint, never as an authority: an
//! input is skipped only when its last line says `done` with the same size, mtime and
//! settings hash, and lists exactly files this run would write for it (names made from
//! the command line, never taken from the manifest: a line naming `../x` or an
//! absolute path elsewhere proves nothing), each of which is a regular file (opened
//! without following a symbolic link and without blocking) with the recorded size and
//! the recorded hash of its bytes. Everything else (failed, missing, changed, damaged
//! or not recorded) runs again. Outputs are deterministic, so the resumed batch ends
//! with the files a clean run writes.
//!
//! The manifest itself is read without following a symbolic link or blocking on a
//! named pipe (under `--resume` a manifest that is not a regular file is refused), and
//! every run first replaces it with a new file of its own (the records kept, through a
//! temporary file and a rename), so a link or a hard link planted in its place is
//! never written through.

use crate::exit::BadArgs;
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

/// One output file of an input, named relative to the output directory, with its
/// size and the hash of its bytes ([`fnv1a`], 16 hex digits).
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Written {
    pub file: String,
    pub bytes: u64,
    #[serde(default)]
    pub fnv1a: String,
}

/// The largest manifest read back (a line is a few hundred bytes per input).
const MAX_BYTES: u64 = primdecomp::ResultFile::MAX_BYTES;

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
    /// there (none if there is no manifest); either way replaces the file with one of
    /// its own (header and the records kept) and appends to that.
    pub fn open(dir: &Path, resume: bool) -> anyhow::Result<Manifest> {
        let path = dir.join(NAME);
        let mut earlier = HashMap::new();
        let mut kept = format!("{HEADER}\n");
        if resume {
            if let Some(text) = read_own(&path)? {
                let mut lines = text.lines();
                if lines.next() != Some(HEADER) {
                    return Err(BadArgs(format!(
                        "{}: not a primdecomp manifest (its first line is not {HEADER}); \
                         remove it, or run without --resume",
                        path.display()
                    ))
                    .into());
                }
                // A line cut by a kill in mid-append does not parse and is dropped.
                for (line, r) in
                    lines.filter_map(|l| Some((l, serde_json::from_str::<Record>(l).ok()?)))
                {
                    kept.push_str(line);
                    kept.push('\n');
                    earlier.insert(r.input.clone(), r);
                }
            }
        }
        // A file of our own, whatever was there (a link, a hard link, a pipe).
        primdecomp_files::write_atomic(&path, kept.as_bytes())?;
        let file = open_no_follow(&path, true)
            .with_context(|| format!("{}: cannot open the manifest", path.display()))?;
        Ok(Manifest {
            path,
            dir: dir.to_path_buf(),
            earlier,
            file: Mutex::new(file),
        })
    }

    /// Whether an earlier run finished `input` as this one would: its last record is
    /// `done` with the same stamp and settings, lists exactly the files `expected`
    /// (the paths this run writes for it: absolute or relative to the working
    /// directory, as the command line names them; `None` where the names depend on
    /// the input, when each listed file must pass `could_write` instead), and each of
    /// them is in place with its recorded size and hash.
    pub fn done_before(
        &self,
        input: &Path,
        stamp: Option<Stamp>,
        settings: &str,
        expected: Option<&[PathBuf]>,
        could_write: &dyn Fn(&Path) -> bool,
    ) -> bool {
        let Some(r) = self.earlier.get(&key(input)) else {
            return false;
        };
        if !(r.status == Status::Done
            && stamp.is_some()
            && r.stamp == stamp
            && r.settings == settings
            && !r.outputs.is_empty())
        {
            return false;
        }
        let listed: Vec<PathBuf> = r.outputs.iter().map(|o| self.dir.join(&o.file)).collect();
        let same_set = match expected {
            Some(want) => {
                let a: std::collections::BTreeSet<PathBuf> =
                    listed.iter().map(|p| lexical(p)).collect();
                let b: std::collections::BTreeSet<PathBuf> =
                    want.iter().map(|p| lexical(p)).collect();
                a == b && a.len() == listed.len()
            }
            None => listed.iter().all(|p| could_write(p)),
        };
        same_set
            && r.outputs
                .iter()
                .zip(&listed)
                .all(|(o, p)| content_is(p, o.bytes, &o.fnv1a))
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
                let bytes = std::fs::read(p).with_context(|| {
                    format!("{}: cannot read an output just written", p.display())
                })?;
                // Relative to the directory; elsewhere (--obj DIR2/) absolute.
                let file = match p.strip_prefix(&self.dir) {
                    Ok(inside) => inside.to_path_buf(),
                    Err(_) => std::path::absolute(p)?,
                };
                Ok(Written {
                    file: file.to_string_lossy().into_owned(),
                    bytes: bytes.len() as u64,
                    fnv1a: format!("{:016x}", fnv1a(&bytes)),
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

/// Opens `path` for reading (or appending) without following a symbolic link in its
/// last component and without blocking (a named pipe opens at once), and refuses
/// anything but a regular file.
fn open_no_follow(path: &Path, append: bool) -> std::io::Result<File> {
    let mut o = OpenOptions::new();
    if append {
        o.append(true);
    } else {
        o.read(true);
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        o.custom_flags(libc::O_NOFOLLOW | libc::O_NONBLOCK | libc::O_NOCTTY);
    }
    let f = o.open(path)?;
    if f.metadata()?.is_file() {
        Ok(f)
    } else {
        Err(std::io::Error::other("not a regular file"))
    }
}

/// The manifest's text, `None` if there is none; refuses (exit 2) one that is a
/// symbolic link, not a regular file, larger than [`MAX_BYTES`] or not UTF-8.
fn read_own(path: &Path) -> anyhow::Result<Option<String>> {
    use std::io::Read;
    let refuse = |what: String| -> anyhow::Error {
        BadArgs(format!(
            "{}: {what}; the manifest is only read as a regular file of this folder: remove \
             it, or run without --resume",
            path.display()
        ))
        .into()
    };
    let meta = match std::fs::symlink_metadata(path) {
        Ok(m) => m,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(e) => return Err(anyhow!("{}: cannot read the manifest: {e}", path.display())),
    };
    if meta.file_type().is_symlink() {
        return Err(refuse("is a symbolic link".into()));
    }
    let file = match primdecomp_files::open_regular(path) {
        Ok((file, _)) => file,
        Err(primdecomp_files::Error::NotAFile { kind, .. }) => {
            return Err(refuse(format!("is {kind}, not a regular file")))
        }
        Err(e) => return Err(e.into()),
    };
    let mut bytes = Vec::new();
    file.take(MAX_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| anyhow!("{}: cannot read the manifest: {e}", path.display()))?;
    if bytes.len() as u64 > MAX_BYTES {
        return Err(refuse(format!("holds more than {MAX_BYTES} bytes")));
    }
    String::from_utf8(bytes)
        .map(Some)
        .map_err(|_| refuse("is not UTF-8 text".into()))
}

/// Whether `path` is a regular file (not followed through a link, not blocking)
/// holding `bytes` bytes whose hash is `hash`.
fn content_is(path: &Path, bytes: u64, hash: &str) -> bool {
    use std::io::Read;
    let Ok(f) = open_no_follow(path, false) else {
        return false;
    };
    if f.metadata().map(|m| m.len()).ok() != Some(bytes) {
        return false;
    }
    let mut v = Vec::new();
    if f.take(bytes + 1).read_to_end(&mut v).is_err() || v.len() as u64 != bytes {
        return false;
    }
    format!("{:016x}", fnv1a(&v)) == hash
}

/// `p` made absolute without touching the file system (`..` kept).
fn lexical(p: &Path) -> PathBuf {
    std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf())
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

    /// `done_before` with the outputs this run would write known up front.
    fn done(m: &Manifest, input: &Path, stamp: Option<Stamp>, h: &str, want: &[PathBuf]) -> bool {
        m.done_before(input, stamp, h, Some(want), &|_| false)
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
        let want = [out.clone()];
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
        assert!(done(&m, &input, stamp, "h1", &want));
        assert!(!done(&m, &input, stamp, "h2", &want), "other settings");
        let touched = stamp.map(|s| Stamp {
            mtime_ns: s.mtime_ns + 1,
            ..s
        });
        assert!(!done(&m, &input, touched, "h1", &want), "input changed");
        assert!(!done(&m, Path::new("b.obj"), None, "h1", &want), "failed");
        assert!(
            !done(&m, Path::new("c.obj"), None, "h1", &want),
            "torn line"
        );
        let other = [d.join("b.primdecomp.json")];
        assert!(
            !done(&m, &input, stamp, "h1", &other),
            "not what this run writes"
        );
        std::fs::write(&out, "{ }").unwrap();
        assert!(
            !done(&m, &input, stamp, "h1", &want),
            "output of another size"
        );
        std::fs::write(&out, "[]").unwrap();
        assert!(
            !done(&m, &input, stamp, "h1", &want),
            "output of other bytes"
        );
        std::fs::remove_file(&out).unwrap();
        assert!(!done(&m, &input, stamp, "h1", &want), "output missing");
        // The record appended after the torn line reads back.
        m.failed(&input, stamp, "h1", "later").unwrap();
        drop(m);
        let text = std::fs::read_to_string(d.join(NAME)).unwrap();
        assert!(text.lines().last().unwrap().contains("\"later\""), "{text}");
        let m = Manifest::open(&d, true).unwrap();
        std::fs::write(&out, "{}").unwrap();
        assert!(
            !done(&m, &input, stamp, "h1", &want),
            "the last record wins"
        );
        // An output in another directory (--obj DIR2/) is recorded by its absolute
        // path and found again.
        let other = crate::scratch_dir("manifest-elsewhere");
        let elsewhere = other.join("a.primdecomp.obj");
        std::fs::write(&elsewhere, "o a\n").unwrap();
        m.done(&input, stamp, "h3", &[out.clone(), elsewhere.clone()])
            .unwrap();
        drop(m);
        let m = Manifest::open(&d, true).unwrap();
        let both = [out.clone(), elsewhere.clone()];
        assert!(done(&m, &input, stamp, "h3", &both));
        assert!(
            !done(&m, &input, stamp, "h3", &want),
            "one file more than this run writes"
        );
        std::fs::remove_dir_all(&other).unwrap();
        assert!(!done(&m, &input, stamp, "h3", &both));
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

    /// A manifest that lies: outputs outside the folder, a link or a pipe in an
    /// output's place, the manifest a link, a hard link or a pipe itself.
    #[cfg(unix)]
    #[test]
    fn a_lying_manifest_is_not_believed() {
        let d = scratch("lies");
        let input = d.join("a.obj");
        std::fs::write(&input, "v 0 0 0\n").unwrap();
        let stamp = Stamp::of(&input);
        let out = d.join("a.primdecomp.json");
        let want = [out.clone()];
        // Recorded outputs outside the folder: `../x` and an absolute path.
        let outside = d
            .parent()
            .unwrap()
            .join(format!("x-{}", std::process::id()));
        std::fs::write(&outside, "abc").unwrap();
        let hash = format!("{:016x}", fnv1a(b"abc"));
        let line = |file: &str| {
            format!(
                r#"{{"input":{},"size":{},"mtime_ns":{},"settings":"h","status":"done","outputs":[{{"file":{},"bytes":3,"fnv1a":"{hash}"}}]}}"#,
                serde_json::json!(key(&input)),
                stamp.unwrap().size,
                stamp.unwrap().mtime_ns,
                serde_json::json!(file)
            )
        };
        for file in [
            format!("../{}", outside.file_name().unwrap().to_string_lossy()),
            outside.display().to_string(),
        ] {
            std::fs::write(d.join(NAME), format!("{HEADER}\n{}\n", line(&file))).unwrap();
            let m = Manifest::open(&d, true).unwrap();
            assert!(!done(&m, &input, stamp, "h", &want), "{file}");
            assert!(
                !m.done_before(&input, stamp, "h", None, &|p| p == out),
                "{file}"
            );
        }
        // An output that is a link to a file of the recorded bytes, or a pipe.
        std::fs::write(
            d.join(NAME),
            format!("{HEADER}\n{}\n", line("a.primdecomp.json")),
        )
        .unwrap();
        std::os::unix::fs::symlink(&outside, &out).unwrap();
        let m = Manifest::open(&d, true).unwrap();
        assert!(!done(&m, &input, stamp, "h", &want), "a link");
        std::fs::remove_file(&out).unwrap();
        let fifo = std::process::Command::new("mkfifo")
            .arg(&out)
            .status()
            .unwrap();
        assert!(fifo.success());
        assert!(
            !done(&m, &input, stamp, "h", &want),
            "a pipe: refused, not read"
        );
        std::fs::remove_file(&out).unwrap();
        std::fs::write(&out, "abc").unwrap();
        assert!(done(&m, &input, stamp, "h", &want), "the real thing");
        drop(m);
        // The manifest a link to a file outside: refused under --resume, replaced
        // (the file outside untouched) without.
        std::fs::remove_file(d.join(NAME)).unwrap();
        std::os::unix::fs::symlink(&outside, d.join(NAME)).unwrap();
        let e = Manifest::open(&d, true).err().unwrap().to_string();
        assert!(e.contains("is a symbolic link"), "{e}");
        let m = Manifest::open(&d, false).unwrap();
        m.failed(&input, stamp, "h", "x").unwrap();
        assert_eq!(std::fs::read(&outside).unwrap(), b"abc");
        assert!(!std::fs::symlink_metadata(d.join(NAME))
            .unwrap()
            .file_type()
            .is_symlink());
        drop(m);
        // A hard link to a file outside: read, but never written through.
        std::fs::remove_file(d.join(NAME)).unwrap();
        std::fs::write(&outside, format!("{HEADER}\n")).unwrap();
        std::fs::hard_link(&outside, d.join(NAME)).unwrap();
        let m = Manifest::open(&d, true).unwrap();
        m.failed(&input, stamp, "h", "x").unwrap();
        assert_eq!(
            std::fs::read(&outside).unwrap(),
            format!("{HEADER}\n").as_bytes()
        );
        drop(m);
        // A pipe: refused at once under --resume, never waited on.
        std::fs::remove_file(d.join(NAME)).unwrap();
        let fifo = std::process::Command::new("mkfifo")
            .arg(d.join(NAME))
            .status()
            .unwrap();
        assert!(fifo.success());
        let e = Manifest::open(&d, true).err().unwrap().to_string();
        assert!(e.contains("is a named pipe (FIFO)"), "{e}");
        std::fs::remove_file(&outside).unwrap();
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
