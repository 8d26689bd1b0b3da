//! glTF 2.0 reader, for both `.gltf` (JSON with external or `data:` buffers) and
//! `.glb` (binary container).
//!
//! The `gltf` crate parses and validates the JSON; everything that touches bytes is
//! done here with bounds checks, so malformed or truncated input is an error, never a
//! panic: the GLB container is split by hand, buffers are loaded by hand (external
//! files relative to the file's directory, base64 `data:` URIs), and accessors are
//! read by hand (any component type, byte strides, sparse substitution).
//!
//! External buffers follow [`LoadOptions::allow_external_uris`]: by default a URI
//! must be a relative path that stays inside the glTF's folder (no absolute path, no
//! `..` component, no symbolic link leading out, no URL scheme but `data:`). Any
//! buffer file must be a regular file (opened without blocking, checked on the
//! handle) holding at least the buffer's declared `byteLength`, checked before
//! reading; exactly that many bytes are read.
//!
//! The default scene (or scene 0) is walked with node transforms composed in f64;
//! a file without scenes contributes every mesh once, untransformed. Triangle lists,
//! strips and fans become triangles; points and lines primitives are counted in
//! [`SkipCounts::other`](crate::input::mesh::SkipCounts::other).

use super::LoadOptions;
use crate::error::{Error, Result};
use crate::input::mesh::MeshBuilder;
use gltf::accessor::sparse::IndexType;
use gltf::accessor::{DataType, Dimensions};
use gltf::json::validation::Validate;
use gltf::mesh::Mode;
use gltf::scene::Transform;
use primdecomp_files::{open_regular, reason, Error as FileError};
use std::borrow::Cow;
use std::io::Read;
use std::path::{Component, Path, PathBuf};

/// Errors inside a primitive; the caller adds which mesh and primitive.
type Res<T> = std::result::Result<T, String>;

/// A 4×4 matrix, column-major like glTF: `m[column][row]`.
type M4 = [[f64; 4]; 4];

#[rustfmt::skip]
const IDENTITY: M4 = [[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]];

/// Accessors without a bufferView (all zeros plus sparse values) may not claim more
/// elements than this, so a lying count cannot make us allocate without bound.
const MAX_VIEWLESS: usize = 1 << 24;

/// Extensions that change how geometry is stored or instanced; we cannot honour them.
const UNSUPPORTED: [&str; 4] = [
    "KHR_draco_mesh_compression",
    "EXT_meshopt_compression",
    "KHR_meshopt_compression",
    "EXT_mesh_gpu_instancing",
];

/// Parses a `.gltf` or `.glb` file with the default [`LoadOptions`]: external
/// buffers are read only from inside the folder of `path`.
#[cfg(test)]
pub(crate) fn parse_gltf(bytes: &[u8], path: &Path) -> Result<MeshBuilder> {
    parse_gltf_with(bytes, path, &LoadOptions::default())
}

/// Parses a `.gltf` or `.glb` file; `path` locates external buffers, which are read
/// as `options.allow_external_uris` allows ([`LoadOptions`]).
pub fn parse_gltf_with(bytes: &[u8], path: &Path, options: &LoadOptions) -> Result<MeshBuilder> {
    if bytes.trim_ascii().is_empty() {
        return Ok(MeshBuilder::new());
    }
    let (json, blob) = if bytes.starts_with(b"glTF") {
        split_glb(bytes, path)?
    } else {
        (bytes, None)
    };
    let doc = document(json, path)?;
    let mut r = Reader {
        out: MeshBuilder::new(),
        buffers: load_buffers(&doc, blob, path, options.allow_external_uris)?,
        path,
    };
    match doc.default_scene().or_else(|| doc.scenes().next()) {
        Some(scene) => r.walk_scene(&doc, &scene)?,
        None => {
            for mesh in doc.meshes() {
                let name = mesh
                    .name()
                    .map_or_else(|| format!("mesh{}", mesh.index()), str::to_string);
                r.out.start_node(name, IDENTITY);
                r.add_mesh(&mesh, &IDENTITY)?;
            }
        }
    }
    Ok(r.out)
}

