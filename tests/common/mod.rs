//! Shared test helpers.
#![allow(dead_code)]
pub mod contain;
pub mod shapes;
