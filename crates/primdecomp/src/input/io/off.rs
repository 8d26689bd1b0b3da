//! OFF (Object File MeshFormat) reader.
//!
//! Reads the `OFF` keyword (the `COFF`, `NOFF`, `CNOFF`, `STOFF`, … variants too),
//! the `vertices faces [edges]` counts (on the keyword's line or the next one), one
//! vertex per line (`x y z`, extra values such as colours or normals ignored) and one
//! face per line (`n i0 … i(n-1)`, extra colour values ignored). `#` starts a comment;
//! blank lines are skipped. Counts that promise more lines than the file has, and
//! indices outside the vertex list, are errors naming the line.

use super::text::{parse_f64, parse_i64, show, strip_comment, tokens, Lines};
use crate::error::{Error, Result};
use crate::input::mesh::MeshBuilder;
use std::path::Path;

/// Parses an ASCII OFF file into positions and polygons.
pub fn parse_off(bytes: &[u8], path: &Path) -> Result<MeshBuilder> {
    let mut lines = Content {
        lines: Lines::new(bytes),
        last: 0,
    };
    let mut out = MeshBuilder::new();
    let Some((nv, nf)) = read_counts(&mut lines, path)? else {
        return Ok(out);
    };
    let cap = bytes.len() / 4;
    out.positions.reserve(nv.min(cap));
    out.face_offsets.reserve(nf.min(cap));
    for i in 0..nv {
        let (no, line) =
            lines.next_or(path, || format!("the file ends after {i} of {nv} vertices"))?;
        out.positions.push(vertex(line, path, no)?);
    }
    let mut corners = Vec::new();
    for i in 0..nf {
        let (no, line) =
            lines.next_or(path, || format!("the file ends after {i} of {nf} faces"))?;
        face(line, nv, &mut corners).map_err(|m| Error::line(path, no, m))?;
        out.push_face(&corners);
    }
    Ok(out)
}

/// Declared vertex and face counts of an OFF header (for the memory check before
/// parsing); `None` if the header does not parse.
pub(crate) fn declared_counts(bytes: &[u8]) -> Option<(u64, u64)> {
    let mut lines = Content {
        lines: Lines::new(bytes),
        last: 0,
    };
    let (v, f) = read_counts(&mut lines, Path::new("")).ok()??;
    Some((v as u64, f as u64))
}

/// Non-blank lines with comments removed; remembers the last line number for errors.
struct Content<'a> {
    lines: Lines<'a>,
    last: u64,
}

impl<'a> Content<'a> {
    fn next(&mut self) -> Option<(u64, &'a [u8])> {
        for (no, raw) in self.lines.by_ref() {
            self.last = no;
            let line = strip_comment(raw);
            if !line.trim_ascii().is_empty() {
                return Some((no, line));
            }
        }
        None
    }
    fn next_or(&mut self, path: &Path, msg: impl Fn() -> String) -> Result<(u64, &'a [u8])> {
        self.next()
            .ok_or_else(|| Error::line(path, self.last, msg()))
    }
}

/// Reads the header keyword and the vertex and face counts; `None` for a file with
/// no content at all.
fn read_counts(lines: &mut Content, path: &Path) -> Result<Option<(usize, usize)>> {
    let Some((no, first)) = lines.next() else {
        return Ok(None);
    };
    let mut t = tokens(first).peekable();
    if let Some(kw) = t.next_if(|k| parse_i64(k).is_none()) {
        check_keyword(kw, path, no)?;
        if t.next_if(|k| k.eq_ignore_ascii_case(b"BINARY")).is_some() {
            return Err(Error::line(
                path,
                no,
                "binary OFF is not supported; convert it to ASCII OFF",
            ));
        }
    }
    let mut nums: Vec<&[u8]> = t.collect();
    let mut count_line = no;
    if nums.is_empty() {
        let (no, line) = lines.next_or(path, || "the file has no vertex and face counts".into())?;
        nums = tokens(line).collect();
        count_line = no;
    }
    let count = |k: usize, what: &str| -> Result<usize> {
        let tok = nums.get(k).copied().unwrap_or(b"");
        parse_i64(tok)
            .and_then(|n| usize::try_from(n).ok())
            .ok_or_else(|| {
                let msg = format!(
                    "the {what} count '{}' is not a non-negative integer",
                    show(tok)
                );
                Error::line(path, count_line, msg)
            })
    };
    let (nv, nf) = (count(0, "vertex")?, count(1, "face")?);
    if nv > u32::MAX as usize {
        return Err(Error::line(
            path,
            count_line,
            format!("{nv} vertices is more than u32 indices allow"),
        ));
    }
    Ok(Some((nv, nf)))
}

/// Accepts `OFF` with the optional `ST`, `C`, `N` prefixes; rejects `4OFF`/`nOFF`.
fn check_keyword(kw: &[u8], path: &Path, no: u64) -> Result<()> {
    let upper = kw.to_ascii_uppercase();
    let Some(prefix) = upper.strip_suffix(b"OFF") else {
        let msg = format!("not an OFF file: expected 'OFF', found '{}'", show(kw));
        return Err(Error::line(path, no, msg));
    };
    let original = &kw[..prefix.len()];
    if original.contains(&b'4') || original.contains(&b'n') {
        let msg = format!("'{}' (not 3D) OFF files are not supported", show(kw));
        return Err(Error::line(path, no, msg));
    }
    if !prefix.iter().all(|c| b"STCN".contains(c)) {
        let msg = format!("unknown OFF variant '{}'", show(kw));
        return Err(Error::line(path, no, msg));
    }
    Ok(())
}

