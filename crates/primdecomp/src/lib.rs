//! primdecomp: decomposition of any 3D mesh into a small set of tight convex
//! primitives for collision detection, after Knodt & Gao, "Convex Primitive
//! Decomposition for Collision Detection" (the paper, §3).
//!
//! ```no_run
//! let mesh = primdecomp::mesh::io::load("datasets/demo_scene.obj".as_ref())?;
//! let params = primdecomp::Params { targets: vec![40], ..Default::default() };
//! let result = primdecomp::decompose(&mesh, &params)?;
//! println!("{} primitives", result.levels[0].primitives.len());
//! # Ok::<(), primdecomp::Error>(())
//! ```

// Loops over the three axes index several parallel arrays; iterators obscure them.
#![allow(clippy::needless_range_loop)]

pub mod budget;
pub mod decompose;
pub mod demo;
pub mod error;
pub mod export;
pub mod math;
pub mod memory;
pub mod merge;
pub mod mesh;
pub mod objects;
pub mod params;
pub mod postprocess;
pub mod primitive;
pub mod quadric;

pub use decompose::{decompose, Decomposition, InputInfo, Level, Timings};
pub use error::{Error, Result};
pub use mesh::Mesh;
pub use objects::{decompose_objects, ObjectTarget, Objects};
pub use params::{Dedup, Params, Partitions, Reduction, Reprice};
pub use primitive::{Kind, Primitive};
