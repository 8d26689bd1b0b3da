//! The output stage: what a run hands back ([`result`]: `Decomposition`, `Level`, …)
//! and how it is written. The JSON result contract (`Decomposition::to_json`,
//! `Objects::to_json`, read back by [`ResultFile::read`]), a conservative
//! triangle-mesh tessellation of the primitives (`Primitive::tessellate`,
//! `Level::to_obj`: each tessellated primitive contains the exact one, so the
//! enclosure guarantee holds for the mesh too). Files are written and names escaped
//! by the `primdecomp-files` crate. The engine exports (glTF, MJCF, URDF, USD, Godot) are the `primdecomp-export` crate,
//! built on these.

pub(crate) mod body;
pub(crate) mod contract;
pub(crate) mod frame;
mod json;
mod obj;
mod read;
pub(crate) mod result;

pub use body::Body;
pub use frame::Frame;
pub(crate) use obj::tessellate;
pub use obj::Tess;
pub use read::ResultFile;
