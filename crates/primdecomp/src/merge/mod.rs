//! Greedy bottom-up merging (§3.3, Alg. 1; §3.4 "Collapsible Primitive Data
//! Structure", "Pairwise Component Merging"): clusters of faces, their candidate
//! merges in a priority queue with lazy deletion, and the loop that drives them.

pub mod absorb;
pub mod bridge;
pub mod cluster;
pub mod components;
pub mod cost;
pub mod driver;
pub mod heap;
mod lazy;
pub mod partition;
pub mod plates;
pub mod rim;
pub mod worker;

pub use cluster::{ClusterId, Clusters};
pub use cost::{Evaluator, Workspace};
pub use driver::{run, run_with, FitCounts, MergeOutput, Snapshot};
pub use heap::{Queue, RadixHeap, StdHeap};
