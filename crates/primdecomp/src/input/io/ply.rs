//! PLY reader: ASCII, binary little-endian and binary big-endian.
//!
//! The header is parsed into elements and properties (`header`); the data section is read
//! by one generic loop over a [`Source`] (ASCII tokens or binary scalars). `x`, `y`,
//! `z` of the `vertex` element (any scalar type) become positions; the `vertex_indices`
//! (or `vertex_index`) list of the `face` element becomes polygons. Every other
//! property and element, lists included, is skipped exactly. Binary data is read in
//! place from the caller's (memory-mapped) slice, without per-element allocation.
//! Errors carry the 1-based line (ASCII) or byte offset (binary) where reading stopped.
//! Large ASCII data of one element a line is read by blocks of lines on every thread,
//! each line by the same loop; any irregular line sends the whole file to the serial
//! reader, so values and errors are the serial reader's.

use super::text::{parse_f64, parse_i64, show};
use crate::error::{Error, Result};
use crate::input::mesh::MeshBuilder;
use std::path::Path;

mod header;
use header::{parse_header, ElRole, Element, Encoding, Header, Kind, Role, Ty};

/// Parses a PLY file (any of the three encodings) into positions and polygons.
pub fn parse_ply(bytes: &[u8], path: &Path) -> Result<MeshBuilder> {
    if bytes.trim_ascii().is_empty() {
        return Ok(MeshBuilder::new());
    }
    let header = parse_header(bytes, path)?;
    let mut out = MeshBuilder::new();
    match header.enc {
        Encoding::Ascii => {
            let sizes = (BY_LINES_MIN, BY_LINES_BLOCK);
            if let Some(out) = ascii_by_lines(bytes, &header, path, sizes) {
                return Ok(out);
            }
            let mut src = Ascii {
                b: bytes,
                pos: header.data_start,
                line: header.data_line,
                tok_line: header.data_line,
                path,
            };
            read_body(&mut src, &header, &mut out)?;
        }
        Encoding::Le | Encoding::Be => {
            let mut src = Binary {
                b: bytes,
                pos: header.data_start,
                start: header.data_start,
                be: header.enc == Encoding::Be,
                path,
            };
            read_body(&mut src, &header, &mut out)?;
        }
    }
    Ok(out)
}

/// ASCII data of at least this many bytes is read by [`ascii_by_lines`] when rayon's
/// pool has two threads or more: the dragon's 33 MB took 0.12 s on one thread, the
/// whole of the load stage, while the other core idled.
const BY_LINES_MIN: usize = 1 << 20;
/// About this many bytes of ASCII data to a block of lines read as one task.
const BY_LINES_BLOCK: usize = 1 << 18;

/// ASCII data written one element to a line, as writers do, read in blocks of whole
/// lines (about `sizes.1` bytes each) in parallel: each line is read by the serial reader's own [`read_one`] on
/// that line alone, and the blocks' results are joined in order, so positions, faces
/// and counts are those [`read_body`] gives. `None` (read it serially, which also
/// finds and locates any error) when the data is shorter than `sizes.0` or the pool
/// has one thread, or unless every element is alone on its line: a line that fails
/// to read, holds tokens past its element or is missing (the data ends early).
fn ascii_by_lines(
    bytes: &[u8],
    h: &Header,
    path: &Path,
    (min_bytes, block): (usize, usize),
) -> Option<MeshBuilder> {
    use rayon::prelude::*;
    let body = bytes.get(h.data_start..)?;
    if body.len() < min_bytes || rayon::current_num_threads() < 2 {
        return None;
    }
    let els: Vec<&Element> = h.elements.iter().filter(|e| !e.props.is_empty()).collect();
    let first = first_lines(&els)?;
    let lines = *first.last()?;
    let (starts, ends) = line_blocks(body, block);
    let newlines: Vec<u64> = (starts.par_iter().zip(&ends))
        .map(|(&a, &b)| body[a..b].iter().filter(|&&c| c == b'\n').count() as u64)
        .collect();
    // The index of each block's first line.
    let block_first: Vec<u64> = newlines
        .iter()
        .scan(0u64, |n, &k| Some(std::mem::replace(n, *n + k)))
        .collect();
    let blocks: Vec<(MeshBuilder, u64)> = (starts.par_iter().zip(&ends).zip(&block_first))
        .map(|((&a, &b), &g)| lines_of(&body[a..b], g, (&els, &first), h.vertex_count, path))
        .collect::<Option<_>>()?;
    // Every element's line was read (the data did not end early).
    if blocks.iter().map(|b| b.1).sum::<u64>() != lines {
        return None;
    }
    Some(joined(blocks, &els))
}

