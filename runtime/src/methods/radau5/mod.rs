//! RADAU5: the 3-stage Radau IIA collocation method of order 5 for stiff
//! problems, as in Hairer & Wanner's code `radau5.f` (Hairer, Wanner,
//! *Solving ODEs II*, §IV.8): simplified Newton on the system transformed by
//! the eigenvectors of A⁻¹ (one real and one complex linear system of size
//! n), Jacobian and factorisation reuse across steps, the embedded error
//! estimate filtered through (γ/h − J)⁻¹, Gustafsson's predictive step
//! control, and continuous output from the collocation polynomial. A model
//! with sensitivity columns is iterated staggered: its own states to
//! convergence, then the columns, linear once the states are fixed, with
//! the same LU.

mod coefficients;
mod counted;
mod iteration;
mod work;

pub(crate) use coefficients::interpolate;

use crate::error::Error;
use crate::linalg::newton::Structure;
use crate::model::Model;
use crate::solution::Solution;
use crate::step::control::Predictive;
use crate::step::driver::{DenseOutput, Driver};
use crate::step::stiffness::{Finish, NonStiffWatch};
use crate::step::Problem;
use coefficients::{FACL, FACR, NIT, SAFE};
use iteration::Iterated;
use work::Radau;

/// What needs redoing before the next step: everything, the factorisation
/// only, or nothing (same h, same LU).
#[derive(Clone, Copy, PartialEq)]
enum Refresh {
    Jacobian,
    Factorisation,
    Nothing,
}

/// The floating-point operations of one factorisation of RADAU5's two
/// Newton matrices (the real one and the complex one, which costs four
/// real ones) and of one solve with both, for `M`'s structure: banded
/// where [`Newton::for_pattern`] bands it, dense otherwise.
pub(crate) fn newton_operations<M: Model>() -> (f64, f64) {
    let n = M::STATES as f64;
    let pattern = if M::MASS.diagonal().is_empty() { M::JACOBIAN.pattern() } else { &[] };
    match Structure::of(M::STATES, pattern) {
        (Structure::Band(ordering), _) => {
            let (kl, ku) = (ordering.lower as f64, ordering.upper as f64);
            (5.0 * 2.0 * n * kl * (kl + ku + 1.0), 5.0 * 2.0 * n * (2.0 * kl + ku + 1.0))
        }
        (Structure::Sparse(sparse), operations) => {
            (5.0 * operations, 5.0 * 2.0 * sparse.entries() as f64)
        }
        (Structure::Dense, _) => (5.0 * 2.0 / 3.0 * n * n * n, 5.0 * 2.0 * n * n),
    }
}

/// Integrates `model` from `t0` to `t1` with RADAU5.
pub(crate) fn integrate<M: Model>(
    problem: Problem<'_, M>,
    solution: Solution,
) -> Result<Solution, Error> {
    integrate_watching(problem, None, solution).map(|(s, _)| s)
}

/// Where the step fell below what the run allows: after Newton failed
/// `failures` times in a row while it shrank, `Error::NewtonFailure`; else
/// `Error::StepSizeUnderflow`.
fn underflow(failures: usize, t: f64, h: f64, partial: Box<Solution>) -> Error {
    if failures == 0 {
        return Error::StepSizeUnderflow { t, h, partial };
    }
    Error::NewtonFailure {
        t,
        h,
        tried: format!(
            "{failures} Newton iterations in a row failed to converge while the step shrank to {h:e}, each retried with a fresh Jacobian or factorisation"
        ),
        partial,
    }
}

