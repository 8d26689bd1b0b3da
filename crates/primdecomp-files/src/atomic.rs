//! Atomic output files: write a temporary file next to the target, flush and
//! `fsync` it, then `rename` it over the target, so a reader (or a crash) never sees
//! a half-written result. Also the naming rule for one output file per target.

use crate::Error;
use std::fs::{self, OpenOptions};
use std::io::{self, Write};
use std::path::Path;
use std::sync::atomic::{AtomicU64, Ordering};

/// Makes temporary names unique within the process (the pid separates processes).
static COUNTER: AtomicU64 = AtomicU64::new(0);

/// Replaces `path` with `bytes` atomically.
///
/// The data goes to `.{name}.tmp.{pid}.{counter}` in the target's directory, is
/// flushed and synced, then renamed over `path`. On any failure the temporary file
/// is removed, the target is left as it was, and the error is [`Error::Write`]
/// naming `path`. A symlink at `path` is replaced by a regular file; the new file
/// gets default permissions, not the old file's.
///
/// A character device or a pipe at `path` (`-o /dev/null`, a FIFO a reader waits on)
/// is written to as a shell's redirect would: a rename would put a regular file in
/// its place (as root, in place of `/dev/null` itself). A link to one, a block device
/// and a socket are refused ([`Error::Write`]): a link planted where an output goes
/// must not steer the write to a device.
///
/// ```
/// let path = std::env::temp_dir().join(format!("primdecomp-doc-{}.txt", std::process::id()));
/// primdecomp_files::write_atomic(&path, b"first")?;
/// primdecomp_files::write_atomic(&path, b"second")?; // replaces it whole, never half-written
/// assert_eq!(std::fs::read(&path)?, b"second");
/// std::fs::remove_file(&path)?;
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), Error> {
    let fail = |error| Error::Write {
        path: path.to_path_buf(),
        error,
    };
    let Some(name) = path.file_name() else {
        return Err(fail(io::Error::new(
            io::ErrorKind::InvalidInput,
            "the output path has no file name",
        )));
    };
    match target(path) {
        Target::File => {}
        Target::Stream => {
            let mut stream = OpenOptions::new().write(true).open(path).map_err(fail)?;
            return stream
                .write_all(bytes)
                .and_then(|()| stream.flush())
                .map_err(fail);
        }
        Target::Refused(why) => return Err(fail(io::Error::new(io::ErrorKind::InvalidInput, why))),
    }
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    // A name near the file system's limit of 255 bytes is cut so the temporary name
    // fits too; the pid and the counter keep it unique.
    let tmp = dir.join(format!(
        ".{}.tmp.{}.{}",
        prefix(&name.to_string_lossy(), MAX_TMP_PREFIX),
        std::process::id(),
        COUNTER.fetch_add(1, Ordering::Relaxed)
    ));
    // `create_new` never clobbers a file someone else owns; if it fails, there is
    // nothing of ours to clean up.
    let mut file = OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&tmp)
        .map_err(fail)?;
    let written = file
        .write_all(bytes)
        .and_then(|()| file.flush())
        .and_then(|()| file.sync_all());
    drop(file);
    if let Err(e) = written.and_then(|()| fs::rename(&tmp, path)) {
        let _ = fs::remove_file(&tmp);
        return Err(fail(e));
    }
    sync_dir(dir);
    Ok(())
}

/// What stands at an output path, for [`write_atomic`]. Without Unix's file types
/// (WebAssembly, Windows) every path is a `File`.
#[cfg_attr(not(unix), allow(dead_code))]
enum Target {
    /// Nothing, a regular file, a directory (the rename fails on it) or a link to
    /// one of those (replaced, never written through): the temporary file and the
    /// rename.
    File,
    /// A character device or a pipe, named itself: written to in place.
    Stream,
    /// Anything else that is not a file: why it is refused.
    Refused(&'static str),
}

#[cfg(unix)]
fn target(path: &Path) -> Target {
    use std::os::unix::fs::FileTypeExt;
    let Ok(own) = fs::symlink_metadata(path) else {
        return Target::File;
    };
    let special =
        |t: fs::FileType| t.is_char_device() || t.is_fifo() || t.is_block_device() || t.is_socket();
    let t = own.file_type();
    if t.is_symlink() {
        match fs::metadata(path) {
            Ok(m) if special(m.file_type()) => Target::Refused(
                "the output path is a link to a device, a pipe or a socket: name the device or pipe itself, or a file",
            ),
            _ => Target::File,
        }
    } else if t.is_char_device() || t.is_fifo() {
        Target::Stream
    } else if special(t) {
        Target::Refused("the output path is a block device or a socket, not a file")
    } else {
        Target::File
    }
}

#[cfg(not(unix))]
fn target(_: &Path) -> Target {
    Target::File
}

/// The most bytes of the target's name a temporary name keeps: with the
/// `.tmp.{pid}.{counter}` around it, it stays under the file systems' 255.
const MAX_TMP_PREFIX: usize = 200;

/// The longest start of `name` of at most `max` bytes that ends on a character
/// boundary.
fn prefix(name: &str, max: usize) -> &str {
    let mut cut = name.len().min(max);
    while !name.is_char_boundary(cut) {
        cut -= 1;
    }
    &name[..cut]
}

/// Best effort: makes the rename itself durable (Unix); errors are ignored because
/// the data is already in place and some file systems refuse directory syncs.
fn sync_dir(dir: &Path) {
    #[cfg(unix)]
    if let Ok(d) = fs::File::open(dir) {
        let _ = d.sync_all();
    }
    #[cfg(not(unix))]
    let _ = dir;
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::PathBuf;

    fn scratch_dir(tag: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!(
            "primdecomp-atomic-{tag}-{}-{}",
            std::process::id(),
            COUNTER.fetch_add(1, Ordering::Relaxed)
        ));
        let _ = fs::remove_dir_all(&d);
        fs::create_dir_all(&d).unwrap();
        d
    }

