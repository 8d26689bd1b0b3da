//! The output stage: what a run hands back ([`result`]: `Decomposition`, `Level`, …)
//! and how it is written. The JSON result contract ([`to_json`], read back by [`read_primitives`];
//! per-object results with [`to_json_objects`] / [`read_objects`]), a conservative
//! triangle-mesh tessellation of the primitives ([`tessellate`], [`to_obj`]: each
//! tessellated primitive contains the exact one, so the enclosure guarantee holds for
//! the mesh too), crash-safe file replacement ([`write_atomic`]) and the visible
//! escapes of every name written ([`visible`]). The engine exports (glTF, MJCF, URDF,
//! USD, Godot) are the `primdecomp-export` crate, built on these.

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
pub use json::{to_json, to_json_objects, to_json_timed};
pub use obj::{circle_frame, tessellate, to_obj, Tess, DEFAULT_DETAIL, MAX_DETAIL};
pub use read::{read_objects, read_primitives, ResultObject};
pub use visible::visible;

/// The largest result, evaluation or settings file the tools read ([`crate::read_regular`]):
/// 256 MiB holds about a million primitives, far more than any export or viewer page
/// takes, and parsing it stays within about a GiB.
pub const MAX_RESULT_BYTES: u64 = 256 << 20;
