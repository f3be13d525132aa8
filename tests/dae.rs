//! DAEs: index reduction at compile time, the index-1 form with projection
//! at run time (course notes chapter 2).

use daegen::prelude::*;

mod support;
use support::harness::{adaptive_methods_for, is_adaptive, methods_for};
use support::tight;

include!("models/items.rs");
include!("models/pendulum.rs");

// The contract's pendulum, with the Taylor method's tape.
contract_pendulum!(dae_model_with! { (taylor = 1) });

// The same pendulum in its angle θ from the downward vertical.
contract_pendulum_angle!();

#[test]
fn the_cartesian_pendulum_has_index_three() {
    assert_eq!(<Pendulum as Model>::INDEX, 3);
    assert_eq!(<PendulumAngle as Model>::INDEX, 0);
    assert_eq!(Pendulum::INFO.algebraics, &["lambda"]);
    // The position constraint and its velocity level are projected onto.
    let levels: Vec<usize> = Pendulum::CONSTRAINTS.iter().map(|c| c.level).collect();
    assert_eq!(levels, [0, 1]);
    assert_eq!(Pendulum::CONSTRAINTS[0].equation, "constraint(x * x + y * y - l * l)");
}

/// The angle form at a tolerance far below the DAE runs' as the reference.
fn angle_reference(t: f64) -> (f64, f64) {
    let opts = Options::new().method(Method::Dop853).tolerance(1e-13);
    let sol = PendulumAngle::default().simulate(0.0, t, &opts).expect("the angle form integrates");
    let theta = sol.last("theta").expect("theta");
    (theta.sin(), -theta.cos())
}

#[test]
fn the_dae_pendulum_follows_the_angle_form_and_keeps_its_constraints() {
    let model = Pendulum::default();
    let (m, g, l) = (model.m, model.g, model.l);
    // Every adaptive method that runs the pendulum: each keeps its
    // constraints by the projection.
    for method in adaptive_methods_for::<Pendulum>() {
        let tol = 1e-10;
        let opts = Options::new().method(method).tolerance(tol);
        let sol = model.simulate(0.0, 100.0, &opts).expect("the pendulum runs");
        let mut drift_100 = 0.0f64;
        for k in 0..sol.times().len() {
            let s = sol.state(k).expect("a step");
            drift_100 = drift_100.max((0.5 * m * (s[2] * s[2] + s[3] * s[3]) + m * g * s[1]).abs());
        }
        // The Taylor method keeps the energy within 10 × tol over all of
        // [0, 100] (measured 1.0e-10 = 1.0e-11 m g l); the others drift
        // like the angle form does (compared in the next test).
        if matches!(method, Method::Taylor) {
            assert!(
                drift_100 <= 10.0 * tol * m * g * l,
                "Taylor: energy drift {drift_100:e} over 100 s"
            );
        }
        // Position and velocity constraints at every accepted step.
        let (mut position, mut velocity, mut energy) = (0.0f64, 0.0f64, 0.0f64);
        for k in 0..sol.times().len() {
            let s = sol.state(k).expect("a step");
            let (x, y, u, v) = (s[0], s[1], s[2], s[3]);
            position = position.max((x * x + y * y - l * l).abs());
            velocity = velocity.max((x * u + y * v).abs());
            // Energy is conserved: E(0) = 0 (at rest, y = 0). Over the
            // first four periods; afterwards the global error grows as it
            // does for the angle form (compared below).
            if sol.times()[k] <= 10.0 {
                energy = energy.max((0.5 * m * (u * u + v * v) + m * g * y).abs());
            }
        }
        assert!(position <= 1e-12, "{method:?}: |Φ| = {position:e}");
        assert!(velocity <= 1e-12, "{method:?}: |Φ_q v| = {velocity:e}");
        assert!(sol.max_constraint_residual() <= 1e-12);
        assert!(sol.max_constraint_residual() > 0.0 || position == 0.0);
        // Within 10× the tolerance of the energy scale m g l (DOPRI5's
        // global error per tolerance is larger: its angle form drifts 1.4e-8
        // too, and the comparison with the angle form below covers it).
        if !matches!(method, Method::Dopri5) {
            assert!(energy <= 10.0 * tol * m * g * l, "{method:?}: energy drift {energy:e}");
        }
        // λ from the acceleration level agrees with the closed form that
        // follows from the constraint: λ l² = m |v|² − m g y.
        for k in (0..sol.times().len()).step_by(17) {
            let s = sol.state(k).expect("a step");
            let want = (m * (s[2] * s[2] + s[3] * s[3]) - m * g * s[1]) / (l * l);
            let t = sol.times()[k];
            let got = sol.at(t, "lambda").expect("lambda");
            assert!(
                (got - want).abs() <= 1e-9 * want.abs().max(1.0),
                "{method:?}: λ({t}) = {got}, closed form {want}"
            );
        }
        // The angle form, at t = 10: agreement to the DAE run's tolerance
        // grown over four periods.
        let (x_ref, y_ref) = angle_reference(10.0);
        let (x, y) = (sol.at(10.0, "x").unwrap(), sol.at(10.0, "y").unwrap());
        let err = (x - x_ref).abs().max((y - y_ref).abs());
        assert!(err <= 1e-7, "{method:?}: |x - x_ref| = {err:e}");
    }
}

