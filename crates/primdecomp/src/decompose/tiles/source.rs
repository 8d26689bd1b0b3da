//! Where a tiled run's faces come from (docs/decisions/out-of-core-tiles.md): the
//! memory-mapped binary PLY, read a tile at a time with its pages released as a pass
//! goes, or any other format parsed whole; and the file's identity (size and content
//! hash), which ties a plan and its tile results to their input.

use super::{Identity, RELEASE_EVERY};
use crate::error::{Error, Result};
use crate::input::io::{format_of, LoadOptions, MeshFormat, PlyLayout};
use crate::input::mesh::Mesh;
use crate::math::V3;
use primdecomp_files::open_regular;
use std::path::Path;

/// Opens the mesh in `path` for a tiled run: the memory-mapped binary PLY, or the
/// mesh parsed whole; with the file's size and content hash.
pub(super) fn open<'p>(path: &'p Path, options: &LoadOptions) -> Result<(Source<'p>, Identity)> {
    let (file, meta) = open_regular(path)?;
    let format = format_of(path)?;
    if meta.len() == 0 {
        return Err(Error::EmptyMesh {
            path: path.to_path_buf(),
        });
    }
    // SAFETY: read-only and private to this call; a concurrent writer truncating the
    // file could fault, as for every mmap reader (`load_with`).
    let map = unsafe { memmap2::Mmap::map(&file) }.map_err(|error| Error::Io {
        path: path.to_path_buf(),
        error,
    })?;
    let input = Identity {
        size: meta.len(),
        hash: content_hash(&map),
    };
    let layout = match format {
        MeshFormat::Ply => PlyLayout::of(&map, path)?,
        _ => None,
    };
    let source = match layout {
        Some(layout) => Source::Mapped { map, layout, path },
        None => Source::Whole(whole(path, options)?),
    };
    Ok((source, input))
}

/// The xxh3-128 hash of the mapped file, its pages released as the hash goes.
fn content_hash(map: &memmap2::Mmap) -> u128 {
    let mut hasher = xxhash_rust::xxh3::Xxh3::new();
    for (i, chunk) in map.chunks(RELEASE_EVERY).enumerate() {
        hasher.update(chunk);
        release(map, i * RELEASE_EVERY, chunk.len());
    }
    hasher.digest128()
}

/// The whole mesh parsed, for a format not read a tile at a time: refused when the
/// parsed mesh alone (its positions and polygons) exceeds the limit.
fn whole(path: &Path, options: &LoadOptions) -> Result<Mesh> {
    let unlimited = LoadOptions {
        max_memory: None,
        ..options.clone()
    };
    if let (Some(limit), Ok((_, meta))) = (options.max_memory, open_regular(path)) {
        // The parse maps the file whole: `load_with`'s refusal of a file over the limit.
        if meta.len() > limit {
            Mesh::load_with(path, options)?;
        }
    }
    let mesh = Mesh::load_with(path, &unlimited)?;
    if let Some(limit) = options.max_memory {
        let need = mesh_bytes(
            mesh.vertex_count() as u64,
            mesh.face_count() as u64,
            mesh.face_indices.len() as u64,
        );
        if need > limit {
            return Err(too_large(path, need, limit));
        }
    }
    Ok(mesh)
}

/// Bytes a parsed [`Mesh`] holds: three f64 a vertex, a u32 a corner and a face.
fn mesh_bytes(vertices: u64, faces: u64, corners: u64) -> u64 {
    vertices
        .saturating_mul(24)
        .saturating_add(corners.saturating_mul(4))
        .saturating_add(faces.saturating_mul(4))
}

