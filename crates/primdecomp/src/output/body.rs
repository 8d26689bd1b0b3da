//! One body of a result: a name, a frame and primitives in that frame, as the
//! exporters take it; what a per-object run's level gives (`Objects::bodies`) and
//! what a result file reads back into (`ResultFile::objects`).

use super::frame::Frame;
use crate::primitive::Primitive;

/// One body of a result, what the exporters write as one node (a glTF node, an MJCF
/// body, a URDF link, a Godot static body, a USD prim): a name, a frame and the
/// primitives in that frame. An entry of a per-object result's `objects`; a result
/// without `objects` is one unnamed body in the world frame. (A per-object run's own
/// result, with each object's whole decomposition, is [`crate::ObjectResult`].)
///
/// ```
/// use primdecomp::{Frame, ResultFile};
///
/// let doc = r#"{"format": "primdecomp", "version": 1,
///   "primitives": [{"kind": "sphere", "center": [1, 2, 3], "radius": 0.5}]}"#;
/// let object = &ResultFile::read(doc, "r.json".as_ref())?.objects[0];
/// assert_eq!((object.name.as_str(), object.frame), ("", Frame::IDENTITY));
/// # Ok::<(), primdecomp::Error>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Body {
    /// The object's name (empty for a result without `objects`).
    pub name: String,
    /// Its frame: world = `frame.point(local)`.
    pub frame: Frame,
    /// Its primitives in local coordinates.
    pub primitives: Vec<Primitive>,
}
