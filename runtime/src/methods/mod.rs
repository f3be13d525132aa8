//! The integration methods, one module per method (Hairer's explicit pairs
//! share `adaptive`, the Taylor methods `taylor`), and `auto`, which
//! switches between them.

pub(crate) mod adaptive;
pub(crate) mod auto;
pub(crate) mod backward_euler;
pub mod dop853;
pub mod dopri5;
pub mod explicit_rk;
pub mod implicit_tableau;
pub(crate) mod radau5;
pub(crate) mod rodas5p;
pub(crate) mod stiffness;
pub mod taylor;

use crate::model::Model;
use crate::options::Options;

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

/// The states the error test measures: all, or the model's own where
/// [`Options::sensitivity_error_control`] leaves the sensitivities out.
pub(crate) fn error_states<M: Model>(options: &Options) -> usize {
    if options.sensitivity_error_control {
        M::STATES
    } else {
        M::STATES / (1 + M::SENSITIVITY_COLUMNS)
    }
}
