//! The universal (Cardan), cylindrical and planar joints of spatial scenes,
//! in body coordinates and in joint coordinates (`scene = recursive`),
//! each against a motion derived by hand: the
//! universal joint's pendulum swings about either cross axis as a compound
//! pendulum, a body on a cylindrical joint falls along its axis spinning
//! freely, and a body on a planar joint slides and turns in its plane.
//! Every joint, spatial and planar, answers to the names the guide
//! documents in both formulations, with the same values.

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
            // turn about it (compared in (−π, π]: body coordinates read it
            // from the attitudes, joint coordinates integrate it).
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

// Every kind of joint between a carrier that spins about the vertical
// (Ω = 0.7 rad/s, on a revolute joint at the origin) and a body hanging
// d = (0, 0, −0.4) below the joint point P = (0.3, 0, 0) of the carrier,
// started with a relative motion in each of the joint's coordinates. The
// body's velocity follows from the joints: v = Ω e_z × P + v_slide + ω_b × d,
// ω_b = Ω e_z + ω_rel (every attitude is the identity at the start).
// `on_a_spinning_carrier!(global, recursive, v, ω_b, joint(axes))`.
macro_rules! on_a_spinning_carrier {
    ($global:ident, $recursive:ident, $v:tt, $w:tt, $joint:ident($($axes:tt)*)) => {
        on_a_spinning_carrier!(@one $global, (taylor = 0), $v, $w, $joint($($axes)*));
        on_a_spinning_carrier!(@one $recursive, (scene = recursive, taylor = 0), $v, $w, $joint($($axes)*));
    };
    (@one $name:ident, ($($attr:tt)*), $v:tt, $w:tt, $joint:ident($($axes:tt)*)) => {
        #[dae_model($($attr)*)]
        fn $name() {
            let ground = ground();
            let carrier = spatial_body(
                1.0,
                vec3(0.1, 0.12, 0.2),
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0, 0.0],
                [0.0, 0.0, 0.0],
                [0.0, 0.0, 0.7],
            );
            let spin = revolute(ground, vec3(0.0, 0.0, 0.0), carrier, vec3(0.0, 0.0, 0.0), vec3(0.0, 0.0, 1.0));
            let body = spatial_body(0.5, vec3(0.02, 0.03, 0.01), [0.3, 0.0, -0.4], [1.0, 0.0, 0.0, 0.0], $v, $w);
            let joint = $joint(carrier, vec3(0.3, 0.0, 0.0), body, vec3(0.0, 0.0, 0.4) $($axes)*);
            gravity(vec3(0.0, 0.0, -9.81));
        }
    };
}

// ω_rel = (1.2, 0, 0): ω_b × d = (0, 0.48, 0).
on_a_spinning_carrier!(revolute_global, revolute_recursive, [0.0, 0.69, 0.0], [1.2, 0.0, 0.7],
    revolute(, vec3(1.0, 0.0, 0.0)));
// A slide of 0.5 m/s along x.
on_a_spinning_carrier!(prismatic_global, prismatic_recursive, [0.5, 0.21, 0.0], [0.0, 0.0, 0.7],
    prismatic(, vec3(1.0, 0.0, 0.0)));
// Both.
on_a_spinning_carrier!(cylindrical_global, cylindrical_recursive, [0.5, 0.69, 0.0], [1.2, 0.0, 0.7],
    cylindrical(, vec3(1.0, 0.0, 0.0)));
// ω_rel = (1.2, −0.4, 0): ω_b × d = (0.16, 0.48, 0).
on_a_spinning_carrier!(universal_global, universal_recursive, [0.16, 0.69, 0.0], [1.2, -0.4, 0.7],
    universal(, vec3(1.0, 0.0, 0.0), vec3(0.0, 1.0, 0.0)));
// Slides of (0.5, −0.3) in the carrier's xy-plane, ω_rel = (0, 0, 1.5).
on_a_spinning_carrier!(planar_global, planar_recursive, [0.5, -0.09, 0.0], [0.0, 0.0, 2.2],
    planar(, vec3(0.0, 0.0, 1.0)));
// ω_rel = (1, −0.5, 0.3): ω_b × d = (0.2, 0.4, 0).
on_a_spinning_carrier!(
    spherical_global,
    spherical_recursive,
    [0.2, 0.61, 0.0],
    [1.0, -0.5, 1.0],
    spherical()
);

// In the plane: an arm hinged at the origin, started at 1 rad/s, a block
// sliding along it at 0.5 m/s from 0.8 m out (its velocity
// (0.5, 0.8) = slide + ω × r).
in_both_formulations!(arm_and_block_global, arm_and_block_recursive, {
    let ground = ground();
    let arm = body(1.0, 1.0 / 12.0, [0.5, 0.0, 0.0], [0.0, 0.5, 1.0]);
    let block = body(0.5, 0.01, [0.8, 0.0, 0.0], [0.5, 0.8, 1.0]);
    let pin = revolute(ground, vec3(0.0, 0.0, 0.0), arm, vec3(-0.5, 0.0, 0.0));
    let joint =
        prismatic(arm, vec3(0.3, 0.0, 0.0), block, vec3(0.0, 0.0, 0.0), vec3(1.0, 0.0, 0.0));
    gravity(vec3(0.0, -9.81, 0.0));
});