/// Splits a GLB container into its JSON chunk and optional BIN chunk.
fn split_glb<'a>(b: &'a [u8], path: &Path) -> Result<(&'a [u8], Option<&'a [u8]>)> {
    let (Some(version), Some(length)) = (u32_at(b, 4), u32_at(b, 8)) else {
        let msg = format!("a GLB header needs 12 bytes, the file has {}", b.len());
        return Err(Error::byte(path, 0, msg));
    };
    if version != 2 {
        let msg = format!("GLB version {version} is not supported (only glTF 2.0)");
        return Err(Error::byte(path, 4, msg));
    }
    let length = length as usize;
    if length > b.len() || length < 20 {
        let msg = format!(
            "the GLB header declares {length} bytes but the file has {} (truncated file?)",
            b.len()
        );
        return Err(Error::byte(path, 8, msg));
    }
    let b = &b[..length];
    let (ty, json, mut pos) = chunk(b, 12, path)?;
    if &ty != b"JSON" {
        return Err(Error::byte(path, 16, "the first GLB chunk is not JSON"));
    }
    let mut bin = None;
    while pos + 8 <= b.len() {
        let (ty, data, next) = chunk(b, pos, path)?;
        if &ty == b"BIN\0" && bin.is_none() {
            bin = Some(data);
        }
        pos = next;
    }
    Ok((json, bin))
}

fn u32_at(b: &[u8], at: usize) -> Option<u32> {
    let c = b.get(at..)?.first_chunk::<4>()?;
    Some(u32::from_le_bytes(*c))
}

/// The GLB chunk at `at`: its type, its data and the offset of the next chunk.
fn chunk<'a>(b: &'a [u8], at: usize, path: &Path) -> Result<([u8; 4], &'a [u8], usize)> {
    let (Some(len), Some(ty)) = (u32_at(b, at), u32_at(b, at + 4)) else {
        let msg = "the file ends inside a GLB chunk header";
        return Err(Error::byte(path, at as u64, msg));
    };
    let end = (at + 8).saturating_add(len as usize);
    let Some(data) = b.get(at + 8..end) else {
        let msg = format!(
            "a GLB chunk of {len} bytes overruns the {} bytes the header declares",
            b.len()
        );
        return Err(Error::byte(path, at as u64, msg));
    };
    Ok((ty.to_le_bytes(), data, end.saturating_add(3) & !3))
}

/// Deserializes and validates the JSON, refusing extensions we cannot honour.
fn document(json: &[u8], path: &Path) -> Result<gltf::Document> {
    let mut root: gltf::json::Root = gltf::json::deserialize::from_slice(json)
        .map_err(|e| Error::format(path, format!("invalid glTF JSON: {e}")))?;
    let required = root.extensions_required.iter();
    let bad = required.clone().find(|e| UNSUPPORTED.contains(&e.as_str()));
    let used = root.extensions_used.iter();
    let instancing = used.clone().find(|e| *e == "EXT_mesh_gpu_instancing");
    if let Some(ext) = bad.or(instancing) {
        let msg = format!("the file uses the glTF extension {ext}, which is not supported");
        return Err(Error::format(path, msg));
    }
    // Other required extensions (materials, texture transforms, mesh quantization)
    // do not change how positions and indices are read.
    root.extensions_required.clear();
    check_attribute_refs(&root, path)?;
    // The crate's validation (index references, enum values) is what makes the
    // document API panic-free; only the POSITION min/max it insists on is optional
    // here, as many exporters omit it and we do not use it (a primitive without
    // POSITION is skipped and counted).
    let mut problems = Vec::new();
    root.validate(&root, gltf::json::Path::new, &mut |at, e| {
        let at = at().0;
        let optional = [".min", ".max", "[\"POSITION\"]"];
        let bounds = optional.iter().any(|end| at.ends_with(end));
        if !(bounds && e == gltf::json::validation::Error::Missing) {
            problems.push(format!("{at}: {e}"));
        }
    });
    if !problems.is_empty() {
        let msg = format!("invalid glTF: {}", problems.join("; "));
        return Err(Error::format(path, msg));
    }
    Ok(gltf::Document::from_json_without_validation(root))
}

