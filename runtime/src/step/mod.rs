//! What every method does around a step: the initial-value [`Problem`] it
//! is handed, step-size control, events on the step's continuous
//! extension, projection onto the constraints, finite-difference
//! Jacobians, the stiffness tests `Method::Auto` switches on, and the
//! driver that runs them around a method's step ([`driver`]).

pub mod control;
pub(crate) mod driver;
pub(crate) mod events;
pub(crate) mod jacobian;
pub(crate) mod projection;
pub(crate) mod stiffness;

use crate::error::Error;
use crate::options::Options;
use crate::solution::Solution;

/// The initial-value problem a method is asked to solve: `model` from the
/// state `y0` at `t0` to `t1` (either direction), with `options`.
pub(crate) struct Problem<'a, M> {
    pub model: &'a M,
    pub t0: f64,
    pub t1: f64,
    pub y0: &'a [f64],
    pub options: &'a Options,
}

impl<M> Clone for Problem<'_, M> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<M> Copy for Problem<'_, M> {}

/// The number of equal steps of about `step` from `t0` to `t1` for a
/// fixed-step method, or `Error::MaxSteps` (with `solution`) when that is
/// more than `options` allow.
pub(crate) fn equal_steps(
    t0: f64,
    t1: f64,
    step: f64,
    options: &Options,
    solution: Solution,
) -> Result<(usize, Solution), Error> {
    let steps = ((t1 - t0).abs() / step).ceil().max(1.0);
    if steps > options.max_steps as f64 {
        return Err(Error::MaxSteps {
            t: t0,
            max_steps: options.max_steps,
            partial: Box::new(solution),
        });
    }
    Ok((steps as usize, solution))
}

/// The equal steps of a method that takes [`Options::step`]: of about that
/// step, or of the interval over 1000 where none is given.
pub(crate) fn option_steps<M>(
    problem: &Problem<'_, M>,
    solution: Solution,
) -> Result<(usize, Solution), Error> {
    let Problem { t0, t1, options, .. } = *problem;
    let step = options.step.unwrap_or((t1 - t0).abs() / 1000.0);
    if !(step.is_finite() && step > 0.0) && t1 != t0 {
        return Err(Error::InvalidOptions {
            message: format!("the step must be positive and finite, not {step}"),
        });
    }
    equal_steps(t0, t1, step, options, solution)
}
