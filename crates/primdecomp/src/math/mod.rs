//! Small fixed-size linear algebra: 3-vectors, symmetric 3×3 matrices, and the
//! branchless 3×3 symmetric eigen-solver (McAdams et al. 2011) used by §3.1–3.2.

pub mod eigen3;
pub mod extremes;
pub mod hull;
pub mod quat;
pub mod sym3;
pub mod vec3;

pub use eigen3::{eigen_sym3, Eigen3};
pub use sym3::Sym3;
pub use vec3::*;