/// The index of each element's first line, then the number of lines in all;
/// `None` if that overflows.
fn first_lines(els: &[&Element]) -> Option<Vec<u64>> {
    let mut first = Vec::with_capacity(els.len() + 1);
    let mut lines = 0u64;
    for el in els {
        first.push(lines);
        lines = lines.checked_add(el.count)?;
    }
    first.push(lines);
    Some(first)
}

/// Blocks of whole lines of about `block` bytes, as (starts, ends): each block
/// but the last ends just after a newline.
fn line_blocks(body: &[u8], block: usize) -> (Vec<usize>, Vec<usize>) {
    let mut ends = Vec::new();
    let mut at = 0;
    while at < body.len() {
        let want = (at + block.max(1)).min(body.len());
        let end = body[want..]
            .iter()
            .position(|&c| c == b'\n')
            .map_or(body.len(), |i| want + i + 1);
        ends.push(end);
        at = end;
    }
    let starts = std::iter::once(0).chain(ends.iter().copied()).collect();
    (starts, ends)
}

/// The blocks' meshes joined in order, face offsets shifted past the faces before
/// them, and the strips' elements counted as skipped, as the serial reader does.
fn joined(blocks: Vec<(MeshBuilder, u64)>, els: &[&Element]) -> MeshBuilder {
    let mut out = MeshBuilder::new();
    for (b, _) in blocks {
        out.positions.extend(b.positions);
        let base = out.face_indices.len() as u32;
        let shifted = b.face_offsets[1..].iter().map(|&o| o.wrapping_add(base));
        out.face_offsets.extend(shifted);
        out.face_indices.extend(b.face_indices);
        out.skipped.short_faces += b.skipped.short_faces;
    }
    for el in els.iter().filter(|el| el.role == ElRole::Strips) {
        out.skipped.other += el.count;
    }
    out
}

/// The elements of `els` (each starting at its line in `first`) on the lines of
/// `block` (whole lines; the first is line `g` of the data), each line read alone,
/// and how many were read; `None` if a line fails to read or holds more tokens than
/// its element.
fn lines_of(
    block: &[u8],
    mut g: u64,
    (els, first): (&[&Element], &[u64]),
    vertex_count: u64,
    path: &Path,
) -> Option<(MeshBuilder, u64)> {
    let mut out = MeshBuilder::new();
    let mut corners = Vec::new();
    let mut e = first.partition_point(|&f| f <= g).saturating_sub(1);
    let mut read = 0;
    for line in block.split_inclusive(|&c| c == b'\n') {
        while e < els.len() && g >= first[e + 1] {
            e += 1;
        }
        if e == els.len() {
            break;
        }
        let mut src = Ascii {
            b: line,
            pos: 0,
            line: 0,
            tok_line: 0,
            path,
        };
        read_one(&mut src, els[e], vertex_count, &mut out, &mut corners).ok()?;
        if src.token().is_ok() {
            return None;
        }
        (g, read) = (g + 1, read + 1);
    }
    Some((out, read))
}

