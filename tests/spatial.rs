//! Spatial multibody scenes (course notes §4.2, body coordinates with
//! quaternion attitudes): checked against a hand-written model, against
//! minimal-coordinate ODEs and against an exact solution.

use daegen::prelude::*;

mod support;
use support::harness::adaptive_methods_for;
use support::tight;

include!("models/heavy_top.rs");

// The heavy top of the kinematics tests as a scene, the spinning top of
// the example: a body on a spherical joint, its centre of mass l = 0.5
// above the pivot along its symmetry axis. With m = 1 and g = 2, m g l = 1
// as in the hand-written model, and the inertia about the centre of mass
// is the one about the pivot minus m l² (Steiner): a = 1 − 0.25 across,
// c = 0.5 along. It starts tilted by β = 0.5 about x, spinning at
// ω = (0, 0.5, 5) in body axes, so its centre is at l (0, −sin β, cos β)
// moving with R(β) (ω × l e3) = (0.25, 0, 0).
#[path = "../examples/spinning_top.rs"]
#[allow(dead_code)]
mod spinning_top;
use spinning_top::SpinningTop as HeavyTopScene;

#[test]
fn a_heavy_top_scene_matches_the_hand_written_quaternion_model() {
    assert_eq!(<HeavyTopScene as Model>::INDEX, 3);
    let tol = 1e-12;
    let scene = tight::<HeavyTopScene>(10.0, tol);
    let hand = tight::<HeavyTop>(10.0, tol);
    assert_eq!(scene.degrees_of_freedom(), Some(3));
    let mut worst = 0.0f64;
    for t in [1.0, 2.5, 5.0, 10.0] {
        for k in 0..4 {
            let a = scene.at(t, &format!("top.q{k}")).unwrap();
            let b = hand.at(t, &format!("q[{k}]")).unwrap();
            worst = worst.max((a - b).abs());
        }
        for (k, w) in ["wx", "wy", "wz"].iter().enumerate() {
            let a = scene.at(t, &format!("top.{w}")).unwrap();
            let b = hand.at(t, &format!("w[{k}]")).unwrap();
            worst = worst.max((a - b).abs());
        }
    }
    // Measured: 1.2e-11 over 155 steps.
    assert!(worst <= 1e-8, "scene vs hand-written top: {worst:e}");
    let e0 = scene.at(0.0, "energy").unwrap();
    let drift = scene
        .times()
        .iter()
        .map(|&t| (scene.at(t, "energy").unwrap() - e0).abs())
        .fold(0.0, f64::max);
    assert!(drift <= 1e-9, "energy drift {drift:e}");
    // The centre sits at l R e3 from the pivot.
    for t in [1.0, 10.0] {
        let (tilt, z) = (scene.at(t, "tilt").unwrap(), scene.at(t, "top.z").unwrap());
        assert!((tilt.cos() - z / 0.5).abs() <= 1e-11, "t = {t}: {tilt} vs {}", z / 0.5);
    }
    assert!(scene.max_constraint_residual() <= 1e-12);
}

/// A bar hinged to the ground about the y axis with a second bar welded to
/// its lower end: one compound pendulum. Both start turned by θ0 = 1 about
/// y, so each centre is at −d (sin θ0, 0, cos θ0).
#[dae_model]
fn welded_pendulum() {
    let g = param(9.81);
    let ground = ground();
    let upper = spatial_body(
        1.0,
        vec3(0.1, 0.1, 0.02),
        [-0.5 * sin(1.0), 0.0, -0.5 * cos(1.0)],
        [cos(0.5), 0.0, sin(0.5), 0.0],
    );
    let lower = spatial_body(
        0.5,
        vec3(0.02, 0.03, 0.01),
        [-1.25 * sin(1.0), 0.0, -1.25 * cos(1.0)],
        [cos(0.5), 0.0, sin(0.5), 0.0],
    );
    let hinge =
        revolute(ground, vec3(0.0, 0.0, 0.0), upper, vec3(0.0, 0.0, 0.5), vec3(0.0, 1.0, 0.0));
    let weld = fixed(upper, vec3(0.0, 0.0, -0.5), lower, vec3(0.0, 0.0, 0.25));
    gravity(vec3(0.0, 0.0, -g));
    /// The rotation about y.
    let angle = output(2.0 * atan2(upper.q2, upper.q0));
    /// How far the lower bar turned relative to the upper one.
    let twist = output(upper.q0 * lower.q2 - upper.q2 * lower.q0);
}

