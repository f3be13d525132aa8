//! Backward (implicit) Euler with a fixed step, solved by Newton's method
//! with the model's Jacobian: y₁ = y₀ + h f(t₁, y₁), order 1, L-stable
//! (course notes §1.3; Hairer & Wanner, *Solving ODEs II*, §IV.3).

use crate::dense_lu::RealLu;
use crate::error::Error;
use crate::events::{stop_at_terminal_event, EventWatch};
use crate::model::{EvalError, Model};
use crate::projection::{project_onto_constraints, Projector};
use crate::solution::Solution;

/// Newton iterations per step before the run stops with an error.
const MAX_NEWTON: usize = 10;

/// Integrates with `steps` equal steps from `t0` to `t1`.
pub(crate) fn integrate<M: Model>(
    model: &M,
    t0: f64,
    t1: f64,
    y0: &[f64],
    steps: usize,
    mut solution: Solution,
) -> Result<Solution, Error> {
    let n = M::STATES;
    let h = (t1 - t0) / steps as f64;
    let (mut y, mut next, mut f, mut delta) =
        (vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let mut jacobian = vec![0.0; n * n];
    let mut values = vec![0.0; M::JACOBIAN_PATTERN.len()];
    let mut lu = RealLu::new(n);
    let (mut evals, mut jacobian_evals) = (0usize, 0usize);
    y.copy_from_slice(y0);
    let mut events = EventWatch::new(model, t0, y0, 1);
    let mut projector = Projector::new(model);
    for step in 0..steps {
        let t_next = if step + 1 == steps {
            t1
        } else {
            t0 + (t1 - t0) * ((step + 1) as f64 / steps as f64)
        };
        // The Jacobian at the start of the step; finite differences for
        // models without an analytic one.
        let fail = |cause, solution| {
            Err(Error::Evaluation {
                t: t_next,
                cause,
                partial: Box::new(solution),
            })
        };
        jacobian.iter_mut().for_each(|v| *v = 0.0);
        jacobian_evals += 1;
        match model.jacobian(t_next, &y, &mut values) {
            Ok(()) => {
                for (&(r, c), &v) in M::JACOBIAN_PATTERN.iter().zip(&values) {
                    jacobian[r * n + c] = v;
                }
            }
            Err(EvalError::JacobianUnavailable) => {
                evals += 1;
                if let Err(cause) = model.rhs(t_next, &y, &mut f) {
                    return fail(cause, solution);
                }
                for j in 0..n {
                    let saved = y[j];
                    let d = (f64::EPSILON * saved.abs().max(1e-5)).sqrt();
                    y[j] = saved + d;
                    evals += 1;
                    let r = model.rhs(t_next, &y, &mut delta);
                    y[j] = saved;
                    if let Err(cause) = r {
                        return fail(cause, solution);
                    }
                    for i in 0..n {
                        jacobian[i * n + j] = (delta[i] - f[i]) / d;
                    }
                }
            }
            Err(cause) => return fail(cause, solution),
        }
        if !lu.factor_shifted(1.0 / h, &jacobian) {
            return Err(Error::SingularMatrix {
                t: t_next,
                partial: Box::new(solution),
            });
        }
        // Newton on g(Y) = (Y − y)/h − f(t₁, Y) from Y = y: (I/h − J) δ = −g.
        next.copy_from_slice(&y);
        let mut converged = false;
        for _ in 0..MAX_NEWTON {
            evals += 1;
            if let Err(cause) = model.rhs(t_next, &next, &mut f) {
                return fail(cause, solution);
            }
            for i in 0..n {
                delta[i] = f[i] - (next[i] - y[i]) / h;
            }
            lu.solve(&mut delta);
            let (mut size, mut scale) = (0.0f64, 0.0f64);
            for i in 0..n {
                next[i] += delta[i];
                size = size.max(delta[i].abs());
                scale = scale.max(next[i].abs());
            }
            if !size.is_finite() {
                break;
            }
            if size <= 1e-13 * scale.max(1e-300) || size == 0.0 {
                converged = true;
                break;
            }
        }
        if !converged {
            let stats = solution.stats_mut();
            stats.rhs_evals = evals;
            stats.jacobian_evals = jacobian_evals;
            return Err(Error::NewtonFailure {
                t: t_next,
                h,
                partial: Box::new(solution),
            });
        }
        y.copy_from_slice(&next);
        project_onto_constraints!(projector, t_next, &mut y, solution);
        solution.push(t_next, &y);
        let stats = solution.stats_mut();
        stats.steps += 1;
        stats.rhs_evals = evals;
        stats.jacobian_evals = jacobian_evals;
        stop_at_terminal_event!(events, solution);
    }
    Ok(solution)
}