/// Declared vertex and face counts of a PLY header (for the memory check before
/// parsing); `None` if the header does not parse.
pub(crate) fn declared_counts(bytes: &[u8]) -> Option<(u64, u64)> {
    let h = parse_header(bytes, Path::new("")).ok()?;
    let count = |r: ElRole| {
        h.elements
            .iter()
            .filter(move |e| e.role == r)
            .map(|e| e.count)
    };
    Some((count(ElRole::Vertex).sum(), count(ElRole::Face).sum()))
}

/// Where a binary PLY keeps its vertices and faces, for reading them straight from the
/// (memory-mapped) file a tile at a time (`crate::tiles`): vertices by index, faces
/// by a scan. Only a layout whose vertex records have a fixed size and whose face
/// element follows elements of fixed size qualifies ([`PlyLayout::of`]).
#[derive(Debug)]
pub(crate) struct PlyLayout {
    be: bool,
    vertex_start: usize,
    vertex_stride: usize,
    /// Offset in a vertex record and type of x, y and z.
    coords: [(usize, Ty); 3],
    pub vertex_count: u64,
    face_start: usize,
    pub face_count: u64,
    face_props: Vec<Kind>,
    /// Which of `face_props` holds the indices.
    indices: usize,
}

impl PlyLayout {
    /// The layout of `bytes`' data, `Ok(None)` when it is ASCII, has no faces, or
    /// puts a list before its faces or in its vertices (then only a whole parse reads
    /// it); a header that does not parse is its usual error.
    pub(crate) fn of(bytes: &[u8], path: &Path) -> Result<Option<PlyLayout>> {
        let h = parse_header(bytes, path)?;
        if h.enc == Encoding::Ascii {
            return Ok(None);
        }
        let fixed = |el: &Element| -> Option<usize> {
            el.props.iter().try_fold(0usize, |n, p| match p.kind {
                Kind::Scalar(t) => n.checked_add(t.size()),
                Kind::List(..) => None,
            })
        };
        let (mut at, mut vertex) = (h.data_start as u64, None);
        for el in &h.elements {
            match el.role {
                ElRole::Face => {
                    let Some((vertex_start, vertex_stride, coords)) = vertex else {
                        return Ok(None);
                    };
                    let indices = el.props.iter().position(|p| p.role == Role::Indices);
                    let Ok(face_start) = usize::try_from(at) else {
                        return Ok(None);
                    };
                    return Ok(Some(PlyLayout {
                        be: h.enc == Encoding::Be,
                        vertex_start,
                        vertex_stride,
                        coords,
                        vertex_count: h.vertex_count,
                        face_start,
                        face_count: el.count,
                        face_props: el.props.iter().map(|p| p.kind).collect(),
                        indices: indices.unwrap_or(usize::MAX),
                    }));
                }
                _ if el.props.is_empty() => {}
                _ => {
                    let Some(size) = fixed(el) else {
                        return Ok(None);
                    };
                    if el.role == ElRole::Vertex {
                        let Ok(start) = usize::try_from(at) else {
                            return Ok(None);
                        };
                        vertex = Some((start, size, coord_offsets(el)));
                    }
                    at = at.saturating_add(el.count.saturating_mul(size as u64));
                }
            }
        }
        Ok(None)
    }
}

/// The offset in a record of element `el` (of fixed size) and the type of x, y and z.
fn coord_offsets(el: &Element) -> [(usize, Ty); 3] {
    let mut coords = [(0, Ty::F32); 3];
    let mut off = 0;
    for p in &el.props {
        if let (Role::Coord(k), Kind::Scalar(t)) = (p.role, p.kind) {
            coords[k] = (off, t);
        }
        off += match p.kind {
            Kind::Scalar(t) => t.size(),
            Kind::List(..) => 0,
        };
    }
    coords
}

