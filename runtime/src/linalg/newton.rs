//! The Newton matrices of the implicit methods, `γ·M − J` and, for
//! RADAU5, `(α + iβ)·M − J`, stored in the form the generated Jacobian's
//! pattern makes cheapest: banded after a reverse Cuthill–McKee
//! renumbering, sparse after a minimum-degree one, or dense (always for
//! finite differences and mass matrices); or, for the Rosenbrock method on
//! request, not factored at all but solved by GMRES (`krylov`); for a
//! model with sensitivity columns, its base block's matrices and block
//! forward substitution.

use crate::linalg::band_lu::{BandNewton, BandOrdering};
use crate::linalg::dense_lu::{ComplexLu, RealLu};
use crate::linalg::krylov::KrylovNewton;
use crate::linalg::sparse_lu::{SparseNewton, SparsePattern};

/// Which shifted matrices a method factors: RADAU5 a real and a complex
/// one, a Rosenbrock method the real one alone.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(crate) enum Shifts {
    /// `γ·M − J` only.
    Real,
    /// `γ·M − J` and `(α + iβ)·M − J`.
    RealAndComplex,
}

/// The factored Newton matrices, in one of three storage forms.
pub(crate) enum Newton {
    /// Dense LU with partial pivoting (the complex one only for
    /// [`Shifts::RealAndComplex`]).
    Dense(RealLu, Option<ComplexLu>),
    /// Banded LU in a renumbering that narrows the band.
    Band(Box<BandNewton>),
    /// Sparse LU on a minimum-degree ordering with a static fill.
    Sparse(Box<SparseNewton>),
    /// GMRES with an ILU(0) preconditioner, real shifts only.
    Krylov(Box<KrylovNewton>),
    /// A model with sensitivity columns: its base block's matrices, and
    /// block forward substitution.
    Sensitivity(Box<SensitivityNewton>),
}

/// The outcome of [`Newton::factor`].
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(crate) enum Factored {
    /// Factored.
    Yes,
    /// A pivot vanished: the method shrinks its step.
    Singular,
    /// The sparse LU gave way to the dense one: evaluate the Jacobian as
    /// a dense matrix and factor again.
    NeedsDenseJacobian,
}

/// Below this many states the dense LU is kept: the sparse one's
/// bookkeeping would not pay.
const SPARSE_FROM: usize = 64;

/// How the Newton matrices of `n` states with Jacobian `pattern` are
/// stored, and the operations of one real factorisation.
pub(crate) enum Structure {
    /// Dense.
    Dense,
    /// Banded in this renumbering.
    Band(BandOrdering),
    /// Sparse with this ordering and fill.
    Sparse(std::sync::Arc<SparsePattern>),
}

impl Structure {
    /// The cheapest storage for `pattern` (empty: dense), and the
    /// operations of one real factorisation in it.
    pub(crate) fn of(n: usize, pattern: &'static [(usize, usize)]) -> (Structure, f64) {
        let dense = 2.0 / 3.0 * (n as f64).powi(3);
        let mut best = (Structure::Dense, dense);
        if pattern.is_empty() {
            return best;
        }
        let ordering = BandOrdering::reverse_cuthill_mckee(n, pattern);
        if ordering.pays() {
            let (kl, ku) = (ordering.lower as f64, ordering.upper as f64);
            best = (Structure::Band(ordering), 2.0 * n as f64 * kl * (kl + ku + 1.0));
        }
        // A pattern over an eighth full fills in whole: not worth renumbering.
        if n >= SPARSE_FROM && 8 * pattern.len() < n * n {
            let sparse = SparsePattern::of_model(n, pattern);
            // The sparse elimination's indirect addressing costs some
            // twice the band's contiguous loops per operation.
            let operations = 2.0 * sparse.factor_operations();
            if operations < best.1 && operations < dense / 4.0 {
                best = (Structure::Sparse(sparse), operations);
            }
        }
        best
    }
}

impl Newton {
    /// The Newton matrices for `pattern`, and the operations of one real
    /// factorisation.
    pub(crate) fn for_pattern(
        n: usize,
        pattern: &'static [(usize, usize)],
        shifts: Shifts,
    ) -> (Newton, f64) {
        let (structure, operations) = Structure::of(n, pattern);
        (Newton::in_structure(n, structure, shifts), operations)
    }

    /// The matrices of `n` states stored as `structure` says.
    pub(crate) fn in_structure(n: usize, structure: Structure, shifts: Shifts) -> Newton {
        let complex = shifts == Shifts::RealAndComplex;
        match structure {
            Structure::Dense => Newton::dense(n, shifts),
            Structure::Band(ordering) => Newton::Band(Box::new(BandNewton::new(ordering, complex))),
            Structure::Sparse(sparse) => {
                Newton::Sparse(Box::new(SparseNewton::new(sparse, complex)))
            }
        }
    }