/// The crate's validation indexes `accessors` with each primitive's POSITION without a
/// bounds check, so dangling attribute references are rejected here first.
fn check_attribute_refs(root: &gltf::json::Root, path: &Path) -> Result<()> {
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, prim) in mesh.primitives.iter().enumerate() {
            let n = root.accessors.len();
            if let Some(a) = prim.attributes.values().find(|a| a.value() >= n) {
                let a = a.value();
                let msg = format!("mesh {m} primitive {p}: attribute accessor {a} does not exist");
                return Err(Error::format(path, msg));
            }
        }
    }
    Ok(())
}

/// Loads every buffer: the GLB BIN chunk, a `data:` URI or a file next to `path`
/// (elsewhere only with `allow_external`).
fn load_buffers<'a>(
    doc: &gltf::Document,
    blob: Option<&'a [u8]>,
    path: &Path,
    allow_external: bool,
) -> Result<Vec<Cow<'a, [u8]>>> {
    let mut out = Vec::new();
    for buf in doc.buffers() {
        let i = buf.index();
        let data = match buf.source() {
            gltf::buffer::Source::Bin => Cow::Borrowed(blob.ok_or_else(|| {
                let msg =
                    format!("buffer {i} refers to the GLB binary chunk, which the file lacks");
                Error::format(path, msg)
            })?),
            gltf::buffer::Source::Uri(uri) => {
                let at = UriAt {
                    uri,
                    path,
                    buffer: i,
                };
                Cow::Owned(at.read(buf.length(), allow_external)?)
            }
        };
        if data.len() < buf.length() {
            let msg = format!(
                "buffer {i} declares {} bytes but holds only {}",
                buf.length(),
                data.len()
            );
            return Err(Error::format(path, msg));
        }
        out.push(data);
    }
    Ok(out)
}

/// What a refusal of an external URI tells the user to do about it.
const OPT_IN: &str = "only files inside the glTF's folder are read without \
                      --allow-external-uris (LoadOptions::allow_external_uris in the library)";

/// Buffer `buffer`'s URI `uri` in the glTF file `path`.
struct UriAt<'a> {
    uri: &'a str,
    path: &'a Path,
    buffer: usize,
}