/// The same pendulum in its one coordinate: I θ'' = −g (Σ m d) sin θ with
/// I = Σ (J_yy + m d²) about the hinge (d = 0.5 and 1.25).
#[dae_model]
fn compound_pendulum() {
    let g = param(9.81);
    let theta = state(1.0);
    let inertia = 0.1 + 1.0 * 0.5 * 0.5 + 0.03 + 0.5 * 1.25 * 1.25;
    let moment = 1.0 * 0.5 + 0.5 * 1.25;
    der(der(theta)) == -g * moment * sin(theta) / inertia;
}

#[test]
fn a_revolute_and_a_fixed_joint_make_a_compound_pendulum() {
    assert_eq!(<WeldedPendulum as Model>::INDEX, 3);
    let tol = 1e-11;
    let scene = tight::<WeldedPendulum>(3.0, tol);
    let minimal = tight::<CompoundPendulum>(3.0, tol);
    assert_eq!(scene.degrees_of_freedom(), Some(1));
    for t in [0.5, 1.0, 2.0, 3.0] {
        let (a, b) = (scene.at(t, "angle").unwrap(), minimal.at(t, "theta").unwrap());
        assert!((a - b).abs() <= 1e-8, "t = {t}: scene {a}, one coordinate {b}");
        assert!(scene.at(t, "twist").unwrap().abs() <= 1e-10);
        // The hinge's coordinate: its turn about y since the start (θ0 = 1).
        let hinge = scene.at(t, "hinge.q").unwrap();
        assert!((hinge - (b - 1.0)).abs() <= 1e-8, "t = {t}: hinge.q {hinge}");
        // The motion stays in the x–z plane.
        assert!(scene.at(t, "upper.y").unwrap().abs() <= 1e-10);
        assert!(scene.at(t, "lower.q1").unwrap().abs() <= 1e-10);
    }
}

/// A block on a prismatic joint along a slope of angle α = 0.3, turned
/// arbitrarily (0.7 about (1, 1, 1)/√3): it slides down with acceleration
/// g sin α and keeps its attitude.
#[dae_model]
fn block_on_a_slope() {
    let g = param(9.81);
    let ground = ground();
    let block = spatial_body(
        2.0,
        vec3(0.1, 0.2, 0.3),
        [0.0, 0.0, 0.0],
        [cos(0.35), sin(0.35) / sqrt(3.0), sin(0.35) / sqrt(3.0), sin(0.35) / sqrt(3.0)],
    );
    let slide = prismatic(
        ground,
        vec3(0.0, 0.0, 0.0),
        block,
        vec3(0.0, 0.0, 0.0),
        vec3(cos(0.3), 0.0, -sin(0.3)),
    );
    gravity(vec3(0.0, 0.0, -g));
}

#[test]
fn a_prismatic_joint_on_a_slope_follows_the_exact_solution() {
    let tol = 1e-10;
    let sol = tight::<BlockOnASlope>(2.0, tol);
    assert_eq!(sol.degrees_of_freedom(), Some(1));
    let (g, alpha) = (9.81f64, 0.3f64);
    let q0 = [
        0.35f64.cos(),
        0.35f64.sin() / 3f64.sqrt(),
        0.35f64.sin() / 3f64.sqrt(),
        0.35f64.sin() / 3f64.sqrt(),
    ];
    for t in [0.5, 1.0, 2.0] {
        let s = 0.5 * g * alpha.sin() * t * t;
        let exact = [s * alpha.cos(), 0.0, -s * alpha.sin()];
        for (k, c) in ["x", "y", "z"].iter().enumerate() {
            let v = sol.at(t, &format!("block.{c}")).unwrap();
            assert!((v - exact[k]).abs() <= 1e-8, "t = {t}: block.{c} = {v}, exact {}", exact[k]);
        }
        // The joint's coordinate: the slide along the slope.
        let slide = sol.at(t, "slide.q").unwrap();
        assert!((slide - s).abs() <= 1e-8, "t = {t}: slide.q {slide}, exact {s}");
        for k in 0..4 {
            let q = sol.at(t, &format!("block.q{k}")).unwrap();
            assert!((q - q0[k]).abs() <= 1e-9, "attitude drifts: q{k} = {q}");
        }
    }
}