#[test]
fn over_a_hundred_seconds_the_dae_drifts_in_energy_like_the_angle_form() {
    // Neither form conserves energy exactly (the methods are not
    // symplectic); the projected DAE must not do worse than a small factor
    // of the minimal-coordinate ODE at the same tolerance.
    let energy_drift = |sol: &Solution, energy: &dyn Fn(&[f64]) -> f64| {
        (0..sol.times().len())
            .map(|k| energy(sol.state(k).expect("a step")).abs())
            .fold(0.0, f64::max)
    };
    for tol in [1e-8, 1e-10, 1e-12] {
        // Every adaptive method that runs both forms.
        let both = |m: Method| is_adaptive(m) && m.refusal::<PendulumAngle>().is_none();
        for method in methods_for::<Pendulum>(both) {
            let opts = Options::new().method(method).tolerance(tol);
            let angle = PendulumAngle::default().simulate(0.0, 100.0, &opts).unwrap();
            let dae = Pendulum::default().simulate(0.0, 100.0, &opts).unwrap();
            let reference = energy_drift(&angle, &|s| 0.5 * s[1] * s[1] - 9.81 * s[0].cos());
            let drift = energy_drift(&dae, &|s| 0.5 * (s[2] * s[2] + s[3] * s[3]) + 9.81 * s[1]);
            assert!(
                drift <= 8.0 * reference,
                "{tol:e} {method:?}: DAE {drift:e}, angle form {reference:e}"
            );
        }
    }
}

include!("models/stiff.rs");
van_der_pol_model!();
robertson_model!();
hires_model!();

#[test]
fn robertson_as_an_index_1_dae_reaches_the_published_solution() {
    assert_eq!(<RobertsonDae as Model>::INDEX, 1);
    assert_eq!(RobertsonDae::STATES, 2);
    // The algebraic equation is solved for y3 symbolically: an explicit ODE
    // with an analytic Jacobian, nothing left to project.
    assert!(RobertsonDae::CONSTRAINTS.is_empty());
    assert!(!RobertsonDae::JACOBIAN.pattern().is_empty());
    for tol in [1e-6, 1e-8, 1e-10] {
        let opts = Options::new().method(Method::Radau5).rtol(tol).atol(1e-6 * tol);
        let sol = RobertsonDae::default().simulate(0.0, 1e11, &opts).unwrap();
        let got = [sol.last("y1").unwrap(), sol.last("y2").unwrap(), sol.last("y3").unwrap()];
        for (k, (g, r)) in got.iter().zip(ROBER_AT_1E11).enumerate() {
            let e = (g - r).abs() / r.abs();
            assert!(e <= 10.0 * tol, "tol {tol:e}: y{} relative error {e:e}", k + 1);
        }
    }
}

/// Cash's index-3 pendulum (`pendul3.f`; ../shared/notes/reference-problems.md §4):
/// g = 1, released from (1, 0) moving up at unit speed. References are the
/// recomputed 30-digit values (the printed ones hold only 9–12 digits).
const PENDUL3: [(f64, [f64; 5]); 3] = [
    (
        1.0,
        [
            0.867348640600439321734308116640,
            0.497701050479672929353712765065,
            -0.0337480180609545196091412779116,
            0.0588130114652500075408496027315,
            -0.493103151439018788061138295195,
        ],
    ),
    (
        10.0,
        [
            0.884392383092720254000816,
            0.466744161964109775211094,
            0.1203726552417017963052549,
            -0.2280835372003925465259898,
            -0.400232485892329325633282,
        ],
    ),
    (
        100.0,
        [
            -0.8823175139579278783335183,
            0.4706546553080100402898502,
            0.1140215562043221987485429,
            0.2137516645659736454845227,
            -0.4119639659240301208695506,
        ],
    ),
];

/// Largest error over x, y, u, v, λ at the reference times up to `t_end`.
fn pendul3_errors(sol: &Solution, t_end: f64) -> Vec<f64> {
    PENDUL3
        .iter()
        .filter(|(t, _)| *t <= t_end)
        .map(|(t, reference)| {
            ["x", "y", "u", "v", "lambda"]
                .iter()
                .zip(reference)
                .map(|(name, r)| (sol.at(*t, name).expect("in range") - r).abs())
                .fold(0.0, f64::max)
        })
        .collect()
}

fn pendul3_run(method: Method, tol: f64, step: f64, t_end: f64) -> Solution {
    let model = Pendulum { g: 1.0, ..Pendulum::default() };
    let opts = Options::new().method(method).tolerance(tol);
    // A step only for the fixed-step methods (0: none given).
    let opts = if step > 0.0 { opts.step(step) } else { opts };
    model.simulate_from(0.0, &[1.0, 0.0, 0.0, 1.0], t_end, &opts).expect("the pendulum runs")
}

