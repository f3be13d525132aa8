//! # Work-precision diagrams
//!
//! A solver is chosen by the time it needs for the error you accept. A
//! work-precision diagram plots, for each method, the error at the end of
//! the run (x axis, logarithmic) against the solve time (y axis,
//! logarithmic), one point per tolerance: lower is faster, further left is
//! more accurate. Compare methods at the same *error*, not the same
//! tolerance: methods that keep their promises differently reach different
//! errors at one tolerance. A curve that flattens on the left has reached
//! the rounding floor; a curve that stops was refused or failed there.
//!
//! To put a model in the benchmarks (`bench/`), give it a problem:
//!
//! ```
//! use daegen::prelude::*;
//! use daegen::runtime::bench::Benchmark;
//!
//! /// Exponential decay with its exact solution.
//! #[dae_model(bench = Bench::until(2.0)
//!     .exact(|t: f64| [(-t).exp()])
//!     .methods([Dopri5, Dop853])
//!     .tolerances(4, 10))]
//! fn decay() {
//!     let x = state(1.0);
//!     der(x) == -x;
//! }
//!
//! let problem = Decay::bench();
//! assert_eq!(problem.tolerances.len(), 7);
//! assert_eq!(Decay::NAME, "decay");
//! ```
//!
//! and add it to the `run!` list of `bench/src/main.rs`; `cd bench && cargo
//! run --release` then sweeps it with every method and every peer that
//! applies, and writes its SVG, its rows of `results.csv` and its section of
//! `summary.md` (the runner is the `daegen-workprecision` crate).
