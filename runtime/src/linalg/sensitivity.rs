//! The Newton matrices of a model with forward-sensitivity columns (made by
//! `with_sensitivities()`): its states are the base model's y, then the
//! columns S_1 … S_m, and its Jacobian is block lower triangular,
//!
//! ```text
//! [ J    0  …  0 ]
//! [ H_1  J  …  0 ]     H_j = ∂(J·S_j + ∂f/∂p_j)/∂y,
//! [ …          … ]
//! [ H_m  0  …  J ]
//! ```
//!
//! so `γ·I − J_aug` is factored through its diagonal block alone and solved
//! by block forward substitution: x_0 = (γ − J)⁻¹ b_0, then
//! x_j = (γ − J)⁻¹ (b_j + H_j·x_0). One factorisation of the base model's
//! size serves every column, as CVODES's simultaneous corrector with the
//! exact Jacobian does (Maly & Petzold, "Numerical methods and software
//! for sensitivity analysis of differential-algebraic systems", Appl.
//! Numer. Math. 20, 1996); the solve is exact, so the methods keep their
//! order and their Newton convergence. A staggered corrector (RADAU5's)
//! solves the model's own block alone first, then the columns with the
//! states fixed, where H_j drops out and each column is solved with the
//! base block.

use crate::linalg::newton::{Factored, Newton, Shifts};

/// The base block's matrices and the couplings `H_j`.
pub(crate) struct SensitivityNewton {
    base: Newton,
    n: usize,
    columns: usize,
    /// The base model's non-zeros: the first entries of the pattern.
    base_pattern: &'static [(usize, usize)],
    /// The couplings: (row among all states, column < n, position in the
    /// pattern's values).
    coupling: Vec<(usize, usize, usize)>,
    /// Their values when the matrices were factored: the solves use the
    /// matrix that was factored, whatever the Jacobian did since.
    coupling_values: Vec<f64>,
    /// The base Jacobian as a dense row-major matrix, where the base
    /// matrices are dense.
    dense: Vec<f64>,
    /// x_0 of the last solve (the complex one: real and imaginary parts).
    first: Vec<f64>,
    first_imaginary: Vec<f64>,
}

impl SensitivityNewton {
    /// The matrices of a model of `n · (1 + columns)` states whose Jacobian
    /// has entries at `pattern` (row-major: the base model's rows first).
    pub(crate) fn new(
        n: usize,
        columns: usize,
        pattern: &'static [(usize, usize)],
        shifts: Shifts,
    ) -> (SensitivityNewton, f64) {
        let base_entries = pattern.iter().take_while(|&&(r, _)| r < n).count();
        let base_pattern = &pattern[..base_entries];
        let (base, operations) = Newton::for_pattern(n, base_pattern, shifts);
        let coupling = pattern
            .iter()
            .enumerate()
            .filter(|(_, &(r, c))| r >= n && c < n)
            .map(|(k, &(r, c))| (r, c, k))
            .collect::<Vec<_>>();
        let coupling_values = vec![0.0; coupling.len()];
        let dense = if base.dense_jacobian() { vec![0.0; n * n] } else { Vec::new() };
        let newton = SensitivityNewton {
            base,
            n,
            columns,
            base_pattern,
            coupling,
            coupling_values,
            dense,
            first: vec![0.0; n],
            first_imaginary: vec![0.0; n],
        };
        (newton, operations)
    }

