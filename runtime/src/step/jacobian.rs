//! The model's Jacobian ∂f/∂y as a dense row-major matrix, for the implicit
//! methods' Newton matrices: the generated sparse one scattered, or forward
//! differences with `radau5.f`'s increments where the model has none.

use crate::info::EvalError;
use crate::model::Model;

/// A dense n × n Jacobian and the scratch it is evaluated in.
pub(crate) struct DenseJacobian {
    /// Row-major ∂f/∂y at the last evaluation.
    pub(crate) matrix: Vec<f64>,
    /// The generated Jacobian's non-zeros, in [`Model::JACOBIAN`] pattern order.
    values: Vec<f64>,
    /// f at a perturbed point (finite differences only).
    perturbed: Vec<f64>,
    /// Whether the last evaluation was the generated Jacobian (in `values`).
    analytic: bool,
    /// Scratch of the power iteration.
    power: (Vec<f64>, Vec<f64>),
}

impl DenseJacobian {
    /// Storage for `M`'s Jacobian.
    pub(crate) fn new<M: Model>() -> DenseJacobian {
        DenseJacobian::with_matrix::<M>(true)
    }

    /// Storage for `M`'s generated Jacobian, scattered into a dense
    /// `matrix` only if `dense` (a banded or sparse LU reads the non-zeros,
    /// and zeroing n² entries would cost a large model more than its LU).
    pub(crate) fn with_matrix<M: Model>(dense: bool) -> DenseJacobian {
        DenseJacobian {
            matrix: if dense { vec![0.0; M::STATES * M::STATES] } else { Vec::new() },
            values: vec![0.0; M::JACOBIAN.pattern().len()],
            perturbed: vec![0.0; M::STATES],
            analytic: false,
            power: (vec![0.0; M::STATES], vec![0.0; M::STATES]),
        }
    }

    /// Evaluates ∂f/∂y at `(t, y)`; `f0 = f(t, y)` is read only by finite
    /// differences, whose right-hand-side calls are added to `evals`. `y` is
    /// perturbed and restored.
    pub(crate) fn evaluate<M: Model>(
        &mut self,
        model: &M,
        t: f64,
        y: &mut [f64],
        f0: &[f64],
        evals: &mut usize,
    ) -> Result<(), EvalError> {
        let n = M::STATES;
        self.matrix.iter_mut().for_each(|v| *v = 0.0);
        self.analytic = false;
        if M::JACOBIAN.is_symbolic() {
            model.jacobian(t, y, &mut self.values)?;
            // A banded or sparse LU reads the non-zeros themselves.
            if !self.matrix.is_empty() {
                for (&(r, c), &v) in M::JACOBIAN.pattern().iter().zip(&self.values) {
                    self.matrix[r * n + c] = v;
                }
            }
            self.analytic = true;
            return Ok(());
        }
        if self.matrix.is_empty() {
            return Err(EvalError::JacobianUnavailable);
        }
        for j in 0..n {
            // A discrete value is constant over the stretch: its column is
            // left zero (see the generated Jacobian).
            if M::INFO.discrete.contains(&M::INFO.states[j]) {
                continue;
            }
            let saved = y[j];
            let delta = (f64::EPSILON * saved.abs().max(1e-5)).sqrt();
            y[j] = saved + delta;
            *evals += 1;
            let r = model.rhs(t, y, &mut self.perturbed);
            y[j] = saved;
            r?;
            for i in 0..n {
                self.matrix[i * n + j] = (self.perturbed[i] - f0[i]) / delta;
            }
        }
        Ok(())
    }

    /// The generated Jacobian's non-zeros at the last evaluation, in
    /// [`Model::JACOBIAN`] pattern order.
    pub(crate) fn values(&self) -> &[f64] {
        &self.values
    }

    /// `out = (J(t, y) − matrix)·direction`: how the Jacobian changed since
    /// it was last evaluated, along `direction`, from the generated Jacobian
    /// (one evaluation, no factorisation). `Ok(false)` when the model has
    /// none, which finite differences would make as costly as a new matrix.
    pub(crate) fn change_along<M: Model>(
        &mut self,
        model: &M,
        t: f64,
        y: &[f64],
        direction: &[f64],
        out: &mut [f64],
    ) -> Result<bool, EvalError> {
        if !M::JACOBIAN.is_symbolic() {
            return Ok(false);
        }
        model.jacobian(t, y, &mut self.values)?;
        let n = M::STATES;
        for (i, o) in out.iter_mut().enumerate() {
            let row = &self.matrix[i * n..(i + 1) * n];
            *o = -row.iter().zip(direction).map(|(a, d)| a * d).sum::<f64>();
        }
        for (&(r, c), &v) in M::JACOBIAN.pattern().iter().zip(&self.values) {
            out[r] += v * direction[c];
        }
        Ok(true)
    }

    /// ρ of the last evaluated Jacobian, by the power iteration: on the
    /// generated sparse Jacobian where there is one, else on the matrix.
    pub(crate) fn spectral_radius<M: Model>(&mut self) -> f64 {
        let (v, w) = (&mut self.power.0, &mut self.power.1);
        let n = M::STATES;
        if self.analytic {
            let values = &self.values;
            crate::linalg::spectral_radius(v, w, |v, w| {
                w.fill(0.0);
                for (&(r, c), &value) in M::JACOBIAN.pattern().iter().zip(values) {
                    w[r] += value * v[c];
                }
            })
        } else {
            let matrix = &self.matrix;
            crate::linalg::spectral_radius(v, w, |v, w| {
                for (i, wi) in w.iter_mut().enumerate() {
                    *wi = matrix[i * n..(i + 1) * n].iter().zip(v.iter()).map(|(a, b)| a * b).sum();
                }
            })
        }
    }
}
