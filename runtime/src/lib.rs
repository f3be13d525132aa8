//! `daegen-runtime`: what generated models run on — the [`Model`] trait that
//! `#[dae_model]` implements, the run API ([`Options`], [`Method`],
//! [`Solution`], [`Error`]), the integrators, and small numerical helpers the
//! generated code calls.
//!
//! Layout: [`model`] and [`info`] are what a model gives, by capability
//! (a core, then groups each led by one typed descriptor, with the
//! [`taylor_tape`] it hands to the Taylor method); `run` checks a request,
//! asks [`Method::refusal`] whether the method runs the model, and hands
//! it to the method's module, every one through the same entry point; the
//! `methods` advance with the helpers of `step` (step-size control,
//! events, projection, Jacobians) and [`linalg`], and fill a
//! [`Solution`]. No module imports one that imports it back, but for
//! [`Error`] and [`Solution`], which hold each other.

// Every public item says what it is for.
#![warn(missing_docs)]
// The numerical kernels index several arrays by one position (y, f, scale, …):
// an index loop says so more plainly than zipped iterators.
#![allow(clippy::needless_range_loop)]

pub mod algebraic;
pub mod bench;
mod describe;
pub mod ensemble;
pub mod error;
pub mod info;
mod input;
pub mod instants;
pub mod kinematics;
pub mod lanes;
pub mod linalg;
mod methods;
pub mod model;
mod options;
mod run;
mod solution;
mod step;
pub mod taylor_tape;

// The methods' public helpers, where users and generated code find them.
pub use linalg::{band_lu, dense_lu};
pub use methods::taylor::{self as taylor, order as taylor_order, series as taylor_series};
pub use methods::{dop853, dopri5, explicit_rk, implicit_tableau};
pub use step::control as step_control;

pub use ensemble::{Batch, Ensemble, FinalState, FinalStates, Shard};
pub use error::Error;
pub use info::{
    BlockInfo, BlockSolution, ClockInfo, ComponentInfo, ConstraintInfo, EvalError, EventDirection,
    EventInfo, ModelInfo, ProjectionLevel, StructureInfo,
};
pub use input::Input;
pub use model::{Availability, Jacobian, MassMatrix, Model, StateVector};
/// The linear-algebra crate of [`kinematics`], re-exported so users get the
/// same version.
pub use nalgebra;
pub use options::{Flow, Formulation, LinearSolver, Method, Options, Step};
pub use run::{simulate, simulate_from, Simulate, MAX_EVENT_ITERATIONS};
pub use solution::table::Table;
pub use solution::{EventHit, InitialCorrection, Jump, Solution, Stats};
