//! RADAU5 on the stiff reference problems of the IVP Test Set (Bari) and
//! Hairer–Wanner (../shared/notes/reference-problems.md §5–§7).

// Published reference values are kept digit for digit as printed.
#![allow(clippy::excessive_precision)]

use daegen::prelude::*;

include!("models/stiff.rs");
van_der_pol_model!();
robertson_model!();
hires_model!();
low_pass_model!();

mod support;
use support::harness::{is_explicit_pair, is_implicit, methods_for};
use support::{final_state as last_state, mixed_error, ProtheroRobinson};

const TOLERANCES: [f64; 5] = [1e-6, 1e-7, 1e-8, 1e-9, 1e-10];

fn radau(tol: f64, atol: f64) -> Options {
    Options::new().method(Method::Radau5).rtol(tol).atol(atol)
}

/// Hairer–Wanner's VDPOL data (hwode `vdp_exact.txt`) at t = 1: the end of
/// a run, and the continuous output of a longer run. RADAU5's continuous
/// output is the collocation polynomial, of order 3 (its stage order), so
/// it is less accurate than the order-5 step values: allow 100 × tol.
#[test]
fn van_der_pol_at_t_1_from_steps_and_from_dense_output() {
    let at_1 = [-0.1863646254808130e1, 0.7535430865435460];
    for tol in [1e-6, 1e-8, 1e-10] {
        let run = VanDerPol::default().simulate(0.0, 1.0, &radau(tol, tol)).unwrap();
        assert!(mixed_error(&last_state(&run), &at_1, 1.0) <= 10.0 * tol);
        let longer = VanDerPol::default().simulate(0.0, 2.0, &radau(tol, tol)).unwrap();
        let dense = [longer.at(1.0, "y1").unwrap(), longer.at(1.0, "y2").unwrap()];
        let e = mixed_error(&dense, &at_1, 1.0);
        assert!(e <= 100.0 * tol, "tol {tol:e}: dense output error {e:e}");
    }
}

/// Robertson to t = 1e11 with Hairer's driver convention atol = 1e-6·rtol
/// (y2 ends near 8e-14): every component, y2 included, within 10 × tol in
/// relative error, and the invariant y1 + y2 + y3 = 1 kept to rounding
/// (collocation methods preserve linear invariants).
#[test]
fn robertson_reaches_t_1e11_with_every_component_accurate() {
    for tol in TOLERANCES {
        let sol = Robertson::default().simulate(0.0, 1e11, &radau(tol, 1e-6 * tol)).unwrap();
        let y = last_state(&sol);
        let e = mixed_error(&y, &ROBER_AT_1E11, 0.0);
        assert!(e <= 10.0 * tol, "tol {tol:e}: relative error {e:e}, y = {y:?}");
        assert!((y[0] + y[1] + y[2] - 1.0).abs() < 1e-13);
    }
}

#[test]
fn hires_reaches_the_published_solution() {
    for tol in TOLERANCES {
        let sol = Hires::default().simulate(0.0, 321.8122, &radau(tol, tol)).unwrap();
        let e = mixed_error(&last_state(&sol), &HIRES_AT_END, 1.0);
        assert!(e <= 10.0 * tol, "tol {tol:e}: mixed error {e:e}");
    }
}

/// x'' = -x, x(0) = 1: x = cos t, also for t < 0. (Stiff test problems are
/// unstable backwards, so the direction is checked on an exact solution.)
#[dae_model]
fn oscillator() {
    let x = state(1.0);
    der(der(x)) == -x;
}

#[test]
fn radau5_integrates_backwards() {
    for tol in [1e-6, 1e-9] {
        let back = Oscillator::default().simulate(0.0, -3.0, &radau(tol, tol)).unwrap();
        assert_eq!(*back.times().last().unwrap(), -3.0);
        let e = (back.last("x").unwrap() - 3f64.cos()).abs();
        assert!(e <= 10.0 * tol, "tol {tol:e}: error {e:e}");
    }
}

