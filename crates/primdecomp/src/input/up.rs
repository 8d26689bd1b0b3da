//! Which axis points up in an input, and what a file format says about it
//! (docs/decisions/0053-up-axis-per-input-format.md): glTF is +Y up by its
//! specification; STL, OBJ, PLY and OFF say nothing, so an axis is assumed per format
//! (STL +Z, as CAD and robot parts mostly are; the others +Y, as modelling tools and
//! scanners mostly write them). A result records the axis and where it came from
//! ([`crate::InputInfo::up`]), and the exports and the viewer read it from there.

use crate::input::io::MeshFormat;
use serde::{Serialize, Serializer};

/// An up axis.
///
/// ```
/// use primdecomp::{MeshFormat, Up};
///
/// assert_eq!(Up::of_format(MeshFormat::Glb).0, Up::Y);
/// assert_eq!(Up::from_axis("z"), Some(Up::Z));
/// assert_eq!(Up::default(), Up::Y);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Up {
    /// +Y up (glTF, Godot).
    #[default]
    Y,
    /// +Z up (MuJoCo, URDF, most CAD).
    Z,
}

impl Up {
    /// `"Y"` or `"Z"`, as USD's `upAxis` spells it.
    pub fn name(self) -> &'static str {
        match self {
            Up::Y => "Y",
            Up::Z => "Z",
        }
    }

    /// `"y"` or `"z"`, as results and the command line spell it.
    ///
    /// ```
    /// use primdecomp::Up;
    /// assert_eq!(Up::from_axis("Z"), Some(Up::Z));
    /// assert_eq!(Up::Z.axis(), "z");
    /// ```
    pub fn axis(self) -> &'static str {
        match self {
            Up::Y => "y",
            Up::Z => "z",
        }
    }

    /// The axis named `y` or `z` (either case); `None` otherwise.
    pub fn from_axis(s: &str) -> Option<Up> {
        match s.trim() {
            "y" | "Y" => Some(Up::Y),
            "z" | "Z" => Some(Up::Z),
            _ => None,
        }
    }

    /// The up axis of a file of `format` and why: declared by glTF's specification,
    /// assumed for the formats that say nothing.
    ///
    /// ```
    /// use primdecomp::{MeshFormat, Up};
    /// assert_eq!(Up::of_format(MeshFormat::Stl).0, Up::Z);
    /// assert_eq!(Up::of_format(MeshFormat::Glb).0, Up::Y);
    /// ```
    pub fn of_format(format: MeshFormat) -> (Up, &'static str) {
        match format {
            MeshFormat::Gltf | MeshFormat::Glb => (Up::Y, "glTF is +Y up by its specification"),
            MeshFormat::Stl => (
                Up::Z,
                "assumed: STL says nothing, and CAD and robot parts are mostly +Z up",
            ),
            MeshFormat::Obj => (
                Up::Y,
                "assumed: OBJ says nothing, and modelling tools mostly write +Y up",
            ),
            MeshFormat::Ply => (
                Up::Y,
                "assumed: PLY says nothing, and scans and modelling tools mostly write +Y up",
            ),
            MeshFormat::Off => (
                Up::Y,
                "assumed: OFF says nothing, and modelling tools mostly write +Y up",
            ),
        }
    }
}

impl Serialize for Up {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.axis())
    }
}
