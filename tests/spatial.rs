//! Spatial multibody scenes (course notes §4.2, global formulation with
//! quaternion attitudes): checked against a hand-written model, against
//! minimal-coordinate ODEs and against an exact solution.

use daegen::prelude::*;

include!("models/heavy_top.rs");

/// The heavy top of the kinematics tests as a scene: a body on a spherical
/// joint, its centre of mass l = 0.5 above the pivot along its symmetry
/// axis. With m = 1 and g = 2, m g l = 1 as in the hand-written model, and
/// the inertia about the centre of mass is the one about the pivot minus
/// m l² (Steiner): a = 1 − 0.25 across, c = 0.5 along. It starts tilted by
/// β = 0.5 about x, spinning at ω = (0, 0.5, 5) in body axes, so its centre
/// is at l (0, −sin β, cos β) moving with R(β) (ω × l e3) = (0.25, 0, 0).
#[dae_model]
fn heavy_top_scene() {
    let m = param(1.0);
    let l = param(0.5);
    let g = param(2.0);
    let ground = ground();
    let top = spatial_body(
        m,
        vec3(1.0 - m * l * l, 1.0 - m * l * l, 0.5),
        [0.0, -l * sin(0.5), l * cos(0.5)],
        [cos(0.25), sin(0.25), 0.0, 0.0],
        [0.25, 0.0, 0.0],
        [0.0, 0.5, 5.0],
    );
    let pivot = spherical(ground, vec3(0.0, 0.0, 0.0), top, vec3(0.0, 0.0, -l));
    gravity(vec3(0.0, 0.0, -g));
    /// Kinetic plus potential energy.
    let energy = output(
        0.5 * m * (der(top.x) * der(top.x) + der(top.y) * der(top.y) + der(top.z) * der(top.z))
            + 0.5 * (0.75 * top.wx * top.wx + 0.75 * top.wy * top.wy + 0.5 * top.wz * top.wz)
            + m * g * top.z,
    );
}

#[test]
fn a_heavy_top_scene_matches_the_hand_written_quaternion_model() {
    assert_eq!(<HeavyTopScene as Model>::INDEX, 3);
    let tol = 1e-12;
    let opts = Options::new().method(Method::Dop853).rtol(tol).atol(tol);
    let scene = HeavyTopScene::default().simulate(0.0, 10.0, &opts).unwrap();
    let hand = HeavyTop::default().simulate(0.0, 10.0, &opts).unwrap();
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
    let hinge = revolute(
        ground,
        vec3(0.0, 0.0, 0.0),
        upper,
        vec3(0.0, 0.0, 0.5),
        vec3(0.0, 1.0, 0.0),
    );
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
    let opts = Options::new().method(Method::Dop853).rtol(tol).atol(tol);
    let scene = WeldedPendulum::default().simulate(0.0, 3.0, &opts).unwrap();
    let minimal = CompoundPendulum::default()
        .simulate(0.0, 3.0, &opts)
        .unwrap();
    assert_eq!(scene.degrees_of_freedom(), Some(1));
    for t in [0.5, 1.0, 2.0, 3.0] {
        let (a, b) = (
            scene.at(t, "angle").unwrap(),
            minimal.at(t, "theta").unwrap(),
        );
        assert!(
            (a - b).abs() <= 1e-8,
            "t = {t}: scene {a}, one coordinate {b}"
        );
        assert!(scene.at(t, "twist").unwrap().abs() <= 1e-10);
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
        [
            cos(0.35),
            sin(0.35) / sqrt(3.0),
            sin(0.35) / sqrt(3.0),
            sin(0.35) / sqrt(3.0),
        ],
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
    let opts = Options::new().method(Method::Dop853).rtol(tol).atol(tol);
    let sol = BlockOnASlope::default().simulate(0.0, 2.0, &opts).unwrap();
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
            assert!(
                (v - exact[k]).abs() <= 1e-8,
                "t = {t}: block.{c} = {v}, exact {}",
                exact[k]
            );
        }
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
    for method in [Method::Dop853, Method::Radau5, Method::Taylor] {
        let tol = 1e-11;
        let opts = Options::new().method(method).rtol(tol).atol(tol);
        let sol = ConicalPendulum::default()
            .simulate(0.0, 3.0 * period, &opts)
            .unwrap();
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