/// The parsed mesh alone needs `need` bytes, over `limit`.
fn too_large(path: &Path, need: u64, limit: u64) -> Error {
    let why = "only binary PLY is read a tile at a time (other formats and ASCII PLY are \
               parsed whole first; convert the file to binary PLY)";
    Error::format(
        path,
        format!(
            "read whole before it is cut into tiles, its positions and polygons hold {}, more \
             than the memory limit of {}: \
             {why}; raise the limit with --max-memory SIZE (in the library: the max_memory \
             of primdecomp::LoadOptions)",
            crate::error::show_bytes(need),
            crate::error::show_bytes(limit)
        ),
    )
}

/// Where the faces come from: the memory-mapped binary PLY, or a parsed mesh.
pub(super) enum Source<'p> {
    Mapped {
        map: memmap2::Mmap,
        layout: PlyLayout,
        path: &'p Path,
    },
    Whole(Mesh),
}

impl Source<'_> {
    pub(super) fn vertex_count(&self) -> usize {
        match self {
            Source::Mapped { layout, .. } => layout.vertex_count as usize,
            Source::Whole(m) => m.vertex_count(),
        }
    }

    /// Bytes the source keeps resident through the run: the parsed mesh, or the
    /// mapped vertices (read at random while faces are scanned) and the face data
    /// read since the last release.
    pub(super) fn resident(&self) -> u64 {
        match self {
            Source::Mapped { layout, .. } => {
                layout.vertex_bytes().saturating_add(RELEASE_EVERY as u64)
            }
            Source::Whole(m) => mesh_bytes(
                m.vertex_count() as u64,
                m.face_count() as u64,
                m.face_indices.len() as u64,
            ),
        }
    }

    pub(super) fn face_count_declared(&self) -> u64 {
        match self {
            Source::Mapped { layout, .. } => layout.face_count,
            Source::Whole(m) => m.face_count() as u64,
        }
    }

    /// Vertex `v`'s world position (`v` in range; the mapped file's checked by
    /// [`Source::vertices`]).
    pub(super) fn pos(&self, v: u32) -> V3 {
        match self {
            Source::Mapped { map, layout, .. } => layout.pos(map, v as usize),
            Source::Whole(m) => m.world_pos(v),
        }
    }

    /// Visits every vertex's world position in order; the mapped file's are checked
    /// (present and finite) with the whole parse's messages.
    pub(super) fn vertices(&self, mut visit: impl FnMut(V3)) -> Result<()> {
        match self {
            Source::Mapped { map, layout, path } => {
                let r = layout.vertices(map, path, visit);
                release(map, 0, map.len());
                r
            }
            Source::Whole(m) => {
                (0..m.vertex_count() as u32).for_each(|v| visit(m.world_pos(v)));
                Ok(())
            }
        }
    }

    /// Visits every face's corners in order (an index out of range or data that
    /// ends early is the whole parse's error). The mapped pages read are released
    /// as the scan goes, so a pass keeps little of the file resident.
    pub(super) fn faces(&self, mut visit: impl FnMut(&[u32])) -> Result<()> {
        match self {
            Source::Mapped { map, layout, path } => {
                let mut released = 0;
                let r = layout.faces(map, path, |corners, at| {
                    visit(corners);
                    if at >= released + RELEASE_EVERY {
                        release(map, released, at - released);
                        released = at;
                    }
                });
                release(map, 0, map.len());
                r
            }
            Source::Whole(m) => {
                (0..m.face_count()).for_each(|f| visit(m.face(f)));
                Ok(())
            }
        }
    }
}

/// Drops the mapped pages of `len` bytes from `offset` from this process's resident
/// memory (they are the file's, read again if needed).
fn release(map: &memmap2::Mmap, offset: usize, len: usize) {
    #[cfg(unix)]
    {
        let page = 4096;
        let start = offset / page * page;
        let len = (offset + len).min(map.len()) - start;
        // SAFETY: the map is read-only and file-backed: dropped pages read back from
        // the file, unchanged.
        let _ =
            unsafe { map.unchecked_advise_range(memmap2::UncheckedAdvice::DontNeed, start, len) };
    }
    #[cfg(not(unix))]
    let _ = (map, offset, len);
}