/// Integrates `model` from `t0` to `t1` with RADAU5, stopping early with
/// [`Finish::NonStiffAt`] where `watch` finds the problem no longer stiff
/// (h·ρ(J), ρ by the power iteration on each new Jacobian).
pub(crate) fn integrate_watching<M: Model>(
    problem: Problem<'_, M>,
    watch: Option<NonStiffWatch>,
    solution: Solution,
) -> Result<(Solution, Finish), Error> {
    let dense = DenseOutput { width: 4, interpolate };
    let mut run = Driver::new(&problem, solution, Some(dense), 1).watching(watch);
    let Problem { model, t0, y0: start, options, .. } = problem;
    let mut r = Radau::new(model, options, t0, start);
    let mut y = start.to_vec();
    if t0 == run.t1 {
        return Ok((run.finish(&r.w.counts), Finish::Done));
    }
    if let Err(cause) = r.evaluate_start(t0, &y) {
        return Err(run.evaluation_failed(t0, cause, &r.w.counts));
    }
    let mut h = options.initial_step.unwrap_or(1e-6).abs().min(run.hmax) * run.direction;
    r.set_scale(&y, h);
    let mut t = t0;
    let mut last = false;
    if run.reaches_end(t, h * 1.0001) {
        h = run.t1 - t;
        last = true;
    }
    let mut h_old = h;
    let mut control = Predictive::new(0.25, SAFE, (FACR, FACL), h);
    let (mut first, mut reject) = (true, false);
    let cfac = SAFE * (1 + 2 * NIT) as f64;
    let (mut refresh, mut singular) = (Refresh::Jacobian, 0usize);
    // ρ(J) at the last Jacobian.
    let mut rho = f64::INFINITY;

    loop {
        let caljac = refresh == Refresh::Jacobian;
        if caljac {
            if let Err(cause) = r.evaluate_jacobian(t, &mut y) {
                return Err(run.evaluation_failed(t, cause, &r.w.counts));
            }
            if watch.is_some() {
                rho = r.w.jacobian.spectral_radius::<M>();
            }
        }
        if refresh != Refresh::Nothing {
            match r.factor(t, &mut y, h) {
                Err(cause) => return Err(run.evaluation_failed(t, cause, &r.w.counts)),
                Ok(true) => {}
                Ok(false) => {
                    singular += 1;
                    if singular >= 5 {
                        let counts = &r.w.counts;
                        return Err(run.fail(counts, |partial| Error::SingularMatrix {
                            t,
                            h,
                            partial,
                        }));
                    }
                    refresh = retry(&mut h, 0.5, &mut reject, &mut last, caljac);
                    continue;
                }
            }
        }
        run.check_steps(t, &r.w.counts)?;
        if run.step_too_small(t, h) {
            let failures = r.newton_failures;
            return Err(run.fail(&r.w.counts, |partial| underflow(failures, t, h, partial)));
        }
        r.starting_values(first, h / h_old);
        let newt = match r.iterate(t, h, &y) {
            Iterated::Converged(iterations) => iterations,
            Iterated::Retry { factor, failed } => {
                r.newton_failures += usize::from(failed);
                refresh = retry(&mut h, factor, &mut reject, &mut last, caljac);
                continue;
            }
            Iterated::Failed { at, cause } => {
                return Err(run.evaluation_failed(at, cause, &r.w.counts));
            }
        };
        let theta = r.state_control.theta;
        r.newton_failures = 0;
        let err = match r.error(t, h, &y, first || reject) {
            Err(cause) => return Err(run.evaluation_failed(t, cause, &r.w.counts)),
            Ok(err) if err.is_finite() => err,
            Ok(_) => {
                refresh = retry(&mut h, 0.5, &mut reject, &mut last, caljac);
                continue;
            }
        };
        let fac = SAFE.min(cfac / (newt + 2 * NIT) as f64);
        let quot = FACR.max(FACL.min(err.powf(0.25) / fac));
        if err >= 1.0 {
            (reject, last) = (true, false);
            h = if first { h * 0.1 } else { h / quot };
            run.rejected += usize::from(run.accepted >= 1);
            refresh = if caljac { Refresh::Factorisation } else { Refresh::Jacobian };
            continue;
        }
        first = false;
        let quot = control.accepted(h, err, quot, run.accepted > 0);
        h_old = h;
        t = if last { run.t1 } else { t + h };
        r.advance(&mut y);
        run.check_finite(t, &y, &r.w.counts)?;
        run.project(t, &mut y, &r.w.counts)?;
        r.set_scale(&y, h);
        let counts = r.w.counts;
        if run.record(t, &y, r.cont(), &counts)? || last {
            break;
        }
        if let Err(cause) = r.evaluate_start(t, &y) {
            return Err(run.evaluation_failed(t, cause, &r.w.counts));
        }
        let h_new = run.next_step(h / quot, h, reject);
        reject = false;
        if run.calm(h.abs() * rho) {
            return Ok((run.finish(&r.w.counts), Finish::NonStiffAt { t, h: h_new }));
        }
        let reuse = r.reuse;
        if run.reaches_end(t, h_new / reuse.quot1) {
            h = run.t1 - t;
            last = true;
        } else {
            let qt = h_new / h;
            if theta <= reuse.thet && (reuse.quot1..=reuse.quot2).contains(&qt) {
                refresh = Refresh::Nothing;
                continue;
            }
            h = h_new;
        }
        refresh = if theta <= reuse.thet { Refresh::Factorisation } else { Refresh::Jacobian };
    }
    Ok((run.finish(&r.w.counts), Finish::Done))
}

/// After a failed Newton iteration or step: shrink h by `factor`, mark the
/// step rejected, and refactor with the same Jacobian if it was just
/// computed, else get a new one (the JAC/DECOMP decision of radau5.f).
fn retry(h: &mut f64, factor: f64, reject: &mut bool, last: &mut bool, caljac: bool) -> Refresh {
    *h *= factor;
    *reject = true;
    *last = false;
    if caljac {
        Refresh::Factorisation
    } else {
        Refresh::Jacobian
    }
}

// Published reference values are kept digit for digit as printed.
#[allow(clippy::excessive_precision)]
#[cfg(test)]
mod tests {
    use super::*;
    use crate::info::{EvalError, ModelInfo};
    use crate::model::MassMatrix;
    use crate::options::Options;