/// Prothero–Robinson (`support`): y' = λ(y − sin t) + cos t, y(0) = 0,
/// exact y = sin t, with λ = −1e6. Backward Euler is L-stable: any step
/// works and the error is O(h/|λ|); explicit Euler with h|λ| ≫ 2 explodes
/// and must say so.
#[test]
fn backward_euler_is_stable_where_explicit_euler_explodes() {
    let model = ProtheroRobinson::default();
    let sol =
        model.simulate(0.0, 2.0, &Options::new().method(Method::BackwardEuler).step(0.01)).unwrap();
    let e = (sol.last("y").unwrap() - 2f64.sin()).abs();
    // Local error h²|y''|/2 damped by 1/(1 − hλ): about h|y''|/|λ| = 1e-8.
    assert!(e < 1e-7, "error {e:e}");
    assert_eq!((sol.stats().steps, sol.stats().rejected), (200, 0));
    let explicit = model.simulate(0.0, 2.0, &Options::new().method(Method::Euler).step(0.01));
    assert!(matches!(explicit, Err(Error::NonFinite { .. })), "{explicit:?}");
}

/// `Method::Auto` starts explicit, detects stiffness and switches to
/// RADAU5, and back where the jumps make the problem non-stiff: Van der Pol still reaches the published value,
/// with a dense output across the methods.
#[test]
fn auto_switches_to_radau5_when_the_problem_turns_stiff() {
    for tol in [1e-6, 1e-8] {
        let sol = VanDerPol::default().simulate(0.0, 2.0, &Options::new().tolerance(tol)).unwrap();
        assert!(sol.stats().jacobian_evals > 0, "RADAU5 took over");
        assert!(sol.stats().method.contains("Radau5") && sol.stats().switches >= 1);
        let e = mixed_error(&last_state(&sol), &VDP_AT_2, 1.0);
        assert!(e <= 10.0 * tol, "tol {tol:e}: mixed error {e:e}");
        assert!(sol.at(1.0, "y1").is_ok() && sol.at(1e-9, "y2").is_ok());
    }
    // A small system keeps RADAU5 at loose tolerances too.
    let loose = VanDerPol::default().simulate(0.0, 2.0, &Options::new().tolerance(1e-4)).unwrap();
    assert!(loose.stats().method.contains("Radau5"), "{:?}", loose.stats());
    // A non-stiff problem never switches.
    let osc = Oscillator::default().simulate(0.0, 10.0, &Options::new().tolerance(1e-8)).unwrap();
    assert_eq!(osc.stats().jacobian_evals, 0);
    assert_eq!((osc.stats().method, osc.stats().switches), ("Dop853", 0));
    assert!((osc.last("x").unwrap() - 10f64.cos()).abs() < 1e-6);
}

/// Robertson to t = 1e5 with an explicit pair: the pair stops where the
/// problem turns stiff (t ≈ 0.01, eigenvalues near −1e4), within a few
/// dozen steps, with an error that says so and what to use instead.
#[test]
fn an_explicit_pair_stops_where_the_problem_turns_stiff() {
    // Every explicit pair that runs the model: each has a stiffness test.
    for method in methods_for::<Robertson>(is_explicit_pair) {
        let err =
            Robertson::default().simulate(0.0, 1e5, &Options::new().method(method)).unwrap_err();
        let message = err.to_string();
        let Error::Stiff { t, onset, .. } = err else {
            panic!("{method:?}: {message}");
        };
        assert!(onset > 1e-4 && onset < 0.1 && t < 1.0, "{message}");
        for word in ["stiff", "Radau5", "Auto", &format!("{method:?}")] {
            assert!(message.contains(word), "{message}");
        }
        let partial = err.partial_solution().unwrap();
        let after_onset = partial.times().iter().filter(|&&s| s >= onset).count();
        assert!(after_onset <= 1000, "{after_onset} steps after the onset");
        assert!(partial.stats().steps < 2000, "{:?}", partial.stats());
    }
}