/// A bob on a massless rod of length L = 1 (a distance joint from the
/// ground to its centre), started on the conical-pendulum orbit: cone angle
/// φ = 0.6, radius ρ = L sin φ, angular speed Ω = √(g / (L cos φ)).
#[dae_model(taylor = 1)]
fn conical_pendulum() {
    let g = param(9.81);
    let ground = ground();
    let bob = spatial_body(
        1.0,
        vec3(0.01, 0.01, 0.01),
        [sin(0.6), 0.0, -cos(0.6)],
        [1.0, 0.0, 0.0, 0.0],
        [0.0, sin(0.6) * sqrt(g / cos(0.6)), 0.0],
        [0.0, 0.0, 0.0],
    );
    let rod = distance(ground, vec3(0.0, 0.0, 0.0), bob, vec3(0.0, 0.0, 0.0), 1.0);
    gravity(vec3(0.0, 0.0, -g));
}

#[test]
fn a_distance_joint_keeps_the_conical_pendulum_on_its_circle() {
    let (g, phi) = (9.81f64, 0.6f64);
    let (rho, omega) = (phi.sin(), (g / phi.cos()).sqrt());
    let period = 2.0 * std::f64::consts::PI / omega;
    // Every adaptive method that runs the model: each keeps the bob on
    // its circle through the joint's constraint.
    for method in adaptive_methods_for::<ConicalPendulum>() {
        let tol = 1e-11;
        let opts = Options::new().method(method).tolerance(tol);
        let sol = ConicalPendulum::default().simulate(0.0, 3.0 * period, &opts).unwrap();
        assert_eq!(sol.degrees_of_freedom(), Some(5));
        for k in 1..=6 {
            let t = 0.5 * k as f64 * period;
            let exact = [rho * (omega * t).cos(), rho * (omega * t).sin(), -phi.cos()];
            for (i, c) in ["x", "y", "z"].iter().enumerate() {
                let v = sol.at(t, &format!("bob.{c}")).unwrap();
                assert!(
                    (v - exact[i]).abs() <= 1e-7,
                    "{method:?}, t = {t}: bob.{c} = {v}, exact {}",
                    exact[i]
                );
            }
        }
    }
}

/// A block on a horizontal prismatic joint held by a spring–damper to the
/// ground: k = 4, c = 0.4, m = 1, rest length 1, released 0.3 stretched.
#[dae_model]
fn damped_block() {
    let ground = ground();
    let block = spatial_body(1.0, vec3(0.1, 0.1, 0.1), [1.3, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0]);
    prismatic(ground, vec3(0.0, 0.0, 0.0), block, vec3(0.0, 0.0, 0.0), vec3(1.0, 0.0, 0.0));
    spring(ground, vec3(0.0, 0.0, 0.0), block, vec3(0.0, 0.0, 0.0), 4.0, 1.0, 0.4);
    gravity(vec3(0.0, 0.0, -9.81));
}

#[test]
fn a_spring_damper_gives_the_damped_oscillator() {
    let tol = 1e-11;
    let sol = tight::<DampedBlock>(5.0, tol);
    // x − 1 = A e^{−ζω t} (cos ω_d t + ζ/√(1−ζ²) sin ω_d t), ω = 2, ζ = 0.1.
    let (omega, zeta, a) = (2.0f64, 0.1f64, 0.3f64);
    let wd = omega * (1.0 - zeta * zeta).sqrt();
    for t in [0.5, 1.0, 2.5, 5.0] {
        let exact = 1.0
            + a * (-zeta * omega * t).exp()
                * ((wd * t).cos() + zeta / (1.0 - zeta * zeta).sqrt() * (wd * t).sin());
        let x = sol.at(t, "block.x").unwrap();
        assert!((x - exact).abs() <= 1e-8, "t = {t}: x = {x}, exact {exact}");
    }
}

