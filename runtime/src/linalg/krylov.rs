//! GMRES with an incomplete LU preconditioner, for the Rosenbrock method's
//! matrix `M/(hγ) − J` on large sparse models where even a sparse LU fills
//! in (two-dimensional grids of thousands of cells): the matrix is kept in
//! the Jacobian's own pattern, factored incompletely inside that pattern
//! (ILU(0): no fill at all), and each stage's system is solved by
//! restarted GMRES on the preconditioned operator. References: Saad,
//! *Iterative Methods for Sparse Linear Systems*, 2nd ed., SIAM 2003
//! (ILU(0), Algorithm 10.4; GMRES with Givens rotations, Algorithm 6.9 and
//! §6.5.3); the scaled, left-preconditioned form and its stopping test in
//! the error weights of the step are CVODE's SPGMR (Brown & Hindmarsh,
//! "Reduced storage matrix methods in stiff ODE systems", Appl. Math.
//! Comput. 31, 1989).

/// Krylov vectors kept before GMRES restarts.
const RESTART: usize = 30;
/// Restarts before a solve counts as failed (the caller shrinks the step,
/// which makes the matrix nearer its diagonal).
const MAX_RESTARTS: usize = 4;
/// A solve stops when the preconditioned residual's weighted RMS norm is
/// below this: a thousandth of the local error the step may make, so that
/// the eight stages' solves together move the error estimate by well
/// under a percent.
pub(crate) const SOLVE_TOLERANCE: f64 = 1e-3;

/// `shift·M − J` in the Jacobian's pattern (the diagonal added), its
/// incomplete factors, and GMRES's work arrays.
pub(crate) struct KrylovNewton {
    n: usize,
    /// Row i's entries at `row_start[i]..row_start[i + 1]`, columns ascending.
    row_start: Vec<usize>,
    columns: Vec<usize>,
    /// Where row i's diagonal is.
    diagonal: Vec<usize>,
    /// Where each entry of the Jacobian's pattern lands.
    slot_of_entry: Vec<usize>,
    /// The matrix's entries.
    matrix: Vec<f64>,
    /// L (unit diagonal, not stored) and U of ILU(0), in the same slots.
    factors: Vec<f64>,
    /// `1 / (atol + rtol·|y_i|)`: the step's error weights.
    weights: Vec<f64>,
    /// Row i's slot of each column while row i is factored (`usize::MAX`: none).
    slot_in_row: Vec<usize>,
    /// The Krylov basis, `RESTART + 1` vectors of n.
    basis: Vec<f64>,
    /// The Hessenberg matrix by columns, `RESTART + 1` entries each.
    hessenberg: Vec<f64>,
    /// The Givens rotations (cos, sin) that make it triangular.
    rotations: Vec<(f64, f64)>,
    /// The rotated right-hand side `β e₁`.
    rotated: Vec<f64>,
    /// The scaled, preconditioned right-hand side, the scaled iterate, and
    /// a work vector.
    rhs: Vec<f64>,
    iterate: Vec<f64>,
    work: Vec<f64>,
    /// GMRES iterations (operator applications) so far.
    pub(crate) iterations: usize,
}

impl KrylovNewton {
    /// The matrices of `n` states whose Jacobian has entries at `pattern`.
    pub(crate) fn new(n: usize, pattern: &[(usize, usize)]) -> KrylovNewton {
        let mut rows: Vec<Vec<usize>> = (0..n).map(|i| vec![i]).collect();
        for &(r, c) in pattern {
            rows[r].push(c);
        }
        let mut row_start = Vec::with_capacity(n + 1);
        let (mut columns, mut diagonal) = (Vec::new(), Vec::with_capacity(n));
        row_start.push(0);
        for (i, row) in rows.iter_mut().enumerate() {
            row.sort_unstable();
            row.dedup();
            diagonal.push(columns.len() + row.iter().position(|&c| c == i).unwrap_or(0));
            columns.extend_from_slice(row);
            row_start.push(columns.len());
        }
        let slot_of_entry = pattern
            .iter()
            .map(|&(r, c)| {
                let row = &columns[row_start[r]..row_start[r + 1]];
                row_start[r] + row.binary_search(&c).unwrap_or(0)
            })
            .collect();
        let entries = columns.len();
        KrylovNewton {
            n,
            row_start,
            columns,
            diagonal,
            slot_of_entry,
            matrix: vec![0.0; entries],
            factors: vec![0.0; entries],
            weights: vec![1.0; n],
            slot_in_row: vec![usize::MAX; n],
            basis: vec![0.0; (RESTART + 1) * n],
            hessenberg: vec![0.0; (RESTART + 1) * RESTART],
            rotations: vec![(1.0, 0.0); RESTART],
            rotated: vec![0.0; RESTART + 1],
            rhs: vec![0.0; n],
            iterate: vec![0.0; n],
            work: vec![0.0; n],
            iterations: 0,
        }
    }