impl PlyLayout {
    /// Checks that `bytes` hold every vertex record and that every vertex is finite,
    /// visiting each world position in order; the error is the whole parse's.
    pub(crate) fn vertices(
        &self,
        bytes: &[u8],
        path: &Path,
        mut visit: impl FnMut([f64; 3]),
    ) -> Result<()> {
        let n = self.vertex_count;
        let held =
            bytes.len().saturating_sub(self.vertex_start) as u64 / self.vertex_stride.max(1) as u64;
        if held < n {
            let at = self.vertex_start as u64 + held * self.vertex_stride as u64;
            return Err(Error::byte(
                path,
                at,
                format!(
                    "the data ends inside vertex {held} of {n} declared in the header \
                     (truncated file, or a wrong header count)"
                ),
            ));
        }
        for i in 0..n as usize {
            let p = self.pos(bytes, i);
            if !p.iter().all(|c| c.is_finite()) {
                let at = (self.vertex_start + i * self.vertex_stride) as u64;
                let msg = format!("vertex {i} of {n}: vertex coordinates {p:?} are not finite");
                return Err(Error::byte(path, at, msg));
            }
            visit(p);
        }
        Ok(())
    }

    /// Bytes of the vertex records.
    pub(crate) fn vertex_bytes(&self) -> u64 {
        self.vertex_count.saturating_mul(self.vertex_stride as u64)
    }

    /// Vertex `i`'s position (`i` below the count, `bytes` checked by
    /// [`PlyLayout::vertices`]).
    pub(crate) fn pos(&self, bytes: &[u8], i: usize) -> [f64; 3] {
        let rec = self.vertex_start + i * self.vertex_stride;
        self.coords.map(|(off, t)| {
            let mut src = Binary {
                b: bytes,
                pos: rec + off,
                start: rec + off,
                be: self.be,
                path: Path::new(""),
            };
            src.real(t).unwrap_or(f64::NAN)
        })
    }

    /// Visits every face's corners in file order (`visit` also gets the byte offset
    /// reached, to release what was read); a face past the data or an index out of
    /// range is the whole parse's error.
    pub(crate) fn faces(
        &self,
        bytes: &[u8],
        path: &Path,
        mut visit: impl FnMut(&[u32], usize),
    ) -> Result<()> {
        let mut src = Binary {
            b: bytes,
            pos: self.face_start,
            start: self.face_start,
            be: self.be,
            path,
        };
        let mut corners = Vec::new();
        let n = self.face_count;
        for i in 0..n {
            self.face(&mut src, &mut corners).map_err(|f| {
                src.error(match f {
                    Fail::Eof => format!(
                        "the data ends inside face {i} of {n} declared in the header \
                         (truncated file, or a wrong header count)"
                    ),
                    Fail::Bad(msg) => format!("face {i} of {n}: {msg}"),
                })
            })?;
            visit(&corners, src.pos);
        }
        Ok(())
    }

    fn face(&self, src: &mut Binary, corners: &mut Vec<u32>) -> Got<()> {
        for (k, kind) in self.face_props.iter().enumerate() {
            match *kind {
                Kind::Scalar(t) => src.skip(t, 1)?,
                Kind::List(ct, it) if k == self.indices => {
                    read_corners(src, ct, it, self.vertex_count, corners)?
                }
                Kind::List(ct, it) => {
                    let n = src.int(ct)?;
                    let n = u64::try_from(n)
                        .map_err(|_| Fail::Bad(format!("negative list count {n}")))?;
                    src.skip(it, n)?;
                }
            }
        }
        Ok(())
    }
}

/// Why reading a value failed: the data ended, or a value is invalid.
enum Fail {
    Eof,
    Bad(String),
}

/// A value read from the data section, or why it could not be.
type Got<T> = std::result::Result<T, Fail>;

/// The data section, as ASCII tokens or binary scalars.
trait Source {
    /// A value converted to f64 (coordinates).
    fn real(&mut self, t: Ty) -> Got<f64>;
    /// An integer value (list counts, indices); `t` is an integer type.
    fn int(&mut self, t: Ty) -> Got<i64>;
    /// Skips `n` values of type `t`.
    fn skip(&mut self, t: Ty, n: u64) -> Got<()>;
    /// Bytes left, for capping reservations.
    fn remaining(&self) -> usize;
    /// An error located at the value read last (or at the end of the data).
    fn error(&self, msg: String) -> Error;
}