/// A body on a spherical joint at its centre of mass, spun up by a constant
/// torque τ = 0.3 about the world z axis, a principal axis (J_z = 0.2).
#[dae_model]
fn spun_body() {
    let ground = ground();
    let rotor = spatial_body(3.0, vec3(0.1, 0.15, 0.2), [0.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0]);
    spherical(ground, vec3(0.0, 0.0, 0.0), rotor, vec3(0.0, 0.0, 0.0));
    torque(rotor, vec3(0.0, 0.0, 0.3));
    gravity(vec3(0.0, 0.0, -9.81));
}

#[test]
fn a_constant_torque_about_a_principal_axis_spins_a_body_up() {
    let tol = 1e-12;
    let sol = tight::<SpunBody>(2.0, tol);
    for t in [0.5, 1.0, 2.0] {
        // ψ = ½ (τ / J_z) t², q = (cos ψ/2, 0, 0, sin ψ/2).
        let psi = 0.5 * 1.5 * t * t;
        let (q0, q3) = (sol.at(t, "rotor.q0").unwrap(), sol.at(t, "rotor.q3").unwrap());
        assert!((q0 - (psi / 2.0).cos()).abs() <= 1e-9, "t = {t}: q0 = {q0}");
        assert!((q3 - (psi / 2.0).sin()).abs() <= 1e-9, "t = {t}: q3 = {q3}");
        assert!((sol.at(t, "rotor.wz").unwrap() - 1.5 * t).abs() <= 1e-9);
        assert!(sol.at(t, "rotor.z").unwrap().abs() <= 1e-12);
    }
}

/// A bar on a hinge about y through its centre, pulled down by a world-fixed
/// force F = 2 at its body point (1, 0, 0): J_y ψ'' = F cos ψ.
#[dae_model]
fn pulled_bar() {
    let ground = ground();
    let bar = spatial_body(1.0, vec3(0.05, 0.5, 0.5), [0.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0]);
    revolute(ground, vec3(0.0, 0.0, 0.0), bar, vec3(0.0, 0.0, 0.0), vec3(0.0, 1.0, 0.0));
    force(bar, vec3(1.0, 0.0, 0.0), vec3(0.0, 0.0, -2.0));
    let psi = output(2.0 * atan2(bar.q2, bar.q0));
}

/// Its one coordinate.
#[dae_model]
fn pulled_bar_angle() {
    let psi = state(0.0);
    der(der(psi)) == 2.0 * cos(psi) / 0.5;
}

#[test]
fn a_force_at_a_body_point_turns_the_bar_as_its_one_coordinate_says() {
    let tol = 1e-11;
    let scene = tight::<PulledBar>(3.0, tol);
    let minimal = tight::<PulledBarAngle>(3.0, tol);
    for t in [0.5, 1.5, 3.0] {
        let (a, b) = (scene.at(t, "psi").unwrap(), minimal.at(t, "psi").unwrap());
        assert!((a - b).abs() <= 1e-8, "t = {t}: scene {a}, one coordinate {b}");
        // An unnamed joint is named by its kind and place among the joints.
        let q = scene.at(t, "revolute1.q").unwrap();
        assert!((q - b).abs() <= 1e-8, "t = {t}: revolute1.q {q}");
    }
}

#[test]
fn the_heavy_top_scene_conserves_energy_and_unit_norm_over_a_thousand_taylor_steps() {
    let tol = 1e-15;
    let opts = Options::new().method(Method::Taylor).tolerance(tol);
    let sol = HeavyTopScene::default().simulate(0.0, 450.0, &opts).unwrap();
    let steps = sol.times().len();
    let e0 = sol.at(0.0, "energy").unwrap();
    let (mut energy, mut norm) = (0.0f64, 0.0f64);
    for &t in sol.times() {
        energy = energy.max((sol.at(t, "energy").unwrap() - e0).abs());
        let q: f64 = (0..4).map(|i| sol.at(t, &format!("top.q{i}")).unwrap().powi(2)).sum();
        norm = norm.max((q - 1.0).abs());
    }
    // Measured: 1227 steps, 8.9e-16 and 6.7e-16 (the hand-written model of
    // the kinematics tests, whose tape is shorter, gets a higher order
    // and 1021 steps).
    assert!(steps >= 1000, "{steps} steps");
    assert!(energy <= 1e-12 * e0, "energy drift {energy:e}");
    assert!(norm <= 1e-15, "|q|² − 1 = {norm:e}");
    assert!(sol.max_constraint_residual() <= 1e-12);
}
