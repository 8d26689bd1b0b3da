//! Shared test helpers.
#![allow(dead_code)]
pub mod check;
pub mod contain;
pub mod demo;
pub mod shapes;