    /// The matrices of a model whose states are `n` base states and
    /// `columns` sensitivity columns of `n` (no mass matrix), and the
    /// operations of one real factorisation.
    pub(crate) fn for_sensitivities(
        n: usize,
        columns: usize,
        pattern: &'static [(usize, usize)],
        shifts: Shifts,
    ) -> (Newton, f64) {
        let (newton, operations) = SensitivityNewton::new(n, columns, pattern, shifts);
        (Newton::Sensitivity(Box::new(newton)), operations)
    }

    /// GMRES on `γ·M − J` in the Jacobian's own `pattern` (not empty),
    /// for methods with [`Shifts::Real`] alone.
    pub(crate) fn krylov(n: usize, pattern: &[(usize, usize)]) -> Newton {
        Newton::Krylov(Box::new(KrylovNewton::new(n, pattern)))
    }

    /// How the matrices are solved, as `Stats::linear_solver` names it.
    pub(crate) fn label(&self) -> &'static str {
        match self {
            Newton::Dense(..) => "dense LU",
            Newton::Band(_) => "band LU",
            Newton::Sparse(_) => "sparse LU",
            Newton::Krylov(_) => "GMRES",
            Newton::Sensitivity(s) => s.label(),
        }
    }

    /// The label of a factorisation that took over from GMRES.
    pub(crate) fn after_gmres(&self) -> &'static str {
        match self {
            Newton::Dense(..) => "GMRES→dense LU",
            Newton::Band(_) => "GMRES→band LU",
            Newton::Sparse(_) => "GMRES→sparse LU",
            Newton::Krylov(_) | Newton::Sensitivity(_) => "GMRES",
        }
    }

    /// GMRES iterations so far (0 for the factorisations).
    pub(crate) fn linear_iterations(&self) -> usize {
        match self {
            Newton::Krylov(krylov) => krylov.iterations,
            _ => 0,
        }
    }

    /// The error weights an iterative solve stops in (the factorisations
    /// solve exactly and ignore them).
    pub(crate) fn set_error_weights(&mut self, y: &[f64], rtol: f64, atol: f64) {
        if let Newton::Krylov(krylov) = self {
            krylov.set_error_weights(y, rtol, atol);
        }
    }

    fn dense(n: usize, shifts: Shifts) -> Newton {
        let complex = (shifts == Shifts::RealAndComplex).then(|| ComplexLu::new(n));
        Newton::Dense(RealLu::new(n), complex)
    }

    /// Whether the Jacobian is needed as a dense matrix.
    pub(crate) fn dense_jacobian(&self) -> bool {
        matches!(self, Newton::Dense(..))
    }

    /// Factors `γ·M − J` (and `(α + iβ)·M − J` where the matrices were made
    /// for both; `complex` is ignored otherwise), `mass` the diagonal of M
    /// (empty: I) or its dense row-major matrix, from the Jacobian as a
    /// dense row-major `matrix` (read by the dense LU) and as the non-zeros
    /// `values` at `pattern` (read by the others). A sparse LU that meets a
    /// pivot too small to keep without interchanges gives way to the dense
    /// LU, which pivots, for the rest of the run (the caller then grows its
    /// dense matrix, and the next evaluation fills it).
    pub(crate) fn factor(
        &mut self,
        gamma: f64,
        complex: (f64, f64),
        mass: &[f64],
        matrix: &[f64],
        values: &[f64],
        pattern: &[(usize, usize)],
    ) -> Factored {
        let (alpha, beta) = complex;
        let ok = match self {
            Newton::Dense(real, complex) => {
                real.factor_shifted_mass(gamma, mass, matrix)
                    && complex.as_mut().is_none_or(|complex| {
                        complex.factor_shifted_mass(alpha, beta, mass, matrix)
                    })
            }
            Newton::Band(band) => {
                band.factor_real(gamma, pattern, values)
                    && (!band.has_complex() || band.factor_complex(alpha, beta))
            }
            Newton::Sensitivity(s) => return s.factor(gamma, complex, values),
            Newton::Sparse(sparse) => {
                if sparse.factor(gamma, alpha, beta, |k| values[k]) {
                    return Factored::Yes;
                }
                let shifts =
                    if sparse.has_complex() { Shifts::RealAndComplex } else { Shifts::Real };
                *self = Newton::dense(sparse.states(), shifts);
                return Factored::NeedsDenseJacobian;
            }
            Newton::Krylov(krylov) => krylov.factor(gamma, mass, values),
        };
        if ok {
            Factored::Yes
        } else {
            Factored::Singular
        }
    }

    /// Solves `(γ·M − J) x = b` in place; `false` only where GMRES did
    /// not reach its tolerance (the factorisations solve exactly).
    pub(crate) fn solve_real(&mut self, b: &mut [f64]) -> bool {
        match self {
            Newton::Dense(real, _) => real.solve(b),
            Newton::Band(band) => band.solve_real(b),
            Newton::Sparse(sparse) => sparse.solve_real(b),
            Newton::Krylov(krylov) => return krylov.solve(b),
            Newton::Sensitivity(s) => s.solve_real(b),
        }
        true
    }

    /// The matrices of a model with sensitivity columns, for a staggered
    /// corrector; `None` for any other.
    pub(crate) fn sensitivity(&mut self) -> Option<&mut SensitivityNewton> {
        match self {
            Newton::Sensitivity(s) => Some(s),
            _ => None,
        }
    }

    /// Solves `((α + iβ)·M − J)(x + iy) = re + i·im` in place; only for
    /// matrices made with [`Shifts::RealAndComplex`].
    pub(crate) fn solve_complex(&mut self, re: &mut [f64], im: &mut [f64]) {
        match self {
            Newton::Dense(_, Some(complex)) => complex.solve(re, im),
            // Real-only matrices belong to methods without complex stages.
            Newton::Dense(_, None) => {}
            Newton::Band(band) => band.solve_complex(re, im),
            Newton::Sparse(sparse) => sparse.solve_complex(re, im),
            // GMRES is made for real shifts alone (`Newton::krylov`).
            Newton::Krylov(_) => {}
            Newton::Sensitivity(s) => s.solve_complex(re, im),
        }
    }
}

