//! The economic Taylor scheme with a fixed step (course notes §1.3.1):
//! y_{k+1} = y_k + h y'_k + h²/2 y''_k + … + hᵖ/p! y⁽ᵖ⁾_k, the derivatives
//! from the model's generated `taylor_derivatives`. The dense output is the
//! step's own Taylor polynomial, so values between the steps have the
//! scheme's order.

use crate::error::Error;
use crate::methods::taylor::interpolate;
use crate::methods::taylor::series::taylor_step;
use crate::model::Model;
use crate::options::Method;
use crate::solution::Solution;
use crate::step::driver::{Counts, DenseOutput, Driver};
use crate::step::Problem;

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
    let (steps, solution) = crate::step::equal_steps(t0, t1, step, options, solution)?;
    let dense_output = DenseOutput { width: order + 1, interpolate };
    let mut run = Driver::new(&problem, solution, Some(dense_output), 1);
    let mut counts = Counts::default();
    let n = M::STATES;
    let (mut y, mut next) = (y0.to_vec(), vec![0.0; n]);
    // The generated code writes all TAYLOR_ORDER blocks' room; only `order` are filled.
    let mut derivatives = vec![0.0; M::TAYLOR_ORDER * n];
    // The step's polynomial in s = (t - t_k)/h: c_j = h^j/j! y^(j), per component.
    let mut dense = vec![0.0; (order + 1) * n];
    for step in 0..steps {
        let t = t0 + (t1 - t0) * (step as f64 / steps as f64);
        let t_next = if step + 1 == steps {
            t1
        } else {
            t0 + (t1 - t0) * ((step + 1) as f64 / steps as f64)
        };
        if let Err(cause) = model.taylor_derivatives(t, &y, order, &mut derivatives) {
            return Err(run.evaluation_failed(t, cause, &counts));
        }
        counts.evals += 1;
        let h = t_next - t;
        taylor_step(&y, &derivatives[..order * n], h, &mut next);
        if run.keep_dense() {
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
        run.check_finite(t_next, &y, &counts)?;
        run.project(t_next, &mut y, &counts)?;
        if run.record(t_next, &y, &dense, &counts)? {
            break;
        }
    }
    Ok(run.finish(&counts))
}
