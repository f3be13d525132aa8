//! Newton's method on the algebraic equations g(t, y, z) = 0 that a
//! generated model solves for z at each evaluation (its nonlinear
//! algebraic equations: a diode's exponential, a rate quadratic in a
//! concentration). The model supplies g and ∂g/∂z; this is the iteration,
//! on stack arrays, with a residual-halving safeguard.

/// Why the iteration stopped without a solution.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AlgebraicTrouble {
    /// ∂g/∂z is singular (or not finite) at an iterate: the equations do
    /// not determine z there (the DAE is not of index 1 at this point).
    Singular,
    /// No convergence within the iterations allowed.
    NoConvergence,
}

/// Iterations before giving up: Newton converges in a handful from a
/// nearby start (the last solution); a poor guess may need a few dozen.
const MAX_ITERATIONS: usize = 50;

/// Solves `g(z) = 0` from `start`, `eval(z, g, ∂g/∂z)` writing the residual
/// and its Jacobian (row-major). Converged when the update is below
/// 1e-14 of the iterate, or at the rounding floor (the update no longer
/// halving once below 1e-8 of it).
pub fn newton<const K: usize>(
    start: [f64; K],
    mut eval: impl FnMut(&[f64; K], &mut [f64; K], &mut [[f64; K]; K]),
) -> Result<[f64; K], AlgebraicTrouble> {
    let norm = |v: &[f64; K]| v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let mut z = start;
    let (mut residual, mut jacobian) = ([0.0; K], [[0.0; K]; K]);
    eval(&z, &mut residual, &mut jacobian);
    let mut residual_norm = norm(&residual);
    let mut previous = f64::INFINITY;
    for _ in 0..MAX_ITERATIONS {
        if !residual_norm.is_finite() {
            return Err(AlgebraicTrouble::NoConvergence);
        }
        // Factored even where the residual already vanishes: a solution
        // where ∂g/∂z is singular is no index-1 point.
        let mut delta = residual;
        if !crate::linalg::solve_in_place(&mut jacobian, &mut delta) {
            return Err(AlgebraicTrouble::Singular);
        }
        if residual_norm == 0.0 {
            return Ok(z);
        }
        // Halve the update until the residual falls (at most ten times);
        // where it never does (rounding, near the root), the full step.
        let mut lambda = 1.0;
        let mut trial = z;
        let mut fell = false;
        for _ in 0..10 {
            for i in 0..K {
                trial[i] = z[i] - lambda * delta[i];
            }
            eval(&trial, &mut residual, &mut jacobian);
            let n = norm(&residual);
            if n.is_finite() && n < residual_norm {
                residual_norm = n;
                fell = true;
                break;
            }
            lambda *= 0.5;
        }
        if !fell {
            lambda = 1.0;
            for i in 0..K {
                trial[i] = z[i] - delta[i];
            }
            eval(&trial, &mut residual, &mut jacobian);
            residual_norm = norm(&residual);
        }
        z = trial;
        let (step, size) = (lambda * norm(&delta), norm(&z));
        if step <= 1e-14 * size || (step >= 0.5 * previous && step <= 1e-8 * size) {
            return Ok(z);
        }
        previous = step;
    }
    Err(AlgebraicTrouble::NoConvergence)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_a_quadratic_and_a_diode() {
        // z² + z − 2 = 0 from z = 5: z = 1.
        let z = newton([5.0], |z, g, j| {
            g[0] = z[0] * z[0] + z[0] - 2.0;
            j[0][0] = 2.0 * z[0] + 1.0;
        })
        .unwrap();
        assert!((z[0] - 1.0).abs() < 1e-15, "{z:?}");
        // A diode in series with a resistor: 1e-12(e^(v/0.026) − 1) =
        // (5 − v)/1000, from v = 0: the exponential needs damping.
        let v = newton([0.0], |v, g, j| {
            g[0] = 1e-12 * ((v[0] / 0.026).exp() - 1.0) - (5.0 - v[0]) / 1000.0;
            j[0][0] = 1e-12 / 0.026 * (v[0] / 0.026).exp() + 1.0 / 1000.0;
        })
        .unwrap();
        let current = (5.0 - v[0]) / 1000.0;
        assert!((1e-12 * ((v[0] / 0.026).exp() - 1.0) - current).abs() < 1e-15);
        assert!(v[0] > 0.4 && v[0] < 0.6, "{v:?}");
    }

    #[test]
    fn a_singular_jacobian_is_reported() {
        // (z1 + z2)² = 1, 2(z1 + z2)² = 2: one equation twice.
        let r = newton([0.3, 0.2], |z, g, j| {
            let s = z[0] + z[1];
            g[0] = s * s - 1.0;
            g[1] = 2.0 * s * s - 2.0;
            j[0] = [2.0 * s, 2.0 * s];
            j[1] = [4.0 * s, 4.0 * s];
        });
        assert_eq!(r, Err(AlgebraicTrouble::Singular));
    }
}
