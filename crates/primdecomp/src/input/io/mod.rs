//! Mesh readers, one file per format. Binary formats are memory-mapped; every reader
//! returns a [`MeshBuilder`] of f64 world coordinates and polygons, or an [`Error`]
//! naming the file and the line or byte offset.
//!
//! Every file is opened through [`open_regular`]: without blocking (a named pipe
//! cannot stall the open) and refused unless the opened handle is a regular file, so
//! pipes, sockets, devices and directories are errors before anything is read.

mod declared;
mod gltf;
pub(crate) mod obj;
mod off;
mod ply;
mod stl;

use crate::error::{Error, Result};
use crate::input::mesh::{Mesh, MeshBuilder};
use primdecomp_files::open_regular;

use std::path::Path;

pub(crate) use self::gltf::parse_gltf_with;
pub(crate) use obj::parse_obj;
pub(crate) use off::declared_counts as off_declared;
pub(crate) use off::parse_off;
pub(crate) use ply::declared_counts as ply_declared;
pub(crate) use ply::parse_ply;
pub(crate) use ply::PlyLayout;
pub(crate) use stl::parse_stl;

/// The mesh formats [`crate::Mesh::load`] reads, chosen by the file's extension.
///
/// ```
/// use primdecomp::MeshFormat;
///
/// assert_eq!(MeshFormat::from_path("Scan.PLY".as_ref()), Some(MeshFormat::Ply));
/// assert_eq!(MeshFormat::from_path("notes.txt".as_ref()), None);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MeshFormat {
    /// Wavefront OBJ (`v` and `f`, polygons kept; `o`/`g` name objects).
    Obj,
    /// PLY, ASCII or binary of either byte order.
    Ply,
    /// STL, ASCII or binary.
    Stl,
    /// OFF.
    Off,
    /// glTF 2.0 with external or embedded buffers (every mesh node, transforms applied).
    Gltf,
    /// Binary glTF.
    Glb,
}

impl MeshFormat {
    /// The format the file's extension names (case-insensitive).
    pub fn from_path(path: &Path) -> Option<MeshFormat> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        Some(match ext.as_str() {
            "obj" => MeshFormat::Obj,
            "ply" => MeshFormat::Ply,
            "stl" => MeshFormat::Stl,
            "off" => MeshFormat::Off,
            "gltf" => MeshFormat::Gltf,
            "glb" => MeshFormat::Glb,
            _ => return None,
        })
    }
}

impl Mesh {
    /// A mesh from bytes already in memory in `format` (a file received over a
    /// network, an archive member); `path` names it in messages and, for `.gltf`, is
    /// where external buffers are resolved from (only from inside its folder: the
    /// default [`LoadOptions`]). Unlike [`Mesh::load`] it does not refuse an empty mesh
    /// or far-flung vertices ([`crate::decompose`] does).
    ///
    /// ```
    /// use primdecomp::{Mesh, MeshFormat};
    ///
    /// let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    /// let mesh = Mesh::parse(obj, MeshFormat::Obj, "triangle.obj".as_ref())?;
    /// assert_eq!(mesh.face_count(), 1);
    /// # Ok::<(), primdecomp::Error>(())
    /// ```
    pub fn parse(bytes: &[u8], format: MeshFormat, path: &Path) -> Result<Mesh> {
        parse_bytes(bytes, format, path).map(Mesh::from_builder)
    }

    /// [`Mesh::parse`] with `options`, of which only the glTF URI policy applies
    /// (`allow_external_uris`: a `.gltf`'s buffers from anywhere `path` points).
    ///
    /// ```
    /// use primdecomp::{LoadOptions, Mesh, MeshFormat};
    ///
    /// let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    /// let options = LoadOptions::default();
    /// let mesh = Mesh::parse_with(obj, MeshFormat::Obj, "t.obj".as_ref(), &options)?;
    /// assert_eq!(mesh.face_count(), 1);
    /// # Ok::<(), primdecomp::Error>(())
    /// ```
    pub fn parse_with(
        bytes: &[u8],
        format: MeshFormat,
        path: &Path,
        options: &LoadOptions,
    ) -> Result<Mesh> {
        parse_bytes_with(bytes, format, path, options).map(Mesh::from_builder)
    }