    /// Sets `shift·M − J` (`mass` its diagonal, I otherwise; `values` J at
    /// the pattern's entries) and its ILU(0) factors; `false` where a pivot
    /// of the incomplete factorisation vanishes or is not finite.
    pub(crate) fn factor(&mut self, shift: f64, mass: &[f64], values: &[f64]) -> bool {
        self.matrix.fill(0.0);
        for (&slot, &v) in self.slot_of_entry.iter().zip(values) {
            self.matrix[slot] -= v;
        }
        let diagonal_mass = mass.len() == self.n;
        for (i, &d) in self.diagonal.iter().enumerate() {
            self.matrix[d] += shift * if diagonal_mass { mass[i] } else { 1.0 };
        }
        // A Jacobian that is not finite has no factors, incomplete or not.
        if !self.matrix.iter().all(|v| v.is_finite()) {
            return false;
        }
        self.factors.copy_from_slice(&self.matrix);
        let a = &mut self.factors;
        for i in 0..self.n {
            let row = self.row_start[i]..self.row_start[i + 1];
            for slot in row.clone() {
                self.slot_in_row[self.columns[slot]] = slot;
            }
            for slot in self.row_start[i]..self.diagonal[i] {
                let k = self.columns[slot];
                let multiplier = a[slot] / a[self.diagonal[k]];
                a[slot] = multiplier;
                for upper in self.diagonal[k] + 1..self.row_start[k + 1] {
                    let target = self.slot_in_row[self.columns[upper]];
                    if target != usize::MAX {
                        a[target] -= multiplier * a[upper];
                    }
                }
            }
            for slot in row {
                self.slot_in_row[self.columns[slot]] = usize::MAX;
            }
            let pivot = a[self.diagonal[i]];
            if pivot == 0.0 || !pivot.is_finite() {
                return false;
            }
        }
        true
    }

    /// The step's error weights: `1 / (atol + rtol·|y_i|)`.
    pub(crate) fn set_error_weights(&mut self, y: &[f64], rtol: f64, atol: f64) {
        for (w, v) in self.weights.iter_mut().zip(y) {
            *w = 1.0 / (atol + rtol * v.abs());
        }
    }

    /// `out = (shift·M − J) x`.
    fn multiply(&self, x: &[f64], out: &mut [f64]) {
        for (i, o) in out.iter_mut().enumerate() {
            let row = self.row_start[i]..self.row_start[i + 1];
            *o = self.matrix[row.clone()]
                .iter()
                .zip(&self.columns[row])
                .map(|(a, &c)| a * x[c])
                .sum();
        }
    }

    /// `x ← (LU)⁻¹ x` with the incomplete factors.
    fn precondition(&self, x: &mut [f64]) {
        let a = &self.factors;
        for i in 0..self.n {
            let mut v = x[i];
            for slot in self.row_start[i]..self.diagonal[i] {
                v -= a[slot] * x[self.columns[slot]];
            }
            x[i] = v;
        }
        for i in (0..self.n).rev() {
            let mut v = x[i];
            for slot in self.diagonal[i] + 1..self.row_start[i + 1] {
                v -= a[slot] * x[self.columns[slot]];
            }
            x[i] = v / a[self.diagonal[i]];
        }
    }

    /// `out = W P⁻¹ A W⁻¹ v`: the scaled, preconditioned operator.
    fn apply(&mut self, v: &[f64], out: &mut [f64]) {
        for ((w, x), s) in self.work.iter_mut().zip(v).zip(&self.weights) {
            *w = x / s;
        }
        self.multiply(&self.work, out);
        self.precondition(out);
        out.iter_mut().zip(&self.weights).for_each(|(o, s)| *o *= s);
        self.iterations += 1;
    }

