//! The integration methods, one module per method (Hairer's explicit pairs
//! share `adaptive`, the Taylor methods `taylor`, the explicit fixed-step
//! methods `explicit_rk`), and `auto`, which switches between them. Every
//! module's entry point has the one shape [`Integrate`], which
//! [`integrator`] hands out by [`Method`]; `refusal` says which models a
//! method does not run, and why.

pub(crate) mod adaptive;
pub(crate) mod auto;
pub(crate) mod backward_euler;
pub mod dop853;
pub mod dopri5;
pub mod explicit_rk;
pub mod implicit_tableau;
pub(crate) mod mass;
pub(crate) mod radau5;
mod refusal;
pub(crate) mod rodas5p;
pub mod taylor;

use crate::error::Error;
use crate::model::Model;
use crate::options::{Method, Options};
use crate::solution::Solution;
use crate::step::Problem;

pub(crate) use refusal::taylor_refusal;

/// The states the error test measures: all, or the model's own where
/// [`Options::sensitivity_error_control`] leaves the sensitivities out.
pub(crate) fn error_states<M: Model>(options: &Options) -> usize {
    if options.sensitivity_error_control {
        M::STATES
    } else {
        M::STATES / (1 + M::SENSITIVITY_COLUMNS)
    }
}

/// A method's entry point: integrates `problem`, appending the steps to
/// `solution` (which holds the initial point), and returns it filled, or
/// the error with the steps taken up to it.
pub(crate) type Integrate<M> = fn(Problem<'_, M>, Solution) -> Result<Solution, Error>;

/// The entry point of `method`'s module: each module reads the method's
/// own parameters (a tableau, an order, a step) from the options.
pub(crate) fn integrator<M: Model>(method: Method) -> Integrate<M> {
    match method {
        Method::Auto => auto::integrate,
        Method::Taylor => taylor::integrate,
        Method::TaylorFixed { .. } => taylor::fixed::integrate,
        Method::Euler
        | Method::Rk4
        | Method::Rk38
        | Method::Midpoint
        | Method::Heun
        | Method::Ralston => explicit_rk::integrate,
        Method::BackwardEuler => backward_euler::integrate,
        Method::Dopri5 => dopri5::integrate,
        Method::Dop853 => dop853::integrate,
        Method::Radau5 => radau5::integrate,
        Method::Rodas5P => rodas5p::integrate,
    }
}
