//! The model's right-hand side and Jacobian as RADAU5 calls them,
//! counted for the run's statistics.

use crate::info::EvalError;
use crate::model::Model;
use crate::step::driver::Counts;
use crate::step::jacobian::DenseJacobian;

/// The model's right-hand side and Jacobian, counted.
pub(super) struct Counted<'m, M> {
    pub(super) model: &'m M,
    pub(super) jacobian: DenseJacobian,
    pub(super) counts: Counts,
}

impl<M: Model> Counted<'_, M> {
    pub(super) fn rhs(&mut self, t: f64, y: &[f64], out: &mut [f64]) -> Result<(), EvalError> {
        self.counts.evals += 1;
        self.model.rhs(t, y, out)
    }

    /// The model's own derivatives alone (`Model::own_rhs`).
    pub(super) fn own_rhs(&mut self, t: f64, y: &[f64], out: &mut [f64]) -> Result<(), EvalError> {
        self.counts.evals += 1;
        self.model.own_rhs(t, y, out).unwrap_or(Err(EvalError::JacobianUnavailable))
    }

    /// The dense Jacobian at `(t, y)`, `f0 = f(t, y)`.
    pub(super) fn evaluate_jacobian(
        &mut self,
        t: f64,
        y: &mut [f64],
        f0: &[f64],
    ) -> Result<(), EvalError> {
        self.counts.jacobian_evals += 1;
        self.jacobian.evaluate(self.model, t, y, f0, &mut self.counts.evals)
    }
}
