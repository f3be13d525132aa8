//! The universal (Cardan), cylindrical and planar joints of spatial scenes,
//! in the global formulation and in joint coordinates (the recursive one),
//! each against a motion derived by hand: the
//! universal joint's pendulum swings about either cross axis as a compound
//! pendulum, a body on a cylindrical joint falls along its axis spinning
//! freely, and a body on a planar joint slides and turns in its plane.

use daegen::prelude::*;

mod support;
use support::tight;

include!("models/both_formulations.rs");

// A rod-like body (m = 1, principal inertias 1/12, 0.2, 0.01 about its
// centre) hanging from the ground by a universal joint at its top, d = 0.5
// above its centre along body z; the cross axes are world x (in the
// ground) and body y, so its attitude is R = R_x(α)·R_y(β): quaternion
// (c_a c_b, s_a c_b, c_a s_b, s_a s_b) with c_a = cos(α/2) …, centre
// d·(−sin β, cos β sin α, −cos β cos α), angular velocity in body axes
// (α′ cos β, β′, α′ sin β). Started at α = 0.8, β = 0.3, α′ = 0.5,
// β′ = −0.4.
in_both_formulations!(cardan_pendulum, cardan_pendulum_in_joint_coordinates, {
    let g = param(9.81);
    let ground = ground();
    let a = 0.8;
    let b = 0.3;
    let da = 0.5;
    let db = -0.4;
    let d = 0.5;
    let rod = spatial_body(
        1.0,
        vec3(1.0 / 12.0, 0.2, 0.01),
        [-d * sin(b), d * cos(b) * sin(a), -d * cos(b) * cos(a)],
        [
            cos(a / 2.0) * cos(b / 2.0),
            sin(a / 2.0) * cos(b / 2.0),
            cos(a / 2.0) * sin(b / 2.0),
            sin(a / 2.0) * sin(b / 2.0),
        ],
        [
            -d * cos(b) * db,
            d * (-sin(b) * sin(a) * db + cos(b) * cos(a) * da),
            d * (sin(b) * cos(a) * db + cos(b) * sin(a) * da),
        ],
        [da * cos(b), db, da * sin(b)],
    );
    let cross = universal(
        ground,
        vec3(0.0, 0.0, 0.0),
        rod,
        vec3(0.0, 0.0, d),
        vec3(1.0, 0.0, 0.0),
        vec3(0.0, 1.0, 0.0),
    );
    gravity(vec3(0.0, 0.0, -g));
});

/// Its Lagrange equations in the Cardan angles: with
/// A(β) = (m d² + I_x) cos²β + I_z sin²β and B = m d² + I_y,
/// T = ½ A α′² + ½ B β′², V = −m g d cos α cos β, so
/// A α″ + A′(β) β′ α′ = −m g d sin α cos β and
/// B β″ − ½ A′(β) α′² = −m g d cos α sin β,
/// A′(β) = −2 sin β cos β (m d² + I_x − I_z).
#[dae_model]
fn cardan_angles() {
    let g = param(9.81);
    let alpha = state(0.8);
    let beta = state(0.3);
    init(der(alpha), 0.5);
    init(der(beta), -0.4);
    let m = 1.0;
    let d = 0.5;
    let ix = 1.0 / 12.0;
    let iy = 0.2;
    let iz = 0.01;
    let a = (m * d * d + ix) * cos(beta) * cos(beta) + iz * sin(beta) * sin(beta);
    let a_prime = -2.0 * sin(beta) * cos(beta) * (m * d * d + ix - iz);
    a * der(der(alpha)) + a_prime * der(beta) * der(alpha) == -m * g * d * sin(alpha) * cos(beta);
    (m * d * d + iy) * der(der(beta)) - 0.5 * a_prime * der(alpha) * der(alpha)
        == -m * g * d * cos(alpha) * sin(beta);
}

