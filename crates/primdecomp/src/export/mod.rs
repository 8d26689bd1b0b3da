//! Writers: the JSON result contract ([`to_json`], read back by [`read_primitives`];
//! per-object results with [`to_json_objects`] / [`read_objects`]), a conservative
//! triangle-mesh tessellation of the primitives ([`tessellate`], [`to_obj`]: each
//! tessellated primitive contains the exact one, so the enclosure guarantee holds for
//! the mesh too), the engine exports ([`write_export`]: glTF with Khronos or OMI
//! physics, MuJoCo's MJCF, URDF, USD, Godot scenes; docs/decisions/
//! exports-engine-conventions.md), and crash-safe file replacement ([`write_atomic`]).

mod atomic;
pub(crate) mod engine;
pub(crate) mod frame;
mod gltf;
mod godot;
mod json;
mod mjcf;
mod obj;
mod urdf;
mod usd;
mod write;
mod xml;

pub use crate::up::Up;
pub use atomic::write_atomic;
pub use engine::{ExportOptions, Files, Format, Physics};
pub use frame::Frame;
pub use json::{
    read_objects, read_primitives, to_json, to_json_objects, to_json_timed, ResultObject,
};
pub use obj::{circle_frame, tessellate, to_obj, Tess, DEFAULT_DETAIL};
pub use write::{render, write_export};
