//! A daegen model as a CVODE system: its generated right-hand side and
//! sparse Jacobian (`Model::jacobian`, in the `Model::JACOBIAN` pattern's order), as a
//! user of CVODE with a hand-written sparse Jacobian would give them.

use super::cvode::System;
use daegen::Model;

/// `model` as a CVODE system.
pub struct ModelSystem<'a, M: Model>(pub &'a M);

impl<M: Model> System for ModelSystem<'_, M> {
    fn states(&self) -> usize {
        M::STATES
    }
    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) -> bool {
        self.0.rhs(t, y, dy).is_ok()
    }
    fn pattern(&self) -> &[(usize, usize)] {
        M::JACOBIAN.pattern()
    }
    fn jacobian(&mut self, t: f64, y: &[f64], values: &mut [f64]) -> bool {
        self.0.jacobian(t, y, values).is_ok()
    }
}
