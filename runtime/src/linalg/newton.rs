//! The Newton matrices of the implicit methods, `γ·M − J` and, for
//! RADAU5, `(α + iβ)·M − J`, stored in the form the generated Jacobian's
//! pattern makes cheapest: banded after a reverse Cuthill–McKee
//! renumbering, sparse after a minimum-degree one, or dense (always for
//! finite differences and mass matrices); or, for the Rosenbrock method on
//! request, not factored at all but solved by GMRES (`krylov`).

use crate::linalg::band_lu::{BandNewton, BandOrdering};
use crate::linalg::dense_lu::{ComplexLu, RealLu};
use crate::linalg::krylov::KrylovNewton;
use crate::linalg::sensitivity::SensitivityNewton;
use crate::linalg::sparse_lu::{SparseNewton, SparsePattern};
use crate::step::jacobian::DenseJacobian;

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
    /// (empty: I) or its dense row-major matrix. A sparse LU that meets a
    /// pivot too small to keep without interchanges gives way to the dense
    /// LU, which pivots, for the rest of the run (`jacobian` then grows its
    /// dense matrix, and the next evaluation fills it).
    pub(crate) fn factor(
        &mut self,
        gamma: f64,
        complex: (f64, f64),
        mass: &[f64],
        jacobian: &DenseJacobian,
        pattern: &[(usize, usize)],
    ) -> Factored {
        self.factor_from(gamma, complex, mass, &jacobian.matrix, jacobian.values(), pattern)
    }

    /// [`Newton::factor`] from the Jacobian as a dense row-major `matrix`
    /// (read by the dense LU) and as the non-zeros `values` at `pattern`
    /// (read by the others).
    pub(crate) fn factor_from(
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

#[cfg(test)]
mod structure_tests {
    use super::*;

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
}