impl UriAt<'_> {
    fn refuse(&self, reason: String) -> Error {
        Error::Uri {
            path: self.path.to_path_buf(),
            buffer: self.buffer,
            uri: show_uri(self.uri),
            reason,
        }
    }

    /// The buffer's `len` declared bytes: a base64 `data:` URI decoded, or read from
    /// the file the URI names relative to the glTF's folder.
    fn read(&self, len: usize, allow_external: bool) -> Result<Vec<u8>> {
        let uri = self.uri;
        let rel = match uri_scheme(uri).map(str::to_ascii_lowercase).as_deref() {
            Some("data") => {
                let b64 = uri.split_once(";base64,").map(|(_, d)| d);
                let msg = "is a data URI without valid base64 data";
                return b64
                    .and_then(base64_decode)
                    .ok_or_else(|| self.refuse(msg.into()));
            }
            Some("file") if allow_external => {
                let rest = &uri["file:".len()..];
                rest.strip_prefix("//").unwrap_or(rest)
            }
            Some("file") => return Err(self.refuse(format!("is a file: URL; {OPT_IN}"))),
            Some(s) => {
                return Err(self.refuse(format!(
                    "uses the URL scheme '{s}:', which is never read (only data: URIs and \
                     file paths are)"
                )))
            }
            None => uri,
        };
        let decoded = percent_decode(rel)
            .ok_or_else(|| self.refuse("is not UTF-8 once its %-escapes are decoded".into()))?;
        if decoded.contains('\0') {
            return Err(self.refuse("holds a NUL character".into()));
        }
        let name = Path::new(&decoded);
        let (base, file) = match self.path.parent() {
            Some(d) if !d.as_os_str().is_empty() => (d, d.join(name)),
            _ => (Path::new("."), name.to_path_buf()),
        };
        let open = if allow_external {
            file.clone()
        } else {
            self.inside(name, base, &file)?
        };
        self.read_file(&file, &open, len)
    }

    /// The real path of `file` (`name` joined to the glTF's folder `base`), refusing
    /// an absolute `name`, a `..` component and a symbolic link leading out of `base`.
    fn inside(&self, name: &Path, base: &Path, file: &Path) -> Result<PathBuf> {
        if name.has_root() || name.is_absolute() {
            return Err(self.refuse(format!("is an absolute path; {OPT_IN}")));
        }
        if name.components().any(|c| c == Component::ParentDir) {
            let msg = format!("climbs out of the glTF's folder with '..'; {OPT_IN}");
            return Err(self.refuse(msg));
        }
        let real = std::fs::canonicalize(file).and_then(|real| {
            let root = std::fs::canonicalize(base)?;
            Ok((real.starts_with(&root), real))
        });
        match real {
            Ok((true, real)) => Ok(real),
            Ok((false, real)) => Err(self.refuse(format!(
                "leads out of the glTF's folder through a symbolic link, to {}; {OPT_IN}",
                real.display()
            ))),
            Err(e) => Err(self.cannot_open(file, &e)),
        }
    }

    fn cannot_open(&self, file: &Path, e: &std::io::Error) -> Error {
        let shown = file.display();
        self.refuse(format!(
            "names {shown}, which cannot be opened: {}",
            reason(e)
        ))
    }

    /// Exactly `len` bytes of `open` (the real path of `file`, which messages name),
    /// after checking that it is a regular file holding at least that many.
    fn read_file(&self, file: &Path, open: &Path, len: usize) -> Result<Vec<u8>> {
        let shown = file.display();
        let io = |error| Error::Io {
            path: file.to_path_buf(),
            error,
        };
        let (handle, meta) = open_regular(open).map_err(|e| match e {
            FileError::Open { error, .. } => self.cannot_open(file, &error),
            FileError::NotAFile { kind, .. } => self.refuse(format!(
                "names {shown}, which is {kind}, not a regular file"
            )),
            FileError::Io { error, .. } => io(error),
            e => e.into(),
        })?;
        if meta.len() < len as u64 {
            return Err(self.refuse(format!(
                "names {shown}, which holds {} bytes; the buffer declares {len}",
                meta.len()
            )));
        }
        let mut data = Vec::new();
        data.try_reserve_exact(len)
            .map_err(|e| io(std::io::Error::new(std::io::ErrorKind::OutOfMemory, e)))?;
        (&handle)
            .take(len as u64)
            .read_to_end(&mut data)
            .map_err(io)?;
        if data.len() < len {
            return Err(self.refuse(format!(
                "names {shown}, which ended after {} of its {len} bytes while being read",
                data.len()
            )));
        }
        Ok(data)
    }
}

/// The URL scheme of `uri` (RFC 3986: a letter, then letters, digits, `+`, `-` or
/// `.`, then `:`), if it has one.
fn uri_scheme(uri: &str) -> Option<&str> {
    let (scheme, _) = uri.split_once(':')?;
    let mut c = scheme.chars();
    let first = c.next()?;
    let ok = first.is_ascii_alphabetic()
        && c.all(|c| c.is_ascii_alphanumeric() || matches!(c, '+' | '-' | '.'));
    ok.then_some(scheme)
}

/// A URI for a message: control characters escaped, cut to 80 characters.
fn show_uri(uri: &str) -> String {
    let mut out = String::new();
    for (n, c) in uri.chars().enumerate() {
        if n == 80 {
            out.push('…');
            break;
        }
        if c.is_control() {
            out.extend(c.escape_default());
        } else {
            out.push(c);
        }
    }
    out
}

/// Standard or URL-safe base64, padding optional, whitespace skipped.
fn base64_decode(s: &str) -> Option<Vec<u8>> {
    let mut out = Vec::with_capacity(s.len() / 4 * 3 + 3);
    let (mut acc, mut bits) = (0u32, 0u32);
    for &c in s.as_bytes() {
        let v = match c {
            b'A'..=b'Z' => c - b'A',
            b'a'..=b'z' => c - b'a' + 26,
            b'0'..=b'9' => c - b'0' + 52,
            b'+' | b'-' => 62,
            b'/' | b'_' => 63,
            b'=' => break,
            c if c.is_ascii_whitespace() => continue,
            _ => return None,
        };
        acc = (acc << 6) | u32::from(v);
        bits += 6;
        if bits >= 8 {
            bits -= 8;
            out.push((acc >> bits) as u8);
            acc &= (1 << bits) - 1;
        }
    }
    Some(out)
}

