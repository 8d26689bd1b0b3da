//! Engine exports of primdecomp results: the colliders of a decomposition written
//! where engines read them — glTF 2.0 / GLB with Khronos (`KHR_implicit_shapes`,
//! `KHR_physics_rigid_bodies`) or OMI physics colliders, MuJoCo MJCF, URDF, USD
//! (`.usda`) and Godot 4 scenes (`.tscn`). Conventions (up axis, scale, which kinds are
//! native shapes and which become convex hulls): docs/decisions/exports-engine-conventions.md.
//!
//! The input is a list of [`primdecomp::Body`]s: one for a whole-mesh result,
//! one per object of a `--per-object` result ([`primdecomp::ResultFile::read`] reads either
//! from the JSON contract). [`render`] gives the bytes, [`write_export`] writes them
//! (through temporary files and renames, [`primdecomp_files::write_atomic`]). Every shape is
//! grown by [`primdecomp::Frame::GROW_REL`] of its magnitude before it is written, so
//! the enclosure guarantee survives the consumer's 32-bit rounding; a result a format's
//! readers could not load (numbers beyond 32-bit floats) is refused with a
//! [`primdecomp::Error`] naming the shape, never written.
//!
//! ```
//! use primdecomp::{Frame, Goal, Params, Body, decompose, demo_scene};
//! use primdecomp_export::{render, ExportOptions, Format};
//!
//! let result = decompose(&demo_scene(), &Params { goal: Goal::counts([40]), ..Params::default() })?;
//! let objects = [Body {
//!     name: "demo".into(),
//!     frame: Frame::IDENTITY,
//!     primitives: result.levels[0].primitives.clone(),
//! }];
//! let files = render(&objects, Format::Mjcf, &ExportOptions::default(), "demo.xml".as_ref())?;
//! let xml = String::from_utf8(files.main).unwrap();
//! assert!(xml.starts_with("<?xml") && xml.contains("<geom"));
//! # Ok::<(), primdecomp::Error>(())
//! ```
//!
//! Errors are the core's [`primdecomp::Error`]: `Format` for options out of range and
//! results a format cannot hold, `Write` for files that cannot be written.

#![deny(missing_docs)]

mod engine;
mod gltf;
mod godot;
mod mjcf;
mod names;
mod range;
mod urdf;
mod usd;
mod write;
mod xml;

pub use engine::{ExportOptions, Files, Format, Physics};
pub use write::{render, write_export};
