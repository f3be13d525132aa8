//! # DAEs: constraints and algebraic variables
//!
//! Declare the algebraic variables with `algebraic(guess)` and write the
//! constraints with `constraint(g)` (meaning g = 0) or as equations without
//! derivatives. The macro finds the index (how often each constraint must
//! be differentiated before it determines its unknowns), differentiates the
//! constraints symbolically, solves the resulting linear system for the
//! highest derivatives and the multipliers (symbolically when it is small),
//! and emits an index-1 system that every method integrates. After each
//! step the run projects onto the constraints and their derivatives, so
//! they hold to rounding (`max_constraint_residual()`); the initial values
//! are made consistent first (`state(x0).fixed()` keeps one).
//!
//! ```
//! use daegen::prelude::*;
//!
//! /// The pendulum in Cartesian coordinates: index 3.
//! #[dae_model]
//! fn pendulum() {
//!     let x = state(1.0);
//!     let y = state(0.0);
//!     let u = state(0.0);
//!     let v = state(1.0);
//!     let lambda = algebraic(1.0);
//!     der(x) == u;
//!     der(y) == v;
//!     der(u) == -lambda * x;
//!     der(v) == -lambda * y - 1.0;
//!     constraint(x * x + y * y - 1.0);
//! }
//!
//! assert_eq!(<Pendulum as Model>::INDEX, 3);
//! let opts = Options::new().method(Method::Dop853).tolerance(1e-10);
//! let sol = Pendulum::default().simulate(0.0, 10.0, &opts)?;
//! assert!(sol.max_constraint_residual() < 1e-12);
//! // The multiplier is the rod's tension per unit mass: u² + v² − y.
//! let (u, v, y) = (sol.last("u")?, sol.last("v")?, sol.last("y")?);
//! assert!((sol.last("lambda")? - (u * u + v * v - y)).abs() < 1e-8);
//! # Ok::<(), daegen::Error>(())
//! ```
//!
//! `Options::formulation(Formulation::MassMatrix)` integrates the
//! Gear–Gupta–Leimkuhler index-2 form with RADAU5 instead, with a singular
//! mass matrix. A constraint that determines nothing, contradicts the
//! dynamics, or a structurally singular system is a compile error that
//! names the equations; a singular configuration met during the run is an
//! [`crate::Error::Constraint`] that names the constraint and keeps the
//! steps before it.
