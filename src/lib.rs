//! daegen: symbolic ODE/DAE models compiled into specialised solvers.
//!
//! Write a model as a function in the model language under `#[dae_model]`;
//! the macro differentiates it symbolically, shares common subexpressions
//! and emits a type implementing [`Model`], which [`Simulate::simulate`] runs.
//!
//! ```
//! use daegen::prelude::*;
//!
//! /// A harmonic oscillator, written with its second derivative.
//! #[dae_model]
//! fn oscillator() {
//!     /// Angular frequency.
//!     let omega = param(2.0);
//!     let x = state(1.0);
//!     init(der(x), 0.0);
//!     der(der(x)) == -omega * omega * x;
//!     let energy = output(0.5 * (der(x) * der(x) + omega * omega * x * x));
//! }
//!
//! let model = Oscillator::default();
//! let sol = model.simulate(0.0, 1.0, &Options::new().method(Method::Rk4).step(1e-3))?;
//! assert!((sol.last("x")? - 2f64.cos()).abs() < 1e-10);
//! assert!((sol.last("der(x)")? + 2.0 * 2f64.sin()).abs() < 1e-10);
//! assert!((sol.last("energy")? - 2.0).abs() < 1e-10);
//! # Ok::<(), daegen::Error>(())
//! ```
//!
//! The crates behind it: [`codegen`] is the symbolic engine, [`runtime`]
//! the integrators and the run API. Start with the [`guide`].

// Every public item says what it is for.
#![warn(missing_docs)]

pub use daegen_codegen as codegen;
#[doc(hidden)]
pub use daegen_macros::{__component_parts, __dae_model_parts};
pub use daegen_macros::{component, dae_model};
pub use daegen_runtime as runtime;
pub use daegen_runtime::{
    Availability, Batch, BlockInfo, BlockSolution, ClockInfo, ComponentInfo, ConstraintInfo,
    Ensemble, Error, EvalError, EventDirection, EventHit, EventInfo, FinalState, FinalStates, Flow,
    Formulation, InitialCorrection, Input, Jacobian, Jump, LinearSolver, MassMatrix, Method, Model,
    ModelInfo, Options, ProjectionLevel, Shard, Simulate, Solution, Stats, Step, StructureInfo,
    Table, MAX_EVENT_ITERATIONS,
};

pub mod guide;
#[cfg(feature = "plot")]
pub mod plot;

/// Everything a model file needs: `use daegen::prelude::*;`.
pub mod prelude {
    pub use crate::{
        component, dae_model, Error, Flow, Formulation, Input, LinearSolver, Method, Model,
        Options, Simulate, Solution, Step,
    };
}

/// The README's code, compiled with the doctests so that it cannot rot.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
