//! Emission: common-subexpression elimination into straight-line programs
//! (`schedule`), programs as Rust tokens (`program`), and the items of a
//! model type (`model`, `benchmark`).

pub mod benchmark;
pub mod model;
pub mod program;
pub mod schedule;
