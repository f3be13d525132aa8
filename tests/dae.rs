//! DAEs: index reduction at compile time, the index-1 form with projection
//! at run time (course notes chapter 2).

use daegen::prelude::*;

/// Planar pendulum as an index-3 DAE in Cartesian coordinates: the model of
/// the contract, the notes' eq. 2.1.
#[dae_model]
fn pendulum() {
    let m = param(1.0);
    let l = param(1.0);
    let g = param(9.81);
    let x = state(1.0);
    let y = state(0.0);
    let u = state(0.0);
    let v = state(0.0);
    let lambda = algebraic(0.0);
    der(x) == u;
    der(y) == v;
    m * der(u) == -lambda * x;
    m * der(v) == -lambda * y - m * g;
    constraint(x * x + y * y - l * l);
    let energy = output(0.5 * m * (u * u + v * v) + m * g * y);
}

/// The same pendulum in its angle θ from the downward vertical
/// (`x = l sin θ`, `y = −l cos θ`): the minimal-coordinate ODE of the notes.
#[dae_model]
fn pendulum_angle() {
    let l = param(1.0);
    let g = param(9.81);
    let theta = state(1.5707963267948966);
    init(der(theta), 0.0);
    l * der(der(theta)) == -g * sin(theta);
}

#[test]
fn the_cartesian_pendulum_has_index_three() {
    assert_eq!(<Pendulum as Model>::INDEX, 3);
    assert_eq!(<PendulumAngle as Model>::INDEX, 0);
    assert_eq!(Pendulum::INFO.algebraics, &["lambda"]);
    // The position constraint and its velocity level are projected onto.
    let levels: Vec<usize> = Pendulum::CONSTRAINTS.iter().map(|c| c.level).collect();
    assert_eq!(levels, [0, 1]);
    assert_eq!(
        Pendulum::CONSTRAINTS[0].equation,
        "constraint(x * x + y * y - l * l)"
    );
}

/// The angle form at a tolerance far below the DAE runs' as the reference.
fn angle_reference(t: f64) -> (f64, f64) {
    let opts = Options::new()
        .method(Method::Dop853)
        .rtol(1e-13)
        .atol(1e-13);
    let sol = PendulumAngle::default()
        .simulate(0.0, t, &opts)
        .expect("the angle form integrates");
    let theta = sol.last("theta").expect("theta");
    (theta.sin(), -theta.cos())
}

#[test]
fn the_dae_pendulum_follows_the_angle_form_and_keeps_its_constraints() {
    let model = Pendulum::default();
    let (m, g, l) = (model.m, model.g, model.l);
    for method in [Method::Dop853, Method::Dopri5, Method::Radau5] {
        let tol = 1e-10;
        let opts = Options::new().method(method).rtol(tol).atol(tol);
        let sol = model
            .simulate(0.0, 100.0, &opts)
            .expect("the pendulum runs");
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
            assert!(
                energy <= 10.0 * tol * m * g * l,
                "{method:?}: energy drift {energy:e}"
            );
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
        for method in [Method::Dop853, Method::Dopri5, Method::Radau5] {
            let opts = Options::new().method(method).rtol(tol).atol(tol);
            let angle = PendulumAngle::default()
                .simulate(0.0, 100.0, &opts)
                .unwrap();
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

/// Robertson's kinetics as a semi-explicit index-1 DAE: the third equation
/// replaced by the conservation law it implies (Hairer–Wanner II §IV.10;
/// test set `rober`).
#[dae_model]
fn robertson_dae() {
    let y1 = state(1.0);
    let y2 = state(0.0);
    let y3 = algebraic(0.0);
    der(y1) == -0.04 * y1 + 1e4 * y2 * y3;
    der(y2) == 0.04 * y1 - 1e4 * y2 * y3 - 3e7 * y2 * y2;
    0.0 == y1 + y2 + y3 - 1.0;
}

/// Published at t = 1e11 (test set rober.f, ../shared/notes/reference-problems.md §6).
#[allow(clippy::excessive_precision)]
const ROBER_AT_1E11: [f64; 3] = [
    0.2083340149701255e-7,
    0.8333360770334713e-13,
    0.9999999791665050,
];

#[test]
fn robertson_as_an_index_1_dae_reaches_the_published_solution() {
    assert_eq!(<RobertsonDae as Model>::INDEX, 1);
    assert_eq!(RobertsonDae::STATES, 2);
    // The algebraic equation is solved for y3 symbolically: an explicit ODE
    // with an analytic Jacobian, nothing left to project.
    assert!(RobertsonDae::CONSTRAINTS.is_empty());
    assert!(!RobertsonDae::JACOBIAN_PATTERN.is_empty());
    for tol in [1e-6, 1e-8, 1e-10] {
        let opts = Options::new()
            .method(Method::Radau5)
            .rtol(tol)
            .atol(1e-6 * tol);
        let sol = RobertsonDae::default().simulate(0.0, 1e11, &opts).unwrap();
        let got = [
            sol.last("y1").unwrap(),
            sol.last("y2").unwrap(),
            sol.last("y3").unwrap(),
        ];
        for (k, (g, r)) in got.iter().zip(ROBER_AT_1E11).enumerate() {
            let e = (g - r).abs() / r.abs();
            assert!(
                e <= 10.0 * tol,
                "tol {tol:e}: y{} relative error {e:e}",
                k + 1
            );
        }
    }
}
