//! Work-precision benchmarks for every registered model, generated: a model
//! declared with `#[dae_model(bench = Bench::until(t1)...)]` implements
//! [`Benchmark`]; a [`Runner`] sweeps its methods over tolerances (or step
//! counts), times each run (median of repeats after a warm-up), measures the
//! error against the model's reference and the work (steps, rejections,
//! right-hand-side and Jacobian evaluations), runs the [`Peer`]s on the same
//! problem, and writes a CSV of every run, an SVG work-precision diagram per
//! problem and a markdown summary with our time over each peer's at matched
//! error.
//!
//! Peers (other crates, Python) live in the benchmark binary, not here, so
//! the test command never compiles them.

#![warn(missing_docs)]

mod arithmetic;
mod expansion;
mod peer;
mod plot;
mod record;
mod runner;
mod summary;
mod sweep;
mod timing;

pub use arithmetic::{function_operations, taylor_jet_operations};
pub use daegen::runtime::bench::{Bench, Benchmark, Reference};
pub use expansion::{expansion_cost, ExpansionCost};
pub use peer::{Peer, PeerProblem};
pub use plot::work_precision_svg;
pub use record::{parse_csv, to_csv, Record};
pub use runner::{Problem, Runner};
pub use summary::{matched_ratio, summary_markdown, time_at_error};
pub use sweep::{mixed_error, plan, reference_values, run_planned, PlannedRun};
pub use timing::{median, median_time, Settings};
