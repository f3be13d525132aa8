//! Planar multibody scenes (course notes §4.2, global formulation): bodies
//! with (x, y, θ) of their centres, joints as constraints with their
//! reactions as algebraic variables, the Newton–Euler equations written by
//! the macro. Checked against hand-written models and minimal-coordinate
//! ODEs.

use daegen::prelude::*;

include!("models/slider_crank.rs");

/// The slider-crank of the DAE tests, built as a scene.
#[dae_model]
fn slider_crank_scene() {
    let r = param(0.15);
    let l = param(0.4);
    let m1 = param(1.0);
    let m2 = param(0.5);
    let g = param(9.81);
    let ground = ground();
    let crank = body(m1, m1 * r * r / 12.0, [0.04, 0.06, 1.0]);
    let slider = body(m2, 1.0, [0.45, 0.0, 0.0]);
    let pivot = revolute(ground, vec3(0.0, 0.0, 0.0), crank, vec3(-0.5 * r, 0.0, 0.0));
    let rod = distance(
        crank,
        vec3(0.5 * r, 0.0, 0.0),
        slider,
        vec3(0.0, 0.0, 0.0),
        l,
    );
    prismatic(
        ground,
        vec3(0.0, 0.0, 0.0),
        slider,
        vec3(0.0, 0.0, 0.0),
        vec3(1.0, 0.0, 0.0),
    );
    gravity(vec3(0.0, -g, 0.0));
    let pin = position(crank, vec3(0.5 * r, 0.0, 0.0));
    let pin_x = output(pin[0]);
}

#[test]
fn a_slider_crank_scene_matches_the_hand_written_model() {
    assert_eq!(<SliderCrankScene as Model>::INDEX, 3);
    let tol = 1e-10;
    let opts = Options::new().method(Method::Dop853).rtol(tol).atol(tol);
    let scene = SliderCrankScene::default()
        .simulate(0.0, 2.0, &opts)
        .unwrap();
    let hand = SliderCrank::default().simulate(0.0, 2.0, &opts).unwrap();
    assert_eq!(scene.degrees_of_freedom(), Some(1));
    for t in [0.0, 0.5, 1.0, 2.0] {
        let (a, b) = (
            scene.at(t, "crank.theta").unwrap(),
            hand.at(t, "theta1").unwrap(),
        );
        assert!(
            (a - b).abs() <= 100.0 * tol,
            "t = {t}: scene θ {a}, hand-written {b}"
        );
        let (a, b) = (scene.at(t, "slider.x").unwrap(), hand.at(t, "xs").unwrap());
        assert!(
            (a - b).abs() <= 100.0 * tol,
            "t = {t}: scene xs {a}, hand-written {b}"
        );
    }
    // The reactions are named: the pivot carries the crank's weight on average.
    assert!(scene.last("pivot[1]").unwrap().is_finite());
    let theta = scene.last("crank.theta").unwrap();
    assert!((scene.last("pin_x").unwrap() - 0.15 * theta.cos()).abs() <= 1e-12);
    assert!(scene.max_constraint_residual() <= 1e-12);
}

/// A four-bar linkage: ground pivots 3 apart, crank 1, coupler 3, rocker 2.5,
/// uniform rods swinging under gravity; one loop, one degree of freedom.
#[dae_model]
fn four_bar() {
    let g = param(9.81);
    let ground = ground();
    let crank = body(1.0, 1.0 / 12.0, [0.25, 0.433, 1.047]);
    let coupler = body(3.0, 27.0 / 12.0, [1.758, 1.683, 0.576]);
    let rocker = body(2.5, 2.5 * 6.25 / 12.0, [3.008, 1.25, 1.564]);
    revolute(ground, vec3(0.0, 0.0, 0.0), crank, vec3(-0.5, 0.0, 0.0));
    revolute(crank, vec3(0.5, 0.0, 0.0), coupler, vec3(-1.5, 0.0, 0.0));
    revolute(coupler, vec3(1.5, 0.0, 0.0), rocker, vec3(1.25, 0.0, 0.0));
    revolute(ground, vec3(3.0, 0.0, 0.0), rocker, vec3(-1.25, 0.0, 0.0));
    gravity(vec3(0.0, -g, 0.0));
}

