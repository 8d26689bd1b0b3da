//! Output writers: the JSON result contract ([`json`]), a conservative OBJ
//! tessellation of the primitives for viewing and physics engines ([`obj`]), the
//! engine exports (issue 28: [`engine`] with the shared conventions, [`gltf`],
//! [`mjcf`], [`urdf`], [`usd`], [`godot`]), and crash-safe file replacement shared
//! by all ([`atomic`]).

pub mod atomic;
pub mod engine;
pub mod frame;
pub mod gltf;
pub mod godot;
pub mod json;
pub mod mjcf;
pub mod obj;
pub mod urdf;
pub mod usd;
mod xml;

pub use crate::math::quat::{axes_from_quat, quat_from_axes};
pub use atomic::{output_path_for, write_atomic};
pub use engine::{render, write_export, ExportOptions, Files, Format, Physics, Up};
pub use json::{read_objects, read_primitives, to_json, to_json_objects, ResultObject};
pub use obj::{tessellate, to_obj, Tess, DEFAULT_DETAIL};
