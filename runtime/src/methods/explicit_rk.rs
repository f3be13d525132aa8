//! Explicit Runge–Kutta methods with a fixed step, driven by their Butcher
//! tableaux (course notes §1.3.2; Hairer, Nørsett, Wanner, *Solving ODEs I*,
//! §II.1). The tableaux are data; one stepping routine serves them all.

use crate::error::Error;
use crate::model::Model;
use crate::options::Method;
use crate::solution::Solution;
use crate::step::driver::{Counts, Driver};
use crate::step::Problem;

/// An explicit Butcher tableau: `a` strictly lower triangular (row i has i
/// entries), weights `b`, nodes `c`.
#[derive(Clone, Copy, Debug)]
pub struct Tableau {
    /// Name for messages.
    pub name: &'static str,
    /// Classical order.
    pub order: usize,
    /// Stage coefficients, row i with i entries.
    pub a: &'static [&'static [f64]],
    /// Weights.
    pub b: &'static [f64],
    /// Nodes.
    pub c: &'static [f64],
}

/// Explicit Euler.
pub const EULER: Tableau = Tableau { name: "Euler", order: 1, a: &[&[]], b: &[1.0], c: &[0.0] };

/// The two-stage family of the course notes, eq. 1.19:
/// `y + h(1−γ) f(x, y) + hγ f(x + h/(2γ), y + h/(2γ) f(x, y))`. γ = 1.
pub const MIDPOINT: Tableau =
    Tableau { name: "midpoint", order: 2, a: &[&[], &[0.5]], b: &[0.0, 1.0], c: &[0.0, 0.5] };

/// Eq. 1.19 with γ = 1/2 (Heun's method, the explicit trapezoidal rule).
pub const HEUN: Tableau =
    Tableau { name: "Heun", order: 2, a: &[&[], &[1.0]], b: &[0.5, 0.5], c: &[0.0, 1.0] };

/// Eq. 1.19 with γ = 3/4 (Ralston's method, smallest error constant).
pub const RALSTON: Tableau = Tableau {
    name: "Ralston",
    order: 2,
    a: &[&[], &[2.0 / 3.0]],
    b: &[0.25, 0.75],
    c: &[0.0, 2.0 / 3.0],
};

/// The classic fourth-order Runge–Kutta method.
pub const RK4: Tableau = Tableau {
    name: "RK4",
    order: 4,
    a: &[&[], &[0.5], &[0.0, 0.5], &[0.0, 0.0, 1.0]],
    b: &[1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0],
    c: &[0.0, 0.5, 0.5, 1.0],
};

/// Kutta's 3/8 rule (fourth order).
pub const RK38: Tableau = Tableau {
    name: "3/8 rule",
    order: 4,
    a: &[&[], &[1.0 / 3.0], &[-1.0 / 3.0, 1.0], &[1.0, -1.0, 1.0]],
    b: &[0.125, 0.375, 0.375, 0.125],
    c: &[0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0],
};

/// Integrates `problem` with the tableau of its method (`Euler`, `Rk4`,
/// `Rk38`, `Midpoint`, `Heun` or `Ralston`) in equal steps of
/// [`crate::Options::step`].
pub(crate) fn integrate<M: Model>(
    problem: Problem<'_, M>,
    solution: Solution,
) -> Result<Solution, Error> {
    let (steps, solution) = crate::step::option_steps(&problem, solution)?;
    let tableau = match problem.options.method {
        Method::Rk4 => &RK4,
        Method::Rk38 => &RK38,
        Method::Euler => &EULER,
        Method::Midpoint => &MIDPOINT,
        Method::Heun => &HEUN,
        Method::Ralston => &RALSTON,
        other => return Err(Error::MethodNotAvailable { method: other }),
    };
    integrate_tableau(&problem, tableau, steps, solution)
}