fn read_body<S: Source>(src: &mut S, h: &Header, out: &mut MeshBuilder) -> Result<()> {
    let mut corners = Vec::new();
    // An element without properties has no data: skip it (its count may be huge).
    for el in h.elements.iter().filter(|el| !el.props.is_empty()) {
        reserve(src, el, out);
        for i in 0..el.count {
            read_one(src, el, h.vertex_count, out, &mut corners).map_err(|f| {
                let what = format!("{} {} of {}", el.name, i, el.count);
                src.error(match f {
                    Fail::Eof => format!(
                        "the data ends inside {what} declared in the header \
                         (truncated file, or a wrong header count)"
                    ),
                    Fail::Bad(msg) => format!("{what}: {msg}"),
                })
            })?;
        }
        if el.role == ElRole::Strips {
            out.skipped.other += el.count;
        }
    }
    Ok(())
}

/// Reserves output space for `el`, capped by what the remaining bytes could hold.
fn reserve<S: Source>(src: &S, el: &Element, out: &mut MeshBuilder) {
    let cap = (src.remaining() / (2 * el.props.len().max(1))) as u64;
    let n = el.count.min(cap) as usize;
    match el.role {
        ElRole::Vertex => out.positions.reserve(n),
        ElRole::Face => {
            out.face_offsets.reserve(n);
            out.face_indices.reserve(3 * n);
        }
        _ => {}
    }
}

fn read_one<S: Source>(
    src: &mut S,
    el: &Element,
    vertex_count: u64,
    out: &mut MeshBuilder,
    corners: &mut Vec<u32>,
) -> Got<()> {
    let mut p = [0.0f64; 3];
    for prop in &el.props {
        match (prop.kind, prop.role) {
            (Kind::Scalar(t), Role::Coord(k)) => p[k] = src.real(t)?,
            (Kind::Scalar(t), _) => src.skip(t, 1)?,
            (Kind::List(ct, it), Role::Indices) => {
                read_corners(src, ct, it, vertex_count, corners)?
            }
            (Kind::List(ct, it), _) => {
                let n = src.int(ct)?;
                let n =
                    u64::try_from(n).map_err(|_| Fail::Bad(format!("negative list count {n}")))?;
                src.skip(it, n)?;
            }
        }
    }
    match el.role {
        ElRole::Vertex if !p.iter().all(|c| c.is_finite()) => Err(Fail::Bad(format!(
            "vertex coordinates {p:?} are not finite"
        ))),
        ElRole::Vertex => {
            out.positions.push(p);
            Ok(())
        }
        ElRole::Face => {
            out.push_face(corners);
            Ok(())
        }
        _ => Ok(()),
    }
}

fn read_corners<S: Source>(
    src: &mut S,
    count_ty: Ty,
    item_ty: Ty,
    vertex_count: u64,
    corners: &mut Vec<u32>,
) -> Got<()> {
    corners.clear();
    let n = src.int(count_ty)?;
    if n < 0 {
        return Err(Fail::Bad(format!("negative list count {n}")));
    }
    for _ in 0..n {
        let i = src.int(item_ty)?;
        if i < 0 || i as u64 >= vertex_count {
            return Err(Fail::Bad(format!(
                "face index {i} is out of range (file has {vertex_count} vertices)"
            )));
        }
        corners.push(i as u32);
    }
    Ok(())
}

/// ASCII data: whitespace-separated tokens, tracking line numbers.
struct Ascii<'a, 'p> {
    b: &'a [u8],
    pos: usize,
    /// Line of `pos`.
    line: u64,
    /// Line of the last token returned.
    tok_line: u64,
    path: &'p Path,
}