    /// Reads the mesh in `path` (OBJ, PLY, STL, OFF, glTF/GLB, by its extension):
    /// memory-mapped, parsed, re-centred, with the default [`LoadOptions`] (no memory
    /// limit, glTF buffers only from inside the glTF's folder): see [`Mesh::load_with`].
    ///
    /// ```
    /// use primdecomp::Mesh;
    ///
    /// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../datasets/demo_scene.obj");
    /// let mesh = Mesh::load(path.as_ref())?;
    /// assert!(mesh.objects().len() > 1);
    /// # Ok::<(), primdecomp::Error>(())
    /// ```
    ///
    /// # Errors
    /// An [`Error`] naming the file and the line or byte offset where it is malformed, an
    /// [`Error::EmptyMesh`] when it has no polygon, [`Error::Extent`] / [`Error::Position`]
    /// for vertices too far apart or from the origin.
    pub fn load(path: &Path) -> Result<Mesh> {
        load(path)
    }

    /// Opens `path` with [`open_regular`] (refusing anything but a regular file before
    /// reading it), memory-maps and parses it, then re-centres it into a [`Mesh`].
    /// `options.max_memory` refuses with [`Error::TooLarge`] an input whose
    /// decomposition would need more than that by the memory model
    /// ([`Mesh::memory_needed`]): once from the counts the file declares, before
    /// parsing, and once from the parsed mesh, before anything else is allocated for
    /// it. `options.allow_external_uris` is the glTF buffer policy ([`LoadOptions`]).
    ///
    /// ```
    /// use primdecomp::{LoadOptions, Mesh};
    ///
    /// let options = LoadOptions { max_memory: Some(1 << 30), ..Default::default() };
    /// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../datasets/demo_scene.obj");
    /// let mesh = Mesh::load_with(path.as_ref(), &options)?;
    /// assert!(mesh.face_count() > 0);
    /// # Ok::<(), primdecomp::Error>(())
    /// ```
    pub fn load_with(path: &Path, options: &LoadOptions) -> Result<Mesh> {
        load_with(path, options)
    }

    /// The peak memory in bytes a decomposition of `path` is expected to need (a
    /// default run, with the merge tree's cut: a count's greedy run needs less), from
    /// the counts its header declares, read without parsing the file; `None` where they
    /// cannot be known before parsing (glTF/GLB, an unreadable file or one that is not
    /// a regular file, a header that does not parse). Schedulers running several
    /// inputs at once reserve this much per input.
    ///
    /// ```
    /// use primdecomp::Mesh;
    ///
    /// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../datasets/demo_scene.obj");
    /// let bytes = Mesh::memory_needed(path.as_ref()).expect("an OBJ declares its counts");
    /// assert!(bytes > std::fs::metadata(path).unwrap().len());
    /// assert_eq!(Mesh::memory_needed("scene.glb".as_ref()), None);
    /// ```
    pub fn memory_needed(path: &Path) -> Option<u64> {
        memory_needed(path)
    }
}

/// How [`Mesh::load_with`] reads an input. `Default` is the
/// safe setting for untrusted files: no memory limit, and glTF buffers read only from
/// `data:` URIs, the GLB's own chunk or files inside the glTF's folder.
///
/// ```
/// use primdecomp::{LoadOptions, Mesh};
///
/// let safe = LoadOptions::default();
/// assert_eq!((safe.max_memory, safe.allow_external_uris), (None, false));
/// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../datasets/demo_scene.obj");
/// let options = LoadOptions { max_memory: Some(1 << 30), ..safe };
/// assert!(Mesh::load_with(path.as_ref(), &options)?.face_count() > 0);
/// # Ok::<(), primdecomp::Error>(())
/// ```
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct LoadOptions {
    /// Refuse with [`Error::TooLarge`] an input whose decomposition would need more
    /// than this many bytes by the memory model ([`Mesh::memory_needed`]): once from the counts the
    /// file declares, before parsing, and once from the parsed mesh. `None`: no limit.
    pub max_memory: Option<u64>,
    /// The decomposition that follows takes no cut of the merge tree (its targets are
    /// counts not cut from the merge tree: [`Goal::uses_cut`](crate::Goal::uses_cut)
    /// is false): `max_memory` is checked against the greedy run's peak, about two
    /// thirds of the cut's. Off (the default): against the cut's, which is never below
    /// the greedy run's, so it covers both.
    pub greedy_only: bool,
    /// glTF: also read buffer URIs that are absolute paths, climb out of the glTF's
    /// folder (a `..` component, or a symbolic link inside the folder that leads out
    /// of it) or are `file:` URLs. Off: such a URI is [`Error::Uri`], so a glTF from an
    /// untrusted source reads nothing outside its own folder. Other URL schemes
    /// (`http:` …) are never read. Either way a buffer must be a regular file holding
    /// at least its declared `byteLength`, and only that many bytes are read.
    pub allow_external_uris: bool,
    /// Keep the coordinates exactly as the file gives them instead of re-centring them
    /// on their bounding box: [`Mesh::centre`] is the origin and [`Mesh::world_pos`]
    /// returns the file's values bit for bit (re-centring and adding the centre back
    /// can change the last bit). For handing a mesh's arrays to another program (the
    /// Python package's `load`, whose arrays then decompose exactly as the file does);
    /// [`Mesh::load_with`] still refuses what it refuses with re-centring. Decomposing such a
    /// mesh directly loses the precision re-centring keeps far from the origin.
    pub keep_world_coordinates: bool,
    /// [`crate::Tiled::decompose`]: decompose in this many spatial tiles (at most
    /// 4096) instead of the fewest that fit `max_memory`. `None` (the
    /// default): the fewest; [`Mesh::load_with`] ignores it.
    pub tiles: Option<usize>,
}

