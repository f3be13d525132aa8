//! `daegen-runtime`: what generated models run on — the [`Model`] trait that
//! `#[dae_model]` implements, the run API ([`Options`], [`Method`],
//! [`Solution`], [`Error`]), the integrators, and small numerical helpers the
//! generated code calls.

// The numerical kernels index several arrays by one position (y, f, scale, …):
// an index loop says so more plainly than zipped iterators.
#![allow(clippy::needless_range_loop)]

mod adaptive;
pub mod algebraic;
mod auto;
mod backward_euler;
pub mod band_lu;
pub mod bench;
mod checks;
pub mod dense_lu;
mod describe;
pub mod dop853;
pub mod dopri5;
pub mod error;
mod events;
pub mod explicit_rk;
pub mod implicit_tableau;
mod jacobian;
pub mod kinematics;
pub mod linalg;
mod model;
mod options;
mod projection;
mod radau5;
mod simulate;
mod solution;
pub mod step_control;
mod stiffness;
mod table;
pub mod taylor;
mod taylor_fixed;
pub mod taylor_order;
pub mod taylor_series;
pub mod taylor_tape;

pub use error::Error;
pub use model::{
    ConstraintInfo, EvalError, EventDirection, EventInfo, Model, ModelInfo, ProjectionLevel,
    StateVector,
};
/// The linear-algebra crate of [`kinematics`], re-exported so users get the
/// same version.
pub use nalgebra;
pub use options::{Flow, Formulation, Method, Options, Step};
pub use simulate::{simulate, simulate_from};
pub use solution::{EventHit, InitialCorrection, Solution, Stats};
pub use table::Table;
