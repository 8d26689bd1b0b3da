//! Meshes: from a file, from bytes in memory, or from the caller's vertex and index
//! arrays (float or double, triangles or polygons).

use crate::args::{array, handle, optional_text, put, text, writable};
use crate::status::{guard, Failure, PrimdecompStatus};
use primdecomp::Mesh;
use std::ffi::c_char;
use std::path::Path;

/// A mesh ready to decompose. Immutable once made: one mesh may be decomposed from
/// several threads at once. Free it with `primdecomp_mesh_free`.
pub struct PrimdecompMesh {
    pub(crate) mesh: Mesh,
    /// What results record as `input.path` (the CLI writes the path it was given).
    pub(crate) path: Option<String>,
}

fn hand_out(
    out: *mut *mut PrimdecompMesh,
    mesh: Mesh,
    path: Option<String>,
) -> Result<(), Failure> {
    let boxed = Box::into_raw(Box::new(PrimdecompMesh { mesh, path }));
    put(out, boxed, "out")
}

/// Reads the mesh file at `path` (OBJ, PLY, STL, OFF, glTF or GLB, by its extension),
/// exactly as `primdecomp decompose` does; results record `path` as the input's path.
/// On success `*out` holds a new mesh.
///
/// # Safety
/// `path` is a NUL-terminated string; `out` points to writable storage for a pointer.
#[no_mangle]
pub unsafe extern "C" fn primdecomp_mesh_load(
    path: *const c_char,
    out: *mut *mut PrimdecompMesh,
) -> PrimdecompStatus {
    guard(|| {
        writable(out, "out")?;
        let path = text(path, "path")?;
        let mesh = primdecomp::Mesh::load(Path::new(path))?;
        hand_out(out, mesh, Some(path.to_string()))
    })
}

/// Parses a mesh file's `len` bytes already in memory; `name`'s extension says the
/// format (`"part.stl"`), names it in messages and is what results record as the
/// input's path. A `.gltf`'s buffers are `data:` URIs or files inside `name`'s
/// folder, as the CLI reads them.
///
/// # Safety
/// `bytes` points to `len` readable bytes (NULL only when `len` is 0); `name` is a
/// NUL-terminated string; `out` points to writable storage for a pointer.
#[no_mangle]
pub unsafe extern "C" fn primdecomp_mesh_parse(
    bytes: *const u8,
    len: usize,
    name: *const c_char,
    out: *mut *mut PrimdecompMesh,
) -> PrimdecompStatus {
    guard(|| {
        writable(out, "out")?;
        let data = array(bytes, len, "bytes")?;
        let name = text(name, "name")?;
        let path = Path::new(name);
        let format = primdecomp::MeshFormat::from_path(path).ok_or_else(|| {
            Failure::new(
                PrimdecompStatus::InvalidInput,
                format!(
                    "{name}: unknown extension: expected .obj, .ply, .stl, .off, .gltf or .glb"
                ),
            )
        })?;
        let mesh = primdecomp::Mesh::parse(data, format, path)?;
        hand_out(out, mesh, Some(name.to_string()))
    })
}

/// The faces of `indices`: `face_sizes` corners each, or triangles when
/// `face_sizes` is empty.
fn faces<'a>(indices: &'a [u32], face_sizes: &[u32]) -> Result<Vec<&'a [u32]>, Failure> {
    if face_sizes.is_empty() {
        if indices.len() % 3 != 0 {
            return Err(Failure::argument(format!(
                "index_count {} is not a multiple of 3 (triangles, as face_sizes is NULL)",
                indices.len()
            )));
        }
        return Ok(indices.chunks_exact(3).collect());
    }
    let total: u64 = face_sizes.iter().map(|&s| s as u64).sum();
    if total != indices.len() as u64 {
        return Err(Failure::argument(format!(
            "face_sizes add up to {total} corners but index_count is {}",
            indices.len()
        )));
    }
    let mut start = 0;
    Ok(face_sizes
        .iter()
        .map(|&s| {
            let f = &indices[start..start + s as usize];
            start += s as usize;
            f
        })
        .collect())
}

