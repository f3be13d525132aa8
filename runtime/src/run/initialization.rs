//! Initialization as its own system: the model's initial equations
//! (`initial(lhs == rhs)`, Modelica's `initial equation`) solved for the
//! states they decide ([`Model::INITIAL_FREE`]) by Newton's method with
//! the generated Jacobian, from the starts given, before the run makes
//! the values consistent with its constraints and takes its first step.

use crate::error::Error;
use crate::model::Model;
use crate::solution::Solution;

/// Newton iterations before initialization gives up: a well-posed start
/// converges quadratically in a handful.
const MAX_ITERATIONS: usize = 50;

/// Moves the decided states of `y` at `t` until every initial equation
/// holds to rounding, or the error naming the equation left furthest from
/// zero (with `solution`, empty, as the partial result).
pub(crate) fn solve_initial_equations<M: Model>(
    model: &M,
    t: f64,
    y: &mut [f64],
    solution: Solution,
) -> Result<Solution, Error> {
    let (free, m) = (M::INITIAL_FREE, M::INITIAL_EQUATIONS.len());
    if m == 0 {
        return Ok(solution);
    }
    let n = free.len();
    let (mut residuals, mut jacobian, mut pivots) = (vec![0.0; m], vec![0.0; m * n], vec![0; n]);
    let scale = |y: &[f64], j: usize| 1.0 + y[free[j]].abs();
    let mut last_step = f64::INFINITY;
    for _ in 0..MAX_ITERATIONS {
        model.initial_residuals(t, y, &mut residuals);
        if residuals.iter().any(|r| !r.is_finite()) {
            return Err(failure::<M>(
                t,
                &residuals,
                "an initial equation is not finite at the start values",
                solution,
            ));
        }
        // Converged: the last step moved no state beyond rounding, or the
        // equations hold exactly.
        if last_step <= 4.0 * f64::EPSILON || residuals.iter().all(|&r| r == 0.0) {
            return Ok(solution);
        }
        model.initial_jacobian(t, y, &mut jacobian);
        if !crate::linalg::lu_factor(&mut jacobian, n, &mut pivots) {
            return Err(failure::<M>(
                t,
                &residuals,
                "the initial equations' Jacobian in the states they decide is singular there",
                solution,
            ));
        }
        crate::linalg::lu_solve(&jacobian, n, &pivots, &mut residuals);
        last_step = 0.0;
        for (j, &dx) in residuals.iter().enumerate() {
            last_step = f64::max(last_step, dx.abs() / scale(y, j));
            y[free[j]] -= dx;
        }
    }
    model.initial_residuals(t, y, &mut residuals);
    Err(failure::<M>(t, &residuals, "Newton's method did not converge", solution))
}

/// The error of an initialization that failed, at the equation furthest
/// from zero.
fn failure<M: Model>(t: f64, residuals: &[f64], why: &str, solution: Solution) -> Error {
    let worst = (0..residuals.len())
        .max_by(|&a, &b| residuals[a].abs().total_cmp(&residuals[b].abs()))
        .unwrap_or(0);
    let decided: Vec<&str> = M::INITIAL_FREE.iter().map(|&j| M::INFO.states[j]).collect();
    Error::Constraint {
        t,
        constraint: M::INITIAL_EQUATIONS[worst],
        level: 0,
        message: format!(
            "initialization failed: {why} (residual {:.3e}); it decides {}: give them starts nearer a solution",
            residuals[worst],
            decided.join(", ")
        ),
        partial: Box::new(solution),
    }
}
