//! Output writers: the JSON result contract ([`json`]), a conservative OBJ
//! tessellation of the primitives for viewing and physics engines ([`obj`]), and
//! crash-safe file replacement shared by both ([`atomic`]).

pub mod atomic;
pub mod json;
pub mod obj;

pub use crate::math::quat::{axes_from_quat, quat_from_axes};
pub use atomic::{output_path_for, write_atomic};
pub use json::{read_primitives, to_json};
pub use obj::{tessellate, to_obj, Tess, DEFAULT_DETAIL};