#[test]
fn a_four_bar_linkage_has_one_degree_of_freedom_and_keeps_its_energy() {
    let tol = 1e-10;
    let opts = Options::new().method(Method::Dop853).rtol(tol).atol(tol);
    let sol = FourBar::default().simulate(0.0, 3.0, &opts).unwrap();
    assert_eq!(sol.degrees_of_freedom(), Some(1));
    assert!(sol.max_constraint_residual() <= 1e-12);
    // Energy: Σ ½ m |v|² + ½ J ω² + m g y over the three links.
    let links = [
        ("crank", 1.0, 1.0 / 12.0),
        ("coupler", 3.0, 27.0 / 12.0),
        ("rocker", 2.5, 2.5 * 6.25 / 12.0),
    ];
    let energy = |t: f64| -> f64 {
        links
            .iter()
            .map(|(name, m, j)| {
                let v = |c: &str| sol.at(t, &format!("der({name}.{c})")).unwrap();
                0.5 * m * (v("x").powi(2) + v("y").powi(2))
                    + 0.5 * j * v("theta").powi(2)
                    + m * 9.81 * sol.at(t, &format!("{name}.y")).unwrap()
            })
            .sum()
    };
    let e0 = energy(0.0);
    for t in [0.5, 1.0, 2.0, 3.0] {
        assert!(
            (energy(t) - e0).abs() <= 1e-7 * e0.abs(),
            "t = {t}: {} vs {e0}",
            energy(t)
        );
    }
    // It moves: the crank turns.
    assert!((sol.last("crank.theta").unwrap() - sol.at(0.0, "crank.theta").unwrap()).abs() > 0.1);
}

/// A double pendulum of two uniform rods (mass 1, length 1) released
/// horizontal, as a scene; each rod's body x axis points from its upper
/// hinge down the rod, so its angle is θ − π/2 for θ from the vertical.
#[dae_model]
fn double_rod_scene() {
    let g = param(9.81);
    let ground = ground();
    let upper = body(1.0, 1.0 / 12.0, [0.5, 0.0, 0.0]);
    let lower = body(1.0, 1.0 / 12.0, [1.5, 0.0, 0.0]);
    revolute(ground, vec3(0.0, 0.0, 0.0), upper, vec3(-0.5, 0.0, 0.0));
    revolute(upper, vec3(0.5, 0.0, 0.0), lower, vec3(-0.5, 0.0, 0.0));
    gravity(vec3(0.0, -g, 0.0));
}

/// Its Lagrange equations in the angles from the downward vertical:
/// M = [[4/3, ½ cos Δ], [½ cos Δ, 1/3]], Δ = θ1 − θ2.
#[dae_model]
fn double_rod_angles() {
    let g = param(9.81);
    let a = state(1.5707963267948966);
    let b = state(1.5707963267948966);
    let c = cos(a - b);
    let s = sin(a - b);
    4.0 / 3.0 * der(der(a)) + 0.5 * c * der(der(b))
        == -0.5 * s * der(b) * der(b) - 1.5 * g * sin(a);
    0.5 * c * der(der(a)) + der(der(b)) / 3.0 == 0.5 * s * der(a) * der(a) - 0.5 * g * sin(b);
}

#[test]
fn a_double_pendulum_scene_follows_its_lagrange_equations() {
    let tol = 1e-11;
    let opts = Options::new().method(Method::Dop853).rtol(tol).atol(tol);
    let sol = DoubleRodScene::default().simulate(0.0, 2.0, &opts).unwrap();
    let reference = DoubleRodAngles::default()
        .simulate(
            0.0,
            2.0,
            &Options::new()
                .method(Method::Dop853)
                .rtol(1e-13)
                .atol(1e-13),
        )
        .unwrap();
    assert_eq!(sol.degrees_of_freedom(), Some(2));
    let half_pi = std::f64::consts::FRAC_PI_2;
    for t in [0.5, 1.0, 2.0] {
        for (body, angle) in [("upper", "a"), ("lower", "b")] {
            let got = sol.at(t, &format!("{body}.theta")).unwrap() + half_pi;
            let want = reference.at(t, angle).unwrap();
            assert!(
                (got - want).abs() <= 1000.0 * tol,
                "t = {t}: {body} {got} vs {want}"
            );
        }
    }
}

/// A block hanging from the ground on a spring–damper (k = 40, c = 2,
/// rest length 1, m = 2): y − y_eq = A e^(−σt) (cos ω t + σ/ω sin ω t).
#[dae_model]
fn hanging_block() {
    let g = param(9.81);
    let ground = ground();
    let block = body(2.0, 0.1, [0.0, -1.8, 0.0]);
    spring(
        ground,
        vec3(0.0, 0.0, 0.0),
        block,
        vec3(0.0, 0.0, 0.0),
        40.0,
        1.0,
        2.0,
    );
    gravity(vec3(0.0, -g, 0.0));
}

