//! Checks a run's request and hands it to the method.

use crate::error::Error;
use crate::explicit_rk;
use crate::model::Model;
use crate::options::{Method, Options};
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
    let step = options.step.unwrap_or((t1 - t0).abs() / 1000.0);
    if !(step.is_finite() && step > 0.0) && t1 != t0 {
        return Err(Error::InvalidOptions {
            message: format!("the step must be positive and finite, not {step}"),
        });
    }
    let tableau = match options.method {
        Method::Auto | Method::Rk4 => &explicit_rk::RK4,
        Method::Rk38 => &explicit_rk::RK38,
        Method::Euler => &explicit_rk::EULER,
        other => return Err(Error::MethodNotAvailable { method: other }),
    };
    let capacity = ((t1 - t0).abs() / step).ceil().min(1e6) as usize + 1;
    let solution = Solution::new(model, capacity);
    explicit_rk::integrate(model, tableau, t0, t1, step, options.max_steps, solution)
}
