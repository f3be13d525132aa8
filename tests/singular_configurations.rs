//! Models evaluated near singularities: each integrates correctly or stops
//! with an error at the singular place, never with a silent wrong answer.

use daegen::prelude::*;

mod support;
use support::harness::{is_adaptive, methods_for};

/// Cash's pendulum (g = 1) thrown at speed w = 20: the multiplier λ = u² +
/// v² − y reaches 400, eighty times the slow case.
#[dae_model]
fn fast_pendulum() {
    let w = param(20.0);
    let x = state(1.0);
    let y = state(0.0);
    let u = state(0.0);
    let v = state(w);
    let lambda = algebraic(400.0);
    der(x) == u;
    der(y) == v;
    der(u) == -lambda * x;
    der(v) == -lambda * y - 1.0;
    constraint(x * x + y * y - 1.0);
}

/// The same in its angle: θ'' = −cos θ, θ'(0) = 20.
#[dae_model]
fn fast_pendulum_angle() {
    let theta = state(0.0);
    init(der(theta), 20.0);
    der(der(theta)) == -cos(theta);
}

#[test]
fn a_pendulum_with_a_large_multiplier_follows_its_angle() {
    let tol = 1e-10;
    // Every adaptive method that runs both forms.
    let both = |m: Method| is_adaptive(m) && m.refusal::<FastPendulumAngle>().is_none();
    for method in methods_for::<FastPendulum>(both) {
        let opts = Options::new().method(method).tolerance(tol);
        let dae = FastPendulum::default().simulate(0.0, 5.0, &opts).unwrap();
        let ode = FastPendulumAngle::default().simulate(0.0, 5.0, &opts).unwrap();
        for t in [1.0, 2.5, 5.0] {
            let theta = ode.at(t, "theta").unwrap();
            let (x, y) = (dae.at(t, "x").unwrap(), dae.at(t, "y").unwrap());
            // About 16 revolutions by t = 5: the angle's error grows with it.
            assert!(
                (x - theta.cos()).abs() <= 1e-6 && (y - theta.sin()).abs() <= 1e-6,
                "{method:?}, t = {t}: ({x}, {y}) vs θ = {theta}"
            );
        }
        assert!(dae.max_constraint_residual() <= 1e-12);
    }
}

/// A slider-crank with crank and rod of equal length r = l = 0.2, started
/// at θ = 1 turning at 3 rad/s: at θ = π/2 the rod stands vertical above
/// the slider, the slider can go either way, and Φ_q loses rank.
#[dae_model]
fn isosceles_crank() {
    let r = param(0.2);
    let ground = ground();
    let crank = body(
        1.0,
        r * r / 12.0,
        [0.5 * r * cos(1.0), 0.5 * r * sin(1.0), 1.0],
        [-1.5 * r * sin(1.0), 1.5 * r * cos(1.0), 3.0],
    );
    let slider = body(0.5, 1.0, [2.0 * r * cos(1.0), 0.0, 0.0], [-6.0 * r * sin(1.0), 0.0, 0.0]);
    revolute(ground, vec3(0.0, 0.0, 0.0), crank, vec3(-0.5 * r, 0.0, 0.0));
    distance(crank, vec3(0.5 * r, 0.0, 0.0), slider, vec3(0.0, 0.0, 0.0), r);
    prismatic(ground, vec3(0.0, 0.0, 0.0), slider, vec3(0.0, 0.0, 0.0), vec3(1.0, 0.0, 0.0));
}

#[test]
fn a_mechanism_reaching_a_singular_configuration_stops_there_with_an_error() {
    let opts = Options::new().method(Method::Dop853).tolerance(1e-10);
    match IsoscelesCrank::default().simulate(0.0, 2.0, &opts) {
        Ok(sol) => {
            // Through it: the joints must still hold and the angle must
            // have passed π/2.
            assert!(sol.max_constraint_residual() <= 1e-9);
            assert!(sol.last("crank.theta").unwrap() > std::f64::consts::FRAC_PI_2);
        }
        Err(e) => {
            let partial = e.partial_solution().expect("the steps before it");
            let theta = partial.last("crank.theta").unwrap();
            assert!(
                (theta - std::f64::consts::FRAC_PI_2).abs() <= 0.05,
                "stopped at θ = {theta}, away from the singular π/2: {e}"
            );
            assert!(partial.max_constraint_residual() <= 1e-9);
            assert!(e.to_string().contains("singular"), "{e}");
        }
    }
}