    /// Cash's pendulum (g = 1) in the Gear–Gupta–Leimkuhler index-2 form,
    /// written by hand: w = (x, y, u, v, λ, μ), M = diag(1, 1, 1, 1, 0, 0),
    /// x' = u − 2xμ, y' = v − 2yμ, u' = −λx, v' = −λy − 1,
    /// 0 = x² + y² − 1, 0 = 2(xu + yv).
    #[derive(Clone)]
    struct GglPendulum;

    impl Model for GglPendulum {
        const STATES: usize = 6;
        type State = [f64; 6];
        const INDEX: usize = 2;
        const INFO: ModelInfo =
            ModelInfo::bare("GglPendulum", &["x", "y", "u", "v", "lambda", "mu"], 6);
        const MASS: MassMatrix = MassMatrix::Diagonal(&[1.0, 1.0, 1.0, 1.0, 0.0, 0.0]);
        const INDEX2_COMPONENTS: &'static [usize] = &[4, 5];
        fn initial_state(&self, y: &mut [f64]) {
            y.copy_from_slice(&[1.0, 0.0, 0.0, 1.0, 1.0, 0.0]);
        }
        fn rhs(&self, _t: f64, w: &[f64], dw: &mut [f64]) -> Result<(), EvalError> {
            let [x, y, u, v, l, mu] = [w[0], w[1], w[2], w[3], w[4], w[5]];
            dw.copy_from_slice(&[
                u - 2.0 * x * mu,
                v - 2.0 * y * mu,
                -l * x,
                -l * y - 1.0,
                x * x + y * y - 1.0,
                2.0 * (x * u + y * v),
            ]);
            Ok(())
        }
    }

    /// (x, y, u, v, λ) at t = 1 and 10, recomputed to 25+ digits
    /// (../shared/notes/reference-problems.md §4).
    const AT_1: [f64; 5] = [
        0.867348640600439321734308116640,
        0.497701050479672929353712765065,
        -0.0337480180609545196091412779116,
        0.0588130114652500075408496027315,
        -0.493103151439018788061138295195,
    ];
    const AT_10: [f64; 5] = [
        0.884392383092720254000816,
        0.466744161964109775211094,
        0.1203726552417017963052549,
        -0.2280835372003925465259898,
        -0.400232485892329325633282,
    ];

    #[test]
    fn only_radau5_integrates_a_singular_mass_matrix() {
        let opts = Options::new().method(crate::Method::Dop853);
        let err = crate::run::simulate(&GglPendulum, 0.0, 1.0, &opts).unwrap_err();
        let message = err.to_string();
        assert!(message.contains("Method::Radau5") && message.contains("lambda, mu"), "{message}");
        let auto = crate::run::simulate(&GglPendulum, 0.0, 1.0, &Options::new()).unwrap();
        assert!(auto.stats().method.contains("Radau5"));
    }

    #[test]
    fn radau5_with_a_singular_mass_matrix_solves_the_ggl_pendulum() {
        let model = GglPendulum;
        for tol in [1e-6, 1e-8, 1e-10] {
            let opts = Options::new().method(crate::Method::Radau5).rtol(tol).atol(tol);
            let mut y0 = [0.0; 6];
            model.initial_state(&mut y0);
            let sol = crate::run::simulate(&model, 0.0, 10.0, &opts).unwrap();
            for (t, reference) in [(1.0, AT_1), (10.0, AT_10)] {
                let errs: Vec<f64> = ["x", "y", "u", "v", "lambda"]
                    .iter()
                    .zip(reference)
                    .map(|(n, r)| (sol.at(t, n).unwrap() - r).abs())
                    .collect();
                // Positions and velocities to the tolerance (measured ≤ 8 ×
                // at t = 1, ≤ 14 × at t = 10).
                let growth = if t == 1.0 { 1.0 } else { 50.0 };

                let e = errs[..4].iter().fold(0.0f64, |a, b| a.max(*b));
                assert!(e <= 20.0 * growth * tol, "tol {tol:e}, t = {t}: error {e:e}");
                // radau5.f controls an index-2 variable's error against
                // tol / h: the bound uses the mean step.
                let h_mean = 10.0 / sol.stats().steps as f64;
                assert!(
                    errs[4] <= 100.0 * tol / h_mean,
                    "tol {tol:e}, t = {t}: λ error {:e}",
                    errs[4]
                );
            }
            // μ vanishes on the exact solution; the constraints hold to the
            // Newton tolerance at every step, with no projection.
            let (mut phi, mut mu) = (0.0f64, 0.0f64);
            for k in 0..sol.times().len() {
                let s = sol.state(k).unwrap();
                phi = phi.max((s[0] * s[0] + s[1] * s[1] - 1.0).abs());
                mu = mu.max(s[5].abs());
            }
            assert!(phi <= tol, "max |Φ| = {phi:e}");
            // μ, zero on the exact solution, is an index-2 variable too.
            let h_mean = 10.0 / sol.stats().steps as f64;
            assert!(mu <= 1000.0 * tol / h_mean, "max |μ| = {mu:e}");
        }
    }
}