fn vertex(line: &[u8], path: &Path, no: u64) -> Result<[f64; 3]> {
    let mut t = tokens(line);
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
            Some(_) => {
                let msg = format!("vertex coordinate '{}' is not finite", show(tok));
                return Err(Error::line(path, no, msg));
            }
            None => {
                let msg = format!("vertex coordinate '{}' is not a number", show(tok));
                return Err(Error::line(path, no, msg));
            }
        };
    }
    Ok(p)
}

/// Reads `n i0 … i(n-1)` into `corners`, checking every index against `nv`.
fn face(line: &[u8], nv: usize, corners: &mut Vec<u32>) -> std::result::Result<(), String> {
    corners.clear();
    let mut t = tokens(line);
    let first = t.next().unwrap_or(b"");
    let n = parse_i64(first)
        .and_then(|n| usize::try_from(n).ok())
        .ok_or_else(|| format!("face size '{}' is not a non-negative integer", show(first)))?;
    for k in 0..n {
        let tok = t
            .next()
            .ok_or_else(|| format!("face declares {n} vertices but lists {k}"))?;
        let i = parse_i64(tok)
            .ok_or_else(|| format!("face index '{}' is not an integer", show(tok)))?;
        if i < 0 || i as u64 >= nv as u64 {
            return Err(format!(
                "face index {i} is out of range (file has {nv} vertices)"
            ));
        }
        corners.push(i as u32);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(s: &str) -> Result<MeshBuilder> {
        parse_off(s.as_bytes(), Path::new("t.off"))
    }

    fn err(s: &str) -> String {
        parse(s).unwrap_err().to_string()
    }

    const QUAD: &str =
        "OFF\n# comment\n4 2 0\n0 0 0\n1 0 0\n1 1 0 # c\n\n0 1 0\n4 0 1 2 3\n3 0 1 2 255 0 0\n";

    #[test]
    fn basic_with_comments_and_colours() {
        let b = parse(QUAD).unwrap();
        assert_eq!(b.positions.len(), 4);
        assert_eq!(b.face_indices, vec![0, 1, 2, 3, 0, 1, 2]);
        assert_eq!(b.face_count(), 2);
    }

    #[test]
    fn variants_and_same_line_counts() {
        let b =
            parse("COFF 3 1 0\n0 0 0 1 0 0 1\n1 0 0 1 0 0 1\n0 1 0 1 0 0 1\n3 0 1 2\n").unwrap();
        assert_eq!(b.face_count(), 1);
        let b = parse("NOFF\r\n3 1 3\r\n0 0 0 0 0 1\r\n1 0 0 0 0 1\r\n0 1 0 0 0 1\r\n3 2 1 0\r\n")
            .unwrap();
        assert_eq!(b.face_indices, vec![2, 1, 0]);
        assert!(err("4OFF\n1 0 0\n0 0 0 0\n").contains("not supported"));
        assert!(err("OFF BINARY\n").contains("binary OFF"));
        assert!(err("PLY\n").contains("not an OFF file"));
    }

    #[test]
    fn lying_counts_and_bad_indices() {
        let e = err(&QUAD.replace("4 2 0", "5 2 0"));
        assert!(
            e.contains("t.off:10:") && e.contains("ends after 1 of 2 faces"),
            "{e}"
        );
        let e = err(&QUAD.replace("4 2 0", "4 3 0"));
        assert!(e.contains("t.off:10:") && e.contains("2 of 3 faces"), "{e}");
        let e = err(&QUAD.replace("4 0 1 2 3", "4 0 1 2 4"));
        assert!(
            e.contains("t.off:9:")
                && e.contains("face index 4 is out of range (file has 4 vertices)"),
            "{e}"
        );
        let e = err(&QUAD.replace("4 0 1 2 3", "5 0 1 2 3"));
        assert!(e.contains("t.off:9:") && e.contains("declares 5"), "{e}");
        let e = err(&QUAD.replace("1 0 0\n", "1 nan 0\n"));
        assert!(e.contains("t.off:5:") && e.contains("not finite"), "{e}");
        let e = err("OFF\n-1 2 0\n");
        assert!(e.contains("t.off:2:"), "{e}");
    }

    #[test]
    fn empty_and_short() {
        assert_eq!(parse("").unwrap().face_count(), 0);
        assert_eq!(parse("# nothing\n").unwrap().face_count(), 0);
        assert_eq!(
            parse("OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n")
                .unwrap()
                .face_count(),
            0
        );
        let b = parse("OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n3 0 1 2\n").unwrap();
        assert_eq!((b.face_count(), b.skipped.short_faces), (1, 1));
        for n in 0..QUAD.len() {
            let _ = parse(&QUAD[..n]);
        }
        let _ = parse_off(b"OFF\n\xff\xff 1 0\n", Path::new("t.off"));
    }
}