/// The Newton matrices of a model with forward-sensitivity columns (made by
/// `with_sensitivities()`): its states are the base model's y, then the
/// columns S_1 … S_m, and its Jacobian is block lower triangular,
///
/// ```text
/// [ J    0  …  0 ]
/// [ H_1  J  …  0 ]     H_j = ∂(J·S_j + ∂f/∂p_j)/∂y,
/// [ …          … ]
/// [ H_m  0  …  J ]
/// ```
///
/// so `γ·I − J_aug` is factored through its diagonal block alone and solved
/// by block forward substitution: x_0 = (γ − J)⁻¹ b_0, then
/// x_j = (γ − J)⁻¹ (b_j + H_j·x_0). One factorisation of the base model's
/// size serves every column, as CVODES's simultaneous corrector with the
/// exact Jacobian does (Maly & Petzold, "Numerical methods and software
/// for sensitivity analysis of differential-algebraic systems", Appl.
/// Numer. Math. 20, 1996); the solve is exact, so the methods keep their
/// order and their Newton convergence. A staggered corrector (RADAU5's)
/// solves the model's own block alone first, then the columns with the
/// states fixed, where H_j drops out and each column is solved with the
/// base block.
///
/// It keeps the base block's matrices and the couplings `H_j`.
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
            match self.base.factor(gamma, complex, &[], dense, base_values, pattern) {
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

    /// The five-point Laplacian's pattern on an m × m periodic grid.
    /// (Leaked: a model's pattern is static.)
    fn periodic_grid(m: usize) -> &'static [(usize, usize)] {
        let mut pattern = Vec::new();
        for i in 0..m {
            for j in 0..m {
                for (a, b) in [
                    (i, j),
                    ((i + 1) % m, j),
                    ((i + m - 1) % m, j),
                    (i, (j + 1) % m),
                    (i, (j + m - 1) % m),
                ] {
                    pattern.push((i * m + j, a * m + b));
                }
            }
        }
        pattern.leak()
    }

    #[test]
    fn each_pattern_gets_its_cheapest_newton_matrices() {
        // A chain: a band of one either side.
        let chain: Vec<(usize, usize)> = (0..100usize)
            .flat_map(|i| [(i, i), (i, (i + 1).min(99)), (i, i.saturating_sub(1))])
            .collect();
        assert!(matches!(Structure::of(100, chain.leak()).0, Structure::Band(_)));
        // A periodic grid: no narrow band, a sparse fill.
        assert!(matches!(Structure::of(256, periodic_grid(16)).0, Structure::Sparse(_)));
        // Small or full: dense.
        assert!(matches!(Structure::of(36, periodic_grid(6)).0, Structure::Dense));
        let full: Vec<(usize, usize)> =
            (0..80).flat_map(|i| (0..80).map(move |j| (i, j))).collect();
        assert!(matches!(Structure::of(80, full.leak()).0, Structure::Dense));
    }

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
