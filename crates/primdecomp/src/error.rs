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
        /// The file.
        path: PathBuf,
        /// What the operating system said.
        #[source]
        source: std::io::Error,
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
         max_memory of primdecomp::load_limited)",
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
    /// An output file could not be written.
    #[error("{path}: cannot write: {source}")]
    Write {
        /// The file.
        path: PathBuf,
        /// What the operating system said.
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
            Error::Io { .. } | Error::Write { .. } | Error::Cancelled => 1,
            _ => 2,
        }
    }
}

/// The library's result type.
pub type Result<T> = std::result::Result<T, Error>;

/// Bytes for a message: `1.5 GiB`, `300 MiB`, `12 KiB`.
pub(crate) fn show_bytes(b: u64) -> String {
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