/// DOPRI5 holds this filter at h·ρ ≈ 1.5, well inside its stability
/// region (the error of the stiff component limits it): Hairer's test
/// never fires, yet RADAU5 takes thirty times fewer steps. `Auto` hands
/// over early: its steps stay within twice RADAU5's.
#[test]
fn auto_hands_a_stiff_filter_to_radau5_early() {
    for tol in [1e-6, 1e-9] {
        let opts = Options::new().tolerance(tol);
        let auto = LowPass::default().simulate(0.0, 1.0, &opts).unwrap();
        let radau = LowPass::default().simulate(0.0, 1.0, &opts.method(Method::Radau5)).unwrap();
        assert!(auto.stats().method.ends_with("→Radau5"), "{:?}", auto.stats());
        assert_eq!(auto.stats().switches, 1);
        let (a, r) = (auto.stats().steps, radau.stats().steps);
        assert!(a <= 2 * r, "Auto {a} steps, Radau5 {r}");
        // As accurate as RADAU5 alone (whose tolerance rtol' = 0.1 rtol^(2/3),
        // radau5.f's, leaves errors of 2.6e-7 here at rtol = 1e-9).
        let error = |s: &Solution| {
            (1..=100)
                .map(|k| {
                    let t = k as f64 / 100.0;
                    (s.at(t, "x").unwrap() - low_pass_exact(t, 2e-4, 10.0 * std::f64::consts::PI))
                        .abs()
                })
                .fold(0.0, f64::max)
        };
        let (e_auto, e_radau) = (error(&auto), error(&radau));
        assert!(e_auto <= 3.0 * e_radau + tol, "tol {tol:e}: Auto {e_auto:e}, Radau5 {e_radau:e}");
    }
}

/// Prothero–Robinson with a stiffness that fades, y' = −k(t)(y − sin t) +
/// cos t, k = 1e5·e^(−5t²): y = sin t exactly whatever k. Stiff at first,
/// non-stiff from t ≈ 1.5 on: `Auto` switches to RADAU5 and back.
#[dae_model]
fn fading_stiffness() {
    let t = time();
    let y = state(0.0);
    der(y) == -1e5 * exp(-5.0 * t * t) * (y - sin(t)) + cos(t);
}

#[test]
fn auto_switches_back_where_the_stiffness_fades() {
    for tol in [1e-6, 1e-9] {
        let sol =
            FadingStiffness::default().simulate(0.0, 10.0, &Options::new().tolerance(tol)).unwrap();
        let stats = sol.stats();
        assert_eq!(stats.switches, 2, "{stats:?}");
        assert!(
            stats.method.ends_with("→Radau5→Dopri5") || stats.method.ends_with("→Radau5→Dop853"),
            "{stats:?}"
        );
        for t in [0.1, 1.0, 5.0, 10.0] {
            let e = (sol.at(t, "y").unwrap() - t.sin()).abs();
            assert!(e <= 100.0 * tol, "tol {tol:e}, t = {t}: error {e:e}");
        }
    }
}

// y' = y² (support::BlowUp): one backward Euler step of h = 1 asks for
// y₁ = 1 + y₁², which has no real root, so Newton cannot converge.

#[test]
fn newton_failures_are_reported_with_the_time_and_what_was_tried() {
    // No root for h = 1 or 1/2; h = 1/4 has the double root y₁ = 2, ahead
    // of the exact y(1/4) = 4/3, so the backward Euler solution blows up
    // before the exact pole at t = 1, and the halved steps end there.
    let err = support::BlowUp::default()
        .simulate(0.0, 1.0, &Options::new().method(Method::BackwardEuler).step(1.0))
        .unwrap_err();
    let message = err.to_string();
    match &err {
        Error::NewtonFailure { t, tried, .. } => {
            assert!(*t > 0.25 && *t < 1.0, "{message}");
            assert!(tried.contains("halved 30 times"), "{message}");
        }
        other => panic!("expected a Newton failure, got {other}"),
    }
    assert!(message.contains("Options::step") && message.contains("Method::Radau5"), "{message}");
    let partial = err.partial_solution().unwrap();
    assert!(partial.times().len() > 2 && partial.stats().rejected >= 30);
    // RADAU5 runs into the pole at t = 1 and stops there with an error.
    let err = support::BlowUp::default()
        .simulate(0.0, 2.0, &Options::new().method(Method::Radau5))
        .unwrap_err();
    let t = match &err {
        Error::NewtonFailure { t, .. }
        | Error::StepSizeUnderflow { t, .. }
        | Error::NonFinite { t, .. } => *t,
        other => panic!("unexpected {other}"),
    };
    assert!((t - 1.0).abs() < 1e-2, "stopped at t = {t}: {err}");
    assert!(!err.to_string().contains("use Method::Radau5"), "{err}");
}

