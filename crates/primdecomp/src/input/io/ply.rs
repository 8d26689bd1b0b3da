//! PLY reader: ASCII, binary little-endian and binary big-endian.
//!
//! The header is parsed into elements and properties; the data section is then read
//! by one generic loop over a [`Source`] (ASCII tokens or binary scalars). `x`, `y`,
//! `z` of the `vertex` element (any scalar type) become positions; the `vertex_indices`
//! (or `vertex_index`) list of the `face` element becomes polygons. Every other
//! property and element, lists included, is skipped exactly. Binary data is read in
//! place from the caller's (memory-mapped) slice, without per-element allocation.
//! Errors carry the 1-based line (ASCII) or byte offset (binary) where reading stopped.

use super::text::{parse_f64, parse_i64, show, tokens, Lines};
use crate::error::{Error, Result};
use crate::input::mesh::MeshBuilder;
use std::path::Path;

/// Parses a PLY file (any of the three encodings) into positions and polygons.
pub fn parse_ply(bytes: &[u8], path: &Path) -> Result<MeshBuilder> {
    if bytes.trim_ascii().is_empty() {
        return Ok(MeshBuilder::new());
    }
    let header = parse_header(bytes, path)?;
    let mut out = MeshBuilder::new();
    match header.enc {
        Encoding::Ascii => {
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

/// A PLY scalar type.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Ty {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Ty {
    fn from_name(n: &[u8]) -> Option<Ty> {
        Some(match n {
            b"char" | b"int8" => Ty::I8,
            b"uchar" | b"uint8" => Ty::U8,
            b"short" | b"int16" => Ty::I16,
            b"ushort" | b"uint16" => Ty::U16,
            b"int" | b"int32" => Ty::I32,
            b"uint" | b"uint32" => Ty::U32,
            b"float" | b"float32" => Ty::F32,
            b"double" | b"float64" => Ty::F64,
            _ => return None,
        })
    }
    fn size(self) -> usize {
        match self {
            Ty::I8 | Ty::U8 => 1,
            Ty::I16 | Ty::U16 => 2,
            Ty::I32 | Ty::U32 | Ty::F32 => 4,
            Ty::F64 => 8,
        }
    }
    fn is_int(self) -> bool {
        !matches!(self, Ty::F32 | Ty::F64)
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    Scalar(Ty),
    /// Count type, item type.
    List(Ty, Ty),
}

/// What the reader does with one property.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Role {
    Skip,
    Coord(usize),
    Indices,
}

/// What the reader does with one element.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum ElRole {
    Vertex,
    Face,
    /// Triangle strips: not read, counted in `skipped.other`.
    Strips,
    Other,
}

#[derive(Debug)]
struct Prop {
    name: Vec<u8>,
    kind: Kind,
    role: Role,
}

#[derive(Debug)]
struct Element {
    name: String,
    count: u64,
    props: Vec<Prop>,
    role: ElRole,
    line: u64,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Encoding {
    Ascii,
    Le,
    Be,
}

#[derive(Debug)]
struct Header {
    enc: Encoding,
    elements: Vec<Element>,
    /// Byte offset of the first data byte.
    data_start: usize,
    /// 1-based line number of the first data line (ASCII).
    data_line: u64,
    /// Declared number of vertices (faces index into these).
    vertex_count: u64,
}

fn parse_header(bytes: &[u8], path: &Path) -> Result<Header> {
    let mut lines = Lines::new(bytes);
    match lines.next() {
        Some((_, l)) if l.trim_ascii() == b"ply" => {}
        _ => {
            return Err(Error::format(
                path,
                "not a PLY file: the first line must be 'ply'",
            ))
        }
    }
    let mut enc = None;
    let mut elements: Vec<Element> = Vec::new();
    while let Some((no, line)) = lines.next() {
        let mut t = tokens(line);
        match t.next() {
            None | Some(b"comment") | Some(b"obj_info") => {}
            Some(b"format") => enc = Some(parse_format(t.next(), path, no)?),
            Some(b"element") => elements.push(parse_element(t, path, no)?),
            Some(b"property") => {
                let el = elements.last_mut().ok_or_else(|| {
                    Error::line(path, no, "'property' appears before any 'element'")
                })?;
                el.props.push(parse_property(t, path, no)?);
            }
            Some(b"end_header") => {
                let enc =
                    enc.ok_or_else(|| Error::line(path, no, "the header has no 'format' line"))?;
                let vertex_count = assign_roles(&mut elements, path)?;
                return Ok(Header {
                    enc,
                    elements,
                    data_start: lines.offset(),
                    data_line: no + 1,
                    vertex_count,
                });
            }
            Some(k) => {
                let msg = format!("unknown header keyword '{}'", show(k));
                return Err(Error::line(path, no, msg));
            }
        }
    }
    Err(Error::format(
        path,
        "the PLY header has no 'end_header' line",
    ))
}

fn parse_format(tok: Option<&[u8]>, path: &Path, no: u64) -> Result<Encoding> {
    match tok {
        Some(b"ascii") => Ok(Encoding::Ascii),
        Some(b"binary_little_endian") => Ok(Encoding::Le),
        Some(b"binary_big_endian") => Ok(Encoding::Be),
        Some(other) => Err(Error::line(
            path,
            no,
            format!("unknown PLY format '{}'", show(other)),
        )),
        None => Err(Error::line(path, no, "'format' line names no format")),
    }
}

fn parse_element<'a>(
    mut t: impl Iterator<Item = &'a [u8]>,
    path: &Path,
    no: u64,
) -> Result<Element> {
    let (Some(name), Some(count)) = (t.next(), t.next()) else {
        return Err(Error::line(path, no, "'element' needs a name and a count"));
    };
    let count = parse_i64(count)
        .and_then(|c| u64::try_from(c).ok())
        .ok_or_else(|| {
            let msg = format!(
                "element count '{}' is not a non-negative integer",
                show(count)
            );
            Error::line(path, no, msg)
        })?;
    Ok(Element {
        name: String::from_utf8_lossy(name).into_owned(),
        count,
        props: Vec::new(),
        role: ElRole::Other,
        line: no,
    })
}

fn parse_property<'a>(mut t: impl Iterator<Item = &'a [u8]>, path: &Path, no: u64) -> Result<Prop> {
    let ty = |tok: Option<&[u8]>| -> Result<Ty> {
        let tok = tok.ok_or_else(|| Error::line(path, no, "incomplete 'property' line"))?;
        Ty::from_name(tok)
            .ok_or_else(|| Error::line(path, no, format!("unknown property type '{}'", show(tok))))
    };
    let first = t.next();
    let kind = if first == Some(b"list") {
        let (count, item) = (ty(t.next())?, ty(t.next())?);
        if !count.is_int() {
            return Err(Error::line(
                path,
                no,
                "a list count type must be an integer type",
            ));
        }
        Kind::List(count, item)
    } else {
        Kind::Scalar(ty(first)?)
    };
    let name = t
        .next()
        .ok_or_else(|| Error::line(path, no, "'property' line names no property"))?;
    Ok(Prop {
        name: name.to_vec(),
        kind,
        role: Role::Skip,
    })
}

