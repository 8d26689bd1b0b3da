//! Everything this crate takes from the core and the evaluation crate, in one place:
//! loading an input mesh, reading a result document's primitives, tessellating a
//! primitive and loading peer hulls. (The core's public API is being reorganised;
//! these are the only call sites to move.)

use primdecomp::Error;
use primdecomp::{Kind, Primitive};
use std::path::Path;

/// Results with the library's one error type.
type Result<T> = std::result::Result<T, Error>;

/// An input mesh as polygons in world coordinates.
pub struct InputMesh {
    pub positions: Vec<[f64; 3]>,
    /// Polygons (≥ 3 vertex indices each) as the file has them.
    pub polygons: Vec<Vec<u32>>,
}

/// Loads any input mesh the core reads (OBJ, PLY, STL, OFF, glTF/GLB) with `options`
/// (the memory limit, the glTF URI policy).
pub fn load_input(path: &Path, options: &primdecomp::LoadOptions) -> Result<InputMesh> {
    Ok(from_core_mesh(&primdecomp::Mesh::load_with(path, options)?))
}

/// The world-coordinate polygons of a mesh the core loaded.
pub fn from_core_mesh(mesh: &primdecomp::Mesh) -> InputMesh {
    InputMesh {
        positions: (0..mesh.vertex_count() as u32)
            .map(|v| mesh.world_pos(v))
            .collect(),
        polygons: (0..mesh.face_count())
            .map(|f| mesh.face(f).to_vec())
            .collect(),
    }
}

/// The primitives of a result document (its `primitives` array).
pub fn read_primitives(json: &str, path: &Path) -> Result<Vec<Primitive>> {
    Ok(primdecomp::ResultFile::read(json, path)?.primitives)
}

/// The kind of a primitive.
pub fn kind(p: &Primitive) -> Kind {
    p.kind()
}

/// A primitive's conservative closed tessellation: vertices and outward polygons.
pub fn tessellate(p: &Primitive, detail: usize) -> (Vec<[f64; 3]>, Vec<Vec<u32>>) {
    let t = p.tessellate(detail);
    (t.vertices, t.faces)
}

/// One convex hull: vertices and the triangles indexing them.
pub type Hull = (Vec<[f64; 3]>, Vec<[u32; 3]>);

/// Convex hulls from an OBJ file, one per `o`/`g` (CoACD's and V-HACD's output), each
/// as vertices and triangles.
pub fn load_hulls(path: &Path) -> Result<Vec<Hull>> {
    let is_obj = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("obj"));
    if !is_obj {
        return Err(Error::format(
            path,
            "--compare takes convex hulls as OBJ (one `o`/`g` per hull)",
        ));
    }
    match primdecomp_eval::collider::load(path)? {
        primdecomp_eval::collider::Collider::Hulls(h) => {
            Ok(h.into_iter().map(|h| (h.positions, h.triangles)).collect())
        }
        primdecomp_eval::collider::Collider::Primitives(_) => {
            Err(Error::format(path, "expected convex hulls in an OBJ file"))
        }
    }
}
