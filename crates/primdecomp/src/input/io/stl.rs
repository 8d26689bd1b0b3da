//! STL reader, binary and ASCII.
//!
//! Binary vs ASCII is decided by content, not by the leading `solid` (many binary
//! files start their 80-byte header with it): a file whose length is exactly
//! `84 + 50 * count` is binary; otherwise a file starting with `solid` followed by
//! text is ASCII; anything else is read as binary, and a count that needs more bytes
//! than the file has is an error at the offset of the first incomplete triangle.
//! Every facet adds its own vertices (no welding here; duplicates are merged later).
//! ASCII loops with more than three vertices are kept as polygons.

use super::text::{parse_f64, show, tokens, Lines};
use crate::error::{Error, Result};
use crate::input::mesh::MeshBuilder;
use std::path::Path;

const HEADER: usize = 84;
const RECORD: usize = 50;

/// Parses a binary or ASCII STL file.
pub fn parse_stl(bytes: &[u8], path: &Path) -> Result<MeshBuilder> {
    if bytes.trim_ascii().is_empty() {
        return Ok(MeshBuilder::new());
    }
    if binary_size_matches(bytes) || !looks_ascii(bytes) {
        parse_binary(bytes, path)
    } else {
        parse_ascii(bytes, path)
    }
}

/// The declared triangle count of a binary file (bytes 80..84), if the file has it.
fn declared_count(bytes: &[u8]) -> Option<u32> {
    let c = bytes.get(80..HEADER)?.first_chunk::<4>()?;
    Some(u32::from_le_bytes(*c))
}

fn binary_size_matches(bytes: &[u8]) -> bool {
    declared_count(bytes)
        .is_some_and(|n| (HEADER as u64) + (RECORD as u64) * u64::from(n) == bytes.len() as u64)
}

/// Starts with `solid` and the first kilobyte is text (no control bytes).
fn looks_ascii(bytes: &[u8]) -> bool {
    let head = &bytes[..bytes.len().min(1024)];
    let text = head
        .iter()
        .all(|&b| b.is_ascii_graphic() || b.is_ascii_whitespace() || b >= 0x80);
    let start = head.trim_ascii_start();
    text && start.len() >= 5 && start[..5].eq_ignore_ascii_case(b"solid")
}

fn parse_binary(bytes: &[u8], path: &Path) -> Result<MeshBuilder> {
    let Some(count) = declared_count(bytes) else {
        let msg = format!(
            "{} bytes is too short for a binary STL (84-byte header) and it is not ASCII STL",
            bytes.len()
        );
        return Err(Error::byte(path, 0, msg));
    };
    let count = count as usize;
    let complete = (bytes.len() - HEADER) / RECORD;
    if count > complete {
        let offset = (HEADER + complete * RECORD) as u64;
        let msg = format!(
            "the header declares {count} triangles ({} bytes) but the file has {} bytes: \
             triangle {complete} is incomplete (truncated file or wrong count)",
            HEADER as u64 + RECORD as u64 * count as u64,
            bytes.len()
        );
        return Err(Error::byte(path, offset, msg));
    }
    let mut out = MeshBuilder::new();
    out.positions.reserve(3 * count);
    out.face_offsets.reserve(count);
    out.face_indices.reserve(3 * count);
    for (t, rec) in bytes[HEADER..].chunks_exact(RECORD).take(count).enumerate() {
        let base = out.positions.len() as u32;
        for v in 0..3 {
            let at = 12 + 12 * v;
            let p = [f32_at(rec, at), f32_at(rec, at + 4), f32_at(rec, at + 8)];
            if !p.iter().all(|c| c.is_finite()) {
                let offset = (HEADER + t * RECORD + at) as u64;
                let msg = format!("triangle {t} has a non-finite vertex {p:?}");
                return Err(Error::byte(path, offset, msg));
            }
            out.positions.push(p);
        }
        out.push_face(&[base, base + 1, base + 2]);
    }
    Ok(out)
}