/// Parses bytes already in memory as `format` with the default `LoadOptions`;
/// `path` is used for messages (and, for `.gltf`, to resolve external buffers).
pub(crate) fn parse_bytes(bytes: &[u8], format: MeshFormat, path: &Path) -> Result<MeshBuilder> {
    parse_bytes_with(bytes, format, path, &LoadOptions::default())
}

/// `parse_bytes` with `options` (of which only the glTF URI policy applies here).
pub(crate) fn parse_bytes_with(
    bytes: &[u8],
    format: MeshFormat,
    path: &Path,
    options: &LoadOptions,
) -> Result<MeshBuilder> {
    if bytes.starts_with(&[0x1f, 0x8b]) {
        return Err(Error::format(
            path,
            "the file is gzip-compressed; decompress it first",
        ));
    }
    match format {
        MeshFormat::Obj => parse_obj(bytes, path),
        MeshFormat::Ply => parse_ply(bytes, path),
        MeshFormat::Stl => parse_stl(bytes, path),
        MeshFormat::Off => parse_off(bytes, path),
        MeshFormat::Gltf | MeshFormat::Glb => parse_gltf_with(bytes, path, options),
    }
}

/// Small byte-level helpers shared by the text readers (OBJ, OFF, ASCII STL, ASCII PLY).
/// Everything works on `&[u8]`: files need not be UTF-8.
pub(crate) mod text {
    /// Lines of a byte slice with 1-based numbers. `\n`, `\r\n` and a lone `\r` all end
    /// a line, so CRLF, LF and old-Mac files (and mixtures) number lines the same way.
    pub(crate) struct Lines<'a> {
        bytes: &'a [u8],
        pos: usize,
        line: u64,
    }

    impl<'a> Lines<'a> {
        pub(crate) fn new(bytes: &'a [u8]) -> Self {
            Lines {
                bytes,
                pos: 0,
                line: 0,
            }
        }
        /// Byte offset of the first byte not yet returned (the start of the next line).
        pub(crate) fn offset(&self) -> usize {
            self.pos
        }
    }

    impl<'a> Iterator for Lines<'a> {
        type Item = (u64, &'a [u8]);
        fn next(&mut self) -> Option<Self::Item> {
            let rest = self.bytes.get(self.pos..).filter(|r| !r.is_empty())?;
            let end = rest
                .iter()
                .position(|&b| b == b'\n' || b == b'\r')
                .unwrap_or(rest.len());
            let mut next = end;
            if end < rest.len() {
                next += 1;
                if rest[end] == b'\r' && rest.get(end + 1) == Some(&b'\n') {
                    next += 1;
                }
            }
            self.pos += next;
            self.line += 1;
            Some((self.line, &rest[..end]))
        }
    }

    /// Whitespace-separated tokens of one line.
    pub(crate) fn tokens(line: &[u8]) -> impl Iterator<Item = &[u8]> {
        line.split(|b| b.is_ascii_whitespace())
            .filter(|t| !t.is_empty())
    }

    /// The part of `line` before the first `#`.
    pub(crate) fn strip_comment(line: &[u8]) -> &[u8] {
        match line.iter().position(|&b| b == b'#') {
            Some(i) => &line[..i],
            None => line,
        }
    }

    /// A decimal float (`1`, `-2.5`, `.5`, `1e-3`, …). `None` if the token is not a
    /// number; `nan`/`inf` parse, so callers check [`f64::is_finite`] themselves.
    /// Results are correctly rounded, exactly as `str::parse::<f64>` gives them.
    #[inline]
    pub(crate) fn parse_f64(tok: &[u8]) -> Option<f64> {
        fast_f64(tok).or_else(|| std::str::from_utf8(tok).ok()?.parse::<f64>().ok())
    }

    /// Clinger's fast path: a mantissa of at most 19 digits below 2^53 and a decimal
    /// exponent within ±22 give a correctly rounded result in one IEEE operation.
    /// `None` means "use the general parser", not "invalid".
    #[inline]
    fn fast_f64(tok: &[u8]) -> Option<f64> {
        const POW10: [f64; 23] = [
            1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
            1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
        ];
        let (neg, s) = match tok.first()? {
            b'-' => (true, &tok[1..]),
            b'+' => (false, &tok[1..]),
            _ => (false, tok),
        };
        let (mut m, mut digits, mut exp) = (0u64, 0u32, 0i32);
        let mut i = 0;
        while let Some(d) = s.get(i).filter(|c| c.is_ascii_digit()) {
            m = m.wrapping_mul(10).wrapping_add(u64::from(d - b'0'));
            (digits, i) = (digits + 1, i + 1);
        }
        if s.get(i) == Some(&b'.') {
            i += 1;
            while let Some(d) = s.get(i).filter(|c| c.is_ascii_digit()) {
                m = m.wrapping_mul(10).wrapping_add(u64::from(d - b'0'));
                (digits, i, exp) = (digits + 1, i + 1, exp - 1);
            }
        }
        if digits == 0 || digits > 19 || m > 1 << 53 {
            return None;
        }
        if matches!(s.get(i), Some(b'e' | b'E')) {
            let e = s.get(i + 1..).filter(|e| e.len() <= 4)?;
            exp += i32::try_from(parse_i64(e)?).ok()?;
        } else if i != s.len() {
            return None;
        }
        let v = m as f64;
        let v = match exp {
            0 => v,
            1..=22 => v * POW10[exp as usize],
            -22..=-1 => v / POW10[(-exp) as usize],
            _ => return None,
        };
        Some(if neg { -v } else { v })
    }

    /// A decimal integer with optional sign; `None` on anything else or on overflow.
    #[inline]
    pub(crate) fn parse_i64(tok: &[u8]) -> Option<i64> {
        let (neg, digits) = match tok.first()? {
            b'-' => (true, &tok[1..]),
            b'+' => (false, &tok[1..]),
            _ => (false, tok),
        };
        if digits.is_empty() {
            return None;
        }
        let mut v: i64 = 0;
        for &d in digits {
            if !d.is_ascii_digit() {
                return None;
            }
            v = v.checked_mul(10)?.checked_sub(i64::from(d - b'0'))?;
        }
        if neg {
            Some(v)
        } else {
            v.checked_neg()
        }
    }

    /// A token for an error message: lossy UTF-8, cut to 40 characters.
    pub(crate) fn show(tok: &[u8]) -> String {
        let s = String::from_utf8_lossy(tok);
        if s.chars().count() > 40 {
            let cut: String = s.chars().take(40).collect();
            format!("{cut}…")
        } else {
            s.into_owned()
        }
    }

    #[cfg(test)]
    mod tests {
        use super::*;

        #[test]
        fn floats_match_std() {
            let fixed = [
                "0",
                "-0",
                "1",
                "-1.5",
                ".5",
                "5.",
                "+2.25",
                "1e5",
                "1E-5",
                "1e+05",
                "-0.0503644",
                "0.1",
                "3.4028235e38",
                "1e38",
                "1e-38",
                "9007199254740993",
                "123456789012345678901",
                "0.30000000000000004",
                "1e23",
                "1e-23",
                "4.9e-324",
                "1e400",
                "inf",
                "-NaN",
                "1e",
                "e5",
                ".",
                "-",
                "",
                "1.2.3",
                "0x10",
                "1e99999",
                "00000000000000000001.5",
            ];
            let mut x: u64 = 99;
            let mut cases: Vec<String> = fixed.iter().map(|s| s.to_string()).collect();
            for _ in 0..20_000 {
                x = x
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                let v = f64::from_bits(x >> 2) * if x & 1 == 0 { 1.0 } else { -1.0 };
                cases.push(format!("{v}"));
                cases.push(format!("{v:e}"));
                cases.push(format!("{:.6}", (x >> 40) as f64 / 1e5));
            }
            for c in &cases {
                let want = c.parse::<f64>().ok();
                let got = parse_f64(c.as_bytes());
                let same = match (want, got) {
                    (Some(a), Some(b)) => a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan()),
                    (None, None) => true,
                    _ => false,
                };
                assert!(same, "{c}: std {want:?}, ours {got:?}");
            }
        }

        #[test]
        fn integers_and_lines() {
            assert_eq!(parse_i64(b"-9223372036854775808"), Some(i64::MIN));
            assert_eq!(parse_i64(b"9223372036854775808"), None);
            assert_eq!(parse_i64(b"+7"), Some(7));
            assert_eq!(parse_i64(b"7a"), None);
            let lines: Vec<_> = Lines::new(b"a\r\nb\rc\n\nd").collect();
            let want: Vec<(u64, &[u8])> =
                vec![(1, b"a"), (2, b"b"), (3, b"c"), (4, b""), (5, b"d")];
            assert_eq!(lines, want);
        }
    }
}

