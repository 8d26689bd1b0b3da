//! Writers: the JSON result contract ([`to_json`], read back by [`read_primitives`]),
//! a conservative triangle-mesh tessellation of the primitives ([`tessellate`],
//! [`to_obj`]: each tessellated primitive contains the exact one, so the enclosure
//! guarantee holds for the mesh too), and crash-safe file replacement
//! ([`write_atomic`]).

mod atomic;
mod json;
mod obj;

pub use atomic::write_atomic;
pub use json::{read_primitives, to_json, to_json_timed};
pub use obj::{circle_frame, tessellate, to_obj, Tess, DEFAULT_DETAIL};
