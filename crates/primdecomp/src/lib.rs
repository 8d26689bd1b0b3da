//! primdecomp turns any 3D mesh into a small set of tight convex primitives —
//! oriented boxes, spheres, capsules, cylinders, frustums and trapezoidal prisms —
//! for collision detection. It implements Knodt & Gao, "Convex Primitive
//! Decomposition for Collision Detection" (the paper): every face becomes a
//! primitive, and a greedy bottom-up pass merges neighbours, cheapest first, until as
//! many primitives remain as asked for (§3). Every input face lies inside at least
//! one output primitive.
//!
//! # In one page
//!
//! Load a mesh (OBJ, PLY, STL, OFF, glTF/GLB) with [`Mesh::load`], or build one from your
//! own arrays with [`Mesh::from_triangles`] or [`Mesh::from_polygons`]; choose
//! [`Params`] (the defaults are the paper's settings with our documented fixes);
//! call [`decompose`]. The [`Decomposition`] holds one [`Level`] per target count,
//! each a list of [`Primitive`]s in the mesh's own coordinates.
//!
//! ```
//! use primdecomp::{decompose, Goal, Kind, Mesh, Params};
//!
//! // A unit cube as six quads.
//! let corners: Vec<[f64; 3]> = (0..8)
//!     .map(|i| [(i & 1) as f64, (i >> 1 & 1) as f64, (i >> 2 & 1) as f64])
//!     .collect();
//! let quads = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]];
//! let cube = Mesh::from_polygons(&corners, &quads)?;
//!
//! let result = decompose(&cube, &Params { goal: Goal::counts([1]), ..Params::default() })?;
//! let level = &result.levels[0];
//! assert_eq!(level.primitives.len(), 1);
//! assert_eq!(level.primitives[0].kind(), Kind::Box);
//! // The enclosure guarantee: every corner lies in the box.
//! assert!(corners.iter().all(|&c| level.primitives[0].contains(c, 1e-9)));
//! # Ok::<(), primdecomp::Error>(())
//! ```
//!
//! Several targets come from one pass, coarse levels of detail for free:
//!
//! ```
//! use primdecomp::{decompose, Goal, Mesh, Params};
//!
//! // The built-in demo: stairs, a table, pipes, a house, a torus and a washer.
//! let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../datasets/demo_scene.obj");
//! let scene = Mesh::load(path.as_ref())?;
//! let params = Params { goal: Goal::counts([200, 50]), ..Params::default() };
//! let result = decompose(&scene, &params)?;
//! for level in &result.levels {
//!     println!("{} primitives, {} bytes", level.primitives.len(), level.bytes());
//!     assert!(level.primitives.len() <= level.target);
//! }
//! # Ok::<(), primdecomp::Error>(())
//! ```
//!
//! Long runs report progress and can be cancelled from another thread through a
//! [`Progress`] ([`decompose_with`]). Results are written with
//! [`Decomposition::to_json`] (the JSON contract the command line writes too, readable
//! again with [`ResultFile::read`]) or as a conservative triangle mesh with
//! [`Primitive::tessellate`] / [`Level::to_obj`] (each tessellated primitive contains
//! the exact one). Everything is deterministic: the
//! same mesh and settings give the same primitives on any number of threads.
//!
//! Errors are one type, [`Error`], naming the file and the line or byte offset where
//! an input is malformed; nothing in this crate panics on bad input.

// Every public item documented; the internals the tests reach are not public API.
#![cfg_attr(not(feature = "test-internals"), deny(missing_docs))]
// Loops over the three axes index several parallel arrays; iterators obscure them.
#![allow(clippy::needless_range_loop)]

mod cut;
mod decompose;
mod error;
mod input;
mod merge;
mod output;
mod params;
mod postprocess;
mod primitive;
mod progress;
mod seed;

// The shared linear algebra, under the name the stages import it by.
use primdecomp_math as math;

pub use decompose::objects::{ObjectResult, Objects};
pub use decompose::tiles::Tiled;
pub use decompose::{decompose, decompose_with};
pub use error::Error;
#[cfg(feature = "demo-scene")]
pub use input::demo::demo_scene;
pub use input::io::{LoadOptions, MeshFormat};
pub use input::mesh::Mesh;
pub use input::up::Up;
pub use output::result::{Decomposition, InputInfo, Level, Shortfall, Stats};
pub use output::{Body, Frame, ResultFile, Tess};
pub use params::{Dedup, Fit, Goal, Params, Partitions, Plates, Reprice, Target, Tolerance};
pub use primitive::{Capsule, Cylinder, Frustum, Kind, Obb, Primitive, Prism, Sphere};
pub use progress::{Progress, Stage};

/// The stages one by one, for the project's own tests and benchmarks (feature
/// `test-internals`, which the workspace's test helpers turn on). Not part of the
/// API: no documentation promises and no stability.
#[cfg(feature = "test-internals")]
#[doc(hidden)]
#[allow(missing_docs)]
pub mod internals {
    pub use crate::input::dedup::{weld, Weld};
    pub use crate::input::mesh::outward_normal;
    use crate::input::mesh::Mesh;
    pub use crate::input::orient::face_signs_of_lists;
    use crate::math::Sym3;
    pub use crate::merge::cluster::Clusters;
    pub use crate::merge::cost::{Fitter, Workspace};
    use crate::merge::driver::MergeOutput;
    pub use crate::merge::heap::StdHeap;
    pub use crate::merge::rim::{FaceAdjacency, Surroundings};
    pub use crate::merge::setup::fitter;
    pub use crate::merge::worker::with_pricer;
    pub use crate::params::{AUTO_MIN_FACES, AUTO_PARTS};
    pub use crate::postprocess::nested::{keep_mask, Cleanup};

    /// Faces sharing an edge, by the faces' corners welded by `weld`.
    pub fn face_pairs(mesh: &Mesh, weld: &Weld) -> Vec<(u32, u32)> {
        let (offsets, indices) = (&mesh.face_offsets, &mesh.face_indices);
        crate::input::adjacency::face_pairs_checked(offsets, indices, weld, &|_| true)
            .map_or_else(Vec::new, |(pairs, _)| pairs)
    }
    pub use crate::input::adjacency::neighbour_lists;

    pub use crate::seed::quadric::face_quadrics;

    /// Each face's seed volume.
    pub fn seed_volumes(fitter: &Fitter, q: &[Sym3]) -> Vec<f64> {
        crate::merge::setup::seed_volumes(fitter, q, &|_| true)
    }

    /// The merge loop through `targets` (decreasing).
    pub fn run(fitter: &Fitter, cl: Clusters, targets: &[usize]) -> MergeOutput {
        crate::merge::driver::run(fitter, cl, targets, &|_| true)
    }

    /// The merge loop on another queue.
    pub fn run_with<Q: crate::merge::heap::Queue>(
        fitter: &Fitter,
        cl: Clusters,
        targets: &[usize],
    ) -> MergeOutput {
        crate::merge::driver::run_with::<Q>(fitter, cl, targets, &|_| true)
    }
}
