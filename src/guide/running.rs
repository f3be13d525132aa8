//! # Running a model
//!
//! `model.simulate(t0, t1, &options)` integrates from the model's initial
//! values and returns a [`crate::Solution`] or a [`crate::Error`];
//! `simulate_from(t0, &y, t1, &options)` starts from another state.
//! [`crate::Options`] chooses the method, tolerances, step, limits and what
//! is stored.
//!
//! | method | use it for |
//! |---|---|
//! | `Auto` (default) | not sure: DOPRI5 or DOP853, switching to RODAS5P (rtol ≥ 5e-5, or a large grid) or RADAU5 when the problem turns stiff |
//! | `Dopri5`, `Dop853` | non-stiff problems; DOP853 below rtol 1e-7 |
//! | `Radau5` | stiff problems and DAEs with a singular mass matrix; it works to 0.1·rtol^(2/3) and scales atol alike, as Hairer's radau5.f (rtol = atol = 1e-10: to 2.2e-8) |
//! | `Rodas5P` | stiff problems at loose tolerances (rtol 1e-3 to 1e-4), large grids at any tolerance; index-1 DAEs in mass-matrix form |
//! | `Taylor` | smooth problems at tight tolerances (orbits); every smooth explicit model has its tape, `unroll = [..]` makes it faster |
//! | `TaylorFixed { order, step }` | the economic Taylor scheme of the course notes |
//! | `BackwardEuler`, `Euler`, `Rk4`, … | fixed steps: teaching, convergence studies |
//!
//! The solution holds the accepted steps: `times()`, `state(k)`,
//! `final_state()`, `last(name)` and `at(t, name)` for any state,
//! `der(x)`, algebraic variable or output (with each method's continuous
//! output), `stats()` (steps, rejections, evaluations; for `Taylor` the
//! order it chose and whether it ran unrolled), `events()`; columns,
//! grids, CSV and plots in [`super::results`].
//!
//! Large stiff models (discretised PDEs written with loops, long chains)
//! need no option: RADAU5 reads the generated Jacobian's sparsity pattern
//! and factors its Newton matrices banded (after a reverse Cuthill–McKee
//! renumbering) or sparse (after a minimum-degree one) where either costs
//! fewer operations than dense LU, and keeps its Jacobian and LU longer
//! where one factorisation is costly, as Hairer recommends for large
//! systems. A 2-D Brusselator of 2048 states runs in about a second.
//! RODAS5P stores its one matrix the same way; it factors it at every step
//! but never iterates, which wins where few digits are asked: at rtol
//! 1e-4 it takes 0.6× CVODE's time at equal error on the 1-D Brusselator,
//! RADAU5 0.8×; from 1e-5 on RADAU5 is the faster (`bench --large`).
//!
//! On grids of 1000 states or more whose LU fills in (two- and
//! three-dimensional grids, which no renumbering bands), RODAS5P does not
//! factor at all: [`crate::LinearSolver::Auto`] solves its systems by
//! GMRES preconditioned by an incomplete LU in the Jacobian's own pattern,
//! and `Method::Auto` takes RODAS5P there at every tolerance. On SUNDIALS'
//! diurnal example (5000 states) that takes 0.2–0.6× the time of CVODE
//! with GMRES, where the sparse LU took 1.1–3.5×. `stats().linear_solver`
//! says how the systems were solved (`"sparse LU"`, `"GMRES"`, or
//! `"GMRES→sparse LU"` where GMRES failed three steps in a row and the run
//! factored from there on); `Options::linear_solver` forces either.
//!
//! ## Sensitivities
//!
//! `#[dae_model(sensitivities = [k, init(x)])]` also generates
//! `<Model>Sensitivities`: the model with the first variational equations
//! S′ = (∂f/∂y)·S + ∂f/∂k as extra states, built symbolically and sharing
//! their subexpressions with the right-hand side. `model.with_sensitivities()`
//! makes one with the same parameters; every method integrates it (the
//! implicit ones factor the model's own matrix once for all columns), and
//! `Solution::sensitivity(t, "x", "k")` reads ∂x/∂k (`"init(x)"` for the
//! initial value). ODE models have them; a DAE's are refused at compile
//! time for now. `examples/fit_parameters.rs` fits a model's rates to
//! noisy data by Levenberg–Marquardt with them.
//!
//! ```
//! use daegen::prelude::*;
//!
//! /// y′ = −k·y: ∂y/∂k = −t·y(0)·e^(−kt).
//! #[dae_model(sensitivities = [k])]
//! fn decay() {
//!     let k = param(0.5);
//!     let y = state(2.0);
//!     der(y) == -k * y;
//! }
//!
//! let sol = Decay::default().with_sensitivities().simulate(0.0, 2.0, &Options::new())?;
//! let exact = -2.0 * 2.0 * (-0.5f64 * 2.0).exp();
//! assert!((sol.sensitivity(2.0, "y", "k")? - exact).abs() < 1e-6);
//! # Ok::<(), daegen::Error>(())
//! ```
//!
//! `Taylor` chooses its order from the tolerance and the model's cost per
//! order (higher than Jorba & Zou's for small models, theirs when the
//! convolutions dominate), and a step whose first dropped term is a fifth
//! of theirs, so that its error at a tolerance is not above heyoka's,
//! among the orders of `unroll = [..]` unless the interpreted tape's is
//! much cheaper:
//! `daegen::runtime::taylor_order::order_to_unroll(&model, tol)` says which
//! order to unroll for a tolerance, and `Options::taylor_order(p)` fixes it
//! (the only way an odd order runs: listing one in `unroll` warns).
//!
//! ```
//! use daegen::prelude::*;
//!
//! /// Van der Pol, stiff for small ε.
//! #[dae_model]
//! fn van_der_pol() {
//!     let eps = param(1e-3);
//!     let y1 = state(2.0);
//!     let y2 = state(0.0);
//!     der(y1) == y2;
//!     der(y2) == ((1.0 - y1 * y1) * y2 - y1) / eps;
//! }
//!
//! let opts = Options::new().method(Method::Radau5).tolerance(1e-8);
//! let sol = VanDerPol::default().simulate(0.0, 2.0, &opts)?;
//! assert!(sol.stats().steps < 2_000);
//! // Stored steps; `at` reads the collocation polynomial between them,
//! // which agrees with a run that ends there.
//! let y = sol.at(1.234, "y1")?;
//! let direct = VanDerPol::default().simulate(0.0, 1.234, &opts)?;
//! assert!((y - direct.last("y1")?).abs() < 1e-5);
//! # Ok::<(), daegen::Error>(())
//! ```
//!
//! A run that fails returns an error that says what happened, where (time
//! and variable) and keeps the steps before it; the table of every error
//! with its cause, remedy and test is in [`crate::runtime::error`]:
//!
//! ```
//! use daegen::prelude::*;
//!
//! /// y' = y², y(0) = 1: a pole at t = 1.
//! #[dae_model]
//! fn blow_up() {
//!     let y = state(1.0);
//!     der(y) == y * y;
//! }
//!
//! let err = BlowUp::default().simulate(0.0, 2.0, &Options::new()).unwrap_err();
//! let partial = err.partial_solution().unwrap();
//! assert!((partial.times().last().unwrap() - 1.0).abs() < 1e-3);
//! println!("{err}");
//! ```
//!
//! Long runs: `Options::keep_every(k)` stores every k-th step and the last
//! one (a million steps in a thousand states); `dense_output(false)` drops
//! the continuous output of adaptive methods.
