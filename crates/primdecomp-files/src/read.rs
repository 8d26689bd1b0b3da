//! Reading: inputs must be regular files, and documents read whole are capped.

use crate::{Error, FileKind};
use std::fs::{File, Metadata};
use std::path::Path;

/// Opens `path` for reading and returns it with its metadata, or refuses it with
/// [`Error::NotAFile`] unless it is a regular file (after following symbolic links).
///
/// The path is `stat`ed first, so a socket or device is refused without being
/// opened; then it is opened with `O_NONBLOCK` (opening a named pipe never waits for
/// a writer) and `O_NOCTTY`, and the *opened handle's* metadata is checked again, so a
/// file swapped for a pipe between the two is refused too. Failing to open is
/// [`Error::Open`]; both are the input's fault (exit code 2).
///
/// ```
/// let (file, meta) = primdecomp_files::open_regular("Cargo.toml".as_ref())?;
/// assert!(meta.is_file());
/// drop(file);
/// assert!(primdecomp_files::open_regular(".".as_ref()).is_err()); // a folder
/// # Ok::<(), primdecomp_files::Error>(())
/// ```
pub fn open_regular(path: &Path) -> Result<(File, Metadata), Error> {
    let open = |error| Error::Open {
        path: path.to_path_buf(),
        error,
    };
    let not_a_file = |kind| Error::NotAFile {
        path: path.to_path_buf(),
        kind,
    };
    let meta = std::fs::metadata(path).map_err(open)?;
    if let Some(kind) = FileKind::of(&meta) {
        return Err(not_a_file(kind));
    }
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        options.custom_flags(libc::O_NONBLOCK | libc::O_NOCTTY);
    }
    let file = options.open(path).map_err(open)?;
    let meta = file.metadata().map_err(|error| Error::Io {
        path: path.to_path_buf(),
        error,
    })?;
    match FileKind::of(&meta) {
        Some(kind) => Err(not_a_file(kind)),
        None => Ok((file, meta)),
    }
}

/// Reads all of `path`, which must be a regular file ([`open_regular`]: a pipe or
/// device is refused before anything is read) of at most `max_bytes` bytes: a larger
/// file (a sparse file of terabytes, say) is refused from its size before reading
/// ([`Error::TooLarge`]), and no more than `max_bytes + 1` bytes are ever read, should
/// it grow meanwhile. For the small documents the tools read whole: results,
/// settings, evaluations.
///
/// ```
/// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../datasets/demo_scene.obj");
/// assert!(primdecomp_files::read_regular(path.as_ref(), 1 << 30)?.starts_with(b"#"));
/// let refused = primdecomp_files::read_regular(path.as_ref(), 1000).unwrap_err();
/// assert!(refused.to_string().contains("more than the 1000 bytes"), "{refused}");
/// assert!(primdecomp_files::read_regular("/dev/zero".as_ref(), 1000).is_err());
/// # Ok::<(), primdecomp_files::Error>(())
/// ```
pub fn read_regular(path: &Path, max_bytes: u64) -> Result<Vec<u8>, Error> {
    use std::io::Read;
    let (file, meta) = open_regular(path)?;
    let too_large = |size: u64| Error::TooLarge {
        path: path.to_path_buf(),
        size,
        max: max_bytes,
    };
    if meta.len() > max_bytes {
        return Err(too_large(meta.len()));
    }
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    (&file)
        .take(max_bytes.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(|error| Error::Io {
            path: path.to_path_buf(),
            error,
        })?;
    if bytes.len() as u64 > max_bytes {
        return Err(too_large(bytes.len() as u64));
    }
    Ok(bytes)
}