/// The little-endian f32 at `at` (callers pass offsets inside a 50-byte record).
fn f32_at(rec: &[u8], at: usize) -> f64 {
    let b = rec.get(at..).and_then(|r| r.first_chunk::<4>());
    b.map_or(f64::NAN, |b| f64::from(f32::from_le_bytes(*b)))
}

/// Where the ASCII reader is in the `facet … endfacet` structure.
#[derive(Clone, Copy, PartialEq, Eq)]
enum State {
    Outside,
    InFacet,
    InLoop,
}

/// The ASCII STL keywords that start a line.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Kw {
    Solid,
    EndSolid,
    Facet,
    Outer,
    Vertex,
    EndLoop,
    EndFacet,
}

/// The keyword `tok` spells, ignoring ASCII case.
fn keyword(tok: &[u8]) -> Option<Kw> {
    const KWS: [(&[u8], Kw); 7] = [
        (b"solid", Kw::Solid),
        (b"endsolid", Kw::EndSolid),
        (b"facet", Kw::Facet),
        (b"outer", Kw::Outer),
        (b"vertex", Kw::Vertex),
        (b"endloop", Kw::EndLoop),
        (b"endfacet", Kw::EndFacet),
    ];
    KWS.iter()
        .find(|(name, _)| name.eq_ignore_ascii_case(tok))
        .map(|&(_, kw)| kw)
}

fn parse_ascii(bytes: &[u8], path: &Path) -> Result<MeshBuilder> {
    let mut out = MeshBuilder::new();
    let mut corners: Vec<u32> = Vec::new();
    let mut state = State::Outside;
    let mut last = 0;
    for (no, line) in Lines::new(bytes) {
        last = no;
        let mut t = tokens(line);
        let Some(key) = t.next() else { continue };
        let next = match (keyword(key), state) {
            (Some(Kw::Solid | Kw::EndSolid), State::Outside) => State::Outside,
            (Some(Kw::Facet), State::Outside) => State::InFacet,
            (Some(Kw::Outer), State::InFacet) => {
                corners.clear();
                State::InLoop
            }
            (Some(Kw::Vertex), State::InLoop) => {
                corners.push(ascii_vertex(t, &mut out, path, no)?);
                State::InLoop
            }
            (Some(Kw::EndLoop), State::InLoop) => {
                out.push_face(&corners);
                State::InFacet
            }
            (Some(Kw::EndFacet), State::InFacet) => State::Outside,
            _ => {
                let msg = format!("unexpected '{}' in ASCII STL", show(key));
                return Err(Error::line(path, no, msg));
            }
        };
        state = next;
    }
    if state != State::Outside {
        return Err(Error::line(path, last, "the file ends inside a facet"));
    }
    Ok(out)
}

