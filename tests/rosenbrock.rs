//! RODAS5P, the Rosenbrock method for stiff problems at loose tolerances:
//! its order on a smooth problem and on Prothero–Robinson's stiff one
//! (the "P" of its name: Steinebach 2023 built it to keep its order
//! there), its continuous output against an exact solution with a
//! time-dependent forcing (which exercises ∂f/∂t). The reference problems
//! run it in `reference_problems.rs`, the banded and sparse Newton
//! matrices in `stiff.rs` and `models.rs`.

use daegen::prelude::*;

mod support;
use support::{BlowUp, ProtheroRobinson};

include!("models/stiff.rs");
low_pass_model!();

/// Every step of length `h`: tolerances no step can fail, and `h` as
/// the first and the largest step.
fn fixed_steps(h: f64) -> Options {
    Options::new().method(Method::Rodas5P).rtol(1e3).atol(1e3).initial_step(h).max_step(h)
}

/// The observed orders log2(e(h)/e(h/2)) of a sequence of errors at
/// halved steps.
fn orders(errors: &[f64]) -> Vec<f64> {
    errors.windows(2).map(|e| (e[0] / e[1]).log2()).collect()
}

#[test]
fn rodas5p_converges_with_order_five_on_a_smooth_problem() {
    // y' = y², y(0) = 1: y = 1/(1 − t), nonlinear (on a linear problem the
    // error may vanish to a higher order than the method's).
    let t1 = 0.5;
    let errors: Vec<f64> = [10, 20, 40, 80]
        .iter()
        .map(|&steps| {
            let sol = BlowUp::default().simulate(0.0, t1, &fixed_steps(t1 / steps as f64)).unwrap();
            assert_eq!(sol.stats().rejected, 0);
            (sol.last("y").unwrap() - 1.0 / (1.0 - t1)).abs()
        })
        .collect();
    for p in orders(&errors) {
        assert!((4.7..5.5).contains(&p), "orders {:?}, errors {errors:?}", orders(&errors));
    }
}

/// Prothero–Robinson (`support`): y' = λ(y − sin t) + cos t, exact sin t.
#[test]
fn rodas5p_keeps_a_high_order_where_the_problem_is_far_stiffer_than_the_step() {
    // With hλ from −1e5 to −1.25e4 a method without the Prothero–Robinson
    // conditions falls towards its stage order (1 for a Rosenbrock
    // method); RODAS5P's error stays small and falls faster than h².
    let t1 = 1.0;
    let errors: Vec<f64> = [10, 20, 40, 80]
        .iter()
        .map(|&steps| {
            let sol = ProtheroRobinson::default()
                .simulate(0.0, t1, &fixed_steps(t1 / steps as f64))
                .unwrap();
            (sol.last("y").unwrap() - t1.sin()).abs()
        })
        .collect();
    for p in orders(&errors) {
        assert!(p >= 2.5, "orders {:?}, errors {errors:?}", orders(&errors));
    }
    assert!(errors[0] <= 1e-8, "errors {errors:?}");
}

/// The low-pass filter x' = (sin ωt − x)/τ with τ = 2e-4 from x(0) = 0:
/// an initial layer of width τ, then a smooth sine far slower than 1/τ.
/// Its exact solution is known, between steps as at them.
#[test]
fn rodas5p_follows_a_forced_stiff_filter_at_and_between_its_steps() {
    let model = LowPass::default();
    for tol in [1e-4, 1e-6, 1e-8] {
        let opts = Options::new().method(Method::Rodas5P).tolerance(tol);
        let sol = model.simulate(0.0, 0.5, &opts).unwrap();
        let exact = |t: f64| low_pass_exact(t, model.tau, model.omega);
        let at_steps = sol
            .times()
            .iter()
            .enumerate()
            .map(|(k, &t)| (sol.state(k).unwrap()[0] - exact(t)).abs())
            .fold(0.0, f64::max);
        // 997 points between the steps, the initial layer included.
        let between = (1..1000)
            .map(|k| 0.5 * k as f64 / 1000.0)
            .map(|t| (sol.at(t, "x").unwrap() - exact(t)).abs())
            .fold(0.0, f64::max);
        assert!(at_steps <= 10.0 * tol, "tol {tol:e}: error {at_steps:e} at the steps");
        // The continuous output is of order 4, one less than the steps.
        assert!(between <= 100.0 * tol, "tol {tol:e}: error {between:e} between the steps");
    }
}
