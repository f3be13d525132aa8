//! Adaptive explicit methods on non-stiff reference problems with exact
//! answers (../shared/notes/reference-problems.md §9, §10).

// Published reference values are kept digit for digit as printed.
#![allow(clippy::excessive_precision)]

use daegen::prelude::*;

include!("models/kepler.rs");
kepler_model!();

/// Arenstorf orbit (Hairer–Nørsett–Wanner I, eq. 0.1): periodic with period T.
#[dae_model]
fn arenstorf() {
    let mu = param(0.012277471);
    let y1 = state(0.994);
    let y2 = state(0.0);
    init(der(y1), 0.0);
    init(der(y2), -2.00158510637908252240537862224);
    let mup = 1.0 - mu;
    let d1 = ((y1 + mu).powi(2) + y2 * y2).powf(1.5);
    let d2 = ((y1 - mup).powi(2) + y2 * y2).powf(1.5);
    der(der(y1)) == y1 + 2.0 * der(y2) - mup * (y1 + mu) / d1 - mu * (y1 - mup) / d2;
    der(der(y2)) == y2 - 2.0 * der(y1) - mup * y2 / d1 - mu * y2 / d2;
}

const ARENSTORF_PERIOD: f64 = 17.0652165601579625588917206249;
const ARENSTORF_START: [f64; 4] = [0.994, 0.0, 0.0, -2.00158510637908252240537862224];

mod support;
use support::harness::{adaptive_methods_for, is_adaptive, methods_for};
use support::{final_state, max_error, BlowUp};

/// Hairer's `dopri5.f` on Arenstorf with h₀ = 1e-4, rtol = atol = 1e-7:
/// 217 accepted and 21 rejected steps, 1429 evaluations, and this final
/// state (as pinned by russell_ode's `test_dopri5_arenstorf.rs`, which
/// compares with dopri5.f). Same algorithm, same controller, same numbers.
#[test]
fn dopri5_reproduces_hairers_statistics_on_arenstorf() {
    let options = Options::new().method(Method::Dopri5).tolerance(1e-7).initial_step(1e-4);
    let sol = Arenstorf::default().simulate(0.0, ARENSTORF_PERIOD, &options).unwrap();
    let stats = sol.stats();
    assert_eq!((stats.steps, stats.rejected, stats.rhs_evals), (217, 21, 1429));
    let reference =
        [0.9940021704037415, 9.040893396741956e-06, 0.0014597586885445324, -2.0012455157289244];
    let y = final_state(&sol); // ordered y1, der(y1), y2, der(y2)
    let got = [y[0], y[2], y[1], y[3]];
    assert!(max_error(&got, &reference) < 1e-9, "{got:?}");
}

/// Least-squares slope of log(error) against log(tol).
fn slope(points: &[(f64, f64)]) -> f64 {
    let n = points.len() as f64;
    let (xs, ys): (Vec<f64>, Vec<f64>) = points.iter().map(|(t, e)| (t.log10(), e.log10())).unzip();
    let (mx, my) = (xs.iter().sum::<f64>() / n, ys.iter().sum::<f64>() / n);
    let sxy: f64 = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = xs.iter().map(|x| (x - mx).powi(2)).sum();
    sxy / sxx
}

/// A sound error controller gives global errors proportional to the
/// tolerance: slope 1 in log–log (Shampine's tolerance proportionality).
/// The constant, error/tol, is a property of the problem: on these long,
/// eccentric orbits it is 10²–10⁴ for the explicit pairs, as for Hairer's codes.
#[test]
fn global_error_is_proportional_to_the_tolerance() {
    let two_pi = 2.0 * std::f64::consts::PI;
    // Every adaptive method that runs both orbits: each controls its error
    // from the tolerance.
    let both = |m: Method| is_adaptive(m) && m.refusal::<Arenstorf>().is_none();
    for method in methods_for::<Kepler>(both) {
        let mut kepler = Vec::new();
        let mut arenstorf = Vec::new();
        for k in 8..=12 {
            let tol = 10f64.powi(-k);
            let o = Options::new().method(method).tolerance(tol);
            let sol = Kepler::default().simulate(0.0, two_pi, &o).unwrap();
            kepler.push((tol, max_error(&final_state(&sol), &kepler_exact(two_pi))));
            let sol = Arenstorf::default().simulate(0.0, ARENSTORF_PERIOD, &o).unwrap();
            let y = final_state(&sol);
            arenstorf.push((tol, max_error(&[y[0], y[2], y[1], y[3]], &ARENSTORF_START)));
        }
        for (name, points) in [("Kepler", &kepler), ("Arenstorf", &arenstorf)] {
            let s = slope(points);
            assert!(
                (0.75..=1.4).contains(&s),
                "{method:?} on {name}: slope {s:.2}, errors {points:?}"
            );
        }
    }
}

