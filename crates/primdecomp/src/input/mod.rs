//! The input stage: reading a mesh file and understanding it before any primitive is
//! fitted (§3: V and polygon faces F). The readers ([`io`]) fill a [`mesh::Mesh`];
//! vertices are welded ([`dedup`]), faces sharing an edge found ([`adjacency`]), each
//! face's outside side chosen ([`orient`], [`visibility`]) and, with `solid`, the
//! interior voxelised ([`solid`]). [`triangles`] keeps the input's triangles under a
//! hierarchy for the cut and thickened plates; [`up`] says which axis points up,
//! [`memory`] what a run on the input will need, and [`demo`] builds the built-in
//! demo scene.

pub(crate) mod adjacency;
pub(crate) mod dedup;
#[cfg(any(test, feature = "demo-scene"))]
pub(crate) mod demo;
pub(crate) mod io;
pub(crate) mod memory;
pub(crate) mod mesh;
pub(crate) mod orient;
pub(crate) mod solid;
pub(crate) mod triangles;
pub(crate) mod up;
pub(crate) mod visibility;
