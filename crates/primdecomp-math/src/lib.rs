//! Small fixed-size linear algebra shared by primdecomp's core and the tools on top
//! of it (evaluation, exports, the viewer, the benchmark), kept out of the core's
//! public API: the 3-vector helpers ([`V3`], [`add`], [`dot`], …), the conversions
//! between rotation axes and the unit quaternions the JSON stores, symmetric 3×3
//! matrices, the branchless 3×3 symmetric eigen-solver (McAdams et al. 2011,
//! §3.1–3.2), the 3D convex hull, convex polygon clipping, a BVH over triangles and
//! the distinct ids of a long list in checked steps.
//!
//! ```
//! use primdecomp_math::{cross, dot, norm, sub};
//!
//! let (a, b, c) = ([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
//! let n = cross(sub(b, a), sub(c, a));
//! assert_eq!(n, [0.0, 0.0, 1.0]);
//! assert_eq!(dot(n, sub(b, a)), 0.0);
//! assert_eq!(norm([3.0, 4.0, 0.0]), 5.0);
//! ```

// Loops over the three axes index several parallel arrays; iterators obscure them.
#![allow(clippy::needless_range_loop)]

pub mod bvh;
pub mod eigen3;
pub mod hull;
pub mod marks;
mod number;
pub mod polygon;
pub mod quat;
pub mod sym3;
mod vec3;

pub use eigen3::eigen_sym3;
pub use number::short;
pub use quat::{axes_from_quat, quat_from_axes};
pub use sym3::Sym3;
pub use vec3::*;
