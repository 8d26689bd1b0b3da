//! Wavefront OBJ reader.
//!
//! Reads `v` positions and `f` polygons (`v`, `v/vt`, `v//vn`, `v/vt/vn` corners,
//! absolute or negative relative indices). Polygons stay polygons. `l` lines and faces
//! with fewer than 3 corners are counted in [`SkipCounts::short_faces`]; every other
//! statement (`vt`, `vn`, `vp`, `s`, `usemtl`, `mtllib`, unknown ones) is ignored;
//! `o` and `g` name the objects the following faces belong to ([`Mesh::objects`]). Lines ending in `\` continue on the next line. The file is parsed as bytes,
//! so non-UTF-8 content never panics; `\n`, `\r\n` and `\r` line ends all work.
//!
//! [`SkipCounts::short_faces`]: crate::input::mesh::SkipCounts::short_faces
//! [`Mesh::objects`]: crate::input::mesh::Mesh::objects

use super::text::{parse_f64, parse_i64, show, strip_comment, tokens, Lines};
use crate::error::{Error, Result};
use crate::input::mesh::MeshBuilder;
use std::path::Path;

/// Parses an OBJ file into world-space positions and polygons.
pub fn parse_obj(bytes: &[u8], path: &Path) -> Result<MeshBuilder> {
    let mut st = ObjState {
        out: MeshBuilder::new(),
        corners: Vec::new(),
        path,
    };
    // A rough upper bound keeps the first growth steps cheap on big files.
    st.out.positions.reserve(bytes.len() / 64);
    for_each_statement(bytes, |line, no| st.statement(line, no))?;
    Ok(st.out)
}

/// Calls `f(statement, line number)` for each statement of an OBJ text: comments
/// stripped, and a line ending in `\` joined with the next (numbered by its first line).
pub(crate) fn for_each_statement(
    bytes: &[u8],
    mut f: impl FnMut(&[u8], u64) -> Result<()>,
) -> Result<()> {
    let mut joined: Vec<u8> = Vec::new();
    let mut joined_line = 0;
    for (no, raw) in Lines::new(bytes) {
        let line = strip_comment(raw);
        if let Some(body) = line.trim_ascii_end().strip_suffix(b"\\") {
            if joined.is_empty() {
                joined_line = no;
            }
            joined.extend_from_slice(body);
            joined.push(b' ');
            continue;
        }
        if joined.is_empty() {
            f(line, no)?;
        } else {
            joined.extend_from_slice(line);
            f(&joined, joined_line)?;
            joined.clear();
        }
    }
    if !joined.is_empty() {
        f(&joined, joined_line)?;
    }
    Ok(())
}

struct ObjState<'p> {
    out: MeshBuilder,
    /// Reused buffer for the corners of the current face.
    corners: Vec<u32>,
    path: &'p Path,
}

impl ObjState<'_> {
    fn statement(&mut self, line: &[u8], no: u64) -> Result<()> {
        let mut toks = tokens(line);
        match toks.next() {
            Some(b"v") => self.vertex(toks, no),
            Some(b"f") => self.face(toks, no),
            Some(b"l") => {
                self.out.skipped.short_faces += 1;
                Ok(())
            }
            Some(b"o" | b"g") => {
                let name: Vec<&[u8]> = toks.collect();
                let name = String::from_utf8_lossy(&name.join(&b' ')).into_owned();
                self.out.start_object(name);
                Ok(())
            }
            _ => Ok(()),
        }
    }

    fn vertex<'a>(&mut self, toks: impl Iterator<Item = &'a [u8]>, no: u64) -> Result<()> {
        let p = position(toks, self.path, no)?;
        if self.out.positions.len() >= u32::MAX as usize {
            return Err(Error::line(
                self.path,
                no,
                "more than 4294967295 vertices; this reader indexes vertices with u32",
            ));
        }
        self.out.positions.push(p);
        Ok(())
    }

    fn face<'a>(&mut self, toks: impl Iterator<Item = &'a [u8]>, no: u64) -> Result<()> {
        self.corners.clear();
        let n = self.out.positions.len();
        for tok in toks {
            let v = resolve_corner(tok, n).map_err(|msg| Error::line(self.path, no, msg))?;
            self.corners.push(v);
        }
        self.out.push_face(&self.corners);
        Ok(())
    }
}