/// `%XX` escapes decoded; `None` if the result is not UTF-8.
fn percent_decode(s: &str) -> Option<String> {
    let hex = |c: u8| (c as char).to_digit(16);
    let b = s.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        let h = b.get(i + 1).and_then(|&c| hex(c));
        let l = b.get(i + 2).and_then(|&c| hex(c));
        match (b[i], h, l) {
            (b'%', Some(h), Some(l)) => {
                out.push((h * 16 + l) as u8);
                i += 3;
            }
            (c, _, _) => {
                out.push(c);
                i += 1;
            }
        }
    }
    String::from_utf8(out).ok()
}

/// Output and the loaded buffers.
struct Reader<'a, 'p> {
    out: MeshBuilder,
    buffers: Vec<Cow<'a, [u8]>>,
    path: &'p Path,
}

impl Reader<'_, '_> {
    fn err(&self, msg: String) -> Error {
        Error::format(self.path, msg)
    }

    /// Depth-first over the scene's node trees (explicit stack: deep trees are fine).
    fn walk_scene(&mut self, doc: &gltf::Document, scene: &gltf::Scene) -> Result<()> {
        let mut visited = vec![false; doc.nodes().len()];
        let mut stack: Vec<(gltf::Node, M4)> = scene.nodes().map(|n| (n, IDENTITY)).collect();
        stack.reverse();
        while let Some((node, parent)) = stack.pop() {
            let i = node.index();
            match visited.get_mut(i) {
                Some(v) if !*v => *v = true,
                _ => {
                    let msg =
                        format!("node {i} is reached twice; the node hierarchy must be a tree");
                    return Err(self.err(msg));
                }
            }
            let m = mul(&parent, &local(node.transform()));
            if let Some(mesh) = node.mesh() {
                // Each mesh node is an object of its own (`--per-object`): its name
                // (else its mesh's, else `node{i}`) and world transform.
                let name = node
                    .name()
                    .or(mesh.name())
                    .map_or_else(|| format!("node{i}"), str::to_string);
                self.out.start_node(name, m);
                self.add_mesh(&mesh, &m)?;
            }
            let children: Vec<_> = node.children().collect();
            stack.extend(children.into_iter().rev().map(|c| (c, m)));
        }
        Ok(())
    }

    fn add_mesh(&mut self, mesh: &gltf::Mesh, m: &M4) -> Result<()> {
        for prim in mesh.primitives() {
            let what = format!("mesh {} primitive {}", mesh.index(), prim.index());
            self.add_primitive(&prim, m)
                .map_err(|msg| self.err(format!("{what}: {msg}")))?;
        }
        Ok(())
    }

    fn add_primitive(&mut self, prim: &gltf::Primitive, m: &M4) -> Res<()> {
        let mode = prim.mode();
        let tris = matches!(
            mode,
            Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
        );
        let (true, Some(pos)) = (tris, prim.get(&gltf::Semantic::Positions)) else {
            self.out.skipped.other += 1;
            return Ok(());
        };
        if pos.dimensions() != Dimensions::Vec3 {
            return Err("POSITION is not a VEC3 accessor".into());
        }
        let values = read_accessor(&pos, &self.buffers)?;
        let n = pos.count();
        let base = self.out.positions.len();
        if base + n > u32::MAX as usize {
            return Err("more than 4294967295 vertices in total".into());
        }
        for p in values.chunks_exact(3) {
            let w = apply(m, [p[0], p[1], p[2]]);
            if !w.iter().all(|c| c.is_finite()) {
                return Err(format!(
                    "vertex {w:?} is not finite (POSITION or transform)"
                ));
            }
            self.out.positions.push(w);
        }
        let idx = match prim.indices() {
            Some(acc) => read_indices(&acc, &self.buffers, n)?,
            None => (0..n as u32).collect(),
        };
        push_triangles(&mut self.out, mode, &idx, base as u32);
        Ok(())
    }
}

