//! Meshes for JavaScript: a file's bytes read by the core's readers, or vertex and
//! index arrays (triangles, or polygons with their corner counts).

use crate::js_error;
use primdecomp::Mesh;
use std::path::Path;
use wasm_bindgen::prelude::*;

/// A mesh ready to decompose.
#[wasm_bindgen(js_name = Mesh)]
pub struct WasmMesh {
    pub(crate) mesh: Mesh,
    /// What results record as `input.path` (the name given, as the CLI records its
    /// argument).
    pub(crate) path: Option<String>,
}

/// The mesh in a file's `bytes`; `name`'s extension says the format (`part.stl`) and
/// results record it as the input's path. glTF buffers must be embedded (`data:`
/// URIs) or in the GLB.
#[wasm_bindgen(js_name = parseMesh)]
pub fn parse_mesh(bytes: &[u8], name: &str) -> Result<WasmMesh, JsError> {
    let path = Path::new(name);
    let format = primdecomp::MeshFormat::from_path(path).ok_or_else(|| {
        js_error(format!(
            "{name}: unknown extension: expected .obj, .ply, .stl, .off, .gltf or .glb"
        ))
    })?;
    let mesh = primdecomp::Mesh::parse(bytes, format, path).map_err(js_error)?;
    Ok(WasmMesh {
        mesh,
        path: Some(name.to_string()),
    })
}

/// The faces of `indices`: `sizes` corners each, or triangles when `sizes` is empty.
fn faces<'a>(indices: &'a [u32], sizes: &[u32]) -> Result<Vec<&'a [u32]>, JsError> {
    if sizes.is_empty() {
        if indices.len() % 3 != 0 {
            return Err(js_error(format!(
                "{} indices are not whole triangles (give faceSizes for polygons)",
                indices.len()
            )));
        }
        return Ok(indices.chunks_exact(3).collect());
    }
    let total: u64 = sizes.iter().map(|&s| s as u64).sum();
    if total != indices.len() as u64 {
        return Err(js_error(format!(
            "faceSizes add up to {total} corners but there are {} indices",
            indices.len()
        )));
    }
    let mut start = 0;
    Ok(sizes
        .iter()
        .map(|&s| {
            let f = &indices[start..start + s as usize];
            start += s as usize;
            f
        })
        .collect())
}

fn from_points(
    points: Vec<[f64; 3]>,
    indices: &[u32],
    sizes: &[u32],
    path: Option<String>,
) -> Result<WasmMesh, JsError> {
    let mesh = Mesh::from_polygons(&points, &faces(indices, sizes)?).map_err(js_error)?;
    Ok(WasmMesh { mesh, path })
}

fn check_xyz(n: usize) -> Result<(), JsError> {
    match n % 3 {
        0 => Ok(()),
        _ => Err(js_error(format!(
            "{n} coordinates are not whole (x, y, z) vertices"
        ))),
    }
}

/// A mesh from double coordinates (x, y, z per vertex) and indices: triangles, or
/// polygons of `face_sizes[i]` corners (kept whole, as the file readers keep them).
#[wasm_bindgen(js_name = meshFromF64)]
pub fn mesh_from_f64(
    positions: &[f64],
    indices: &[u32],
    face_sizes: &[u32],
    path: Option<String>,
) -> Result<WasmMesh, JsError> {
    check_xyz(positions.len())?;
    let points = positions
        .chunks_exact(3)
        .map(|p| [p[0], p[1], p[2]])
        .collect();
    from_points(points, indices, face_sizes, path)
}

/// [`mesh_from_f64`] for float coordinates (each converted to double exactly).
#[wasm_bindgen(js_name = meshFromF32)]
pub fn mesh_from_f32(
    positions: &[f32],
    indices: &[u32],
    face_sizes: &[u32],
    path: Option<String>,
) -> Result<WasmMesh, JsError> {
    check_xyz(positions.len())?;
    let points = positions
        .chunks_exact(3)
        .map(|p| [p[0] as f64, p[1] as f64, p[2] as f64])
        .collect();
    from_points(points, indices, face_sizes, path)
}

#[wasm_bindgen(js_class = Mesh)]
impl WasmMesh {
    /// Polygon faces.
    #[wasm_bindgen(getter, js_name = faceCount)]
    pub fn face_count(&self) -> usize {
        self.mesh.face_count()
    }

    /// Vertices as given.
    #[wasm_bindgen(getter, js_name = vertexCount)]
    pub fn vertex_count(&self) -> usize {
        self.mesh.vertex_count()
    }

    /// The name results record as the input's path.
    #[wasm_bindgen(getter)]
    pub fn path(&self) -> Option<String> {
        self.path.clone()
    }

    /// The centre of the mesh's bounding box: [`WasmMesh::triangle_positions`] and
    /// the tessellations are relative to it.
    pub fn centre(&self) -> Vec<f64> {
        self.mesh.centre().to_vec()
    }

    /// Every vertex relative to [`WasmMesh::centre`], as floats (x, y, z each), for
    /// drawing.
    #[wasm_bindgen(js_name = trianglePositions)]
    pub fn triangle_positions(&self) -> Vec<f32> {
        (0..self.mesh.vertex_count() as u32)
            .flat_map(|v| self.mesh.pos(v).map(|c| c as f32))
            .collect()
    }

    /// The faces fanned into triangles (three indices each), for drawing.
    #[wasm_bindgen(js_name = triangleIndices)]
    pub fn triangle_indices(&self) -> Vec<u32> {
        (0..self.mesh.face_count())
            .flat_map(|f| {
                let p = self.mesh.face(f);
                (1..p.len().saturating_sub(1)).flat_map(move |k| [p[0], p[k], p[k + 1]])
            })
            .collect()
    }
}
