//! Linear algebra: the LU factorisations of the implicit methods (dense,
//! banded, sparse, GMRES in `krylov`, and `newton` choosing among them),
//! the product with a dense mass matrix, the spectral radius by the power
//! iteration, and dense solves for the small mass-matrix blocks that
//! generated code cannot solve symbolically (`M(q) q'' = f` with `M` full
//! and configuration-dependent; stack arrays, no allocation).

pub mod band_lu;
pub mod dense_lu;
pub(crate) mod krylov;
pub(crate) mod newton;
pub mod sparse_lu;

/// `out = M x` for the dense row-major mass matrix `m`.
pub(crate) fn apply_mass(m: &[f64], x: &[f64], out: &mut [f64]) {
    let n = x.len();
    for (i, o) in out.iter_mut().enumerate() {
        *o = m[i * n..(i + 1) * n].iter().zip(x).map(|(a, b)| a * b).sum();
    }
}

/// Solves `a x = b` in place (`b` becomes `x`) by Gaussian elimination with
/// partial pivoting; `a` is row-major `N × N` and is destroyed. Returns
/// `false` when a pivot is zero or not finite (a singular matrix).
pub fn solve_in_place<const N: usize>(a: &mut [[f64; N]; N], b: &mut [f64; N]) -> bool {
    for col in 0..N {
        let mut pivot = col;
        for row in col + 1..N {
            if a[row][col].abs() > a[pivot][col].abs() {
                pivot = row;
            }
        }
        let p = a[pivot][col];
        if p == 0.0 || !p.is_finite() {
            return false;
        }
        a.swap(col, pivot);
        b.swap(col, pivot);
        for row in col + 1..N {
            let factor = a[row][col] / p;
            if factor != 0.0 {
                let (above, below) = a.split_at_mut(row);
                for (target, p) in below[0][col..].iter_mut().zip(&above[col][col..]) {
                    *target -= factor * p;
                }
                b[row] -= factor * b[col];
            }
        }
    }
    for col in (0..N).rev() {
        let mut v = b[col];
        for k in col + 1..N {
            v -= a[col][k] * b[k];
        }
        b[col] = v / a[col][col];
    }
    true
}

/// Factors the row-major `n × n` matrix `a` in place into L (below the
/// diagonal, unit diagonal) and U with partial pivoting, row `i` of the
/// factors being row `pivots[i]` of `a` swapped in step by step (Golub &
/// Van Loan, Alg. 3.4.1). `false` when a pivot is zero or not finite.
pub(crate) fn lu_factor(a: &mut [f64], n: usize, pivots: &mut [usize]) -> bool {
    for col in 0..n {
        let pivot = (col..n)
            .max_by(|&p, &q| a[p * n + col].abs().total_cmp(&a[q * n + col].abs()))
            .unwrap_or(col);
        pivots[col] = pivot;
        let p = a[pivot * n + col];
        if p == 0.0 || !p.is_finite() {
            return false;
        }
        if pivot != col {
            for c in 0..n {
                a.swap(col * n + c, pivot * n + c);
            }
        }
        for row in col + 1..n {
            let factor = a[row * n + col] / p;
            a[row * n + col] = factor;
            if factor != 0.0 {
                for c in col + 1..n {
                    a[row * n + c] -= factor * a[col * n + c];
                }
            }
        }
    }
    true
}

/// Solves `a x = b` in place with the factors and pivots of [`lu_factor`].
pub(crate) fn lu_solve(lu: &[f64], n: usize, pivots: &[usize], b: &mut [f64]) {
    // The rows were swapped whole (L's columns too): all interchanges
    // first, then the triangles (LAPACK's getrs).
    for (col, &pivot) in pivots.iter().enumerate().take(n) {
        b.swap(col, pivot);
    }
    for col in 0..n {
        let v = b[col];
        for row in col + 1..n {
            b[row] -= lu[row * n + col] * v;
        }
    }
    for col in (0..n).rev() {
        let mut v = b[col];
        for c in col + 1..n {
            v -= lu[col * n + c] * b[c];
        }
        b[col] = v / lu[col * n + col];
    }
}

