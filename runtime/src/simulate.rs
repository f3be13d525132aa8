//! Checks a run's request and hands it to the method.

use crate::adaptive;
use crate::backward_euler;
use crate::dop853::Dop853;
use crate::dopri5::Dopri5;
use crate::error::Error;
use crate::explicit_rk;
use crate::model::Model;
use crate::options::{Method, Options};
use crate::radau5;
use crate::solution::Solution;

/// Integrates `model` from `t0` to `t1` with `options`.
pub fn simulate<M: Model + Clone + Send + Sync + 'static>(
    model: &M,
    t0: f64,
    t1: f64,
    options: &Options,
) -> Result<Solution, Error> {
    if !t0.is_finite() || !t1.is_finite() {
        return Err(Error::InvalidOptions {
            message: format!("the interval [{t0}, {t1}] must be finite"),
        });
    }
    let tolerances_ok = options.rtol.is_finite()
        && options.atol.is_finite()
        && options.rtol >= 0.0
        && options.atol >= 0.0
        && (options.rtol >= 1e-15 || options.atol > 0.0);
    if !tolerances_ok {
        return Err(Error::InvalidOptions {
            message: format!(
                "tolerances must be finite and non-negative, with rtol ≥ 1e-15 or atol > 0; got rtol = {}, atol = {}",
                options.rtol, options.atol
            ),
        });
    }
    let method = match options.method {
        Method::Auto if options.rtol >= 1e-7 => Method::Dopri5,
        Method::Auto => Method::Dop853,
        m => m,
    };
    let capacity = 1024;
    match method {
        Method::Dopri5 => {
            return adaptive::integrate::<M, Dopri5>(
                model,
                t0,
                t1,
                options,
                Solution::new(model, capacity),
            )
        }
        Method::Radau5 => {
            return radau5::integrate(model, t0, t1, options, Solution::new(model, capacity))
        }
        Method::Dop853 => {
            return adaptive::integrate::<M, Dop853>(
                model,
                t0,
                t1,
                options,
                Solution::new(model, capacity),
            )
        }
        _ => {}
    }
    let step = options.step.unwrap_or((t1 - t0).abs() / 1000.0);
    if !(step.is_finite() && step > 0.0) && t1 != t0 {
        return Err(Error::InvalidOptions {
            message: format!("the step must be positive and finite, not {step}"),
        });
    }
    let tableau = match method {
        Method::Rk4 => &explicit_rk::RK4,
        Method::Rk38 => &explicit_rk::RK38,
        Method::Euler => &explicit_rk::EULER,
        Method::Midpoint => &explicit_rk::MIDPOINT,
        Method::Heun => &explicit_rk::HEUN,
        Method::Ralston => &explicit_rk::RALSTON,
        Method::BackwardEuler => {
            let steps = ((t1 - t0).abs() / step).ceil().max(1.0);
            if steps > options.max_steps as f64 {
                return Err(Error::InvalidOptions {
                    message: format!(
                        "{steps} steps of {step} exceed Options::max_steps ({})",
                        options.max_steps
                    ),
                });
            }
            return backward_euler::integrate(
                model,
                t0,
                t1,
                steps as usize,
                Solution::new(model, steps as usize + 1),
            );
        }
        other => return Err(Error::MethodNotAvailable { method: other }),
    };
    let capacity = ((t1 - t0).abs() / step).ceil().min(1e6) as usize + 1;
    let solution = Solution::new(model, capacity);
    explicit_rk::integrate(model, tableau, t0, t1, step, options.max_steps, solution)
}