    fn entries(dir: &Path) -> Vec<String> {
        let mut v: Vec<String> = fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }

    #[test]
    fn writes_and_replaces_without_leftovers() {
        let d = scratch_dir("ok");
        let p = d.join("out.json");
        write_atomic(&p, b"first").unwrap();
        assert_eq!(fs::read(&p).unwrap(), b"first");
        write_atomic(&p, b"second, longer").unwrap();
        assert_eq!(fs::read(&p).unwrap(), b"second, longer");
        write_atomic(&p, b"").unwrap();
        assert_eq!(fs::read(&p).unwrap(), b"");
        assert_eq!(entries(&d), vec!["out.json".to_string()]);
        fs::remove_dir_all(&d).unwrap();
    }

    /// A file name of 255 bytes, the file system's limit, is written: its temporary
    /// name is cut to fit.
    #[test]
    fn the_longest_file_name_is_written() {
        let d = scratch_dir("long");
        let name = format!("{}.json", "é".repeat(125));
        assert_eq!(name.len(), 255);
        write_atomic(&d.join(&name), b"x").unwrap();
        assert_eq!(entries(&d), vec![name]);
        fs::remove_dir_all(&d).unwrap();
    }

    #[test]
    fn missing_directory_is_a_write_error_naming_the_target() {
        let d = scratch_dir("missing");
        let p = d.join("no/such/dir/out.json");
        match write_atomic(&p, b"x") {
            Err(Error::Write { path, .. }) => assert_eq!(path, p),
            other => panic!("expected Error::Write, got {other:?}"),
        }
        fs::remove_dir_all(&d).unwrap();
    }

    #[test]
    fn failed_rename_leaves_target_and_removes_temp() {
        // The target is a non-empty directory: the rename must fail.
        let d = scratch_dir("rename");
        let p = d.join("out.obj");
        fs::create_dir(&p).unwrap();
        fs::write(p.join("keep"), b"old").unwrap();
        let err = write_atomic(&p, b"new").unwrap_err();
        assert!(
            matches!(&err, Error::Write { path, .. } if path == &p),
            "{err:?}"
        );
        assert!(err.to_string().contains("out.obj"));
        assert_eq!(fs::read(p.join("keep")).unwrap(), b"old");
        assert_eq!(entries(&d), vec!["out.obj".to_string()]);
        fs::remove_dir_all(&d).unwrap();
    }

    /// A pipe named as the output is written to and stays a pipe: renaming a file
    /// over it would do to it what it did to `/dev/null` (a regular file in its place).
    #[cfg(target_os = "linux")]
    #[test]
    fn a_pipe_is_written_to_in_place() {
        use std::io::Read;
        use std::os::unix::fs::{FileTypeExt, OpenOptionsExt};
        let d = scratch_dir("fifo");
        let p = d.join("out.json");
        let made = std::process::Command::new("mkfifo").arg(&p).status();
        assert!(made.map(|s| s.success()).unwrap_or(false), "mkfifo");
        // The reader opens first, without blocking (Linux's O_NONBLOCK), so the
        // writer's open returns and a file renamed over the pipe fails the test
        // instead of leaving a reader waiting.
        let mut reader = OpenOptions::new()
            .read(true)
            .custom_flags(0o4000)
            .open(&p)
            .unwrap();
        write_atomic(&p, b"through the pipe").unwrap();
        assert!(fs::symlink_metadata(&p).unwrap().file_type().is_fifo());
        let mut got = Vec::new();
        reader.read_to_end(&mut got).unwrap();
        assert_eq!(got, b"through the pipe");
        assert_eq!(entries(&d), vec!["out.json".to_string()]);
        fs::remove_dir_all(&d).unwrap();
    }

    /// A link to a device where an output goes is refused and left as it is: it is
    /// neither written through nor replaced.
    #[cfg(unix)]
    #[test]
    fn a_link_to_a_device_is_refused() {
        let d = scratch_dir("devlink");
        let p = d.join("out.json");
        std::os::unix::fs::symlink("/dev/null", &p).unwrap();
        let err = write_atomic(&p, b"x").unwrap_err();
        assert!(err.to_string().contains("out.json"), "{err}");
        assert!(fs::symlink_metadata(&p).unwrap().file_type().is_symlink());
        assert_eq!(entries(&d), vec!["out.json".to_string()]);
        fs::remove_dir_all(&d).unwrap();
    }

    #[test]
    fn path_without_file_name_is_refused() {
        assert!(matches!(
            write_atomic(Path::new("/"), b"x"),
            Err(Error::Write { .. })
        ));
    }
}
