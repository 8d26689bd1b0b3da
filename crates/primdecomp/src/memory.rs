//! Memory limit (issue 6, "Limits"): an input whose decomposition would need more memory
//! than allowed is refused up front with [`Error::TooLarge`], instead of being killed by
//! the operating system halfway through a batch.
//!
//! The need is a linear model of the input's vertex, face and corner counts, fitted on
//! the peak resident memory of CLI runs (see [`estimate`]). The counts come from the
//! file before parsing ([`declared_counts`]: header counts for PLY, OFF and binary
//! STL, a byte scan for OBJ and ASCII STL, each capped by what the file's size could
//! hold) and again, exactly, from the parsed mesh (which also covers glTF, whose counts
//! live in its JSON). The parsers themselves cap every reservation by the file size.

use crate::error::{Error, Result};
use crate::mesh::io::{text, Format};
use std::path::Path;

/// Vertex, face and corner (index) counts of an input.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Counts {
    pub vertices: u64,
    pub faces: u64,
    pub corners: u64,
}

/// Fixed cost of a run (binary, thread stacks, allocator arenas), bytes.
const BASE: u64 = 32 << 20;
/// Bytes per vertex, face and corner. Fitted on the peak resident memory of
/// `primdecomp decompose FILE -n 1% --max-memory none` under `/usr/bin/time -v`:
/// lucy_100k.obj (99,970 faces, 49,987 vertices) 64.8 MB and dragon_vrip_res2.ply
/// (202,520 faces, 100,250 vertices) 97.5 MB, i.e. 32 MB + 320 bytes per triangle.
/// Two triangle meshes cannot separate the three rates; the split below gives that
/// slope for triangles (½ vertex + 1 face + 3 corners per triangle) and charges
/// polygons by their corners.
const PER_VERTEX: u64 = 100;
const PER_FACE: u64 = 150;
const PER_CORNER: u64 = 40;

/// Peak bytes a run on an input of these counts is expected to need: the fitted model
/// above plus 25% for what it does not capture (more targets, more threads).
pub fn estimate(c: Counts) -> u64 {
    let linear = BASE
        .saturating_add(PER_VERTEX.saturating_mul(c.vertices))
        .saturating_add(PER_FACE.saturating_mul(c.faces))
        .saturating_add(PER_CORNER.saturating_mul(c.corners));
    linear.saturating_add(linear / 4)
}

/// `MemAvailable` from `/proc/meminfo`, in bytes; `None` where it cannot be read.
pub fn available() -> Option<u64> {
    let info = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = info.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    kib.checked_mul(1024)
}

/// Refuses `counts` when their estimate exceeds `limit` bytes.
pub fn check(path: &Path, counts: Counts, limit: u64) -> Result<()> {
    let needed = estimate(counts);
    if needed <= limit {
        return Ok(());
    }
    Err(Error::TooLarge {
        path: path.to_path_buf(),
        faces: counts.faces,
        vertices: counts.vertices,
        needed,
        limit,
    })
}

/// Counts an input claims, read without allocating: `None` for glTF/GLB (its counts
/// live in the JSON; the parsed mesh is checked instead) and for files whose header
/// does not parse (the parser reports those). Each count is capped by the most the
/// file's size could hold, so a lying header gets the parser's precise error.
pub fn declared_counts(bytes: &[u8], format: Format) -> Option<Counts> {
    let len = bytes.len() as u64;
    let c = match format {
        Format::Obj => obj_counts(bytes),
        Format::Stl => stl_counts(bytes),
        Format::Ply => {
            let (v, f) = crate::mesh::io::ply_declared(bytes)?;
            // Smallest records: 3 one-byte coordinates; a count byte and 3 one-byte indices.
            Counts {
                vertices: v.min(len / 3),
                faces: f.min(len / 4),
                corners: 3 * f.min(len / 4),
            }
        }
        Format::Off => {
            let (v, f) = crate::mesh::io::off_declared(bytes)?;
            // Smallest lines: "0 0 0\n" and "3 0 0 0\n".
            Counts {
                vertices: v.min(len / 6),
                faces: f.min(len / 8),
                corners: 3 * f.min(len / 8),
            }
        }
        Format::Gltf | Format::Glb => return None,
    };
    Some(c)
}

/// `v` and `f` statements and the corners of the `f` lines.
fn obj_counts(bytes: &[u8]) -> Counts {
    let mut c = Counts::default();
    for (_, line) in text::Lines::new(bytes) {
        let mut t = text::tokens(line);
        match t.next() {
            Some(b"v") => c.vertices += 1,
            Some(b"f") => {
                c.faces += 1;
                c.corners += t.count() as u64;
            }
            _ => {}
        }
    }
    c
}