#[test]
fn dense_output_adds_no_error_to_the_steps() {
    let two_pi = 2.0 * std::f64::consts::PI;
    for (method, tol) in [(Method::Dopri5, 1e-8), (Method::Dop853, 1e-12)] {
        let sol = Kepler::default()
            .simulate(0.0, two_pi, &Options::new().method(method).tolerance(tol))
            .unwrap();
        let (at_steps, between) = kepler_errors_at_and_between_steps(&sol, 1000);
        assert!(
            between <= 1.5 * at_steps,
            "{method:?}: {between:e} between steps, {at_steps:e} at steps"
        );
        let energy = sol.at(1.234, "energy").unwrap();
        assert!(
            (energy + 0.5).abs() < 1e3 * tol,
            "H = -1/2 on this orbit, dense output gives {energy}"
        );
    }
}

#[test]
fn integrates_backwards_in_time() {
    // The orbit is 2π-periodic: from the perihelion state at t = 2π back to 0.
    let two_pi = 2.0 * std::f64::consts::PI;
    let o = Options::new().method(Method::Dop853).tolerance(1e-10);
    let forward = Kepler::default().simulate(0.0, two_pi, &o).unwrap();
    let backward = Kepler::default().simulate(two_pi, 0.0, &o).unwrap();
    assert_eq!(*backward.times().last().unwrap(), 0.0);
    let (ef, eb) = (
        max_error(&final_state(&forward), &kepler_exact(0.0)),
        max_error(&final_state(&backward), &kepler_exact(0.0)),
    );
    assert!(eb < 10.0 * ef && ef < 10.0 * eb, "forward {ef:e}, backward {eb:e}");
    assert!(backward.at(1.0, "q1").is_ok());
}

#[test]
fn a_singularity_stops_the_run_with_an_error_and_the_partial_solution() {
    // Every adaptive method that runs the model: each shrinks its step
    // towards the pole until it stops.
    for method in adaptive_methods_for::<BlowUp>() {
        let err = BlowUp::default().simulate(0.0, 2.0, &Options::new().method(method)).unwrap_err();
        let (t, partial) = match &err {
            Error::StepSizeUnderflow { t, partial, .. } | Error::NonFinite { t, partial, .. } => {
                (*t, partial)
            }
            other => panic!("{method:?}: expected a step-size underflow, got {other}"),
        };
        assert!((t - 1.0).abs() < 1e-3, "{method:?} stopped at t = {t}");
        // Up to t = 0.999 the partial solution is the exact one. (The last
        // accepted step may overshoot the pole by ~1e-7 with a huge y:
        // relative error control accepts it, as in Hairer's codes; the run
        // then stops with the error above.)
        let times = partial.times();
        let checked = (0..times.len()).filter(|&k| times[k] <= 0.999).count();
        assert!(
            times[checked - 1] > 0.99,
            "{method:?}: partial solution ends at {}",
            times[checked - 1]
        );
        // u = 1/y obeys u' = -1, so an error δ in u (≈ the tolerance, 1e-6)
        // is a relative error δ·y in y: allow ten times that.
        for k in 0..checked {
            let y = partial.state(k).unwrap()[0];
            let relative = (y - 1.0 / (1.0 - times[k])).abs() / y;
            assert!(
                relative < 1e-5 * y,
                "{method:?}: y({}) = {y}, relative error {relative:e}",
                times[k]
            );
        }
    }
}