#[test]
fn cash_index_3_pendulum_matches_the_reference_including_lambda() {
    // At t = 1 (before the first turning point): within 20 × tol (RADAU5's
    // global error per tolerance is the largest: 17 × at 1e-10).
    // Every adaptive method that runs the pendulum.
    for method in adaptive_methods_for::<Pendulum>() {
        for tol in [1e-6, 1e-8, 1e-10] {
            let e = pendul3_errors(&pendul3_run(method, tol, 0.0, 1.0), 1.0)[0];
            assert!(e <= 20.0 * tol, "{method:?} tol {tol:e}: error {e:e} at t = 1");
        }
    }
    // Twelve periods: the phase error grows, the constraints do not.
    let sol = pendul3_run(Method::Dop853, 1e-12, 0.0, 100.0);
    let e = pendul3_errors(&sol, 100.0);
    assert!(e[2] <= 1000.0 * 1e-12, "DOP853 at 1e-12: error {:e} at t = 100", e[2]);
    assert!(sol.max_constraint_residual() <= 1e-14);
}

#[test]
fn rk4_on_the_index_1_form_with_projection_converges_with_order_four() {
    let errors: Vec<f64> = [0.02, 0.01, 0.005]
        .iter()
        .map(|&h| pendul3_errors(&pendul3_run(Method::Rk4, 1e-6, h, 1.0), 1.0)[0])
        .collect();
    for pair in errors.windows(2) {
        let order = (pair[0] / pair[1]).log2();
        assert!((3.7..4.4).contains(&order), "observed order {order} from {errors:?}");
    }
}

include!("models/slider_crank.rs");

#[test]
fn slider_crank_in_global_coordinates_follows_its_crank_angle_ode() {
    assert_eq!(<SliderCrank as Model>::INDEX, 3);
    let tol = 1e-10;
    let opts = Options::new().method(Method::Dop853).tolerance(tol);
    let sol = SliderCrank::default().simulate(0.0, 5.0, &opts).expect("runs");
    // Consistent initialization put the guesses on the joints.
    let s0 = sol.state(0).expect("the initial state");
    let (r, l) = (0.15, 0.4);
    let phi0 = s0[4];
    assert!((s0[0] - 0.5 * r * phi0.cos()).abs() < 1e-12);
    assert!((s0[2] - 0.5 * r * phi0.sin()).abs() < 1e-12);
    assert!(s0[8].abs() < 1e-12, "ys = {}", s0[8]);
    assert!(sol.max_constraint_residual() <= 1e-12);
    let reference = SliderCrankAngle { phi0, ..SliderCrankAngle::default() }
        .simulate(0.0, 5.0, &Options::new().method(Method::Dop853).tolerance(1e-13))
        .expect("the angle form runs");
    for t in [0.5, 1.0, 2.0, 5.0] {
        let phi = reference.at(t, "phi").unwrap();
        let theta = sol.at(t, "theta1").unwrap();
        let xs_ref = r * phi.cos() + (l * l - (r * phi.sin()).powi(2)).sqrt();
        let xs = sol.at(t, "xs").unwrap();
        // 100 × tol: the global error of about two crank revolutions
        // (measured 2.5e-9 at t = 5).
        assert!((theta - phi).abs() <= 100.0 * tol, "t = {t}: θ1 = {theta}, φ = {phi}");
        assert!((xs - xs_ref).abs() <= 100.0 * tol, "t = {t}: xs = {xs}, from φ {xs_ref}");
    }
}

// Linear DAEs `E y' + A y = c(t)` of known Kronecker index (course notes
// §2.1): built from the canonical form `N α' + α = d`, `β' + J β = e` with
// d = (sin t, cos t, t²), e = 1, J = 1/2 and N nilpotent of order 1, 2, 3,
// then mixed by P⁻¹ = [1 0 1 0; 1 1 0 0; 0 1 1 1; 0 0 1 1] and
// Q⁻¹ = [1 1 0 0; 0 1 1 0; 0 0 1 0; 1 1 1 1] (both unimodular):
// E = P⁻¹ diag(N, 1) Q⁻¹, A = P⁻¹ diag(I, J) Q⁻¹, c = P⁻¹ (d, e), y = Q (α, β).
// The closed form (2.9): α = Σ (−1)^j N^j d^(j), β = 2 + (β0 − 2) e^(−t/2).

/// `linear_dae!(name, [E₁ y'], [E₂ y'], [E₃ y'])`: the system above, its
/// rows sharing A y and c(t) and differing in E y' (the fourth row's E y'
/// is `dy` in every one); each `[..]` is a row's E y' with a trailing `+`,
/// or empty.
macro_rules! linear_dae {
    ($name:ident, [$($e1:tt)*], [$($e2:tt)*], [$($e3:tt)*]) => {
        #[dae_model]
        fn $name() {
            let t = time();
            let y = state_array([0.0, 0.0, 0.0, 0.0]);
            let dy = der(y[0]) + der(y[1]) + der(y[2]) + der(y[3]);
            $($e1)* y[0] + y[1] + y[2] == sin(t) + t * t;
            $($e2)* y[0] + 2.0 * y[1] + y[2] == sin(t) + cos(t);
            dy + $($e3)* 0.5 * y[0] + 1.5 * y[1] + 2.5 * y[2] + 0.5 * y[3] == cos(t) + t * t + 1.0;
            dy + 0.5 * y[0] + 0.5 * y[1] + 1.5 * y[2] + 0.5 * y[3] == t * t + 1.0;
        }
    };
}
linear_dae!(linear_index_1, [], [], []);
linear_dae!(linear_index_2, [der(y[1]) + der(y[2]) +], [der(y[1]) + der(y[2]) +], []);
linear_dae!(
    linear_index_3,
    [der(y[1]) + der(y[2]) +],
    [der(y[1]) + 2.0 * der(y[2]) +],
    [der(y[2]) +]
);

