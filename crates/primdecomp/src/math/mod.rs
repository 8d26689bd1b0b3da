//! Small fixed-size linear algebra. Public: the 3-vector helpers the primitives'
//! fields are written with ([`V3`], [`add`], [`dot`], …) and the conversions between
//! rotation axes and the unit quaternions the JSON stores. Inside the crate also:
//! symmetric 3×3 matrices, the branchless 3×3 symmetric eigen-solver (McAdams et al.
//! 2011, §3.1–3.2) and the 3D convex hull.
//!
//! ```
//! use primdecomp::math::{cross, dot, norm, sub};
//!
//! let (a, b, c) = ([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
//! let n = cross(sub(b, a), sub(c, a));
//! assert_eq!(n, [0.0, 0.0, 1.0]);
//! assert_eq!(dot(n, sub(b, a)), 0.0);
//! assert_eq!(norm([3.0, 4.0, 0.0]), 5.0);
//! ```

pub mod bvh;
pub(crate) mod eigen3;
pub(crate) mod hull;
pub(crate) mod polygon;
pub(crate) mod quat;
pub(crate) mod sym3;
mod vec3;

pub(crate) use eigen3::eigen_sym3;
pub use quat::{axes_from_quat, quat_from_axes};
pub(crate) use sym3::Sym3;
pub use vec3::*;
