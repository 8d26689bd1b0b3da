//! Greedy bottom-up merging (§3.3, Alg. 1; §3.4 "Collapsible Primitive Data
//! Structure", "Pairwise Component Merging"): clusters of faces, their candidate
//! merges in a priority queue with lazy deletion, and the loop that drives them.

pub(crate) mod bridge;
pub(crate) mod cluster;
pub(crate) mod components;
pub(crate) mod cost;
pub(crate) mod driver;
pub(crate) mod heap;
mod lazy;
mod median;
pub(crate) mod partition;
pub(crate) mod rim;
pub(crate) mod setup;
pub(crate) mod stage;
pub(crate) mod worker;

pub(crate) use cluster::Clusters;
pub(crate) use cost::{Fitter, Workspace};
pub(crate) use driver::{run, run_for_tree, FitCounts, MergeLog, MergeOutput, Snapshot, TreeHulls};