/// Appends the triangles of a list, strip or fan; indices are relative to `base`.
fn push_triangles(out: &mut MeshBuilder, mode: Mode, idx: &[u32], base: u32) {
    let mut tri = |a: u32, b: u32, c: u32| out.push_face(&[base + a, base + b, base + c]);
    match mode {
        Mode::TriangleStrip => {
            for (i, w) in idx.windows(3).enumerate() {
                if i % 2 == 0 {
                    tri(w[0], w[1], w[2]);
                } else {
                    tri(w[0], w[2], w[1]);
                }
            }
        }
        Mode::TriangleFan => {
            if let Some((&first, rest)) = idx.split_first() {
                for w in rest.windows(2) {
                    tri(first, w[0], w[1]);
                }
            }
        }
        _ => {
            for t in idx.chunks_exact(3) {
                tri(t[0], t[1], t[2]);
            }
            if idx.len() % 3 != 0 {
                out.skipped.short_faces += 1;
            }
        }
    }
}

fn read_indices(acc: &gltf::Accessor, bufs: &[Cow<[u8]>], n: usize) -> Res<Vec<u32>> {
    let int = matches!(
        acc.data_type(),
        DataType::U8 | DataType::U16 | DataType::U32
    );
    if acc.dimensions() != Dimensions::Scalar || !int {
        return Err("indices must be a SCALAR accessor of unsigned bytes, shorts or ints".into());
    }
    let values = read_accessor(acc, bufs)?;
    let mut out = Vec::with_capacity(values.len());
    for v in values {
        if v >= n as f64 {
            return Err(format!(
                "index {v} is out of range (POSITION has {n} vertices)"
            ));
        }
        out.push(v as u32);
    }
    Ok(out)
}

/// The bytes of a bufferView, checked against its buffer.
fn view_bytes<'b>(view: &gltf::buffer::View, bufs: &'b [Cow<[u8]>]) -> Res<&'b [u8]> {
    let (b, start) = (view.buffer().index(), view.offset());
    let end = start.checked_add(view.length());
    let data = bufs.get(b).zip(end).and_then(|(buf, e)| buf.get(start..e));
    data.ok_or_else(|| format!("bufferView {} overruns buffer {b}", view.index()))
}

/// All components of an accessor as f64 (normalized integers mapped per the spec),
/// with sparse substitutions applied.
fn read_accessor(acc: &gltf::Accessor, bufs: &[Cow<[u8]>]) -> Res<Vec<f64>> {
    let (a, dt, norm) = (acc.index(), acc.data_type(), acc.normalized());
    let (dims, count, elem) = (acc.dimensions().multiplicity(), acc.count(), acc.size());
    let mut vals = match acc.view() {
        Some(view) => {
            let data = view_bytes(&view, bufs)?;
            let stride = view.stride().unwrap_or(elem);
            let need = count.checked_sub(1).map_or(Some(0), |last| {
                last.checked_mul(stride)?
                    .checked_add(acc.offset())?
                    .checked_add(elem)
            });
            if stride < elem || need.is_none_or(|need| need > data.len()) {
                let v = view.index();
                return Err(format!(
                    "accessor {a} ({count} elements) overruns bufferView {v}"
                ));
            }
            let mut v = Vec::with_capacity(count * dims);
            for i in 0..count {
                let at = acc.offset() + i * stride;
                for k in 0..dims {
                    v.push(component(data, at + k * dt.size(), dt, norm));
                }
            }
            v
        }
        None if count <= MAX_VIEWLESS => vec![0.0; count * dims],
        None => {
            return Err(format!(
                "accessor {a} has {count} elements and no bufferView"
            ))
        }
    };
    if let Some(sparse) = acc.sparse() {
        apply_sparse(&sparse, &mut vals, acc, bufs)?;
    }
    Ok(vals)
}