/// y(t) from the closed form, β0 = (Q⁻¹ y(0))₄ = y1 + y2 + y3 + y4 at t = 0.
fn linear_closed_form(alpha: [f64; 3], beta0: f64, t: f64) -> [f64; 4] {
    let beta = 2.0 + (beta0 - 2.0) * (-t / 2.0).exp();
    let [a1, a2, a3] = alpha;
    // Q = [1 -1 1 0; 0 1 -1 0; 0 0 1 0; -1 0 -1 1]
    [a1 - a2 + a3, a2 - a3, a3, -a1 - a3 + beta]
}

fn check_linear_dae(sol: &Solution, alpha: &dyn Fn(f64) -> [f64; 3], tol: f64) {
    let y0 = sol.state(0).expect("initial state");
    let beta0: f64 = y0.iter().sum();
    for t in [0.0, 1.0, 2.0, 5.0] {
        let want = linear_closed_form(alpha(t), beta0, t);
        for (i, w) in want.iter().enumerate() {
            let got = sol.at(t, &format!("y[{i}]")).expect("in range");
            assert!((got - w).abs() <= 100.0 * tol, "t = {t}: y[{i}] = {got}, closed form {w}");
        }
    }
}

#[test]
fn linear_daes_of_kronecker_index_1_2_3_match_the_closed_form() {
    assert_eq!(<LinearIndex1 as Model>::INDEX, 1);
    assert_eq!(<LinearIndex2 as Model>::INDEX, 2);
    assert_eq!(<LinearIndex3 as Model>::INDEX, 3);
    let tol = 1e-10;
    let opts = Options::new().method(Method::Dop853).tolerance(tol);
    let sol = LinearIndex1::default().simulate(0.0, 5.0, &opts).expect("index 1 runs");
    check_linear_dae(&sol, &|t: f64| [t.sin(), t.cos(), t * t], tol);
    let sol = LinearIndex2::default().simulate(0.0, 5.0, &opts).expect("index 2 runs");
    check_linear_dae(&sol, &|t: f64| [2.0 * t.sin(), t.cos(), t * t], tol);
    let sol = LinearIndex3::default().simulate(0.0, 5.0, &opts).expect("index 3 runs");
    check_linear_dae(&sol, &|t: f64| [2.0 * t.sin() + 2.0, t.cos() - 2.0 * t, t * t], tol);
}

/// The pendulum with its abscissa fixed at 0.6 and a rough guess for the
/// ordinate: initialization must move only y, onto the nearer root −0.8.
#[dae_model]
fn pendulum_fixed_abscissa() {
    let l = param(1.0);
    let g = param(9.81);
    let x = state(0.6).fixed();
    let y = state(-0.7);
    let u = state(0.3);
    let v = state(0.0);
    let lambda = algebraic(0.0);
    der(x) == u;
    der(y) == v;
    der(u) == -lambda * x;
    der(v) == -lambda * y - g;
    constraint(x * x + y * y - l * l);
}

#[test]
fn initialization_keeps_fixed_values_and_reports_the_degrees_of_freedom() {
    let sol = tight::<PendulumFixedAbscissa>(1.0, 1e-10);
    let s = sol.state(0).unwrap();
    assert_eq!(s[0], 0.6);
    assert!((s[1] + 0.8).abs() <= 1e-14, "y0 = {}", s[1]);
    // Velocities: the minimal-norm correction of (0.3, 0) onto x u + y v = 0
    // removes the radial part: (u, v) = 0.3 (1 − x²) , −0.3 x y... exactly
    // the tangential projection of (0.3, 0) onto (−y, x)/l = (0.8, 0.6).
    let (u, v) = (0.3 * 0.8 * 0.8, 0.3 * 0.8 * 0.6);
    assert!((s[2] - u).abs() <= 1e-14 && (s[3] - v).abs() <= 1e-14, "{s:?}");
    assert_eq!(sol.degrees_of_freedom(), Some(1));
    assert_eq!(tight::<SliderCrank>(0.1, 1e-10).degrees_of_freedom(), Some(1));
    assert_eq!(tight::<PendulumAngle>(0.1, 1e-10).degrees_of_freedom(), None);
    let stats = sol.stats();
    assert_eq!(stats.method, "Dop853");
    assert!(stats.formulation.contains("projected"), "{}", stats.formulation);
    let auto = Pendulum::default().simulate(0.0, 1.0, &Options::new().tolerance(1e-6)).unwrap();
    assert_eq!(auto.stats().method, "Dopri5");
}

