//! The library's one error type. Every variant carries what a user needs to fix the
//! input: the file, and the line or byte offset where parsing stopped.

use primdecomp_files::reason;
pub(crate) use primdecomp_files::show_bytes;
use std::path::PathBuf;

/// Everything that can go wrong in primdecomp. Kernels never return this; only I/O,
/// parsing, parameter validation and the driver do. Its message names the file and
/// where in it; [`Error::exit_code`] tells the input's fault (2) from the system's (1).
///
/// ```
/// use primdecomp::{Error, Mesh, MeshFormat};
///
/// let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n";
/// let err = Mesh::parse(obj, MeshFormat::Obj, "broken.obj".as_ref()).unwrap_err();
/// assert!(matches!(err, Error::ParseLine { line: 4, .. }), "{err}");
/// assert!(err.to_string().starts_with("broken.obj:4: "));
/// assert_eq!(err.exit_code(), 2);
/// ```
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// The file was opened but could not be mapped or read (a device, memory or
    /// system failure, not the input's fault: exit code 1). The message holds the OS
    /// error's text once; it is not also given as the error's `source`, so printing
    /// the chain does not repeat it.
    #[error("{path}: cannot read: {}", reason(error))]
    Io {
        /// The file.
        path: PathBuf,
        /// What the operating system said.
        error: std::io::Error,
    },
    /// An input, or a file an input names (a glTF buffer), could not be opened: it
    /// does not exist, permission is denied, its path loops through symbolic links or
    /// runs through something that is not a directory (exit code 2).
    #[error("{path}: cannot open: {}", reason(error))]
    Open {
        /// The file.
        path: PathBuf,
        /// What the operating system said.
        error: std::io::Error,
    },
    /// An input is not a regular file (a directory, named pipe, socket or device):
    /// refused before anything is read from it, so a pipe cannot block the run and a
    /// device cannot feed it without end (exit code 2).
    #[error("{path}: is {kind}, not a regular file")]
    NotAFile {
        /// The file.
        path: PathBuf,
        /// What it is instead.
        kind: primdecomp_files::FileKind,
    },
    /// A glTF buffer's URI was refused or names nothing usable: a path outside the
    /// glTF's folder without [`LoadOptions::allow_external_uris`], a URL scheme
    /// other than `data:`, or a file that is missing, not a regular file or shorter
    /// than the buffer's declared `byteLength` (exit code 2).
    ///
    /// [`LoadOptions::allow_external_uris`]: crate::LoadOptions::allow_external_uris
    #[error("{path}: buffer {buffer}: the URI '{uri}' {reason}")]
    Uri {
        /// The glTF file.
        path: PathBuf,
        /// The buffer's index in the document.
        buffer: usize,
        /// The URI as the document gives it (cut to 80 characters, control
        /// characters escaped).
        uri: String,
        /// Why it was not read, as the end of a sentence.
        reason: String,
    },
    /// A text format is malformed at a given 1-based line.
    #[error("{path}:{line}: {msg}")]
    ParseLine {
        /// The file.
        path: PathBuf,
        /// 1-based line number.
        line: u64,
        /// What is wrong there.
        msg: String,
    },
    /// A binary format is malformed at a given byte offset.
    #[error("{path}: at byte {offset}: {msg}")]
    ParseByte {
        /// The file.
        path: PathBuf,
        /// 0-based byte offset.
        offset: u64,
        /// What is wrong there.
        msg: String,
    },
    /// The file is not in a format we read (unknown extension, compressed data, a directory…).
    #[error("{path}: {msg}")]
    Format {
        /// The file.
        path: PathBuf,
        /// What is wrong with it.
        msg: String,
    },
    /// The input parsed but has no polygon face to decompose.
    #[error(
        "{path}: the mesh has no polygon faces (faces with fewer than 3 vertices are skipped)"
    )]
    EmptyMesh {
        /// The file (`<mesh>` for a mesh built in memory).
        path: PathBuf,
    },
    /// A vertex lies so far from the others that volumes (cubes of lengths) and the
    /// eigen-solver's squared entries would overflow f64.
    #[error(
        "{path}: vertex {vertex} lies {distance:e} from the centre of the mesh's bounding box; \
         every vertex must lie within {limit:e} of it (rescale the mesh)"
    )]
    Extent {
        /// The file (`<mesh>` for a mesh built in memory).
        path: PathBuf,
        /// 1-based, in the order the file lists vertices.
        vertex: u64,
        /// Its distance from the centre of the bounding box.
        distance: f64,
        /// The largest distance accepted.
        limit: f64,
    },
    /// A vertex lies so far from the origin that the written cylinders and frustums
    /// could not keep their axes within f64's range of lengths (`mesh::MAX_POSITION`).
    #[error(
        "{path}: vertex {vertex} has a coordinate of {coordinate:e}; every coordinate must \
         lie within ±{limit:e} (move the mesh nearer the origin)"
    )]
    Position {
        /// The file (`<mesh>` for a mesh built in memory).
        path: PathBuf,
        /// 1-based, in the order the file lists vertices.
        vertex: u64,
        /// The offending coordinate.
        coordinate: f64,
        /// The largest magnitude accepted.
        limit: f64,
    },
    /// Decomposing the input would need more memory than allowed (checked before
    /// parsing from the counts the file declares, and after parsing).
    #[error(
        "{path}: decomposing this mesh ({faces} faces, {vertices} vertices) needs about {}, \
         more than the memory limit of {} (default: the memory available now); raise the \
         limit with --max-memory SIZE, e.g. --max-memory 64G (in the library: the \
         max_memory of primdecomp::LoadOptions)",
        show_bytes(*needed),
        show_bytes(*limit)
    )]
    TooLarge {
        /// The file.
        path: PathBuf,
        /// Faces it holds (or declares).
        faces: u64,
        /// Vertices it holds (or declares).
        vertices: u64,
        /// Bytes the decomposition is estimated to need.
        needed: u64,
        /// The limit, bytes.
        limit: u64,
    },
    /// A setting is out of range or inconsistent.
    #[error("invalid setting: {0}")]
    InvalidParams(String),
    /// The caller's [`crate::Progress`] cancelled the run.
    #[error("cancelled")]
    Cancelled,
    /// An output file could not be written (exit code 1). Like [`Error::Io`], the
    /// OS error is in the message and the `error` field, not the `source`.
    #[error("{path}: cannot write: {}", reason(error))]
    Write {
        /// The file.
        path: PathBuf,
        /// What the operating system said.
        error: std::io::Error,
    },
}