/// Integrates `problem` from `t0` to `t1` in `steps` equal steps, landing
/// exactly on `t1`. Stage buffers are allocated once, before the loop.
fn integrate_tableau<M: Model>(
    problem: &Problem<'_, M>,
    tableau: &Tableau,
    steps: usize,
    solution: Solution,
) -> Result<Solution, Error> {
    let Problem { model, t0, t1, y0, .. } = *problem;
    let mut run = Driver::new(problem, solution, None, 1);
    let mut counts = Counts::default();
    let n = M::STATES;
    let s = tableau.b.len();
    let mut y = vec![0.0; n];
    y.copy_from_slice(y0);
    let span = t1 - t0;
    let h = span / steps as f64;
    let mut k = vec![0.0; s * n];
    let mut stage = vec![0.0; n];
    for step in 0..steps {
        // t from the step count, not by accumulation: no drift over long runs.
        let t = t0 + span * (step as f64 / steps as f64);
        for i in 0..s {
            stage.copy_from_slice(&y);
            for (j, &aij) in tableau.a[i].iter().enumerate() {
                if aij != 0.0 {
                    for (st, kj) in stage.iter_mut().zip(&k[j * n..(j + 1) * n]) {
                        *st += h * aij * kj;
                    }
                }
            }
            let ti = t + tableau.c[i] * h;
            let (_, rest) = k.split_at_mut(i * n);
            if let Err(cause) = model.rhs(ti, &stage, &mut rest[..n]) {
                return Err(run.evaluation_failed(ti, cause, &counts));
            }
            counts.evals += 1;
        }
        for (i, &bi) in tableau.b.iter().enumerate() {
            for (yv, ki) in y.iter_mut().zip(&k[i * n..(i + 1) * n]) {
                *yv += h * bi * ki;
            }
        }
        let t_next =
            if step + 1 == steps { t1 } else { t0 + span * ((step + 1) as f64 / steps as f64) };
        run.check_finite(t_next, &y, &counts)?;
        run.project(t_next, &mut y, &counts)?;
        if run.record(t_next, &y, &[], &counts)? {
            break;
        }
    }
    Ok(run.finish(&counts))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Order conditions up to order 4 (Hairer–Nørsett–Wanner I, Table II.2.1).
    fn order_conditions(t: &Tableau) -> Vec<f64> {
        let s = t.b.len();
        let a = |i: usize, j: usize| t.a[i].get(j).copied().unwrap_or(0.0);
        let (b, c) = (t.b, t.c);
        let sum = |f: &dyn Fn(usize) -> f64| (0..s).map(f).sum::<f64>();
        let mut residuals = vec![sum(&|i| b[i]) - 1.0];
        if t.order >= 2 {
            residuals.push(sum(&|i| b[i] * c[i]) - 0.5);
        }
        if t.order >= 3 {
            residuals.push(sum(&|i| b[i] * c[i] * c[i]) - 1.0 / 3.0);
            residuals.push(sum(&|i| b[i] * sum(&|j| a(i, j) * c[j])) - 1.0 / 6.0);
        }
        if t.order >= 4 {
            residuals.push(sum(&|i| b[i] * c[i].powi(3)) - 0.25);
            residuals.push(sum(&|i| b[i] * c[i] * sum(&|j| a(i, j) * c[j])) - 0.125);
            residuals.push(sum(&|i| b[i] * sum(&|j| a(i, j) * c[j] * c[j])) - 1.0 / 12.0);
            residuals
                .push(sum(&|i| b[i] * sum(&|j| a(i, j) * sum(&|k| a(j, k) * c[k]))) - 1.0 / 24.0);
        }
        // Row sums equal the nodes.
        residuals.extend((0..s).map(|i| sum(&|j| a(i, j)) - c[i]));
        residuals
    }

    #[test]
    fn tableaux_satisfy_their_order_conditions() {
        for t in [EULER, MIDPOINT, HEUN, RALSTON, RK4, RK38] {
            for (k, r) in order_conditions(&t).into_iter().enumerate() {
                assert!(r.abs() < 1e-15, "{}: condition {k} off by {r}", t.name);
            }
        }
    }
}