/// Robertson at t = 40, where SUNDIALS' cvRoberts_dns prints y =
/// (7.1583e-01, 9.1855e-06, 2.8416e-01): RADAU5 at tight tolerances as the
/// reference, checked against those digits.
fn robertson_at_40() -> Vec<f64> {
    let reference = Robertson::default().simulate(0.0, 40.0, &radau(1e-12, 1e-18)).unwrap();
    let y = last_state(&reference);
    let printed = [7.1583e-01, 9.1855e-06, 2.8416e-01];
    assert!(mixed_error(&y, &printed, 0.0) < 1e-4, "{y:?}");
    y
}

/// Backward Euler is L-stable and of order 1: on Robertson (stiff from
/// t ≈ 1e-4 on, eigenvalues to −1e4) any step works, and the error falls
/// tenfold with the step.
#[test]
fn backward_euler_integrates_robertson_to_first_order() {
    let reference = robertson_at_40();
    let error = |h: f64| {
        let sol = Robertson::default()
            .simulate(0.0, 40.0, &Options::new().method(Method::BackwardEuler).step(h))
            .unwrap();
        mixed_error(&last_state(&sol), &reference, 0.0)
    };
    let (coarse, fine) = (error(1e-2), error(1e-3));
    assert!(coarse < 3e-4, "h = 1e-2: relative error {coarse:e}");
    let ratio = coarse / fine;
    assert!((8.0..12.5).contains(&ratio), "error ratio {ratio}");
}

/// Van der Pol with ε = 1e-6 and h ≫ ε: at each fold of the slow manifold
/// the backward Euler equation has one real root, far on the wrong side of
/// the jump (at t = 0.805, h = 1e-3: y ≈ (−0.999, −2035)), so steps taken
/// whole would bounce between the branches. Such steps are taken in halves,
/// counted as rejected, and the run follows the jumps to the published
/// solution at t = 2, more closely the smaller the step.
#[test]
fn backward_euler_follows_van_der_pol_across_its_relaxation_jumps() {
    let mut last = f64::INFINITY;
    for (h, bound) in [(1e-2, 0.3), (1e-3, 0.08)] {
        let sol = VanDerPol::default()
            .simulate(0.0, 2.0, &Options::new().method(Method::BackwardEuler).step(h))
            .unwrap();
        let e = mixed_error(&last_state(&sol), &VDP_AT_2, 1.0);
        assert!(e < bound && e < last, "h = {h:e}: error {e:e}");
        last = e;
        assert!(sol.stats().rejected > 0, "the jumps were refined");
        // Every grid point is among the steps.
        let times = sol.times();
        for k in 0..=(2.0 / h).round() as usize {
            let t = (k as f64 * h).min(2.0);
            assert!(times.iter().any(|&s| (s - t).abs() <= 1e-12), "t = {t} missing");
        }
    }
}

#[test]
fn a_minimum_step_stops_the_run_early() {
    let err = support::BlowUp::default()
        .simulate(0.0, 2.0, &Options::new().method(Method::Dopri5).min_step(1e-6))
        .unwrap_err();
    match err {
        Error::StepSizeUnderflow { t, h, .. } => assert!(t < 1.0 && h.abs() < 1e-6),
        other => panic!("expected a step-size underflow, got {other}"),
    }
}

/// A damped string of 50 beads (the wave equation by central differences,
/// dx = 1/51, damping c): 100 states, a tridiagonal coupling, eigenvalues
/// down to about −1e4. RADAU5 and RODAS5P solve their linear systems
/// banded here.
#[dae_model]
fn damped_string() {
    const M: usize = 50;
    let c = param(10.0);
    let q = state_array([0.0; M]);
    for i in 0..M {
        let mut laplacian = -2.0 * q[i];
        if i > 0 {
            laplacian += q[i - 1];
        }
        if i + 1 < M {
            laplacian += q[i + 1];
        }
        der(der(q[i])) == 2601.0 * laplacian - c * der(q[i]);
    }
}