// The pendulum variants below differ from the contract's in a line or two;
// each is written out so that its test shows the model it examines.
/// A constraint no real configuration satisfies.
#[dae_model]
fn impossible_circle() {
    let x = state(1.0);
    let y = state(0.0);
    let u = state(0.0);
    let v = state(0.0);
    let lambda = algebraic(0.0);
    constraint(x * x + y * y + 1.0);
    der(x) == u;
    der(y) == v;
    der(u) == -lambda * x;
    der(v) == -lambda * y;
}

/// The same circle twice, each with its own multiplier: Φ_q has rank 1.
#[dae_model]
fn doubled_constraint() {
    let x = state(1.0);
    let y = state(0.0);
    let u = state(0.0);
    let v = state(1.0);
    let a = algebraic(0.0);
    let b = algebraic(0.0);
    der(x) == u;
    der(y) == v;
    der(u) == -(a + 2.0 * b) * x;
    der(v) == -(a + 2.0 * b) * y;
    constraint(x * x + y * y - 1.0);
    constraint(2.0 * x * x + 2.0 * y * y - 2.0);
}

#[test]
fn unrepairable_or_redundant_constraints_are_errors_that_name_the_constraint() {
    let opts = Options::new().method(Method::Dop853);
    let err = ImpossibleCircle::default().simulate(0.0, 1.0, &opts).unwrap_err();
    let message = err.to_string();
    assert!(message.contains("constraint(x * x + y * y + 1.0)"), "{message}");
    assert!(
        message.contains("cannot be made consistent") || message.contains("rank-deficient"),
        "{message}"
    );
    assert!(matches!(err, Error::Constraint { t, .. } if t == 0.0));
    assert!(err.partial_solution().is_some());
    let err = DoubledConstraint::default().simulate(0.0, 1.0, &opts).unwrap_err();
    let message = err.to_string();
    assert!(message.contains("redundant"), "{message}");
    assert!(message.contains("constraint(2.0 * x * x + 2.0 * y * y - 2.0)"), "{message}");
    // Both fixed: nothing left to correct.
    let err = PendulumFixedAbscissa::default()
        .simulate_from(0.0, &[2.0, 0.0, 0.0, 0.0], 1.0, &opts)
        .unwrap_err();
    assert!(err.to_string().contains("cannot be made consistent"), "{err}");
}

/// A rheonomic constraint (course notes §4.2): a pendulum whose support
/// moves as s(t) = a sin(ω t).
#[dae_model]
fn pendulum_on_a_shaking_support() {
    let t = time();
    let a = param(0.1);
    let w = param(3.0);
    let l = param(1.0);
    let g = param(9.81);
    let x = state(0.5);
    let y = state(-0.85);
    let u = state(0.0);
    let v = state(0.0);
    let lambda = algebraic(0.0);
    let s = a * sin(w * t);
    der(x) == u;
    der(y) == v;
    der(u) == -lambda * (x - s);
    der(v) == -lambda * y - g;
    constraint((x - s) * (x - s) + y * y - l * l);
}

/// Its angle form: θ'' = −(g/l) sin θ − (s''(t)/l) cos θ.
#[dae_model]
fn shaken_pendulum_angle() {
    let t = time();
    let a = param(0.1);
    let w = param(3.0);
    let l = param(1.0);
    let g = param(9.81);
    let theta0 = param(0.0);
    let omega0 = param(0.0);
    let theta = state(theta0);
    init(der(theta), omega0);
    der(der(theta)) == -g / l * sin(theta) + a * w * w / l * sin(w * t) * cos(theta);
}

#[test]
fn a_pendulum_on_a_moving_support_follows_its_angle_form() {
    assert_eq!(<PendulumOnAShakingSupport as Model>::INDEX, 3);
    let tol = 1e-10;
    let sol = tight::<PendulumOnAShakingSupport>(5.0, tol);
    let (a, w, l) = (0.1, 3.0, 1.0);
    // The consistent start (the velocity constraint involves s'(0) = a ω).
    let s0 = sol.state(0).unwrap();
    // States in order x, y, u, v; s(0) = 0, s'(0) = a ω.
    let theta0 = s0[0].atan2(-s0[1]);
    let omega0 = (s0[2] - a * w) / (l * theta0.cos());
    let reference = ShakenPendulumAngle { theta0, omega0, ..ShakenPendulumAngle::default() }
        .simulate(0.0, 5.0, &Options::new().method(Method::Dop853).tolerance(1e-13))
        .unwrap();
    for t in [1.0, 3.0, 5.0] {
        let theta = reference.at(t, "theta").unwrap();
        let (x, y) = (a * (w * t).sin() + l * theta.sin(), -l * theta.cos());
        let e = (sol.at(t, "x").unwrap() - x).abs().max((sol.at(t, "y").unwrap() - y).abs());
        assert!(e <= 100.0 * tol, "t = {t}: error {e:e}");
    }
    assert!(sol.max_constraint_residual() <= 1e-12);
}

