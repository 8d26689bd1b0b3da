//! A finished decomposition for JavaScript: the CLI's JSON document of each level
//! (the JavaScript side builds its typed primitives from it, numbers exact), the
//! engine exports in memory, and the tessellation the live page draws.

use crate::js_error;
use primdecomp::{Body, Decomposition, Frame, Level, Params, Up};
use primdecomp_export::{render, ExportOptions, Format, Physics};
use wasm_bindgen::prelude::*;

/// A decomposition and the settings that made it.
#[wasm_bindgen(js_name = Result)]
pub struct WasmResult {
    dec: Decomposition,
    params: Params,
    /// The mesh's centre: tessellations are drawn relative to it.
    centre: [f64; 3],
}

/// Triangles of a level's primitives (their conservative tessellation), for drawing.
#[wasm_bindgen]
pub struct Tessellation {
    positions: Vec<f32>,
    indices: Vec<u32>,
    starts: Vec<u32>,
    kinds: Vec<u8>,
}

#[wasm_bindgen]
impl Tessellation {
    /// Vertices relative to the mesh's centre (x, y, z each).
    pub fn positions(&self) -> Vec<f32> {
        self.positions.clone()
    }
    /// Three vertex indices per triangle.
    pub fn indices(&self) -> Vec<u32> {
        self.indices.clone()
    }
    /// Primitive `i`'s triangles are `starts[i]..starts[i + 1]`.
    pub fn starts(&self) -> Vec<u32> {
        self.starts.clone()
    }
    /// Each primitive's kind (0 box … 5 prism).
    pub fn kinds(&self) -> Vec<u8> {
        self.kinds.clone()
    }
}

impl WasmResult {
    pub(crate) fn new(dec: Decomposition, params: Params, centre: [f64; 3]) -> WasmResult {
        WasmResult {
            dec,
            params,
            centre,
        }
    }

    fn level(&self, i: usize) -> Result<&Level, JsError> {
        self.dec.levels.get(i).ok_or_else(|| {
            js_error(format!(
                "level {i} out of range: the result has {} levels",
                self.dec.levels.len()
            ))
        })
    }
}

#[wasm_bindgen(js_class = Result)]
impl WasmResult {
    /// Levels, one per target.
    #[wasm_bindgen(getter, js_name = levelCount)]
    pub fn level_count(&self) -> usize {
        self.dec.levels.len()
    }

    /// The centre of the mesh's bounding box, which tessellations are relative to.
    pub fn centre(&self) -> Vec<f64> {
        self.centre.to_vec()
    }

    /// A level's JSON document, byte for byte the CLI's for the same file and
    /// settings.
    pub fn json(&self, level: usize) -> Result<String, JsError> {
        self.level(level)?;
        Ok(self.dec.to_json(level, &self.params))
    }

    /// A level in `format` (`obj`, `gltf`, `glb`, `mjcf`, `urdf`, `usda`, `tscn`) as
    /// `primdecomp decompose --export` writes it, the model named `model`; `up_z`,
    /// `scale`, `omi`, `preview`, `urdf_capsule` and `detail` are the CLI's export
    /// flags. A URDF whose frustums or prisms need mesh files beside it is refused.
    #[allow(clippy::too_many_arguments)]
    pub fn export(
        &self,
        level: usize,
        format: &str,
        model: &str,
        up_z: bool,
        scale: f64,
        omi: bool,
        preview: bool,
        urdf_capsule: bool,
        detail: usize,
    ) -> Result<Vec<u8>, JsError> {
        let lv = self.level(level)?;
        if format.eq_ignore_ascii_case("obj") {
            return Ok(lv.to_obj(detail.max(3)).into_bytes());
        }
        let f = Format::from_name(format).ok_or_else(|| {
            js_error(format!(
                "unknown format \"{format}\": expected json, obj, gltf, glb, mjcf, urdf, usda or tscn"
            ))
        })?;
        let opts = ExportOptions {
            up: if up_z { Up::Z } else { Up::Y },
            scale,
            detail,
            physics: if omi { Physics::Omi } else { Physics::Khr },
            preview,
            urdf_capsule,
            model: model.to_string(),
            input_mesh: None,
        };
        opts.validate().map_err(js_error)?;
        let objects = [Body {
            name: String::new(),
            frame: Frame::IDENTITY,
            primitives: lv.primitives.clone(),
        }];
        // In memory the model's name stands for the path (it names files beside).
        let files = render(&objects, f, &opts, std::path::Path::new(model)).map_err(js_error)?;
        if let Some((name, _)) = files.beside.first() {
            return Err(js_error(format!(
                "{} needs files beside the main one ({name}); in memory only single-file formats",
                f.name()
            )));
        }
        Ok(files.main)
    }

    /// The conservative tessellation of a level's primitives with `detail` segments
    /// around circles, relative to the mesh's centre.
    pub fn tessellate(&self, level: usize, detail: usize) -> Result<Tessellation, JsError> {
        let lv = self.level(level)?;
        let mut t = Tessellation {
            positions: Vec::new(),
            indices: Vec::new(),
            starts: vec![0],
            kinds: Vec::new(),
        };
        for p in &lv.primitives {
            let base = (t.positions.len() / 3) as u32;
            let tess = p.tessellate(detail.max(3));
            for v in &tess.vertices {
                t.positions
                    .extend((0..3).map(|k| (v[k] - self.centre[k]) as f32));
            }
            for f in &tess.faces {
                for k in 1..f.len().saturating_sub(1) {
                    t.indices
                        .extend([base + f[0], base + f[k], base + f[k + 1]]);
                }
            }
            t.starts.push((t.indices.len() / 3) as u32);
            t.kinds.push(p.kind() as u8);
        }
        Ok(t)
    }
}