/// Marks the vertex coordinates and the face index list; returns the vertex count.
fn assign_roles(elements: &mut [Element], path: &Path) -> Result<u64> {
    let mut vertex_count = 0;
    let (mut seen_vertex, mut seen_face) = (false, false);
    for el in elements.iter_mut() {
        if el.name == "vertex" && !seen_vertex {
            seen_vertex = true;
            el.role = ElRole::Vertex;
            vertex_count = el.count;
            mark_coords(el, path)?;
        } else if el.name == "face" && !seen_face {
            seen_face = true;
            el.role = ElRole::Face;
            mark_indices(el, path)?;
        } else if el.name == "tristrips" {
            el.role = ElRole::Strips;
        }
    }
    if vertex_count > u64::from(u32::MAX) {
        let msg = format!("{vertex_count} vertices is more than this reader's u32 indices allow");
        return Err(Error::format(path, msg));
    }
    Ok(vertex_count)
}

fn mark_coords(el: &mut Element, path: &Path) -> Result<()> {
    for (k, axis) in ["x", "y", "z"].into_iter().enumerate() {
        let msg = match el.props.iter_mut().find(|p| p.name == axis.as_bytes()) {
            Some(p) if matches!(p.kind, Kind::Scalar(_)) => {
                p.role = Role::Coord(k);
                continue;
            }
            Some(_) => format!("vertex property '{axis}' is a list, not a scalar"),
            None => format!("element vertex has no '{axis}' property"),
        };
        return Err(Error::line(path, el.line, msg));
    }
    Ok(())
}

fn mark_indices(el: &mut Element, path: &Path) -> Result<()> {
    let is_idx = |p: &Prop| p.name == b"vertex_indices" || p.name == b"vertex_index";
    let Some(prop) = el.props.iter_mut().find(|p| is_idx(p)) else {
        let msg = "element face has no 'vertex_indices' (or 'vertex_index') list property";
        return Err(Error::line(path, el.line, msg));
    };
    match prop.kind {
        Kind::List(_, item) if item.is_int() => {
            prop.role = Role::Indices;
            Ok(())
        }
        Kind::List(..) => Err(Error::line(path, el.line, "face indices must be integers")),
        Kind::Scalar(_) => Err(Error::line(path, el.line, "face indices must be a list")),
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