/// [`Mesh::memory_needed`].
pub(crate) fn memory_needed(path: &Path) -> Option<u64> {
    let format = MeshFormat::from_path(path)?;
    let (file, meta) = open_regular(path).ok()?;
    if meta.len() == 0 {
        return None;
    }
    // SAFETY: as in `load_with`: a read-only map living only for this call.
    let map = unsafe { memmap2::Mmap::map(&file) }.ok()?;
    // Reading maps the whole file: its size is a floor of the need.
    declared::declared_counts(&map, format)
        .map(|c| crate::input::memory::estimate(c, crate::input::memory::Run::Cut).max(meta.len()))
}

/// The format `path`'s extension names, or the error saying which are known.
pub(crate) fn format_of(path: &Path) -> Result<MeshFormat> {
    MeshFormat::from_path(path).ok_or_else(|| {
        Error::format(
            path,
            "unknown extension: expected .obj, .ply, .stl, .off, .gltf or .glb",
        )
    })
}

/// [`Mesh::load`].
pub(crate) fn load(path: &Path) -> Result<Mesh> {
    load_with(path, &LoadOptions::default())
}

/// [`Mesh::load_with`].
pub(crate) fn load_with(path: &Path, options: &LoadOptions) -> Result<Mesh> {
    let (file, meta) = open_regular(path)?;
    let format = format_of(path)?;
    let max_memory = options.max_memory;
    let run = if options.greedy_only {
        crate::input::memory::Run::Greedy
    } else {
        crate::input::memory::Run::Cut
    };
    file_within(path, meta.len(), max_memory)?;
    let builder = if meta.len() == 0 {
        parse_bytes_with(&[], format, path, options)?
    } else {
        // SAFETY: the map is read-only and lives only for this call; we accept that a
        // concurrent writer truncating the file could fault, as every mmap reader does.
        let map = unsafe { memmap2::Mmap::map(&file) }.map_err(|error| Error::Io {
            path: path.to_path_buf(),
            error,
        })?;
        let declared = declared::declared_counts(&map, format);
        if let (Some(limit), Some(counts)) = (max_memory, declared) {
            crate::input::memory::check(path, counts, run, limit)?;
        }
        parse_bytes_with(&map, format, path, options)?
    };
    if let Some(limit) = max_memory {
        let counts = crate::input::memory::Counts {
            vertices: builder.positions.len() as u64,
            faces: builder.face_count() as u64,
            corners: builder.face_indices.len() as u64,
        };
        crate::input::memory::check(path, counts, run, limit)?;
    }
    let world = options
        .keep_world_coordinates
        .then(|| builder.positions.clone());
    let mut mesh = Mesh::from_builder(builder);
    if mesh.face_count() == 0 {
        return Err(Error::EmptyMesh {
            path: path.to_path_buf(),
        });
    }
    mesh.check_extent(path)?;
    if let Some(world) = world {
        mesh.set_world_coordinates(&world);
    }
    Ok(mesh)
}

/// Refuses a file of `size` bytes over the memory limit: the mapped file becomes
/// resident as it is read, so a file larger than the limit (a sparse file of zeros,
/// say) cannot be read within it.
fn file_within(path: &Path, size: u64, max_memory: Option<u64>) -> Result<()> {
    match max_memory.filter(|&l| size > l) {
        None => Ok(()),
        Some(limit) => Err(Error::format(
            path,
            format!(
                "the file holds {}, more than the memory limit of {} (default: the memory \
                 available now), and reading it maps it into memory whole; raise the limit \
                 with --max-memory SIZE (in the library: the max_memory of \
                 primdecomp::LoadOptions)",
                crate::error::show_bytes(size),
                crate::error::show_bytes(limit)
            ),
        )),
    }
}