/// Binary: the declared count, capped by the file's size; ASCII: `vertex` lines.
fn stl_counts(bytes: &[u8]) -> Counts {
    let head = bytes.get(80..84).and_then(|b| b.first_chunk::<4>());
    let declared = head.map(|b| u64::from(u32::from_le_bytes(*b)));
    let binary = !bytes.trim_ascii_start().starts_with(b"solid")
        || declared.is_some_and(|n| 84 + 50 * n == bytes.len() as u64);
    if binary {
        let tris = declared
            .unwrap_or(0)
            .min((bytes.len() as u64).saturating_sub(84) / 50);
        return Counts {
            vertices: 3 * tris,
            faces: tris,
            corners: 3 * tris,
        };
    }
    let corners = text::Lines::new(bytes)
        .filter(|(_, l)| text::tokens(l).next() == Some(b"vertex"))
        .count() as u64;
    Counts {
        vertices: corners,
        faces: corners / 3,
        corners,
    }
}

/// A size such as `512M`, `8G`, `1.5T` or `1048576` (bytes; K, M, G, T are powers of
/// 1024, an optional trailing `B` or `iB` is accepted).
pub fn parse_size(s: &str) -> Option<u64> {
    let t = s.trim().to_ascii_uppercase();
    let t = t.trim_end_matches("IB").trim_end_matches('B');
    let (num, shift) = match t.chars().last()? {
        'K' => (&t[..t.len() - 1], 10),
        'M' => (&t[..t.len() - 1], 20),
        'G' => (&t[..t.len() - 1], 30),
        'T' => (&t[..t.len() - 1], 40),
        _ => (t, 0),
    };
    let v: f64 = num.trim().parse().ok()?;
    let bytes = v * (1u64 << shift) as f64;
    (v.is_finite() && v >= 0.0 && bytes < u64::MAX as f64).then_some(bytes as u64)
}

/// Bytes for a message: `1.5 GiB`, `300 MiB`, `12 KiB`.
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
    fn sizes() {
        assert_eq!(parse_size("1048576"), Some(1 << 20));
        assert_eq!(parse_size("512M"), Some(512 << 20));
        assert_eq!(parse_size("8g"), Some(8 << 30));
        assert_eq!(parse_size("1.5GiB"), Some(3 << 29));
        assert_eq!(parse_size("2KB"), Some(2048));
        assert_eq!(parse_size("-1G"), None);
        assert_eq!(parse_size("lots"), None);
        assert_eq!(show_bytes(3 << 29), "1.5 GiB");
        assert_eq!(show_bytes(300 << 20), "300 MiB");
        assert_eq!(show_bytes(12), "12 bytes");
    }

    #[test]
    fn counts_before_parsing() {
        let obj = b"v 0 0 0\nv 1 0 0\r\nv 0 1 0\nvt 0 0\nf 1 2 3\nf 1/1 2/1 3/1 1\n";
        let want = Counts {
            vertices: 3,
            faces: 2,
            corners: 7,
        };
        assert_eq!(declared_counts(obj, Format::Obj), Some(want));
        // A PLY header claiming 4e9 vertices in a 200-byte file is capped by the size.
        let ply = b"ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\nproperty float y\nproperty float z\nelement face 7\nproperty list uchar int vertex_indices\nend_header\n";
        let c = declared_counts(ply, Format::Ply).unwrap();
        assert_eq!((c.vertices, c.faces), (ply.len() as u64 / 3, 7));
        let off = b"OFF\n# c\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
        let c = declared_counts(off, Format::Off).unwrap();
        assert_eq!((c.vertices, c.faces, c.corners), (3, 1, 3));
        let mut stl = vec![0u8; 84 + 100];
        stl[80] = 200; // declares 200 triangles, holds 2
        let c = declared_counts(&stl, Format::Stl).unwrap();
        assert_eq!((c.faces, c.vertices), (2, 6));
        assert_eq!(declared_counts(b"{}", Format::Gltf), None);
    }

    #[test]
    fn check_refuses_above_the_limit() {
        let c = Counts {
            vertices: 1000,
            faces: 2000,
            corners: 6000,
        };
        assert!(check(Path::new("m.obj"), c, estimate(c)).is_ok());
        let e = check(Path::new("m.obj"), c, estimate(c) - 1).unwrap_err();
        assert!(matches!(e, Error::TooLarge { faces: 2000, .. }), "{e}");
        assert_eq!(e.exit_code(), 2);
    }
}