/// The x, y and z of a `v` statement's tokens (a w or colour after them is ignored).
pub(crate) fn position<'a>(
    mut toks: impl Iterator<Item = &'a [u8]>,
    path: &Path,
    no: u64,
) -> Result<[f64; 3]> {
    let mut p = [0.0f64; 3];
    for (k, slot) in p.iter_mut().enumerate() {
        let tok = toks.next().ok_or_else(|| {
            Error::line(
                path,
                no,
                format!("vertex has {k} coordinates; x, y and z are needed"),
            )
        })?;
        *slot = coordinate(tok, path, no)?;
    }
    Ok(p)
}

/// One finite coordinate.
pub(crate) fn coordinate(tok: &[u8], path: &Path, no: u64) -> Result<f64> {
    match parse_f64(tok) {
        Some(x) if x.is_finite() => Ok(x),
        Some(_) => Err(Error::line(
            path,
            no,
            format!("vertex coordinate '{}' is not finite", show(tok)),
        )),
        None => Err(Error::line(
            path,
            no,
            format!("vertex coordinate '{}' is not a number", show(tok)),
        )),
    }
}

/// The 0-based vertex index of a face corner `v`, `v/vt`, `v//vn` or `v/vt/vn`, given
/// `n` vertices defined so far.
pub(crate) fn resolve_corner(tok: &[u8], n: usize) -> std::result::Result<u32, String> {
    let v = tok.split(|&b| b == b'/').next().unwrap_or(tok);
    let Some(i) = parse_i64(v) else {
        return Err(format!(
            "face corner '{}' has no valid vertex index",
            show(tok)
        ));
    };
    let n64 = n as i64;
    if i == 0 {
        return Err("face index 0 is invalid (OBJ indices start at 1)".to_string());
    }
    if i > 0 {
        if i > n64 {
            return Err(format!(
                "face index {i} is out of range (file has {n} vertices so far)"
            ));
        }
        return Ok((i - 1) as u32);
    }
    if i < -n64 {
        return Err(format!(
            "relative face index {i} is out of range (file has {n} vertices so far)"
        ));
    }
    Ok((n64 + i) as u32)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(s: &[u8]) -> Result<MeshBuilder> {
        parse_obj(s, Path::new("t.obj"))
    }

    fn faces(b: &MeshBuilder) -> Vec<Vec<u32>> {
        (0..b.face_count())
            .map(|f| {
                let r = b.face_offsets[f] as usize..b.face_offsets[f + 1] as usize;
                b.face_indices[r].to_vec()
            })
            .collect()
    }

    fn err(s: &[u8]) -> String {
        parse(s).unwrap_err().to_string()
    }

    const QUAD: &[u8] = b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";

    #[test]
    fn corner_forms_and_polygons() {
        let mut s = QUAD.to_vec();
        s.extend_from_slice(b"vt 0 0\nvn 0 0 1\nf 1 2 3\nf 1/1 2/1 3/1 4/1\n");
        s.extend_from_slice(b"f 1//1 2//1 3//1\nf 1/1/1 2/1/1 3/1/1 4/1/1\nf 1 2 3 4 1 2\n");
        let b = parse(&s).unwrap();
        assert_eq!(b.positions.len(), 4);
        let f = faces(&b);
        assert_eq!(f[0], vec![0, 1, 2]);
        assert_eq!(f[1], vec![0, 1, 2, 3]);
        assert_eq!(f[2], vec![0, 1, 2]);
        assert_eq!(f[3], vec![0, 1, 2, 3]);
        assert_eq!(f[4].len(), 6);
    }

    #[test]
    fn negative_indices_and_groups() {
        let s = b"o a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\ng b\nv 5 5 5\nf 1 -1 -2\n";
        let b = parse(s).unwrap();
        assert_eq!(faces(&b), vec![vec![0, 1, 2], vec![0, 3, 2]]);
    }

    #[test]
    fn w_and_colors_ignored_and_values_kept() {
        let b = parse(b"v 1 2 3 1.0\nv 4 5 6 0.5 0.2 0.1\nv 1e38 -1e-38 7\nf 1 2 3\n").unwrap();
        assert_eq!(b.positions[0], [1.0, 2.0, 3.0]);
        assert_eq!(b.positions[1], [4.0, 5.0, 6.0]);
        assert_eq!(b.positions[2][0], 1e38);
    }

    #[test]
    fn lines_and_short_faces_counted() {
        let mut s = QUAD.to_vec();
        s.extend_from_slice(b"l 1 2\nl 1 2 3\nf 1 2\nf 3\nf\nf 1 2 3\n");
        let b = parse(&s).unwrap();
        assert_eq!(b.face_count(), 1);
        assert_eq!(b.skipped.short_faces, 5);
    }

    #[test]
    fn repeated_indices_kept() {
        let b = parse(b"v 0 0 0\nv 1 0 0\nf 1 2 2\n").unwrap();
        assert_eq!(faces(&b), vec![vec![0, 1, 1]]);
    }

    #[test]
    fn ignored_statements_and_comments() {
        let s = b"# hi\nmtllib a.mtl\nusemtl m\ns off\nvp 0.1\nfoo bar\nv 0 0 0 # c\nv 1 0 0\nv 0 1 0\nf 1 2 3 # tri\n";
        let b = parse(s).unwrap();
        assert_eq!(b.face_count(), 1);
    }

    #[test]
    fn line_endings_and_continuation() {
        let s = b"v 0 0 0\r\nv 1 0 0\rv 0 1 0\nv 0 0 1\r\nf 1 2 \\\r\n 3 4\n";
        let mut bad = s.to_vec();
        bad.extend_from_slice(b"f 1 2 k\x80\n");
        let e = err(&bad);
        assert!(e.contains("t.obj:7:") && e.contains("'k\u{fffd}'"), "{e}");
        let b = parse(s).unwrap();
        assert_eq!(faces(&b), vec![vec![0, 1, 2, 3]]);
    }

    #[test]
    fn bad_indices_name_line_and_index() {
        let e = err(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n");
        assert!(e.contains(":4:") && e.contains("index 0"), "{e}");
        let e = err(b"v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 9\n");
        assert!(
            e.contains(":5:")
                && e.contains("face index 9 is out of range (file has 3 vertices so far)"),
            "{e}"
        );
        let e = err(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n");
        assert!(e.contains(":4:") && e.contains("-4"), "{e}");
        let e = err(b"f 1 2 3\nv 0 0 0\n");
        assert!(e.contains(":1:") && e.contains("0 vertices"), "{e}");
        let e = err(b"v 0 0 0\nf 1 x 1\n");
        assert!(e.contains(":2:") && e.contains("'x'"), "{e}");
        let e = err(b"v 0 0 0\nf 1 99999999999999999999999 1\n");
        assert!(e.contains(":2:"), "{e}");
    }

    #[test]
    fn bad_coordinates() {
        for s in [&b"v 0 nan 0\n"[..], b"v inf 0 0\n", b"v 1e400 0 0\n"] {
            let e = err(s);
            assert!(e.contains(":1:") && e.contains("not finite"), "{e}");
        }
        let e = err(b"\nv 0 0\n");
        assert!(e.contains(":2:") && e.contains("2 coordinates"), "{e}");
        let e = err(b"v 0 abc 0\n");
        assert!(e.contains("'abc'"), "{e}");
    }

    #[test]
    fn empty_inputs() {
        for s in [
            &b""[..],
            b"# only a comment\n",
            b"v 0 0 0\nv 1 1 1\n",
            b"\xff\xfe\x00\n\\",
        ] {
            assert_eq!(parse(s).unwrap().face_count(), 0);
        }
    }

    #[test]
    fn huge_polygon() {
        let n = 100_000;
        let mut s = Vec::new();
        for i in 0..n {
            s.extend_from_slice(format!("v {i} {} 0\n", i % 7).as_bytes());
        }
        s.push(b'f');
        for i in 1..=n {
            s.extend_from_slice(format!(" {i}").as_bytes());
        }
        let b = parse(&s).unwrap();
        assert_eq!(b.face_count(), 1);
        assert_eq!(b.face_indices.len(), n);
    }
}
