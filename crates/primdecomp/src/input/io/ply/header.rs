//! A PLY header: its format line, elements and properties, and which of them carry
//! the positions and the face indices (every other property is skipped exactly).

use super::super::text::{parse_i64, show, tokens, Lines};
use crate::error::{Error, Result};
use std::path::Path;

/// A PLY scalar type.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Ty {
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
    pub(super) fn from_name(n: &[u8]) -> Option<Ty> {
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
    pub(super) fn size(self) -> usize {
        match self {
            Ty::I8 | Ty::U8 => 1,
            Ty::I16 | Ty::U16 => 2,
            Ty::I32 | Ty::U32 | Ty::F32 => 4,
            Ty::F64 => 8,
        }
    }
    pub(super) fn is_int(self) -> bool {
        !matches!(self, Ty::F32 | Ty::F64)
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Kind {
    Scalar(Ty),
    /// Count type, item type.
    List(Ty, Ty),
}

/// What the reader does with one property.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Role {
    Skip,
    Coord(usize),
    Indices,
}

/// What the reader does with one element.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum ElRole {
    Vertex,
    Face,
    /// Triangle strips: not read, counted in `skipped.other`.
    Strips,
    Other,
}

#[derive(Debug)]
pub(super) struct Prop {
    pub(super) name: Vec<u8>,
    pub(super) kind: Kind,
    pub(super) role: Role,
}

#[derive(Debug)]
pub(super) struct Element {
    pub(super) name: String,
    pub(super) count: u64,
    pub(super) props: Vec<Prop>,
    pub(super) role: ElRole,
    pub(super) line: u64,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Encoding {
    Ascii,
    Le,
    Be,
}

#[derive(Debug)]
pub(super) struct Header {
    pub(super) enc: Encoding,
    pub(super) elements: Vec<Element>,
    /// Byte offset of the first data byte.
    pub(super) data_start: usize,
    /// 1-based line number of the first data line (ASCII).
    pub(super) data_line: u64,
    /// Declared number of vertices (faces index into these).
    pub(super) vertex_count: u64,
}

pub(super) fn parse_header(bytes: &[u8], path: &Path) -> Result<Header> {
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

pub(super) fn parse_format(tok: Option<&[u8]>, path: &Path, no: u64) -> Result<Encoding> {
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

pub(super) fn parse_element<'a>(
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

pub(super) fn parse_property<'a>(
    mut t: impl Iterator<Item = &'a [u8]>,
    path: &Path,
    no: u64,
) -> Result<Prop> {
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
pub(super) fn assign_roles(elements: &mut [Element], path: &Path) -> Result<u64> {
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

pub(super) fn mark_coords(el: &mut Element, path: &Path) -> Result<()> {
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

pub(super) fn mark_indices(el: &mut Element, path: &Path) -> Result<()> {
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