impl From<primdecomp_files::Error> for Error {
    /// The same failure in the core's words (the same message and exit code).
    fn from(e: primdecomp_files::Error) -> Error {
        use primdecomp_files::Error as E;
        match e {
            E::Open { path, error } => Error::Open { path, error },
            E::NotAFile { path, kind } => Error::NotAFile { path, kind },
            E::Io { path, error } => Error::Io { path, error },
            E::Write { path, error } => Error::Write { path, error },
            E::TooLarge { path, size, max } => Error::Format {
                path,
                msg: format!(
                    "the file holds {}, more than the {} read from a file of this kind",
                    show_bytes(size),
                    show_bytes(max)
                ),
            },
        }
    }
}

impl Error {
    /// Helper for text parsers.
    pub fn line(path: &std::path::Path, line: u64, msg: impl Into<String>) -> Self {
        Error::ParseLine {
            path: path.to_path_buf(),
            line,
            msg: msg.into(),
        }
    }
    /// Helper for binary parsers.
    pub fn byte(path: &std::path::Path, offset: u64, msg: impl Into<String>) -> Self {
        Error::ParseByte {
            path: path.to_path_buf(),
            offset,
            msg: msg.into(),
        }
    }
    /// Helper for whole-file format problems.
    pub fn format(path: &std::path::Path, msg: impl Into<String>) -> Self {
        Error::Format {
            path: path.to_path_buf(),
            msg: msg.into(),
        }
    }
    /// Exit code the CLI uses: 2 for bad input or settings (an input that cannot be
    /// opened, is not a regular file, or does not parse, included), 1 for failures
    /// that are not the input's fault (reading an opened file, writing, plotting).
    pub fn exit_code(&self) -> i32 {
        match self {
            Error::Io { .. } | Error::Write { .. } | Error::Cancelled => 1,
            _ => 2,
        }
    }
}

/// The library's result type.
pub(crate) type Result<T> = std::result::Result<T, Error>;
