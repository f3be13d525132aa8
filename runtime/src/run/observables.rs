//! A solution's window on its model after the run: outputs and algebraic
//! variables by index, and y' for the Hermite interpolant, without a type
//! parameter on `Solution`.

use crate::model::{has_mass_matrix, Model};
use crate::solution::{Names, Observables, Solution};
use std::sync::Arc;

struct ModelObservables<M>(M);

impl<M: Model + Send + Sync> Observables for ModelObservables<M> {
    fn output(&self, index: usize, t: f64, y: &[f64]) -> f64 {
        self.0.output(index, t, y)
    }

    fn derivative(&self, t: f64, y: &[f64], dy: &mut [f64]) -> bool {
        !has_mass_matrix::<M>() && self.0.rhs(t, y, dy).is_ok()
    }
}

/// An empty solution of `model`.
pub(crate) fn solution_of<M: Model + Clone + Send + Sync + 'static>(model: &M) -> Solution {
    let observables = Arc::new(ModelObservables(model.clone()));
    Solution::new(Names::of(&M::INFO), observables, M::STATES)
}
