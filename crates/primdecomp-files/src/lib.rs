//! Files as primdecomp reads and writes them, shared by the core and every tool on
//! top of it: an input must be a regular file ([`open_regular`]: a named pipe or a
//! device is refused before anything is read from it), a document read whole is
//! capped in size ([`read_regular`]), an output replaces its file whole or not at all
//! ([`write_atomic`]), and every name written or quoted shows its hidden characters
//! ([`visible`]). Errors name the file ([`Error`]); the core turns them into its own
//! `primdecomp::Error` with the same words.

#![deny(missing_docs)]

mod atomic;
mod read;
mod visible;

pub use atomic::write_atomic;
pub use read::{open_regular, read_regular};
pub use visible::visible;

use std::path::PathBuf;

/// What can go wrong with a file: the file, and what the operating system said.
/// Each message reads as the core's `primdecomp::Error` for the same failure.
///
/// ```
/// use primdecomp_files::{read_regular, Error};
///
/// let err = read_regular("no/such/file.json".as_ref(), 1 << 20).unwrap_err();
/// assert!(matches!(err, Error::Open { .. }));
/// assert_eq!(err.to_string(), "no/such/file.json: cannot open: no such file or directory");
/// assert_eq!(err.exit_code(), 2);
/// ```
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// The file could not be opened: it does not exist, permission is denied, its
    /// path loops through symbolic links or runs through something that is not a
    /// directory (the input's fault: exit code 2).
    #[error("{path}: cannot open: {}", reason(error))]
    Open {
        /// The file.
        path: PathBuf,
        /// What the operating system said.
        error: std::io::Error,
    },
    /// The file is not a regular file (a directory, named pipe, socket or device):
    /// refused before anything is read from it (exit code 2).
    #[error("{path}: is {kind}, not a regular file")]
    NotAFile {
        /// The file.
        path: PathBuf,
        /// What it is instead.
        kind: FileKind,
    },
    /// The file was opened but could not be read (not the input's fault: exit code 1).
    #[error("{path}: cannot read: {}", reason(error))]
    Io {
        /// The file.
        path: PathBuf,
        /// What the operating system said.
        error: std::io::Error,
    },
    /// The file holds more than a reader of its kind takes ([`read_regular`]'s
    /// `max_bytes`; exit code 2).
    #[error(
        "{path}: the file holds {}, more than the {} read from a file of this kind",
        show_bytes(*size),
        show_bytes(*max)
    )]
    TooLarge {
        /// The file.
        path: PathBuf,
        /// Its size in bytes (or what was read of it).
        size: u64,
        /// The most bytes read.
        max: u64,
    },
    /// An output could not be written ([`write_atomic`]; exit code 1).
    #[error("{path}: cannot write: {}", reason(error))]
    Write {
        /// The file.
        path: PathBuf,
        /// What the operating system said.
        error: std::io::Error,
    },
}

impl Error {
    /// The exit code of a command that stops on this error: 2 when the input is at
    /// fault (missing, not a file, too large), 1 when the system is (a read or write
    /// failed).
    pub fn exit_code(&self) -> i32 {
        match self {
            Error::Io { .. } | Error::Write { .. } => 1,
            _ => 2,
        }
    }
}

/// What an input that is not a regular file is.
///
/// ```
/// use primdecomp_files::{open_regular, Error, FileKind};
///
/// let folder = std::env::temp_dir();
/// match open_regular(&folder) {
///     Err(Error::NotAFile { kind, .. }) => assert_eq!(kind, FileKind::Directory),
///     other => panic!("a folder is not a file: {other:?}"),
/// }
/// assert_eq!(FileKind::Directory.to_string(), "a directory");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FileKind {
    /// A directory.
    Directory,
    /// A named pipe (FIFO).
    NamedPipe,
    /// A Unix socket.
    Socket,
    /// A character device (`/dev/zero`, a terminal).
    CharDevice,
    /// A block device (a disk).
    BlockDevice,
    /// Anything else that is not a regular file.
    Other,
}

impl FileKind {
    /// The kind of a file that is not a regular file; `None` for a regular file.
    ///
    /// ```
    /// let meta = std::fs::metadata(".")?;
    /// assert_eq!(primdecomp_files::FileKind::of(&meta), Some(primdecomp_files::FileKind::Directory));
    /// # Ok::<(), std::io::Error>(())
    /// ```
    pub fn of(meta: &std::fs::Metadata) -> Option<FileKind> {
        let t = meta.file_type();
        if t.is_file() {
            return None;
        }
        if t.is_dir() {
            return Some(FileKind::Directory);
        }
        #[cfg(unix)]
        {
            use std::os::unix::fs::FileTypeExt;
            let kinds = [
                (t.is_fifo(), FileKind::NamedPipe),
                (t.is_socket(), FileKind::Socket),
                (t.is_char_device(), FileKind::CharDevice),
                (t.is_block_device(), FileKind::BlockDevice),
            ];
            if let Some((_, k)) = kinds.iter().find(|(is, _)| *is) {
                return Some(*k);
            }
        }
        Some(FileKind::Other)
    }
}

impl std::fmt::Display for FileKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            FileKind::Directory => "a directory",
            FileKind::NamedPipe => "a named pipe (FIFO)",
            FileKind::Socket => "a socket",
            FileKind::CharDevice => "a character device",
            FileKind::BlockDevice => "a block device",
            FileKind::Other => "neither a regular file nor a directory",
        })
    }
}

/// An OS error as the end of a sentence: lower case, without the "(os error N)"
/// that `std` appends, and a symbolic-link loop called one.
///
/// ```
/// let e = std::io::Error::from(std::io::ErrorKind::NotFound);
/// assert_eq!(primdecomp_files::reason(&e), "entity not found");
/// ```
pub fn reason(e: &std::io::Error) -> String {
    #[cfg(unix)]
    if e.raw_os_error() == Some(libc::ELOOP) {
        return "too many levels of symbolic links (a symbolic link loop?)".into();
    }
    let text = e.to_string();
    let text = match text.rfind(" (os error ") {
        Some(i) if text.ends_with(')') => &text[..i],
        _ => &text,
    };
    let mut c = text.chars();
    match c.next() {
        Some(first) => first.to_lowercase().chain(c).collect(),
        None => String::new(),
    }
}

/// Bytes for a message: `1.5 GiB`, `300 MiB`, `12 KiB`.
///
/// ```
/// assert_eq!(primdecomp_files::show_bytes(3 << 29), "1.5 GiB");
/// ```
pub fn show_bytes(b: u64) -> String {
    const UNITS: [&str; 5] = ["bytes", "KiB", "MiB", "GiB", "TiB"];
    let mut v = b as f64;
    let mut u = 0;
    while v >= 1024.0 && u + 1 < UNITS.len() {
        v /= 1024.0;
        u += 1;
    }
    if u == 0 || v >= 100.0 {
        format!("{v:.0} {}", UNITS[u])
    } else {
        format!("{v:.1} {}", UNITS[u])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_in_messages() {
        assert_eq!(show_bytes(3 << 29), "1.5 GiB");
        assert_eq!(show_bytes(300 << 20), "300 MiB");
        assert_eq!(show_bytes(12), "12 bytes");
    }
}