#[test]
fn every_planar_joint_answers_to_its_documented_names_in_both_formulations() {
    let global = tight::<ArmAndBlockGlobal>(1.0, 1e-11);
    let recursive = tight::<ArmAndBlockRecursive>(1.0, 1e-11);
    let mut names = Vec::new();
    for joint in ["pin", "joint"] {
        names.extend([format!("{joint}.q"), format!("der({joint}.q)")]);
    }
    for body in ["arm", "block"] {
        for c in ["x", "y", "theta"] {
            names.extend([format!("{body}.{c}"), format!("der({body}.{c})")]);
        }
    }
    assert_same_by_name("a planar scene", &global, &recursive, &names, &[0.0, 0.5, 1.0], |_| false);
}

/// Asserts that every one of `names` reads in both solutions of `scene`
/// and has the same value at `times`, `wraps(name)` telling the angles
/// body coordinates read in (−π, π].
fn assert_same_by_name(
    scene: &str,
    global: &Solution,
    recursive: &Solution,
    names: &[String],
    times: &[f64],
    wraps: impl Fn(&str) -> bool,
) {
    for name in names {
        for &t in times {
            let (a, b) = match (global.at(t, name), recursive.at(t, name)) {
                (Ok(a), Ok(b)) => (a, b),
                (a, b) => panic!("{scene}: `{name}` at {t}: {a:?} in body coordinates, {b:?} in joint coordinates"),
            };
            let mut gap = a - b;
            if wraps(name) {
                gap -= (gap / std::f64::consts::TAU).round() * std::f64::consts::TAU;
            }
            assert!(
                gap.abs() < 1e-8 * (1.0 + b.abs()),
                "{scene}: `{name}` at {t}: {a} in body coordinates, {b} in joint coordinates"
            );
        }
    }
}

/// The names the guide documents for a spatial joint of `kind` named
/// `joint`, with the rates of those that are second-order.
fn documented_joint_names(kind: &str, joint: &str) -> Vec<String> {
    let (coordinates, rates): (&[&str], bool) = match kind {
        "revolute" | "prismatic" => (&["q"], true),
        "cylindrical" => (&["q", "angle"], true),
        "universal" => (&["q1", "q2"], true),
        "planar" => (&["u", "v", "angle"], true),
        _ => (&["q0", "q1", "q2", "q3", "wx", "wy", "wz"], false),
    };
    let mut names: Vec<String> = coordinates.iter().map(|c| format!("{joint}.{c}")).collect();
    if rates {
        names.extend(coordinates.iter().map(|c| format!("der({joint}.{c})")));
    }
    names
}

/// A spatial body's documented names.
fn documented_body_names(body: &str) -> Vec<String> {
    let mut names = Vec::new();
    for c in ["x", "y", "z"] {
        names.push(format!("{body}.{c}"));
        names.push(format!("der({body}.{c})"));
    }
    for c in ["q0", "q1", "q2", "q3", "wx", "wy", "wz"] {
        names.push(format!("{body}.{c}"));
    }
    names
}

#[test]
fn every_joint_answers_to_its_documented_names_in_both_formulations() {
    fn both<G: Simulate + Default, R: Simulate + Default>() -> (Solution, Solution) {
        (tight::<G>(1.5, 1e-11), tight::<R>(1.5, 1e-11))
    }
    let scenes = [
        ("revolute", both::<RevoluteGlobal, RevoluteRecursive>()),
        ("prismatic", both::<PrismaticGlobal, PrismaticRecursive>()),
        ("cylindrical", both::<CylindricalGlobal, CylindricalRecursive>()),
        ("universal", both::<UniversalGlobal, UniversalRecursive>()),
        ("planar", both::<PlanarGlobal, PlanarRecursive>()),
        ("spherical", both::<SphericalGlobal, SphericalRecursive>()),
    ];
    for (kind, (global, recursive)) in &scenes {
        let mut names = documented_joint_names(kind, "joint");
        names.extend(documented_joint_names("revolute", "spin"));
        names.extend(documented_body_names("carrier"));
        names.extend(documented_body_names("body"));
        // Body coordinates read a joint's angles in (−π, π].
        let wraps = |name: &str| {
            !name.starts_with("der(")
                && (name.ends_with(".angle")
                    || (name.ends_with(".q1") || name.ends_with(".q2")) && *kind == "universal"
                    || name == "spin.q"
                    || name == "joint.q" && *kind == "revolute")
        };
        assert_same_by_name(kind, global, recursive, &names, &[0.0, 0.5, 1.0, 1.5], wraps);
        for name in &names {
            // Every coordinate moves, so the comparison is not of zeros.
            let span = (global.at(1.5, name).unwrap() - global.at(0.0, name).unwrap()).abs();
            if name.starts_with("joint.") && !name.starts_with("joint.q0") {
                assert!(span > 1e-3, "{kind}: `{name}` barely moves ({span:e})");
            }
        }
    }
}