#[test]
fn a_cardan_pendulum_follows_its_lagrange_equations_in_the_cardan_angles() {
    let tol = 1e-11;
    let reference = tight::<CardanAngles>(3.0, 1e-13);
    let global = tight::<CardanPendulum>(3.0, tol);
    assert_eq!(global.degrees_of_freedom(), Some(2));
    // Consistent as given: nothing moved.
    assert!(global.initial_corrections().is_empty(), "{:?}", global.initial_corrections());
    assert!(global.max_constraint_residual() <= 1e-12);
    let joint_coordinates = tight::<CardanPendulumInJointCoordinates>(3.0, tol);
    for sol in [&global, &joint_coordinates] {
        let d = 0.5;
        for t in [0.5, 1.5, 3.0] {
            let (x, y, z) = (
                sol.at(t, "rod.x").unwrap(),
                sol.at(t, "rod.y").unwrap(),
                sol.at(t, "rod.z").unwrap(),
            );
            let (alpha, beta) = (y.atan2(-z), (-x / d).asin());
            let (want_alpha, want_beta) =
                (reference.at(t, "alpha").unwrap(), reference.at(t, "beta").unwrap());
            assert!(
                (alpha - want_alpha).abs() <= 1e3 * tol,
                "t = {t}: α {alpha} against {want_alpha}"
            );
            assert!((beta - want_beta).abs() <= 1e3 * tol, "t = {t}: β {beta} against {want_beta}");
        }
        // At every step, the centre at d from the pivot.
        for &t in sol.times() {
            let r: f64 =
                ["rod.x", "rod.y", "rod.z"].iter().map(|n| sol.at(t, n).unwrap().powi(2)).sum();
            assert!((r.sqrt() - d).abs() <= 1e-12, "t = {t}: {}", r.sqrt());
        }
    }
    // In joint coordinates the Cardan angles are the states, from the start:
    // R = R_x(0.8 + q1)·R_y(0.3 + q2).
    for t in [0.5, 1.5, 3.0] {
        let q1 = joint_coordinates.at(t, "cross.q1").unwrap();
        let q2 = joint_coordinates.at(t, "cross.q2").unwrap();
        let (alpha, beta) = (reference.at(t, "alpha").unwrap(), reference.at(t, "beta").unwrap());
        assert!((0.8 + q1 - alpha).abs() <= 1e3 * tol, "t = {t}: q1 {q1}");
        assert!((0.3 + q2 - beta).abs() <= 1e3 * tol, "t = {t}: q2 {q2}");
    }
}

// A body (m = 2, inertias 0.1, 0.2, 0.3) on a cylindrical joint along
// world z, started spinning at 3 rad/s about that axis and moving up at
// 1 m/s: it falls along the axis, z = t − g t²/2, spinning at a constant
// rate, its attitude turning about z by 3t.
in_both_formulations!(spinning_slider, spinning_slider_in_joint_coordinates, {
    let g = param(9.81);
    let ground = ground();
    let body = spatial_body(
        2.0,
        vec3(0.1, 0.2, 0.3),
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, 3.0],
    );
    let sleeve =
        cylindrical(ground, vec3(0.0, 0.0, 0.0), body, vec3(0.0, 0.0, 0.0), vec3(0.0, 0.0, 1.0));
    gravity(vec3(0.0, 0.0, -g));
});

