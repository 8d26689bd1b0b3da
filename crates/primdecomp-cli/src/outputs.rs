//! No output is ever written over an input, and no two outputs of one run are the
//! same file. Files are compared by identity (device and inode after following
//! symbolic links), not by spelling, so `m.obj`, `./m.obj`, `/abs/m.obj`, a symbolic
//! link to it and a hard link all count as the input `m.obj`. Outputs are checked
//! before anything is written: up front where their names are known from the
//! arguments, and again per input just before its files are written (names that
//! depend on a percentage target are known only then).

use crate::exit::BadArgs;
use anyhow::anyhow;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// What identifies a file whatever its spelling.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct FileId {
    #[cfg(unix)]
    dev_ino: (u64, u64),
    #[cfg(not(unix))]
    real: PathBuf,
}

impl FileId {
    /// The identity of the file at `path` (following symbolic links); `None` if
    /// nothing can be found there.
    pub fn of(path: &Path) -> Option<FileId> {
        #[cfg(unix)]
        {
            use std::os::unix::fs::MetadataExt;
            let m = std::fs::metadata(path).ok()?;
            Some(FileId {
                dev_ino: (m.dev(), m.ino()),
            })
        }
        #[cfg(not(unix))]
        {
            Some(FileId {
                real: std::fs::canonicalize(path).ok()?,
            })
        }
    }
}

/// One file a run will write, with how to name it to the user.
pub struct Out {
    pub path: PathBuf,
    /// How the user asked for it, e.g. "-o ./m.obj" or "out/x.primdecomp.json (the
    /// output for x.obj)".
    pub what: String,
}

impl Out {
    /// The file `path` from option `flag`, given as `given` (the two differ where a
    /// target suffix was added).
    pub fn flag(flag: &str, given: &Path, path: PathBuf) -> Out {
        let what = if path == given {
            format!("{flag} {}", given.display())
        } else {
            format!("{flag} {} (as {})", given.display(), path.display())
        };
        Out { path, what }
    }

    /// `path`, an output of `input` in a batch.
    pub fn of_input(path: PathBuf, input: &Path) -> Out {
        let what = format!("{} (the output for {})", path.display(), input.display());
        Out { path, what }
    }
}

/// The inputs of a run (every file it reads that the user named), and the files it
/// has written so far; both looked up by identity in hash maps, so checking n
/// outputs takes time linear in n.
pub struct Guard {
    inputs: HashMap<FileId, PathBuf>,
    written: Mutex<HashMap<FileId, String>>,
}

impl Guard {
    /// Identities of `inputs`; an input that cannot be found is left out (loading it
    /// fails with its own message).
    pub fn new<'a>(inputs: impl IntoIterator<Item = &'a Path>) -> Guard {
        let mut by_id = HashMap::new();
        for p in inputs {
            if let Some(id) = FileId::of(p) {
                by_id.entry(id).or_insert_with(|| p.to_path_buf());
            }
        }
        Guard {
            inputs: by_id,
            written: Mutex::new(HashMap::new()),
        }
    }

    /// Refuses (exit 2) an output that is one of the inputs, or that is the same file
    /// as another of `outs`, or as a file this run already wrote.
    pub fn check(&self, outs: &[Out]) -> Result<(), BadArgs> {
        let mut seen: HashMap<PathBuf, &str> = HashMap::with_capacity(outs.len());
        let written = self.written.lock().unwrap_or_else(|e| e.into_inner());
        for o in outs {
            if is_stdout(&o.path) {
                // Not a file: only a second output to standard output can clash with it.
                if let Some(what) = seen.insert(PathBuf::from("-"), &o.what) {
                    return Err(BadArgs(format!(
                        "{what} and {} both go to standard output, which holds one: give \
                         one of them a file name",
                        o.what
                    )));
                }
                continue;
            }
            // A name the file system cannot hold fails only when written: refuse it now.
            let name = o.path.file_name().map_or(0, |n| n.len());
            if name > 255 {
                return Err(BadArgs(format!(
                    "{}: the file name is {name} bytes long, more than the 255 a file system \
                     takes; choose a shorter output path (or rename the input it is named after)",
                    o.what
                )));
            }
            if let Some(id) = FileId::of(&o.path) {
                if let Some(input) = self.inputs.get(&id) {
                    return Err(BadArgs(format!(
                        "{} is the input {} (the same file): refusing to overwrite an input; \
                         choose another output path",
                        o.what,
                        input.display()
                    )));
                }
                if let Some(what) = written.get(&id) {
                    return Err(same_file(&o.what, what));
                }
            }
            if let Some(what) = seen.insert(out_key(&o.path), &o.what) {
                return Err(same_file(what, &o.what));
            }
        }
        Ok(())
    }

    /// Records that `out` was written, so no later output of the run may be the same
    /// file (a second spelling that `check` could not tell apart before the file
    /// existed, e.g. on a case-insensitive file system).
    pub fn wrote(&self, out: &Out) {
        if is_stdout(&out.path) {
            return;
        }
        if let Some(id) = FileId::of(&out.path) {
            let mut w = self.written.lock().unwrap_or_else(|e| e.into_inner());
            w.entry(id).or_insert_with(|| out.what.clone());
        }
    }
}