/// Reads `x y z` after `vertex`, appends the position and returns its index.
fn ascii_vertex<'a>(
    mut t: impl Iterator<Item = &'a [u8]>,
    out: &mut MeshBuilder,
    path: &Path,
    no: u64,
) -> Result<u32> {
    let mut p = [0.0f64; 3];
    for (k, slot) in p.iter_mut().enumerate() {
        let tok = t.next().ok_or_else(|| {
            Error::line(
                path,
                no,
                format!("vertex has {k} coordinates; x, y and z are needed"),
            )
        })?;
        *slot = match parse_f64(tok) {
            Some(x) if x.is_finite() => x,
            _ => {
                let msg = format!("vertex coordinate '{}' is not a finite number", show(tok));
                return Err(Error::line(path, no, msg));
            }
        };
    }
    if out.positions.len() >= u32::MAX as usize {
        return Err(Error::line(path, no, "more than 4294967295 vertices"));
    }
    out.positions.push(p);
    Ok((out.positions.len() - 1) as u32)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(s: &[u8]) -> Result<MeshBuilder> {
        parse_stl(s, Path::new("t.stl"))
    }

    fn binary(header: &[u8], count: u32, tris: usize) -> Vec<u8> {
        let mut v = header.to_vec();
        v.resize(80, b' ');
        v.extend_from_slice(&count.to_le_bytes());
        for t in 0..tris {
            v.extend_from_slice(&[0u8; 12]);
            for k in 0..9 {
                v.extend_from_slice(&((t * 9 + k) as f32).to_le_bytes());
            }
            v.extend_from_slice(&[0, 0]);
        }
        v
    }

    const ASCII: &[u8] = b"solid cube\n  facet normal 0 0 1\n    outer loop\n      vertex 0 0 0\n      vertex 1 0 0\n      vertex 1 1 0\n    endloop\n  endfacet\n  facet normal 0 0 1\n    outer loop\n      vertex 0 0 0\n      vertex 1 1 0\n      vertex 0 1 0e0\n    endloop\n  endfacet\nendsolid cube\n";

    #[test]
    fn binary_with_solid_header() {
        let b = parse(&binary(b"solid but binary", 2, 2)).unwrap();
        assert_eq!(b.face_count(), 2);
        assert_eq!(b.positions.len(), 6);
        assert_eq!(b.positions[5], [15.0, 16.0, 17.0]);
        assert_eq!(b.face_indices, vec![0, 1, 2, 3, 4, 5]);
    }

    #[test]
    fn binary_lying_count_errors_with_offset() {
        let e = parse(&binary(b"x", 3, 2)).unwrap_err().to_string();
        assert!(
            e.contains("at byte 184:") && e.contains("declares 3"),
            "{e}"
        );
        let mut v = binary(b"solid x", 2, 2);
        v.truncate(150);
        let e = parse(&v).unwrap_err().to_string();
        assert!(e.contains("at byte 134:"), "{e}");
        let e = parse(b"\x00\x01\x02").unwrap_err().to_string();
        assert!(e.contains("too short"), "{e}");
    }

    #[test]
    fn binary_non_finite() {
        let mut v = binary(b"", 1, 1);
        v[84 + 12 + 4..84 + 12 + 8].copy_from_slice(&f32::NAN.to_le_bytes());
        let e = parse(&v).unwrap_err().to_string();
        assert!(e.contains("at byte 96:") && e.contains("triangle 0"), "{e}");
    }

    #[test]
    fn ascii_and_crlf() {
        let b = parse(ASCII).unwrap();
        assert_eq!(b.face_count(), 2);
        assert_eq!(b.positions.len(), 6);
        let crlf: Vec<u8> = String::from_utf8_lossy(ASCII)
            .replace('\n', "\r\n")
            .into_bytes();
        assert_eq!(parse(&crlf).unwrap().face_count(), 2);
        let upper = String::from_utf8_lossy(ASCII).to_uppercase().into_bytes();
        assert_eq!(parse(&upper).unwrap().face_count(), 2);
    }

    #[test]
    fn ascii_errors() {
        let s = String::from_utf8_lossy(ASCII);
        let e = parse(
            s.replace("1 1 0\n    endloop", "1 x 0\n    endloop")
                .as_bytes(),
        )
        .unwrap_err();
        assert!(e.to_string().contains("t.stl:6:"), "{e}");
        let cut = s.find("    endloop").unwrap();
        let e = parse(&ASCII[..cut]).unwrap_err().to_string();
        assert!(e.contains("ends inside a facet"), "{e}");
        let e = parse(s.replace("outer loop", "outer lop\nbogus").as_bytes()).unwrap_err();
        assert!(
            e.to_string().contains("t.stl:4:") && e.to_string().contains("'bogus'"),
            "{e}"
        );
    }

    #[test]
    fn empty_and_headers_only() {
        assert_eq!(parse(b"").unwrap().face_count(), 0);
        assert_eq!(parse(b"solid x\nendsolid x\n").unwrap().face_count(), 0);
        assert_eq!(parse(&binary(b"", 0, 0)).unwrap().face_count(), 0);
        for n in 0..ASCII.len() {
            let _ = parse(&ASCII[..n]);
        }
    }
}