/// ρ(J) by the power iteration, `multiply(v, w)` writing w = J v: a lower
/// bound, close for the well-separated stiff eigenvalues that matter here,
/// and enough to a few percent for the decisions it serves. `v` holds the
/// start (the last call's eigenvector, warm; zeros make a fresh start) and
/// ends with the new one; `w` is scratch of the state's length. Stops when
/// the estimate settles to 1 %, after at most 30 products.
pub(crate) fn spectral_radius(
    v: &mut [f64],
    w: &mut [f64],
    mut multiply: impl FnMut(&[f64], &mut [f64]),
) -> f64 {
    let norm = |x: &[f64]| x.iter().map(|a| a * a).sum::<f64>().sqrt();
    let start = norm(v);
    if start == 0.0 || !start.is_finite() {
        for (i, x) in v.iter_mut().enumerate() {
            // A start with a component along every eigenvector, almost surely.
            *x = 1.0 + (i as f64 * 0.618_033_988_749_895) % 1.0;
        }
    }
    let mut norm_v = norm(v);
    let mut rho = f64::NAN;
    for _ in 0..30 {
        multiply(v, w);
        let norm_w = norm(w);
        if norm_w == 0.0 || !norm_w.is_finite() {
            v.fill(0.0);
            return if norm_w == 0.0 { 0.0 } else { f64::INFINITY };
        }
        let estimate = norm_w / norm_v;
        for (x, y) in v.iter_mut().zip(w.iter()) {
            *x = y / norm_w;
        }
        norm_v = 1.0;
        let settled = (estimate - rho).abs() <= 0.01 * estimate;
        rho = estimate;
        if settled {
            break;
        }
    }
    rho
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lu_factors_solve_a_system_that_needs_pivoting() {
        // x = (1, 2, 3, 4); the first pivot is zero and the rows change
        // places twice. Solved twice with one factorisation, as the tape's
        // linear systems are.
        let a0 = [0.0, 2.0, 1.0, 1.0, 1.0, 1.0, 1.0, 5.0, 2.0, 1.0, 3.0, 0.5, 4.0, 0.0, 1.0, 1.0];
        let x = [1.0, 2.0, 3.0, 4.0];
        let mut a = a0;
        let mut pivots = [0; 4];
        assert!(lu_factor(&mut a, 4, &mut pivots));
        for scale in [1.0, -2.0] {
            let mut b: Vec<f64> =
                (0..4).map(|i| scale * (0..4).map(|c| a0[i * 4 + c] * x[c]).sum::<f64>()).collect();
            lu_solve(&a, 4, &pivots, &mut b);
            for (got, want) in b.iter().zip(x) {
                assert!((got - scale * want).abs() < 1e-13, "{b:?}");
            }
        }
        let mut singular = [1.0, 2.0, 2.0, 4.0];
        assert!(!lu_factor(&mut singular, 2, &mut pivots));
    }

    #[test]
    fn solves_a_system_that_needs_pivoting() {
        // x = (1, 2, 3); the first pivot is zero.
        let mut a = [[0.0, 2.0, 1.0], [1.0, 1.0, 1.0], [2.0, 1.0, 3.0]];
        let mut b = [7.0, 6.0, 13.0];
        assert!(solve_in_place(&mut a, &mut b));
        for (x, want) in b.iter().zip([1.0, 2.0, 3.0]) {
            assert!((x - want).abs() < 1e-14);
        }
    }

    #[test]
    fn reports_a_singular_matrix() {
        let mut a = [[1.0, 2.0], [2.0, 4.0]];
        let mut b = [1.0, 2.0];
        assert!(!solve_in_place(&mut a, &mut b));
    }

    #[test]
    fn the_power_iteration_finds_the_dominant_eigenvalue() {
        // J = [[-1000, 1], [0, -1]]: ρ = 1000, to the 1 % asked for, from
        // a fresh start and again from the eigenvector found.
        let (mut v, mut w) = ([0.0; 2], [0.0; 2]);
        let j = |v: &[f64], w: &mut [f64]| {
            w[0] = -1000.0 * v[0] + v[1];
            w[1] = -v[1];
        };
        for _ in 0..2 {
            let rho = spectral_radius(&mut v, &mut w, j);
            assert!((rho - 1000.0).abs() < 1e-2 * 1000.0, "{rho}");
        }
    }
}