/// A non-holonomic constraint (course notes §4.2): a knife edge on a plane
/// inclined in x (gravity component g sin α along −x), free to turn at the
/// constant rate ω; the blade cannot move sideways: −sin φ ẋ + cos φ ẏ = 0.
#[dae_model]
fn knife_edge() {
    let m = param(1.0);
    let inertia = param(0.2);
    let gs = param(1.0);
    let x = state(0.0);
    let y = state(0.0);
    let phi = state(0.0);
    let u = state(1.0);
    let v = state(0.0);
    let w = state(1.0);
    let lambda = algebraic(0.0);
    der(x) == u;
    der(y) == v;
    der(phi) == w;
    m * der(u) == -m * gs + lambda * sin(phi);
    m * der(v) == -lambda * cos(phi);
    inertia * der(w) == 0.0;
    constraint(-sin(phi) * u + cos(phi) * v);
}

#[test]
fn a_knife_edge_follows_its_closed_form() {
    // Index 2: the velocity-level constraint is differentiated once.
    assert_eq!(<KnifeEdge as Model>::INDEX, 2);
    // It corrects the velocities, not the heading.
    assert_eq!(KnifeEdge::PROJECTION[0].slots, &[3, 4]);
    let tol = 1e-10;
    let sol = tight::<KnifeEdge>(10.0, tol);
    // φ = ω t and the speed along the blade V − (g sin α/ω) sin ω t give
    // x = (V/ω) sin ωt − g sin α/(2ω²) sin² ωt,
    // y = (V/ω)(1 − cos ωt) − (g sin α/ω)(t/2 − sin 2ωt/(4ω)) (V = ω = g sin α = 1).
    for t in [1.0f64, 5.0, 10.0] {
        let x = t.sin() - 0.5 * t.sin().powi(2);
        let y = (1.0 - t.cos()) - (t / 2.0 - (2.0 * t).sin() / 4.0);
        let e = (sol.at(t, "x").unwrap() - x).abs().max((sol.at(t, "y").unwrap() - y).abs());
        assert!(e <= 100.0 * tol, "t = {t}: error {e:e}");
    }
}

// With the Taylor method's tape: the 3 × 3 KKT system is solved
// symbolically, so the index-1 form has Taylor recurrences.
cash_pendulum_model!(taylor = 1, unroll = [12, 16]);

#[test]
fn the_taylor_method_integrates_the_index_1_form_with_projection() {
    for compact in [false, true] {
        for tol in [1e-10, 1e-14] {
            let opts = Options::new().method(Method::Taylor).tolerance(tol).taylor_compact(compact);
            let sol = CashPendulum::default().simulate(0.0, 10.0, &opts).unwrap();
            let e = pendul3_errors(&sol, 10.0);
            // 10 × tol at t = 1, and the global error of a period at t = 10.
            assert!(e[0] <= 10.0 * tol, "tol {tol:e}: error {:e} at t = 1", e[0]);
            assert!(e[1] <= 1000.0 * tol, "tol {tol:e}: error {:e} at t = 10", e[1]);
            assert!(sol.max_constraint_residual() <= 1e-14);
        }
    }
}

#[test]
fn the_gear_gupta_leimkuhler_form_with_radau5_matches_the_references() {
    // Cash's pendulum: w = (x, y, u, v, λ, μ), index 2, no projection.
    let names = CashPendulumMassForm::INFO.states;
    assert_eq!(names, &["x", "y", "u", "v", "lambda", "mu[0]"]);
    assert_eq!(
        CashPendulumMassForm::MASS,
        daegen::MassMatrix::Diagonal(&[1.0, 1.0, 1.0, 1.0, 0.0, 0.0])
    );
    for tol in [1e-6, 1e-8, 1e-10] {
        let opts = Options::new()
            .method(Method::Radau5)
            .tolerance(tol)
            .formulation(Formulation::MassMatrix);
        let sol = CashPendulum::default().simulate(0.0, 10.0, &opts).unwrap();
        for (t, reference) in &PENDUL3[..2] {
            let e = ["x", "y", "u", "v"]
                .iter()
                .zip(reference)
                .map(|(n, r)| (sol.at(*t, n).unwrap() - r).abs())
                .fold(0.0, f64::max);
            let bound = if *t == 1.0 { 20.0 } else { 1000.0 } * tol;
            assert!(e <= bound, "tol {tol:e}, t = {t}: error {e:e}");
        }
        let mu = (0..sol.times().len()).map(|k| sol.state(k).unwrap()[5].abs()).fold(0.0, f64::max);
        let h_mean = 10.0 / sol.stats().steps as f64;
        assert!(mu <= 1000.0 * tol / h_mean, "max |μ| = {mu:e}");
    }
    // The slider-crank: four joint forces, four multipliers.
    assert_eq!(SliderCrankMassForm::STATES, 18);
    let opts =
        Options::new().method(Method::Radau5).tolerance(1e-9).formulation(Formulation::MassMatrix);
    let sol = SliderCrank::default().simulate(0.0, 2.0, &opts).unwrap();
    let s0 = sol.state(0).unwrap();
    let reference = SliderCrankAngle { phi0: s0[4], ..SliderCrankAngle::default() }
        .simulate(0.0, 2.0, &Options::new().method(Method::Dop853).tolerance(1e-13))
        .unwrap();
    for t in [0.5, 1.0, 2.0] {
        let (phi, theta) = (reference.at(t, "phi").unwrap(), sol.at(t, "theta1").unwrap());
        assert!((theta - phi).abs() <= 1e-6, "t = {t}: θ1 = {theta}, φ = {phi}");
    }
    // Other methods are refused with a message that says what to do.
    let err = CashPendulum::default()
        .simulate(
            0.0,
            1.0,
            &Options::new().method(Method::Dop853).formulation(Formulation::MassMatrix),
        )
        .unwrap_err();
    assert!(err.to_string().contains("Method::Radau5"), "{err}");
    // A Rosenbrock method does not converge on the index-2 multipliers of
    // the mass-matrix form: refused, naming them.
    let err = CashPendulum::default()
        .simulate(
            0.0,
            1.0,
            &Options::new().method(Method::Rodas5P).formulation(Formulation::MassMatrix),
        )
        .unwrap_err();
    let message = err.to_string();
    assert!(message.contains("index 2") && message.contains("Method::Radau5"), "{message}");
}

