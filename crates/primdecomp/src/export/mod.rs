//! Writers: the JSON result contract ([`to_json`], read back by [`read_primitives`];
//! per-object results with [`to_json_objects`] / [`read_objects`]), a conservative
//! triangle-mesh tessellation of the primitives ([`tessellate`], [`to_obj`]: each
//! tessellated primitive contains the exact one, so the enclosure guarantee holds for
//! the mesh too), the engine exports ([`write_export`]: glTF with Khronos or OMI
//! physics, MuJoCo's MJCF, URDF, USD, Godot scenes; docs/decisions/
//! exports-engine-conventions.md), and crash-safe file replacement ([`write_atomic`]).

mod atomic;
pub(crate) mod contract;
pub(crate) mod engine;
pub(crate) mod frame;
mod gltf;
mod godot;
mod json;
mod mjcf;
pub(crate) mod names;
mod obj;
mod range;
mod urdf;
mod usd;
mod write;
mod xml;

pub use crate::input::up::Up;
pub use atomic::write_atomic;
pub use engine::{ExportOptions, Files, Format, Physics};
pub use frame::Frame;
pub use json::{
    read_objects, read_primitives, to_json, to_json_objects, to_json_timed, ResultObject,
};
pub use names::visible;
pub use obj::{circle_frame, tessellate, to_obj, Tess, DEFAULT_DETAIL, MAX_DETAIL};
pub use write::{render, write_export};

/// The largest result, evaluation or settings file the tools read ([`crate::read_regular`]):
/// 256 MiB holds about a million primitives, far more than any export or viewer page
/// takes, and parsing it stays within about a GiB.
pub const MAX_RESULT_BYTES: u64 = 256 << 20;