// Van der Pol with ε = 1e-6 (reference-problems.md §5a): far too stiff for
// an explicit method, which must stop at the step limit, not hang.
include!("models/stiff.rs");
van_der_pol_model!();
robertson_model!();
hires_model!();

#[test]
fn a_stiff_problem_hits_the_step_limit_with_a_clear_error() {
    // Told to go on where the problem turns stiff, DOPRI5 runs into the limit.
    let err = VanDerPol::default()
        .simulate(
            0.0,
            2.0,
            &Options::new().method(Method::Dopri5).stiffness_detection(false).max_steps(2000),
        )
        .unwrap_err();
    assert!(matches!(err, Error::MaxSteps { max_steps: 2000, .. }), "{err}");
    assert!(err.partial_solution().is_some_and(|p| p.times().len() > 1));
    assert!(err.to_string().contains("Method::Radau5"), "{err}");
}

/// Without dense output a run takes the same steps to the same end (the
/// continuous extension never feeds back into the steps), DOP853 saves its
/// three extra stages per accepted step, and `at` interpolates by cubic Hermite
/// between the kept steps.
#[test]
fn runs_without_dense_output_take_the_same_steps_for_less_work() {
    let t1 = 2.0 * std::f64::consts::PI;
    // Every adaptive method that runs the model: each keeps its continuous
    // extension, which a run without dense output skips.
    for method in adaptive_methods_for::<Kepler>() {
        let with = Options::new().method(method).tolerance(1e-10);
        let without = with.dense_output(false);
        let a = Kepler::default().simulate(0.0, t1, &with).unwrap();
        let b = Kepler::default().simulate(0.0, t1, &without).unwrap();
        assert_eq!(a.times(), b.times(), "{method:?}");
        assert_eq!(final_state(&a), final_state(&b), "{method:?}");
        // DOP853's extension costs three stages (Auto runs DOP853 here).
        let extra = if a.stats().method == "Dop853" { 3 } else { 0 };
        assert_eq!(
            a.stats().rhs_evals - b.stats().rhs_evals,
            extra * a.stats().steps,
            "{method:?}"
        );
        // Cubic Hermite between the two steps around t = 1, from q1 and
        // its derivative p1 at both.
        let hermite = hermite_between_steps(&b, 1.0, 0, 2);
        assert!((b.at(1.0, "q1").unwrap() - hermite).abs() <= 1e-14, "{method:?}");
        assert!((a.at(1.0, "q1").unwrap() - kepler_exact(1.0)[0]).abs() < 1e-7, "{method:?}");
    }
}

/// What a local-error controller promises: each accepted step, taken from
/// the exact solution, lands within a small multiple of the tolerance of
/// the exact solution (the global error after many steps is a different
/// matter: see the proportionality test). Every accepted step of one
/// Kepler orbit (e = 0.9, exact solution by Kepler's equation) is redone
/// from the exact state with the same step size; its error, per component
/// scaled by atol + rtol·|y|, must stay within 10 across tol 1e-4 … 1e-12.
#[test]
fn every_accepted_step_is_within_ten_times_the_tolerance_of_the_exact_step() {
    let two_pi = 2.0 * std::f64::consts::PI;
    // Every adaptive method that runs the model: each makes this promise.
    for method in adaptive_methods_for::<Kepler>() {
        for k in [4, 6, 8, 10, 12] {
            let tol = 10f64.powi(-k);
            let o = Options::new().method(method).tolerance(tol);
            let sol = Kepler::default().simulate(0.0, two_pi, &o).unwrap();
            let times = sol.times();
            let mut worst = 0.0f64;
            for w in times.windows(2) {
                let (t0, t1) = (w[0], w[1]);
                let start = kepler_exact(t0);
                let one = o.initial_step(t1 - t0).max_step(t1 - t0);
                let step = Kepler::default().simulate_from(t0, &start, t1, &one).unwrap();
                let exact = kepler_exact(t1);
                for (got, want) in final_state(&step).iter().zip(&exact) {
                    worst = worst.max((got - want).abs() / (tol + tol * want.abs()));
                }
            }
            assert!(
                worst <= 10.0,
                "{method:?}, tol {tol:e}: a step's error is {worst:.1} × tol ({} steps)",
                times.len() - 1
            );
        }
    }
}
