//! The output stage: what a run hands back ([`result`]: `Decomposition`, `Level`, …)
//! and how it is written. The JSON result contract (`Decomposition::to_json`,
//! `Objects::to_json`, read back by [`ResultFile::read`]), a conservative
//! triangle-mesh tessellation of the primitives (`Primitive::tessellate`,
//! `Level::to_obj`: each tessellated primitive contains the exact one, so the
//! enclosure guarantee holds for the mesh too), crash-safe file replacement
//! ([`write_atomic`]) and the visible escapes of every name written ([`visible`]). The
//! engine exports (glTF, MJCF, URDF, USD, Godot) are the `primdecomp-export` crate,
//! built on these.

mod atomic;
pub(crate) mod contract;
pub(crate) mod frame;
mod json;
mod obj;
mod read;
pub(crate) mod result;
mod visible;

pub use atomic::write_atomic;
pub use frame::Frame;
pub(crate) use obj::tessellate;
pub use obj::Tess;
pub use read::{ResultFile, ResultObject};
pub use visible::visible;
