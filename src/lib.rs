//! daegen: symbolic ODE/DAE models compiled into specialised solvers.
//!
//! The facade over the workspace: [`codegen`] is the symbolic engine
//! (expression DAG, differentiation, CSE, emission), [`runtime`] the code that
//! generated models run on. The `#[dae_model]` front end is being built on
//! top of them (see the README for what works today).

pub use daegen_codegen as codegen;
pub use daegen_runtime as runtime;