/// `-` (and `/dev/stdout`, its usual spelling) as an output (`decompose -o`, `export
/// -o`, `view -o`/`--png`, `eval --json`): it goes to standard output, not to a file.
pub fn is_stdout(path: &Path) -> bool {
    path == Path::new("-") || path == Path::new("/dev/stdout")
}

/// Writes `bytes` to standard output when `path` names it ([`is_stdout`]), else to
/// the file `path`, whole or not at all (`primdecomp_files::write_atomic`).
pub fn write_out(path: &Path, bytes: &[u8]) -> anyhow::Result<()> {
    if !is_stdout(path) {
        return Ok(primdecomp_files::write_atomic(path, bytes)?);
    }
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    out.write_all(bytes)
        .and_then(|()| out.flush())
        .map_err(|e| anyhow!("cannot write the result to standard output: {e}"))
}

fn same_file(a: &str, b: &str) -> BadArgs {
    BadArgs(format!(
        "{a} and {b} are the same file: one would replace the other; give them different paths"
    ))
}

/// A key equal for two spellings of one path that may not exist yet: the real path
/// if it exists, else its folder's real path joined with its name, else the path
/// made absolute with `.` components dropped.
fn out_key(p: &Path) -> PathBuf {
    if let Ok(real) = std::fs::canonicalize(p) {
        return real;
    }
    let parent = match p.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    match (std::fs::canonicalize(parent), p.file_name()) {
        (Ok(dir), Some(name)) => dir.join(name),
        _ => std::path::absolute(p)
            .unwrap_or_else(|_| p.to_path_buf())
            .components()
            .filter(|c| *c != std::path::Component::CurDir)
            .collect(),
    }
}

/// `path` names a directory as an output: it ends in a path separator or is an
/// existing directory.
pub fn names_dir(path: &Path) -> bool {
    let s = path.as_os_str().to_string_lossy();
    s.ends_with('/') || s.ends_with(std::path::MAIN_SEPARATOR) || path.is_dir()
}

/// Refuses `dir` as the output directory `flag` of a batch of `n` inputs when it
/// looks like a file: it ends in `.{ext}`, or it exists and is not a directory.
pub fn check_batch_dir(
    flag: &str,
    dir: &Path,
    n: usize,
    ext: &str,
    each: &str,
) -> Result<(), BadArgs> {
    let has_ext = dir
        .extension()
        .is_some_and(|e| e.to_string_lossy().eq_ignore_ascii_case(ext))
        && !names_dir(dir);
    let file = dir.exists() && !dir.is_dir();
    if !has_ext && !file {
        return Ok(());
    }
    let inputs = if n == 1 {
        "with -o naming a directory".to_string()
    } else {
        format!("with {n} inputs")
    };
    let is = if file {
        "exists and is not a directory".to_string()
    } else {
        format!("ends in .{ext}")
    };
    Err(BadArgs(format!(
        "{flag} {}: {is}, but {inputs} {flag} names a directory (each input writes \
         DIR/{each}); give a directory, or one input",
        dir.display()
    )))
}