    /// How the base block is solved (`Newton::label`).
    pub(crate) fn label(&self) -> &'static str {
        self.base.label()
    }

    /// Factors the base block of `γ·I − J` (and `(α + iβ)·I − J`) from the
    /// Jacobian's non-zeros `values`.
    pub(crate) fn factor(&mut self, gamma: f64, complex: (f64, f64), values: &[f64]) -> Factored {
        let base_values = &values[..self.base_pattern.len()];
        for (v, &(_, _, k)) in self.coupling_values.iter_mut().zip(&self.coupling) {
            *v = values[k];
        }
        loop {
            if !self.dense.is_empty() {
                self.scatter(base_values);
            }
            let (dense, pattern) = (&self.dense, self.base_pattern);
            match self.base.factor_from(gamma, complex, &[], dense, base_values, pattern) {
                // The sparse LU gave way to the dense one: the base block's
                // dense matrix comes from the same non-zeros (once).
                Factored::NeedsDenseJacobian if self.dense.is_empty() => {
                    self.dense = vec![0.0; self.n * self.n];
                }
                other => return other,
            }
        }
    }

    fn scatter(&mut self, base_values: &[f64]) {
        self.dense.fill(0.0);
        for (&(r, c), &v) in self.base_pattern.iter().zip(base_values) {
            self.dense[r * self.n + c] = v;
        }
    }

    /// Solves `(γ·I − J_aug) x = b` in place.
    pub(crate) fn solve_real(&mut self, b: &mut [f64]) {
        let n = self.n;
        self.base.solve_real(&mut b[..n]);
        self.first.copy_from_slice(&b[..n]);
        for (&(r, c, _), v) in self.coupling.iter().zip(&self.coupling_values) {
            b[r] += v * self.first[c];
        }
        for j in 1..=self.columns {
            self.base.solve_real(&mut b[j * n..(j + 1) * n]);
        }
    }

    /// Solves `(γ·I − J) x = b` in place for the model's own states
    /// (`b` of the base size): a staggered corrector's first part.
    pub(crate) fn solve_own_real(&mut self, b: &mut [f64]) {
        self.base.solve_real(b);
    }

    /// Solves `((α + iβ)·I − J)(x + iy) = re + i·im` in place for the
    /// model's own states.
    pub(crate) fn solve_own_complex(&mut self, re: &mut [f64], im: &mut [f64]) {
        self.base.solve_complex(re, im);
    }

    /// Solves `(γ·I − J) x_j = b_j` in place for every column of `b` (all
    /// states; the model's own are left alone): with the states fixed, the
    /// columns' equations are uncoupled, each with the base matrix.
    pub(crate) fn solve_columns_real(&mut self, b: &mut [f64]) {
        let n = self.n;
        for j in 1..=self.columns {
            self.base.solve_real(&mut b[j * n..(j + 1) * n]);
        }
    }

    /// The complex counterpart of [`SensitivityNewton::solve_columns_real`].
    pub(crate) fn solve_columns_complex(&mut self, re: &mut [f64], im: &mut [f64]) {
        let n = self.n;
        for j in 1..=self.columns {
            let block = j * n..(j + 1) * n;
            self.base.solve_complex(&mut re[block.clone()], &mut im[block]);
        }
    }

    /// Solves `((α + iβ)·I − J_aug)(x + iy) = re + i·im` in place.
    pub(crate) fn solve_complex(&mut self, re: &mut [f64], im: &mut [f64]) {
        let n = self.n;
        self.base.solve_complex(&mut re[..n], &mut im[..n]);
        self.first.copy_from_slice(&re[..n]);
        self.first_imaginary.copy_from_slice(&im[..n]);
        for (&(r, c, _), v) in self.coupling.iter().zip(&self.coupling_values) {
            re[r] += v * self.first[c];
            im[r] += v * self.first_imaginary[c];
        }
        for j in 1..=self.columns {
            let block = j * n..(j + 1) * n;
            self.base.solve_complex(&mut re[block.clone()], &mut im[block]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linalg::solve_in_place;

    /// Two base states and one column: J = [[1, 2], [3, 4]] on the
    /// diagonal blocks, H = [[5, 6], [7, 8]] below.
    const PATTERN: [(usize, usize); 12] = [
        (0, 0),
        (0, 1),
        (1, 0),
        (1, 1),
        (2, 0),
        (2, 1),
        (2, 2),
        (2, 3),
        (3, 0),
        (3, 1),
        (3, 2),
        (3, 3),
    ];
    const VALUES: [f64; 12] = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 1.0, 2.0, 7.0, 8.0, 3.0, 4.0];

    #[test]
    fn block_substitution_solves_the_whole_matrix() {
        let gamma = 10.0;
        let (mut newton, _) = SensitivityNewton::new(2, 1, &PATTERN, Shifts::Real);
        assert_eq!(newton.factor(gamma, (0.0, 0.0), &VALUES), Factored::Yes);
        let b = [1.0, -2.0, 0.5, 3.0];
        let mut x = b;
        newton.solve_real(&mut x);
        // γI − J_aug, dense, solved with pivoting.
        let mut a = [[0.0; 4]; 4];
        for (&(r, c), v) in PATTERN.iter().zip(VALUES) {
            a[r][c] -= v;
        }
        (0..4).for_each(|i| a[i][i] += gamma);
        let mut want = b;
        assert!(solve_in_place(&mut a, &mut want));
        for (got, want) in x.iter().zip(want) {
            assert!((got - want).abs() <= 1e-14 * want.abs().max(1.0), "{x:?} against {want}");
        }
    }
}