#[test]
fn a_body_on_a_cylindrical_joint_falls_along_its_axis_spinning_freely() {
    let tol = 1e-11;
    let global = tight::<SpinningSlider>(2.0, tol);
    assert_eq!(global.degrees_of_freedom(), Some(2));
    assert!(global.initial_corrections().is_empty(), "{:?}", global.initial_corrections());
    let joint_coordinates = tight::<SpinningSliderInJointCoordinates>(2.0, tol);
    for sol in [&global, &joint_coordinates] {
        for t in [0.5f64, 1.0, 2.0] {
            let z = t - 0.5 * 9.81 * t * t;
            let (half, turn) =
                (1.5 * t, [("body.q0", (1.5 * t).cos()), ("body.q3", (1.5 * t).sin())]);
            assert!((sol.at(t, "body.z").unwrap() - z).abs() <= 1e3 * tol, "t = {t}");
            // The joint's coordinates: the slide along the axis, and the
            // turn about it (compared in (−π, π]: the global formulation
            // reads it from the attitudes, the recursive one integrates it).
            assert!((sol.at(t, "sleeve.q").unwrap() - z).abs() <= 1e3 * tol, "t = {t}");
            let angle = wrap(sol.at(t, "sleeve.angle").unwrap());
            let wrapped = wrap(3.0 * t);
            assert!(
                (angle - wrapped).abs() <= 1e3 * tol,
                "t = {t}: angle {angle} against {wrapped}"
            );
            assert!((sol.at(t, "body.wz").unwrap() - 3.0).abs() <= 1e3 * tol, "t = {t}");
            for (name, want) in turn {
                let got = sol.at(t, name).unwrap();
                assert!(
                    (got - want).abs() <= 1e3 * tol,
                    "t = {t}, half-angle {half}: {name} {got} against {want}"
                );
            }
            for name in ["body.x", "body.y", "body.wx", "body.wy"] {
                assert!(sol.at(t, name).unwrap().abs() <= 1e3 * tol, "t = {t}: {name}");
            }
        }
    }
    // Unwrapped in joint coordinates.
    let angle = joint_coordinates.at(2.0, "sleeve.angle").unwrap();
    assert!((angle - 6.0).abs() <= 1e3 * tol, "{angle}");
}

/// An angle in (−π, π].
fn wrap(angle: f64) -> f64 {
    use std::f64::consts::PI;
    -((PI - angle).rem_euclid(2.0 * PI) - PI)
}

// A puck (m = 0.5, inertias 0.01, 0.01, 0.02) on a planar joint keeping
// it on the ground's plane z = 0, gravity along −x in the plane, started
// at (0, 0, 0) moving at (1, 2, 0) and turning at 2 rad/s about z:
// x = t − g t²/2, y = 2t, z = 0, the attitude turning about z by 2t.
in_both_formulations!(sliding_puck, sliding_puck_in_joint_coordinates, {
    let g = param(9.81);
    let ground = ground();
    let puck = spatial_body(
        0.5,
        vec3(0.01, 0.01, 0.02),
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0, 0.0],
        [1.0, 2.0, 0.0],
        [0.0, 0.0, 2.0],
    );
    planar(ground, vec3(0.0, 0.0, 0.0), puck, vec3(0.0, 0.0, 0.0), vec3(0.0, 0.0, 1.0));
    gravity(vec3(-g, 0.0, 0.0));
});

#[test]
fn a_body_on_a_planar_joint_slides_and_turns_in_its_plane() {
    let tol = 1e-11;
    let global = tight::<SlidingPuck>(2.0, tol);
    assert_eq!(global.degrees_of_freedom(), Some(3));
    assert!(global.initial_corrections().is_empty(), "{:?}", global.initial_corrections());
    let joint_coordinates = tight::<SlidingPuckInJointCoordinates>(2.0, tol);
    for sol in [&global, &joint_coordinates] {
        for t in [0.5f64, 1.0, 2.0] {
            let want = [
                ("puck.x", t - 0.5 * 9.81 * t * t),
                ("puck.y", 2.0 * t),
                ("puck.z", 0.0),
                ("puck.wz", 2.0),
                ("puck.q0", t.cos()),
                ("puck.q3", t.sin()),
                ("puck.q1", 0.0),
                ("puck.q2", 0.0),
            ];
            for (name, value) in want {
                let got = sol.at(t, name).unwrap();
                assert!((got - value).abs() <= 1e3 * tol, "t = {t}: {name} {got} against {value}");
            }
        }
    }
    // Its coordinates: slides along the plane's two directions (n × e_x = e_y
    // for the axis e_x least aligned with n, then n × e_y = −e_x), and the turn.
    for t in [0.5f64, 1.0, 2.0] {
        let want = [
            ("planar1.u", 2.0 * t),
            ("planar1.v", 0.5 * 9.81 * t * t - t),
            ("planar1.angle", 2.0 * t),
        ];
        for (name, value) in want {
            let got = joint_coordinates.at(t, name).unwrap();
            assert!((got - value).abs() <= 1e3 * tol, "t = {t}: {name} {got} against {value}");
        }
    }
}
