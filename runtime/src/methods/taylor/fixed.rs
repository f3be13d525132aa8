//! The economic Taylor scheme with a fixed step (course notes §1.3.1):
//! y_{k+1} = y_k + h y'_k + h²/2 y''_k + … + hᵖ/p! y⁽ᵖ⁾_k, the derivatives
//! from the model's generated `taylor_derivatives`. The dense output is the
//! step's own Taylor polynomial, so values between the steps have the
//! scheme's order.

use crate::error::Error;
use crate::methods::taylor::series::taylor_step;
use crate::methods::Problem;
use crate::model::Model;
use crate::options::Method;
use crate::solution::Solution;
use crate::step::events::{after_accepted_step, EventWatch};
use crate::step::projection::{project_onto_constraints, Projector};
use crate::step::return_if_not_finite;

/// Integrates with the order and step of `Method::TaylorFixed` in
/// `options`, in equal steps that end at `t1`.
pub(crate) fn integrate<M: Model>(
    problem: Problem<'_, M>,
    solution: Solution,
) -> Result<Solution, Error> {
    let Problem { model, t0, t1, y0, options } = problem;
    let Method::TaylorFixed { order, step } = options.method else {
        return Err(Error::MethodNotAvailable { method: options.method });
    };
    let (steps, mut solution) = crate::step::equal_steps(t0, t1, step, options, solution)?;
    let n = M::STATES;
    let (mut y, mut next) = (y0.to_vec(), vec![0.0; n]);
    // The generated code writes all TAYLOR_ORDER blocks' room; only `order` are filled.
    let mut derivatives = vec![0.0; M::TAYLOR_ORDER * n];
    let mut events = EventWatch::new(model, t0, y0, 1);
    let mut projector = Projector::new(model);
    // The step's polynomial in s = (t - t_k)/h: c_j = h^j/j! y^(j), per component.
    let mut dense = vec![0.0; (order + 1) * n];
    let keep_dense = options.dense_output || events.is_some();
    if keep_dense {
        solution.set_interpolant(order + 1, crate::methods::taylor::interpolate);
    }
    for step in 0..steps {
        let t = t0 + (t1 - t0) * (step as f64 / steps as f64);
        let t_next = if step + 1 == steps {
            t1
        } else {
            t0 + (t1 - t0) * ((step + 1) as f64 / steps as f64)
        };
        if let Err(cause) = model.taylor_derivatives(t, &y, order, &mut derivatives) {
            return Err(Error::Evaluation { t, cause, partial: Box::new(solution) });
        }
        let h = t_next - t;
        taylor_step(&y, &derivatives[..order * n], h, &mut next);
        if keep_dense {
            for i in 0..n {
                let c = &mut dense[i * (order + 1)..(i + 1) * (order + 1)];
                c[0] = y[i];
                let mut scale = 1.0;
                for j in 1..=order {
                    scale *= h / j as f64;
                    c[j] = scale * derivatives[(j - 1) * n + i];
                }
            }
        }
        std::mem::swap(&mut y, &mut next);
        return_if_not_finite!(y, t_next, M, solution);
        project_onto_constraints!(projector, t_next, &mut y, solution);
        if keep_dense {
            solution.push_dense(t_next, &y, &dense);
        } else {
            solution.push(t_next, &y);
        }
        let stats = solution.stats_mut();
        stats.steps += 1;
        stats.rhs_evals += 1;
        after_accepted_step!(events, solution);
    }
    Ok(solution)
}