/// An index-1 DAE whose algebraic equation is nonlinear in its variable:
/// y' = −z, 0 = z² − y, z > 0, so y = (1 − t/2)², z = 1 − t/2. Newton's
/// method solves for z at each evaluation, so every method runs it; RADAU5
/// runs its mass-matrix form too.
#[dae_model]
fn square_root_decay() {
    let y = state(1.0);
    let z = algebraic(0.9);
    der(y) == -z;
    z * z == y;
    let rate = output(-z);
}

#[test]
fn an_algebraic_equation_nonlinear_in_its_variable_runs_with_every_method() {
    assert_eq!(<SquareRootDecay as Model>::INDEX, 1);
    assert_eq!(SquareRootDecay::INFO.states, &["y"]);
    assert_eq!(SquareRootDecay::INFO.algebraics, &["z"]);
    assert_eq!(SquareRootDecayMassForm::MASS, daegen::MassMatrix::Diagonal(&[1.0, 0.0]));
    let exact = |t: f64| ((1.0 - t / 2.0) * (1.0 - t / 2.0), 1.0 - t / 2.0);
    for tol in [1e-6, 1e-9] {
        let base = Options::new().tolerance(tol);
        for (options, what) in [
            (base.method(Method::Dopri5), "Dopri5"),
            (base.method(Method::Dop853), "Dop853"),
            (base.method(Method::Radau5), "Radau5"),
            (base.clone(), "Auto"),
            (base.method(Method::Radau5).formulation(Formulation::MassMatrix), "mass-matrix form"),
        ] {
            let sol = SquareRootDecay::default().simulate(0.0, 1.5, &options).unwrap();
            for t in [0.5, 1.0, 1.5] {
                let (y, z) = exact(t);
                let e =
                    (sol.at(t, "y").unwrap() - y).abs().max((sol.at(t, "z").unwrap() - z).abs());
                assert!(e <= 10.0 * tol, "{what}, tol {tol:e}, t = {t}: error {e:e}");
                // `rate` solves for z anew from y (in the mass-matrix form,
                // z is a component, consistent to the tolerance).
                let (rate, z) = (sol.at(t, "rate").unwrap(), sol.at(t, "z").unwrap());
                assert!((rate + z).abs() <= 10.0 * tol, "{what}: {rate} vs {z}");
            }
        }
    }
}

// Two unit masses on unit massless rods, with their energy.
double_pendulum_cartesian!(dae_model_with! { () } {
    let energy = output(
        0.5 * (der(x1) * der(x1) + der(y1) * der(y1) + der(x2) * der(x2) + der(y2) * der(y2))
            + g * (y1 + y2),
    );
});

// The same double pendulum in its angles: the mass matrix [[2, c], [c, 1]].
double_pendulum_released_horizontal!();

#[test]
fn the_cartesian_double_pendulum_follows_its_angle_form() {
    // Chaotic: compared over 2 s, where both runs agree to their tolerance.
    let tol = 1e-11;
    let sol = tight::<DoublePendulumCartesian>(2.0, tol);
    let reference = tight::<DoublePendulumAngles>(2.0, 1e-13);
    for t in [0.5, 1.0, 2.0] {
        let (a, b) = (reference.at(t, "a").unwrap(), reference.at(t, "b").unwrap());
        let (x2, y2) = (a.sin() + b.sin(), -a.cos() - b.cos());
        let e = (sol.at(t, "x2").unwrap() - x2).abs().max((sol.at(t, "y2").unwrap() - y2).abs());
        assert!(e <= 1000.0 * tol, "t = {t}: error {e:e}");
    }
    // Energy: 0 at the start (both rods horizontal, at rest).
    assert!(sol.last("energy").unwrap().abs() <= 1e-8);
    assert!(sol.max_constraint_residual() <= 1e-12);
}

/// The pendulum in momentum form with the mass a parameter: `m der(x) = p`
/// defines der(x) explicitly, so the constraint's derivatives go through it.
#[dae_model]
fn pendulum_momentum() {
    let m = param(2.0);
    let g = param(1.0);
    let x = state(1.0);
    let y = state(0.0);
    let px = state(0.0);
    let py = state(2.0);
    let lambda = algebraic(0.0);
    m * der(x) == px;
    m * der(y) == py;
    der(px) == -lambda * x;
    der(py) == -lambda * y - m * g;
    constraint(x * x + y * y - 1.0);
}