#[test]
fn a_spring_damper_in_a_scene_gives_the_damped_oscillation() {
    assert_eq!(<HangingBlock as Model>::INDEX, 0);
    let tol = 1e-11;
    let sol = HangingBlock::default()
        .simulate(
            0.0,
            3.0,
            &Options::new().method(Method::Dop853).rtol(tol).atol(tol),
        )
        .unwrap();
    let (m, k, c, l0, g) = (2.0f64, 40.0f64, 2.0f64, 1.0f64, 9.81f64);
    let y_eq = -l0 - m * g / k;
    let a0 = -1.8 - y_eq;
    let sigma = c / (2.0 * m);
    let omega = (k / m - sigma * sigma).sqrt();
    for t in [0.5f64, 1.0, 3.0] {
        let want = y_eq
            + a0 * (-sigma * t).exp() * ((omega * t).cos() + sigma / omega * (omega * t).sin());
        let got = sol.at(t, "block.y").unwrap();
        assert!(
            (got - want).abs() <= 100.0 * tol,
            "t = {t}: {got} vs {want}"
        );
        assert!(sol.at(t, "block.x").unwrap().abs() <= 1e-15);
    }
}

/// A chain of ten uniform rods (mass 1, length 1) hanging from the ground,
/// released horizontal: 30 coordinates, 20 constraint rows.
#[dae_model]
fn ten_rod_chain() {
    let g = param(9.81);
    let ground = ground();
    let rod0 = body(1.0, 1.0 / 12.0, [0.5, 0.0, 0.0]);
    let rod1 = body(1.0, 1.0 / 12.0, [1.5, 0.0, 0.0]);
    let rod2 = body(1.0, 1.0 / 12.0, [2.5, 0.0, 0.0]);
    let rod3 = body(1.0, 1.0 / 12.0, [3.5, 0.0, 0.0]);
    let rod4 = body(1.0, 1.0 / 12.0, [4.5, 0.0, 0.0]);
    let rod5 = body(1.0, 1.0 / 12.0, [5.5, 0.0, 0.0]);
    let rod6 = body(1.0, 1.0 / 12.0, [6.5, 0.0, 0.0]);
    let rod7 = body(1.0, 1.0 / 12.0, [7.5, 0.0, 0.0]);
    let rod8 = body(1.0, 1.0 / 12.0, [8.5, 0.0, 0.0]);
    let rod9 = body(1.0, 1.0 / 12.0, [9.5, 0.0, 0.0]);
    revolute(ground, vec3(0.0, 0.0, 0.0), rod0, vec3(-0.5, 0.0, 0.0));
    revolute(rod0, vec3(0.5, 0.0, 0.0), rod1, vec3(-0.5, 0.0, 0.0));
    revolute(rod1, vec3(0.5, 0.0, 0.0), rod2, vec3(-0.5, 0.0, 0.0));
    revolute(rod2, vec3(0.5, 0.0, 0.0), rod3, vec3(-0.5, 0.0, 0.0));
    revolute(rod3, vec3(0.5, 0.0, 0.0), rod4, vec3(-0.5, 0.0, 0.0));
    revolute(rod4, vec3(0.5, 0.0, 0.0), rod5, vec3(-0.5, 0.0, 0.0));
    revolute(rod5, vec3(0.5, 0.0, 0.0), rod6, vec3(-0.5, 0.0, 0.0));
    revolute(rod6, vec3(0.5, 0.0, 0.0), rod7, vec3(-0.5, 0.0, 0.0));
    revolute(rod7, vec3(0.5, 0.0, 0.0), rod8, vec3(-0.5, 0.0, 0.0));
    revolute(rod8, vec3(0.5, 0.0, 0.0), rod9, vec3(-0.5, 0.0, 0.0));
    gravity(vec3(0.0, -g, 0.0));
}

#[test]
fn a_ten_rod_chain_keeps_its_constraints_and_energy() {
    let tol = 1e-9;
    let opts = Options::new().method(Method::Dop853).rtol(tol).atol(tol);
    let sol = TenRodChain::default().simulate(0.0, 1.0, &opts).unwrap();
    assert_eq!(sol.degrees_of_freedom(), Some(10));
    assert!(sol.max_constraint_residual() <= 1e-12);
    let energy = |t: f64| -> f64 {
        (0..10)
            .map(|i| {
                let v = |c: &str| sol.at(t, &format!("der(rod{i}.{c})")).unwrap();
                0.5 * (v("x").powi(2) + v("y").powi(2))
                    + 0.5 / 12.0 * v("theta").powi(2)
                    + 9.81 * sol.at(t, &format!("rod{i}.y")).unwrap()
            })
            .sum()
    };
    // E(0) = 0 (horizontal, at rest); the chain falls 1 s.
    for t in [0.25, 0.5, 1.0] {
        assert!(energy(t).abs() <= 1e-6, "t = {t}: energy {}", energy(t));
    }
}