#[test]
fn a_banded_newton_solve_follows_the_exact_damped_mode() {
    use daegen::runtime::band_lu::BandOrdering;
    let n = <DampedString as Model>::STATES;
    let ordering =
        BandOrdering::reverse_cuthill_mckee(n, <DampedString as Model>::JACOBIAN.pattern());
    assert!(ordering.pays(), "the banded path is the one tested: {ordering:?}");
    // Start in the first mode v_j = sin(jπ/51) at rest: it stays in that
    // mode, q(t) = v·(A e^(s1 t) + B e^(s2 t)) with s² + c s − λ = 0,
    // λ = −4·51²·sin²(π/102), A = −s2/(s1 − s2), B = s1/(s1 − s2).
    let (m, c) = (50usize, 10.0f64);
    let lambda = -4.0 * 2601.0 * (std::f64::consts::PI / 102.0).sin().powi(2);
    let root = (c * c + 4.0 * lambda).sqrt();
    let (s1, s2) = ((-c + root) / 2.0, (-c - root) / 2.0);
    let (a, b) = (-s2 / (s1 - s2), s1 / (s1 - s2));
    let mode = |j: usize| ((j + 1) as f64 * std::f64::consts::PI / 51.0).sin();
    let mut y0 = vec![0.0; n];
    for j in 0..m {
        y0[2 * j] = mode(j);
    }
    let t1 = 0.5;
    for (method, tol) in [
        (Method::Radau5, 1e-6),
        (Method::Radau5, 1e-9),
        (Method::Rodas5P, 1e-4),
        (Method::Rodas5P, 1e-7),
    ] {
        let opts = Options::new().method(method).tolerance(tol);
        let sol = DampedString::default().simulate_from(0.0, &y0, t1, &opts).unwrap();
        let y = last_state(&sol);
        let amplitude = a * (s1 * t1).exp() + b * (s2 * t1).exp();
        let error = (0..m).map(|j| (y[2 * j] - mode(j) * amplitude).abs()).fold(0.0, f64::max);
        assert!(error <= 10.0 * tol, "{method:?}, tol {tol:e}: error {error:e}");
    }
}

/// Heat conduction along a rod of 100 cells, u' = k·Δu with fixed ends:
/// eigenvalues from −9.7 down to −4k = −4e4, a parabolic problem stiff
/// wherever the solution is smooth.
#[dae_model]
fn heated_rod() {
    const N: usize = 100;
    const PI: f64 = 3.141592653589793;
    let k = param(1.0e4);
    let u = state_array((0..N).map(|i| sin(PI * ((i + 1) as f64) / ((N + 1) as f64))));
    for i in 0..N {
        let left = if i == 0 { 0.0 } else { u[i - 1] };
        let right = if i + 1 == N { 0.0 } else { u[i + 1] };
        der(u[i]) == k * (left - 2.0 * u[i] + right);
    }
}

/// `Auto` on a large stiff system at a loose tolerance hands it to
/// RODAS5P, at a tight one to RADAU5; both follow the exact slowest mode
/// u_i = sin(π(i+1)/101)·exp(−4k sin²(π/202) t).
#[test]
fn auto_gives_a_large_stiff_system_to_rodas5p_where_few_digits_are_asked() {
    let model = HeatedRod::default();
    let rate = 4.0 * model.k * (std::f64::consts::PI / 202.0).sin().powi(2);
    let t1 = 0.3;
    for (tol, stiff) in [(1e-4, "Rodas5P"), (1e-7, "Radau5")] {
        let sol = model.simulate(0.0, t1, &Options::new().tolerance(tol)).unwrap();
        assert!(sol.stats().method.ends_with(stiff), "tol {tol:e}: {:?}", sol.stats());
        let y = last_state(&sol);
        let error = (0..100)
            .map(|i| {
                let mode = (std::f64::consts::PI * (i + 1) as f64 / 101.0).sin();
                (y[i] - mode * (-rate * t1).exp()).abs()
            })
            .fold(0.0, f64::max);
        assert!(error <= 10.0 * tol, "tol {tol:e}: error {error:e}");
    }
}