#[test]
fn explicit_definitions_may_have_parameter_coefficients() {
    assert_eq!(<PendulumMomentum as Model>::INDEX, 3);
    // Cash's pendulum again (unit speed, g = 1), whatever the mass.
    let tol = 1e-10;
    let sol = tight::<PendulumMomentum>(1.0, tol);
    let e = (sol.last("x").unwrap() - PENDUL3[0].1[0])
        .abs()
        .max((sol.last("y").unwrap() - PENDUL3[0].1[1]).abs());
    assert!(e <= 20.0 * tol, "error {e:e}");
}

/// Both formulations of the contract's pendulum report the same things,
/// truthfully: every name (states, the multiplier, the output), which
/// formulation ran, the constraint residuals measured at every accepted
/// step at the position and at the velocity level, and the degrees of
/// freedom.
#[test]
fn every_formulation_reports_its_names_residuals_and_degrees_of_freedom() {
    let tol = 1e-8;
    let base = Options::new().method(Method::Radau5).tolerance(tol);
    let projected = Pendulum::default().simulate(0.0, 3.0, &base).unwrap();
    let mass =
        Pendulum::default().simulate(0.0, 3.0, &base.formulation(Formulation::MassMatrix)).unwrap();
    for (sol, what) in [(&projected, "projected"), (&mass, "mass-matrix")] {
        let stats = sol.stats();
        assert!(stats.formulation.contains(what), "{what}: {}", stats.formulation);
        assert_eq!(sol.degrees_of_freedom(), Some(1), "{what}");
        // The output and the multiplier by name, at a step and between.
        // Released at rest level with the pivot: the energy stays 0.
        let energy = sol.last("energy").unwrap();
        assert!(energy.abs() < 1e-4, "{what}: energy {energy}");
        assert!(sol.at(1.234, "energy").unwrap().is_finite(), "{what}");
        let lambda = sol.at(1.5, "lambda").unwrap();
        assert!(lambda.is_finite() && lambda.abs() > 1.0, "{what}: λ = {lambda}");
        // Measured, not assumed: above zero, below the tolerance's reach.
        let (p, v) = (sol.max_constraint_residual(), sol.max_velocity_constraint_residual());
        assert!(p > 0.0 && v > 0.0, "{what}: residuals {p:e}, {v:e}");
        assert!(p < 1e-6 && v < 1e-4, "{what}: residuals {p:e}, {v:e}");
    }
    assert!(mass.stats().formulation.contains("Gear–Gupta–Leimkuhler"));
    // Projection holds the constraints to rounding; the GGL form to its
    // Newton tolerance, well above.
    assert!(projected.max_constraint_residual() < 1e-13);
    assert!(mass.max_constraint_residual() > projected.max_constraint_residual());
}

/// Inconsistent initial values are moved onto the constraints and the
/// moves are reported; with strict_initial_values they are an error that
/// names the values, and consistent ones move nothing.
#[test]
fn moved_initial_values_are_reported_or_refused() {
    let model = Pendulum::default();
    let opts = Options::new().method(Method::Radau5);
    // |(1.1, 0)| = 1.1 on a pendulum of length 1: x moves to 1 (the
    // minimum-norm correction along Φ_q = (2x, 2y)); y, u, v stay.
    let sol = model.simulate_from(0.0, &[1.1, 0.0, 0.0, 0.0], 1.0, &opts).unwrap();
    let moved = sol.initial_corrections();
    assert_eq!(moved.len(), 1, "{moved:?}");
    assert_eq!((moved[0].name, moved[0].given), ("x", 1.1));
    assert!((moved[0].used - 1.0).abs() < 1e-15, "{moved:?}");
    // Consistent values move nothing; so does an ODE.
    let consistent = model.simulate(0.0, 1.0, &opts).unwrap();
    assert!(consistent.initial_corrections().is_empty());
    let strict = opts.strict_initial_values(true);
    assert!(model.simulate(0.0, 1.0, &strict).is_ok());
    // Strict: the move is an error naming the constraint and the values.
    let err = model.simulate_from(0.0, &[1.1, 0.0, 0.0, 0.0], 1.0, &strict).unwrap_err();
    let message = err.to_string();
    assert!(
        matches!(
            err,
            Error::Constraint { constraint: "constraint(x * x + y * y - l * l)", level: 0, .. }
        ),
        "{message}"
    );
    assert!(message.contains("`x` from 1.1 to 1"), "{message}");
    // The mass-matrix formulation reports the same moves.
    let mass = model
        .simulate_from(0.0, &[1.1, 0.0, 0.0, 0.0], 1.0, &opts.formulation(Formulation::MassMatrix))
        .unwrap();
    assert_eq!(mass.initial_corrections(), sol.initial_corrections());
    // An algebraic variable's guess is no initial value: Newton starts
    // from it, and nothing is reported moved.
    let decay = SquareRootDecay::default().simulate(0.0, 1.0, &Options::new()).unwrap();
    assert!(decay.initial_corrections().is_empty());
}
