//! The guide: how to write models and run them, in the order a newcomer
//! needs it. Every code block here is compiled and run as a doctest.
//!
//! 1. [`language`]: the model language (states, parameters, equations,
//!    outputs, events, arrays and loops, vectors and rotations).
//! 2. [`running`]: the run API, the methods and when to use each, the
//!    solution, and the errors a run can return.
//! 3. [`results`]: values by name, columns, samples on a grid, output
//!    times, CSV, plots, streaming a run and stopping it, progress.
//! 4. [`daes`]: constraints and algebraic variables, what the macro does
//!    with them (index reduction, projection), and the two formulations.
//! 5. [`structure`]: equations in any order: aliases, matching and
//!    sorting into blocks, tearing, arrays of algebraic variables and
//!    outputs, and the structural errors.
//! 6. [`components`]: models built from parts of several domains
//!    (electrical, mechanical, thermal, control) joined by `connect`; the
//!    standard library; parts of your own, shared across crates; functions
//!    of the model.
//! 7. [`hybrid`]: events that act (`.reinit`, `pre`), discrete values
//!    and modes, clocks for sampled controllers, inputs from outside
//!    (functions, tables, co-simulation), and how every method restarts.
//! 8. [`mechanisms`]: multibody scenes, planar and spatial, global and
//!    recursive, and the names they answer to.
//! 9. [`kinematics`]: rotations, angle sequences, quaternions, angular
//!    velocities and frames, in the model language and numerically.
//! 10. [`ensembles`]: one model run many times, on every core, and shards
//!     of it spread over machines.
//! 11. [`fmi`]: a model as a Functional Mock-up Unit (FMI 3.0 and 2.0,
//!     Model Exchange and Co-Simulation) for FMPy, Simulink and the rigs.
//! 12. [`work_precision`]: registering a model in the benchmarks and
//!     reading a work-precision diagram.
//! 13. [`from_modelica`]: coming from Modelica: each construct a Modelica
//!     model uses and ours, with an example of the Modelica Standard
//!     Library rewritten.

pub mod components;
pub mod daes;
pub mod ensembles;
pub mod fmi;
pub mod from_modelica;
pub mod hybrid;
pub mod kinematics;
pub mod language;
pub mod mechanisms;
pub mod results;
pub mod running;
pub mod structure;
pub mod work_precision;