fn apply_sparse(
    sp: &gltf::accessor::sparse::Sparse,
    vals: &mut [f64],
    acc: &gltf::Accessor,
    bufs: &[Cow<[u8]>],
) -> Res<()> {
    let (a, dt, norm) = (acc.index(), acc.data_type(), acc.normalized());
    let (dims, n, elem) = (acc.dimensions().multiplicity(), sp.count(), acc.size());
    let (ind, val) = (sp.indices(), sp.values());
    let ity = match ind.index_type() {
        IndexType::U8 => DataType::U8,
        IndexType::U16 => DataType::U16,
        IndexType::U32 => DataType::U32,
    };
    let idata = view_bytes(&ind.view(), bufs)?;
    let vdata = view_bytes(&val.view(), bufs)?;
    let fits = |off: usize, size: usize, len: usize| {
        n.checked_mul(size)
            .and_then(|s| s.checked_add(off))
            .is_some_and(|e| e <= len)
    };
    if !fits(ind.offset(), ity.size(), idata.len()) || !fits(val.offset(), elem, vdata.len()) {
        return Err(format!(
            "sparse data of accessor {a} overruns its bufferView"
        ));
    }
    for j in 0..n {
        let target = component(idata, ind.offset() + j * ity.size(), ity, false) as usize;
        for k in 0..dims {
            let v = component(vdata, val.offset() + j * elem + k * dt.size(), dt, norm);
            let slot = vals.get_mut(target * dims + k);
            let slot = slot
                .ok_or_else(|| format!("sparse index {target} of accessor {a} is out of range"))?;
            *slot = v;
        }
    }
    Ok(())
}

/// One component at byte `at` (NaN if out of bounds, which the callers rule out).
fn component(data: &[u8], at: usize, dt: DataType, norm: bool) -> f64 {
    let Some(b) = data.get(at..at.saturating_add(dt.size())) else {
        return f64::NAN;
    };
    let b4 = |b: &[u8]| [b[0], b[1], b[2], b[3]];
    let (x, scale) = match dt {
        DataType::I8 => (f64::from(b[0] as i8), 127.0),
        DataType::U8 => (f64::from(b[0]), 255.0),
        DataType::I16 => (f64::from(i16::from_le_bytes([b[0], b[1]])), 32767.0),
        DataType::U16 => (f64::from(u16::from_le_bytes([b[0], b[1]])), 65535.0),
        DataType::U32 => (f64::from(u32::from_le_bytes(b4(b))), 1.0),
        DataType::F32 => return f64::from(f32::from_le_bytes(b4(b))),
    };
    if norm {
        (x / scale).max(-1.0)
    } else {
        x
    }
}

/// The node's local transform in f64 (TRS: translation × rotation × scale).
#[rustfmt::skip]
fn local(t: Transform) -> M4 {
    let (t, r, s) = match t {
        Transform::Matrix { matrix } => return matrix.map(|c| c.map(f64::from)),
        Transform::Decomposed { translation, rotation, scale } => (translation, rotation, scale),
    };
    let [x, y, z, w] = r.map(f64::from);
    let len = (x * x + y * y + z * z + w * w).sqrt();
    let [x, y, z, w] = if len > 0.0 { [x / len, y / len, z / len, w / len] } else { [0.0, 0.0, 0.0, 1.0] };
    let [sx, sy, sz] = s.map(f64::from);
    [
        [sx * (1.0 - 2.0 * (y * y + z * z)), sx * 2.0 * (x * y + z * w), sx * 2.0 * (x * z - y * w), 0.0],
        [sy * 2.0 * (x * y - z * w), sy * (1.0 - 2.0 * (x * x + z * z)), sy * 2.0 * (y * z + x * w), 0.0],
        [sz * 2.0 * (x * z + y * w), sz * 2.0 * (y * z - x * w), sz * (1.0 - 2.0 * (x * x + y * y)), 0.0],
        [f64::from(t[0]), f64::from(t[1]), f64::from(t[2]), 1.0],
    ]
}

fn mul(a: &M4, b: &M4) -> M4 {
    let mut m = [[0.0; 4]; 4];
    for (c, col) in m.iter_mut().enumerate() {
        for (r, v) in col.iter_mut().enumerate() {
            *v = (0..4).map(|k| a[k][r] * b[c][k]).sum();
        }
    }
    m
}

fn apply(m: &M4, p: [f64; 3]) -> [f64; 3] {
    let row = |r: usize| m[0][r] * p[0] + m[1][r] * p[1] + m[2][r] * p[2] + m[3][r];
    [row(0), row(1), row(2)]
}

#[cfg(test)]
mod tests;