    /// Solves `(shift·M − J) x = b` in place to [`SOLVE_TOLERANCE`] in the
    /// error weights; `false` where GMRES did not get there.
    pub(crate) fn solve(&mut self, b: &mut [f64]) -> bool {
        let n = self.n;
        let tolerance = SOLVE_TOLERANCE * (n as f64).sqrt();
        self.precondition(b);
        for ((r, x), s) in self.rhs.iter_mut().zip(b.iter()).zip(&self.weights) {
            *r = x * s;
        }
        self.iterate.fill(0.0);
        let mut residual = norm(&self.rhs);
        // The residual of the restart: at first the right-hand side itself.
        let mut start = std::mem::take(&mut self.basis);
        start[..n].copy_from_slice(&self.rhs);
        let mut converged = residual <= tolerance;
        for _ in 0..MAX_RESTARTS {
            if converged || !residual.is_finite() {
                break;
            }
            // Arnoldi with modified Gram–Schmidt, H made triangular as it grows.
            start[..n].iter_mut().for_each(|x| *x /= residual);
            self.rotated.fill(0.0);
            self.rotated[0] = residual;
            let mut columns = 0;
            for j in 0..RESTART {
                let (done, next) = start.split_at_mut((j + 1) * n);
                let next = &mut next[..n];
                self.apply(&done[j * n..], next);
                let column = &mut self.hessenberg[j * (RESTART + 1)..(j + 1) * (RESTART + 1)];
                for i in 0..=j {
                    let vi = &done[i * n..(i + 1) * n];
                    let h = dot(next, vi);
                    column[i] = h;
                    next.iter_mut().zip(vi).for_each(|(x, v)| *x -= h * v);
                }
                let length = norm(next);
                column[j + 1] = length;
                for (i, &(c, s)) in self.rotations[..j].iter().enumerate() {
                    let (a, b) = (column[i], column[i + 1]);
                    column[i] = c * a + s * b;
                    column[i + 1] = -s * a + c * b;
                }
                let (a, b) = (column[j], column[j + 1]);
                let r = a.hypot(b);
                // A diagonal of the triangle at rounding level: the operator
                // is singular on the Krylov space, and the iterate would
                // grow without bound along its null vector.
                let scale = column[..=j].iter().fold(b.abs(), |m, v| m.max(v.abs()));
                if r <= 64.0 * f64::EPSILON * scale {
                    self.basis = start;
                    return false;
                }
                let (c, s) = (a / r, b / r);
                self.rotations[j] = (c, s);
                column[j] = r;
                column[j + 1] = 0.0;
                self.rotated[j + 1] = -s * self.rotated[j];
                self.rotated[j] *= c;
                columns = j + 1;
                residual = self.rotated[j + 1].abs();
                if residual <= tolerance || length == 0.0 || !residual.is_finite() {
                    break;
                }
                next.iter_mut().for_each(|x| *x /= length);
            }
            // y from the triangle, the iterate moved along the basis.
            let mut y = [0.0; RESTART];
            for i in (0..columns).rev() {
                let mut v = self.rotated[i];
                for k in i + 1..columns {
                    v -= self.hessenberg[k * (RESTART + 1) + i] * y[k];
                }
                y[i] = v / self.hessenberg[i * (RESTART + 1) + i];
            }
            for (k, &yk) in y[..columns].iter().enumerate() {
                let vk = &start[k * n..(k + 1) * n];
                self.iterate.iter_mut().zip(vk).for_each(|(x, v)| *x += yk * v);
            }
            converged = residual <= tolerance;
            if !converged {
                // The true residual starts the next cycle.
                let (first, rest) = start.split_at_mut(n);
                let iterate = std::mem::take(&mut self.iterate);
                self.apply(&iterate, &mut rest[..n]);
                self.iterate = iterate;
                for ((r, c), a) in first.iter_mut().zip(&self.rhs).zip(&rest[..n]) {
                    *r = c - a;
                }
                residual = norm(first);
                converged = residual <= tolerance;
            }
        }
        self.basis = start;
        for ((x, z), s) in b.iter_mut().zip(&self.iterate).zip(&self.weights) {
            *x = z / s;
        }
        converged && self.iterate.iter().all(|v| v.is_finite())
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn norm(a: &[f64]) -> f64 {
    dot(a, a).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The five-point Laplacian's pattern on an m × m periodic grid, and
    /// its values (a Jacobian −4/h² on the diagonal, 1/h² beside it).
    fn periodic_laplacian(m: usize) -> (Vec<(usize, usize)>, Vec<f64>) {
        let (mut pattern, mut values) = (Vec::new(), Vec::new());
        let scale = (m * m) as f64;
        for i in 0..m {
            for j in 0..m {
                for (a, b, v) in [
                    (i, j, -4.0),
                    ((i + 1) % m, j, 1.0),
                    ((i + m - 1) % m, j, 1.0),
                    (i, (j + 1) % m, 1.0),
                    (i, (j + m - 1) % m, 1.0),
                ] {
                    pattern.push((i * m + j, a * m + b));
                    values.push(v * scale);
                }
            }
        }
        (pattern, values)
    }

    #[test]
    fn solves_a_stiff_grid_to_its_weighted_tolerance() {
        // x known, b = (shift·I − J) x: GMRES stops at a thousandth of the
        // weights' unit in the preconditioned residual, which bounds the
        // error through ‖(P⁻¹A)⁻¹‖ (here J dwarfs the shift, ILU(0) is
        // rough, and that norm is some tens): well below the unit, in far
        // fewer iterations than states.
        let m = 40;
        let (pattern, values) = periodic_laplacian(m);
        let n = m * m;
        let mut krylov = KrylovNewton::new(n, &pattern);
        let shift = 10.0;
        assert!(krylov.factor(shift, &[], &values));
        let exact: Vec<f64> = (0..n).map(|k| (k as f64 * 0.37).sin() + 2.0).collect();
        let mut b = vec![0.0; n];
        krylov.multiply(&exact, &mut b);
        let (rtol, atol) = (1e-6, 1e-6);
        krylov.set_error_weights(&exact, rtol, atol);
        assert!(krylov.solve(&mut b));
        let worst = b
            .iter()
            .zip(&exact)
            .map(|(x, e)| (x - e).abs() / (atol + rtol * e.abs()))
            .fold(0.0, f64::max);
        assert!(worst < 0.1, "weighted error {worst:e}");
        assert!(krylov.iterations < 100, "{} iterations", krylov.iterations);
    }

    #[test]
    fn a_singular_matrix_behind_regular_incomplete_factors_fails_the_solve() {
        // A = [[1, 1, 0], [0, 1, 1], [1, 0, −1]] is singular (the third
        // column is the second minus the first) and b = (1, 0, 0) is not in
        // its range; ILU(0) drops the fill at (2, 1) and its pivots are
        // 1, 1, −1. GMRES cannot reach the tolerance and says so.
        let pattern = [(0, 0), (0, 1), (1, 1), (1, 2), (2, 0), (2, 2)];
        let a = [1.0, 1.0, 1.0, 1.0, 1.0, -1.0];
        // shift·I − J = A with shift 0: J = −A.
        let jacobian: Vec<f64> = a.iter().map(|v| -v).collect();
        let mut krylov = KrylovNewton::new(3, &pattern);
        assert!(krylov.factor(0.0, &[], &jacobian));
        let mut b = [1.0, 0.0, 0.0];
        assert!(!krylov.solve(&mut b));
        assert!(krylov.iterations <= (RESTART + 1) * MAX_RESTARTS);
    }

    #[test]
    fn a_vanishing_pivot_fails_the_factorisation() {
        // shift·I − J with J = shift·I on the diagonal: zero pivots.
        let pattern = [(0, 0), (1, 1)];
        let mut krylov = KrylovNewton::new(2, &pattern);
        assert!(!krylov.factor(2.0, &[], &[2.0, 2.0]));
        assert!(krylov.factor(3.0, &[], &[2.0, 2.0]));
        assert!(!krylov.factor(3.0, &[], &[f64::NAN, 2.0]));
    }
}