fn from_arrays<T: Copy + Into<f64>>(
    positions: *const T,
    vertex_count: usize,
    indices: *const u32,
    index_count: usize,
    face_sizes: *const u32,
    face_count: usize,
    out: *mut *mut PrimdecompMesh,
) -> PrimdecompStatus {
    guard(|| {
        writable(out, "out")?;
        let n = vertex_count
            .checked_mul(3)
            .ok_or_else(|| Failure::argument("vertex_count is too large"))?;
        let flat = array(positions, n, "positions")?;
        let points: Vec<[f64; 3]> = flat
            .chunks_exact(3)
            .map(|p| [p[0].into(), p[1].into(), p[2].into()])
            .collect();
        let indices = array(indices, index_count, "indices")?;
        let sizes = array(face_sizes, face_count, "face_sizes")?;
        let mesh = Mesh::from_polygons(&points, &faces(indices, sizes)?)?;
        hand_out(out, mesh, None)
    })
}

/// A mesh from `vertex_count` vertices (`positions`: x, y, z of each, doubles) and
/// `index_count` indices into them: triangles when `face_sizes` is NULL, otherwise
/// `face_count` polygons of `face_sizes[i]` corners each (polygons are kept whole, as
/// the file readers keep them; an OBJ's quads given as quads decompose exactly as
/// the CLI decomposes the file). The arrays are copied.
///
/// # Safety
/// Each pointer points to as many readable elements as its count says (NULL only
/// for a count of 0; `positions` holds 3 × `vertex_count` values); `out` points to
/// writable storage for a pointer.
#[no_mangle]
pub unsafe extern "C" fn primdecomp_mesh_from_doubles(
    positions: *const f64,
    vertex_count: usize,
    indices: *const u32,
    index_count: usize,
    face_sizes: *const u32,
    face_count: usize,
    out: *mut *mut PrimdecompMesh,
) -> PrimdecompStatus {
    from_arrays(
        positions,
        vertex_count,
        indices,
        index_count,
        face_sizes,
        face_count,
        out,
    )
}

/// `primdecomp_mesh_from_doubles` for float positions (each converted to double
/// exactly).
///
/// # Safety
/// As for `primdecomp_mesh_from_doubles`.
#[no_mangle]
pub unsafe extern "C" fn primdecomp_mesh_from_floats(
    positions: *const f32,
    vertex_count: usize,
    indices: *const u32,
    index_count: usize,
    face_sizes: *const u32,
    face_count: usize,
    out: *mut *mut PrimdecompMesh,
) -> PrimdecompStatus {
    from_arrays(
        positions,
        vertex_count,
        indices,
        index_count,
        face_sizes,
        face_count,
        out,
    )
}

/// Sets the path results record as the input's (`input.path` in the JSON); NULL or
/// empty records none. For a mesh built from arrays read from a file, so that its
/// JSON names that file as the CLI's does.
///
/// # Safety
/// `mesh` is a mesh from this library, not freed, and not used by another thread
/// during this call; `path` is NULL or a NUL-terminated string.
#[no_mangle]
pub unsafe extern "C" fn primdecomp_mesh_set_path(
    mesh: *mut PrimdecompMesh,
    path: *const c_char,
) -> PrimdecompStatus {
    guard(|| {
        // SAFETY: the caller passes a live mesh no other thread uses meanwhile.
        let m = unsafe { mesh.as_mut() }.ok_or_else(|| Failure::argument("mesh is NULL"))?;
        m.path = optional_text(path, "path")?.map(str::to_string);
        Ok(())
    })
}

/// The mesh's polygon faces (0 for NULL).
///
/// # Safety
/// `mesh` is NULL or a mesh from this library, not freed.
#[no_mangle]
pub unsafe extern "C" fn primdecomp_mesh_face_count(mesh: *const PrimdecompMesh) -> usize {
    handle(mesh, "mesh").map_or(0, |m| m.mesh.face_count())
}

/// The mesh's vertices as given (0 for NULL).
///
/// # Safety
/// `mesh` is NULL or a mesh from this library, not freed.
#[no_mangle]
pub unsafe extern "C" fn primdecomp_mesh_vertex_count(mesh: *const PrimdecompMesh) -> usize {
    handle(mesh, "mesh").map_or(0, |m| m.mesh.vertex_count())
}

/// Frees a mesh (NULL is ignored). Results made from it stay valid.
///
/// # Safety
/// `mesh` is NULL or a mesh from this library, freed only once and not in use.
#[no_mangle]
pub unsafe extern "C" fn primdecomp_mesh_free(mesh: *mut PrimdecompMesh) {
    if !mesh.is_null() {
        // SAFETY: a pointer from Box::into_raw in this module, freed once.
        drop(unsafe { Box::from_raw(mesh) });
    }
}