/// y' = 2y: backward Euler's Newton matrix I/h − J is zero for h = 1/2,
/// so each step of 1/2 is taken as two of 1/4.
#[dae_model]
fn growth() {
    let y = state(1.0);
    der(y) == 2.0 * y;
}

#[test]
fn a_step_whose_newton_matrix_is_singular_is_taken_in_halves() {
    let opts = Options::new().method(Method::BackwardEuler).step(0.5);
    let sol = Growth::default().simulate(0.0, 2.0, &opts).unwrap();
    // Eight steps of 1/4, each multiplying y by 1/(1 − 2·1/4) = 2.
    assert_eq!(sol.last("y").unwrap(), 256.0);
    assert_eq!((sol.stats().steps, sol.stats().rejected), (8, 4));
}

/// y' = √y from y = 0: the Jacobian 1/(2√y) is infinite at the start.
#[dae_model]
fn square_root() {
    let y = state(0.0);
    der(y) == sqrt(y);
}

#[test]
fn a_newton_matrix_that_stays_singular_is_an_error_with_the_time() {
    // Every implicit method that runs the model (each factors a matrix
    // with the Jacobian from its first step) but Auto, which starts with an
    // explicit pair and needs no matrix here.
    let from_the_start = |m: Method| is_implicit(m) && m != Method::Auto;
    for method in methods_for::<SquareRoot>(from_the_start) {
        match SquareRoot::default().simulate(0.0, 1.0, &Options::new().method(method)) {
            Err(Error::SingularMatrix { t, partial, .. }) => {
                assert!(t < 1e-6, "{method:?}: t = {t}");
                assert_eq!(partial.times(), &[0.0]);
            }
            other => panic!("{method:?}: expected SingularMatrix, got {other:?}"),
        }
    }
    let message = SquareRoot::default()
        .simulate(0.0, 1.0, &Options::new().method(Method::Radau5))
        .unwrap_err()
        .to_string();
    assert!(message.contains("not finite"), "{message}");
}

/// RADAU5's continuous output is its collocation polynomial (CONTR5):
/// between steps it is about as accurate as at them. On Van der Pol and
/// HIRES the largest error at the steps' midpoints is within 10× of the
/// largest at their ends. On Robertson's initial transient the ends are
/// superconvergent (order 5) while the polynomial has the stage order 3,
/// and midpoints reach 20× the ends; they stay within 10 × tol.
#[test]
fn radau5_is_as_accurate_between_steps_as_at_them() {
    fn errors<M: Model + Default + Clone + Send + Sync + 'static>(
        t1: f64,
        tol: f64,
        atol: f64,
    ) -> (f64, f64) {
        let run =
            |rtol: f64, atol: f64| M::default().simulate(0.0, t1, &radau(rtol, atol)).unwrap();
        let (sol, reference) = (run(tol, atol), run(1e-13, atol * 1e-5));
        let error = |t: f64| {
            M::INFO
                .states
                .iter()
                .map(|n| {
                    let r = reference.at(t, n).unwrap();
                    (sol.at(t, n).unwrap() - r).abs() / r.abs().max(atol / tol)
                })
                .fold(0.0, f64::max)
        };
        let (mut ends, mut middles) = (0.0f64, 0.0f64);
        for w in sol.times().windows(2) {
            ends = ends.max(error(w[1]));
            middles = middles.max(error(0.5 * (w[0] + w[1])));
        }
        (ends, middles)
    }
    for tol in [1e-6, 1e-8] {
        let (ends, middles) = errors::<VanDerPol>(2.0, tol, tol);
        assert!(middles <= 10.0 * ends, "VdP tol {tol:e}: {middles:e} vs {ends:e}");
        let (ends, middles) = errors::<Hires>(321.8122, tol, tol);
        assert!(middles <= 10.0 * ends, "HIRES tol {tol:e}: {middles:e} vs {ends:e}");
        let (ends, middles) = errors::<Robertson>(40.0, tol, 1e-6 * tol);
        assert!(
            middles <= 10.0 * tol && middles <= 30.0 * ends,
            "Robertson tol {tol:e}: {middles:e} vs {ends:e}"
        );
    }
}