/// Refuses (exit 2) two inputs of a batch that would write the same output name.
pub fn check_stems(inputs: &[PathBuf], name: impl Fn(&Path) -> PathBuf) -> Result<(), BadArgs> {
    let mut seen: std::collections::HashMap<PathBuf, &Path> = Default::default();
    for input in inputs {
        let out = name(input);
        if let Some(first) = seen.insert(out.clone(), input) {
            return Err(BadArgs(format!(
                "{} and {} would both write {} (outputs are named after the input's file \
                 name without its extension): rename one of them, or run them separately",
                first.display(),
                input.display(),
                out.display()
            )));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(tag: &str) -> PathBuf {
        crate::scratch_dir(&format!("outputs-{tag}"))
    }

    /// An input is found by identity however the output spells it; a new file and
    /// a distinct existing file pass.
    #[cfg(unix)]
    #[test]
    fn outputs_equal_to_inputs_are_found_by_identity() {
        let d = scratch("identity");
        let m = d.join("m.obj");
        std::fs::write(&m, "v 0 0 0\n").unwrap();
        std::os::unix::fs::symlink(&m, d.join("link.json")).unwrap();
        std::fs::hard_link(&m, d.join("hard.json")).unwrap();
        std::fs::write(d.join("other.json"), "x").unwrap();
        let guard = Guard::new([m.as_path()]);
        let spellings = [
            m.clone(),
            d.join(".").join("m.obj"),
            d.join("sub/../m.obj"),
            d.join("link.json"),
            d.join("hard.json"),
        ];
        std::fs::create_dir(d.join("sub")).unwrap();
        for s in spellings {
            let e = guard.check(&[Out::flag("-o", &s, s.clone())]).unwrap_err();
            assert!(
                e.0.contains("is the input") && e.0.contains("m.obj"),
                "{s:?}: {}",
                e.0
            );
        }
        for ok in ["other.json", "new.json"] {
            let p = d.join(ok);
            guard.check(&[Out::flag("-o", &p, p.clone())]).unwrap();
        }
        std::fs::remove_dir_all(&d).unwrap();
    }

    /// Two outputs of a run that are one file, existing or not, are refused.
    #[cfg(unix)]
    #[test]
    fn two_outputs_that_are_one_file_are_refused() {
        let d = scratch("twice");
        let guard = Guard::new([]);
        let a = d.join("r.json");
        let b = d.join(".").join("r.json");
        let outs = [
            Out::flag("-o", &a, a.clone()),
            Out::flag("--obj", &b, b.clone()),
        ];
        let e = guard.check(&outs).unwrap_err();
        assert!(e.0.contains("are the same file"), "{}", e.0);
        let c = d.join("r.obj");
        guard
            .check(&[
                Out::flag("-o", &a, a.clone()),
                Out::flag("--obj", &c, c.clone()),
            ])
            .unwrap();
        // After it is written, a later output through a symbolic link to it is refused.
        std::fs::write(&a, "x").unwrap();
        guard.wrote(&Out::flag("-o", &a, a.clone()));
        std::os::unix::fs::symlink(&a, d.join("l.json")).unwrap();
        let l = d.join("l.json");
        let e = guard
            .check(&[Out::of_input(l, Path::new("y.obj"))])
            .unwrap_err();
        assert!(e.0.contains("are the same file"), "{}", e.0);
        std::fs::remove_dir_all(&d).unwrap();
    }

    #[test]
    fn stems_and_batch_dirs() {
        let ins = [
            PathBuf::from("a/x.obj"),
            PathBuf::from("b/y.obj"),
            PathBuf::from("b/x.ply"),
        ];
        let name = |p: &Path| PathBuf::from(p.file_stem().unwrap());
        let e = check_stems(&ins, name).unwrap_err();
        assert!(
            e.0.starts_with("a/x.obj and b/x.ply would both write x"),
            "{}",
            e.0
        );
        check_stems(&ins[..2], name).unwrap();
        let e = check_batch_dir("-o", Path::new("one.JSON"), 2, "json", "S.json").unwrap_err();
        assert!(
            e.0.contains("ends in .json") && e.0.contains("with 2 inputs"),
            "{}",
            e.0
        );
        check_batch_dir("-o", Path::new("one.json/"), 2, "json", "S.json").unwrap();
        check_batch_dir("-o", Path::new("results"), 2, "json", "S.json").unwrap();
    }
}