impl<'a> Ascii<'a, '_> {
    #[inline]
    fn token(&mut self) -> Got<&'a [u8]> {
        let b = self.b;
        let mut i = self.pos;
        while i < b.len() && b[i].is_ascii_whitespace() {
            if b[i] == b'\n' || (b[i] == b'\r' && b.get(i + 1) != Some(&b'\n')) {
                self.line += 1;
            }
            i += 1;
        }
        let start = i;
        while i < b.len() && !b[i].is_ascii_whitespace() {
            i += 1;
        }
        self.pos = i;
        self.tok_line = self.line;
        if start == i {
            return Err(Fail::Eof);
        }
        Ok(&b[start..i])
    }
}

impl Source for Ascii<'_, '_> {
    fn real(&mut self, _t: Ty) -> Got<f64> {
        let tok = self.token()?;
        parse_f64(tok).ok_or_else(|| Fail::Bad(format!("'{}' is not a number", show(tok))))
    }
    fn int(&mut self, _t: Ty) -> Got<i64> {
        let tok = self.token()?;
        parse_i64(tok).ok_or_else(|| Fail::Bad(format!("'{}' is not an integer", show(tok))))
    }
    fn skip(&mut self, _t: Ty, n: u64) -> Got<()> {
        for _ in 0..n {
            self.token()?;
        }
        Ok(())
    }
    fn remaining(&self) -> usize {
        self.b.len().saturating_sub(self.pos)
    }
    fn error(&self, msg: String) -> Error {
        Error::line(self.path, self.tok_line, msg)
    }
}

/// Binary data read in place; `start` is the offset of the value read last.
struct Binary<'a, 'p> {
    b: &'a [u8],
    pos: usize,
    start: usize,
    be: bool,
    path: &'p Path,
}

impl Binary<'_, '_> {
    #[inline]
    fn take<const N: usize>(&mut self) -> Got<[u8; N]> {
        self.start = self.pos;
        let a = self.b.get(self.pos..).and_then(|r| r.first_chunk::<N>());
        let a = *a.ok_or(Fail::Eof)?;
        self.pos += N;
        Ok(a)
    }
}

/// Reads one `$t` from a [`Binary`] in its byte order.
macro_rules! rd {
    ($s:expr, $t:ty) => {{
        let a = $s.take::<{ std::mem::size_of::<$t>() }>()?;
        if $s.be {
            <$t>::from_be_bytes(a)
        } else {
            <$t>::from_le_bytes(a)
        }
    }};
}

impl Source for Binary<'_, '_> {
    #[inline]
    fn real(&mut self, t: Ty) -> Got<f64> {
        Ok(match t {
            Ty::F32 => f64::from(rd!(self, f32)),
            Ty::F64 => rd!(self, f64),
            _ => self.int(t)? as f64,
        })
    }
    #[inline]
    fn int(&mut self, t: Ty) -> Got<i64> {
        Ok(match t {
            Ty::I8 => i64::from(rd!(self, i8)),
            Ty::U8 => i64::from(rd!(self, u8)),
            Ty::I16 => i64::from(rd!(self, i16)),
            Ty::U16 => i64::from(rd!(self, u16)),
            Ty::I32 => i64::from(rd!(self, i32)),
            Ty::U32 => i64::from(rd!(self, u32)),
            Ty::F32 | Ty::F64 => {
                return Err(Fail::Bad("a float where an integer is needed".into()))
            }
        })
    }
    fn skip(&mut self, t: Ty, n: u64) -> Got<()> {
        self.start = self.pos;
        let len = n.checked_mul(t.size() as u64).ok_or(Fail::Eof)?;
        if len > self.remaining() as u64 {
            return Err(Fail::Eof);
        }
        self.pos += len as usize;
        Ok(())
    }
    fn remaining(&self) -> usize {
        self.b.len().saturating_sub(self.pos)
    }
    fn error(&self, msg: String) -> Error {
        Error::byte(self.path, self.start as u64, msg)
    }
}

#[cfg(test)]
mod tests;
