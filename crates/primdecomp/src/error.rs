//! The library's one error type. Every variant carries what a user needs to fix the
//! input: the file, and the line or byte offset where parsing stopped.

use std::path::PathBuf;

/// Everything that can go wrong in primdecomp. Kernels never return this; only I/O,
/// parsing, parameter validation and the driver do.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// The file could not be opened, mapped or read.
    #[error("{path}: cannot read: {source}")]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    /// A text format is malformed at a given 1-based line.
    #[error("{path}:{line}: {msg}")]
    ParseLine {
        path: PathBuf,
        line: u64,
        msg: String,
    },
    /// A binary format is malformed at a given byte offset.
    #[error("{path}: at byte {offset}: {msg}")]
    ParseByte {
        path: PathBuf,
        offset: u64,
        msg: String,
    },
    /// The file is not in a format we read (unknown extension, compressed data, a directory…).
    #[error("{path}: {msg}")]
    Format { path: PathBuf, msg: String },
    /// The input parsed but has no polygon face to decompose.
    #[error(
        "{path}: the mesh has no polygon faces (faces with fewer than 3 vertices are skipped)"
    )]
    EmptyMesh { path: PathBuf },
    /// A vertex lies so far from the others that volumes (cubes of lengths) and the
    /// eigen-solver's squared entries would overflow f64.
    #[error(
        "{path}: vertex {vertex} lies {distance:e} from the centre of the mesh's bounding box; \
         every vertex must lie within {limit:e} of it (rescale the mesh)"
    )]
    Extent {
        path: PathBuf,
        /// 1-based, in the order the file lists vertices.
        vertex: u64,
        distance: f64,
        limit: f64,
    },
    /// A vertex lies so far from the origin that the written cylinders and frustums
    /// could not keep their axes within f64's range of lengths (`mesh::MAX_POSITION`).
    #[error(
        "{path}: vertex {vertex} has a coordinate of {coordinate:e}; every coordinate must \
         lie within ±{limit:e} (move the mesh nearer the origin)"
    )]
    Position {
        path: PathBuf,
        /// 1-based, in the order the file lists vertices.
        vertex: u64,
        coordinate: f64,
        limit: f64,
    },
    /// Decomposing the input would need more memory than allowed (checked before
    /// parsing from the counts the file declares, and after parsing).
    #[error(
        "{path}: decomposing this mesh ({faces} faces, {vertices} vertices) needs about {}, \
         more than the memory limit of {} (default: the memory available now); raise the \
         limit with --max-memory SIZE, e.g. --max-memory 64G (in the library: the \
         max_memory of mesh::io::load_limited)",
        crate::memory::show_bytes(*needed),
        crate::memory::show_bytes(*limit)
    )]
    TooLarge {
        path: PathBuf,
        faces: u64,
        vertices: u64,
        needed: u64,
        limit: u64,
    },
    /// A setting is out of range or inconsistent.
    #[error("invalid setting: {0}")]
    InvalidParams(String),
    /// A plot could not be drawn (no usable font, drawing failed).
    #[error("{path}: cannot draw the plot: {msg}")]
    Plot { path: PathBuf, msg: String },
    /// An output file could not be written.
    #[error("{path}: cannot write: {source}")]
    Write {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
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
    /// Exit code the CLI uses: 2 for bad input or settings, 1 for anything else.
    pub fn exit_code(&self) -> i32 {
        match self {
            Error::Io { .. } | Error::Write { .. } | Error::Plot { .. } => 1,
            _ => 2,
        }
    }
}

pub type Result<T> = std::result::Result<T, Error>;
