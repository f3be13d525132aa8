//! Joint coordinates for spatial scenes (joint coordinates, mass
//! matrix by the composite-rigid-body algorithm, bias forces by recursive
//! Newton–Euler) against body coordinates of the same scenes.

use daegen::prelude::*;

mod support;
use support::{assert_agree, tight};

include!("models/both_formulations.rs");

include!("models/spatial_chains.rs");

spatial_double_pendulum!(double_pendulum_global,);
spatial_double_pendulum!(double_pendulum_recursive, scene = recursive);

rssr_loop!(rssr_global,);
rssr_loop!(rssr_recursive, scene = recursive);
// Body coordinates written out: the 7 MB of code a default scene refuses.
seven_joint_arm!(arm_global, scene = global);
seven_joint_arm!(arm_recursive, scene = recursive);

/// Asserts that every name both solutions answer to agrees within `bound`
/// at `times`; returns how many there were.
fn same_values_by_name(a: &Solution, b: &Solution, times: &[f64], bound: f64) -> usize {
    let shared: Vec<&str> = a.names().into_iter().filter(|n| b.names().contains(n)).collect();
    assert_agree(a, b, &shared, times, bound);
    shared.len()
}

/// A body of a solution: its name, mass and principal inertias.
type Body<'a> = (&'a str, f64, [f64; 3]);

/// R(q) v, body to world.
fn turn(q: [f64; 4], v: [f64; 3]) -> [f64; 3] {
    let [w, x, y, z] = q;
    let r = [
        [w * w + x * x - y * y - z * z, 2.0 * (x * y - w * z), 2.0 * (x * z + w * y)],
        [2.0 * (x * y + w * z), w * w - x * x + y * y - z * z, 2.0 * (y * z - w * x)],
        [2.0 * (x * z - w * y), 2.0 * (y * z + w * x), w * w - x * x - y * y + z * z],
    ];
    [0, 1, 2].map(|i| r[i][0] * v[0] + r[i][1] * v[1] + r[i][2] * v[2])
}

/// A body's centre, velocity, attitude and body rates at `t`, by name.
fn body_state(sol: &Solution, t: f64, name: &str) -> ([f64; 3], [f64; 3], [f64; 4], [f64; 3]) {
    let read = |c: &str| sol.at(t, &format!("{name}.{c}")).unwrap();
    let rate = |c: &str| sol.at(t, &format!("der({name}.{c})")).unwrap();
    (
        ["x", "y", "z"].map(read),
        ["x", "y", "z"].map(rate),
        ["q0", "q1", "q2", "q3"].map(read),
        ["wx", "wy", "wz"].map(read),
    )
}

/// Kinetic plus potential energy of `bodies` in the gravity `g`.
fn energy(sol: &Solution, t: f64, bodies: &[Body], g: [f64; 3]) -> f64 {
    let mut e = 0.0;
    for &(name, m, j) in bodies {
        let (c, v, _, w) = body_state(sol, t, name);
        e += 0.5 * m * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        e += 0.5 * (j[0] * w[0] * w[0] + j[1] * w[1] * w[1] + j[2] * w[2] * w[2]);
        e -= m * (g[0] * c[0] + g[1] * c[1] + g[2] * c[2]);
    }
    e
}

/// Linear momentum and angular momentum about the origin of `bodies`.
fn momenta(sol: &Solution, t: f64, bodies: &[Body]) -> [f64; 6] {
    let mut out = [0.0; 6];
    for &(name, m, j) in bodies {
        let (c, v, q, w) = body_state(sol, t, name);
        let spin = turn(q, [j[0] * w[0], j[1] * w[1], j[2] * w[2]]);
        let p = v.map(|x| m * x);
        let orbit =
            [c[1] * p[2] - c[2] * p[1], c[2] * p[0] - c[0] * p[2], c[0] * p[1] - c[1] * p[0]];
        for k in 0..3 {
            out[k] += p[k];
            out[3 + k] += orbit[k] + spin[k];
        }
    }
    out
}

#[test]
fn the_spatial_double_pendulum_matches_the_global_formulation() {
    let tol = 1e-10;
    let global = tight::<DoublePendulumGlobal>(2.0, tol);
    let recursive = tight::<DoublePendulumRecursive>(2.0, tol);
    // Two spherical joints: a relative quaternion and three rates each.
    assert!(recursive.names().contains(&"elbow.q0") && recursive.names().contains(&"elbow.wz"));
    assert_eq!(recursive.degrees_of_freedom(), Some(6));
    assert_eq!(global.degrees_of_freedom(), Some(6));
    let times = [0.0, 0.5, 1.0, 1.5, 2.0];
    // Both bodies' 10 coordinates and 3 velocities, both joints' relative
    // quaternions and rates, and the tip.
    assert_eq!(same_values_by_name(&global, &recursive, &times, 1e-7), 2 * 13 + 2 * 7 + 3);
}

#[test]
fn the_spatial_double_pendulum_in_joint_coordinates_keeps_its_energy() {
    let tol = 1e-12;
    let sol = tight::<DoublePendulumRecursive>(10.0, tol);
    let bodies = [("upper", 1.0, [0.1, 0.1, 0.02]), ("lower", 1.0, [0.1, 0.1, 0.02])];
    let g = [0.0, 0.0, -9.81];
    let e0 = energy(&sol, 0.0, &bodies, g);
    let drift =
        sol.times().iter().map(|&t| (energy(&sol, t, &bodies, g) - e0).abs()).fold(0.0, f64::max);
    // A run at tol keeps its relative error within about tol per unit time:
    // 100·tol of the energy's scale (15 J) over these 10 s.
    assert!(drift <= 1e2 * tol * e0.abs().max(1.0), "drift {drift:e} of {e0}");
    // Each joint's quaternion stays a unit one.
    for &t in sol.times() {
        for joint in ["shoulder", "elbow"] {
            let n: f64 = ["q0", "q1", "q2", "q3"]
                .iter()
                .map(|c| sol.at(t, &format!("{joint}.{c}")).unwrap().powi(2))
                .sum();
            assert!((n - 1.0).abs() <= 1e-12, "t = {t}: |{joint}| = {n}");
        }
    }
}

#[test]
fn the_spatial_four_bar_loop_matches_the_global_formulation() {
    let tol = 1e-10;
    let global = tight::<RssrGlobal>(2.0, tol);
    let recursive = tight::<RssrRecursive>(2.0, tol);
    // The loop's degree of freedom and the coupler's spin about its axis.
    assert_eq!(global.degrees_of_freedom(), Some(2));
    assert_eq!(recursive.degrees_of_freedom(), Some(2));
    // The cut joint holds at every step.
    assert!(
        recursive.max_constraint_residual() <= 1e-10,
        "{}",
        recursive.max_constraint_residual()
    );
    let times = [0.0, 0.5, 1.0, 1.5, 2.0];
    // Three bodies' coordinates and velocities, the two revolute joints'
    // angles and their rates, the two spherical joints' relative
    // quaternions and rates (the cut one's from the bodies' in both), the
    // cut joint's three multipliers and the two outputs.
    let shared = same_values_by_name(&global, &recursive, &times, 1e-7);
    assert_eq!(shared, 3 * 13 + 2 * 2 + 2 * 7 + 3 + 2, "{:?}", recursive.names());
}

#[test]
fn the_seven_joint_arm_matches_the_global_formulation() {
    let tol = 1e-10;
    let global = tight::<ArmGlobal>(1.0, tol);
    let recursive = tight::<ArmRecursive>(1.0, tol);
    // An ODE in its seven joint angles and their rates, against 91
    // coordinates, their 21 velocities and 35 multipliers.
    assert_eq!(<ArmRecursive as Model>::INDEX, 0);
    assert_eq!(ArmRecursive::INFO.states.len(), 14);
    let times = [0.0, 0.25, 0.5, 0.75, 1.0];
    let joints = ["j1.q", "j2.q", "j3.q", "j4.q", "j5.q", "j6.q", "j7.q"];
    let shared: Vec<&str> = global
        .names()
        .into_iter()
        .filter(|n| recursive.names().contains(n) && !joints.contains(n))
        .collect();
    // The bodies' coordinates and velocities, the joints' rates and the
    // hand.
    assert_eq!(shared.len(), 7 * 13 + 7 + 3);
    assert_agree(&global, &recursive, &shared, &times, 1e-7);
    // The joint angles: read from the attitudes in (−π, π] in body
    // coordinates, integrated (unwrapped) in joint coordinates.
    use std::f64::consts::PI;
    for joint in joints {
        for t in times {
            let (a, b) = (global.at(t, joint).unwrap(), recursive.at(t, joint).unwrap());
            let d = (a - b + PI).rem_euclid(2.0 * PI) - PI;
            assert!(d.abs() <= 1e-7, "t = {t}: {joint} {a} against {b}");
        }
    }
    // The arm falls far: the hand is more than a metre from where it started.
    let moved = (recursive.at(1.0, "hand_x").unwrap() - 2.1).abs();
    assert!(moved > 1.0, "{moved}");
}

in_both_formulations!(tumbling_pair, tumbling_pair_in_joint_coordinates, {
    // Two bodies joined by a spherical joint, floating without gravity:
    // in joint coordinates the first hangs from nothing (a free
    // joint), the second from it. A consistent start: the joint point
    // moves at v1 + ω1 × (0.5, 0, 0) = v2 + ω2 × (−0.5, 0, 0) = (0.1, 0.5, 0).
    // Nothing holds it to the ground.
    let ground = ground();
    let first = spatial_body(
        1.0,
        vec3(0.1, 0.2, 0.3),
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0, 0.0],
        [0.1, 0.0, 0.0],
        [0.0, 0.0, 1.0],
    );
    let second = spatial_body(
        2.0,
        vec3(0.3, 0.1, 0.2),
        [1.0, 0.0, 0.0],
        [1.0, 0.0, 0.0, 0.0],
        [0.1, 0.5, 0.0],
        [1.0, 0.0, 0.0],
    );
    let ball = spherical(first, vec3(0.5, 0.0, 0.0), second, vec3(-0.5, 0.0, 0.0));
});

#[test]
fn a_free_floating_pair_keeps_its_momenta_and_energy() {
    let tol = 1e-11;
    let sol = tight::<TumblingPairInJointCoordinates>(5.0, tol);
    // The first body keeps its own coordinates (a free joint).
    assert!(sol.names().contains(&"first.q0") && sol.names().contains(&"ball.wx"));
    let bodies = [("first", 1.0, [0.1, 0.2, 0.3]), ("second", 2.0, [0.3, 0.1, 0.2])];
    // Exact at the start: p = (0.3, 1, 0), and L about the origin is the
    // spins plus c2 × m2 v2 = (0, 0, 1).
    let start = momenta(&sol, 0.0, &bodies);
    let want = [0.3, 1.0, 0.0, 0.3, 0.0, 0.3 + 1.0];
    for k in 0..6 {
        assert!((start[k] - want[k]).abs() <= 1e-14, "{start:?}");
    }
    let e0 = energy(&sol, 0.0, &bodies, [0.0; 3]);
    for &t in sol.times() {
        let m = momenta(&sol, t, &bodies);
        for k in 0..6 {
            assert!((m[k] - want[k]).abs() <= 1e2 * tol, "t = {t}: {m:?}");
        }
        let e = energy(&sol, t, &bodies, [0.0; 3]);
        assert!((e - e0).abs() <= 1e2 * tol, "t = {t}: energy {e} against {e0}");
    }
    let global = tight::<TumblingPair>(5.0, tol);
    let times = [0.0, 1.0, 2.5, 5.0];
    // Both bodies' coordinates and velocities, and the joint's relative
    // quaternion and rates.
    assert_eq!(same_values_by_name(&global, &sol, &times, 1e-7), 2 * 13 + 7);
}

#[test]
fn every_method_runs_the_spatial_scenes_in_joint_coordinates() {
    // A 7 × 7 mass matrix solved at run time (the arm), two spherical
    // joints' quaternions (the pendulum), and a cut joint (the loop).
    let arm = tight::<ArmRecursive>(1.0, 1e-13);
    let pendulum = tight::<DoublePendulumRecursive>(2.0, 1e-13);
    let four_bar = tight::<RssrRecursive>(2.0, 1e-13);
    let tol = 1e-8;
    for method in [
        Method::Dopri5,
        Method::Dop853,
        Method::Radau5,
        Method::Rodas5P,
        Method::Taylor,
        Method::Auto,
    ] {
        let options = Options::new().method(method).tolerance(tol);
        let at = |sol: &Solution, reference: &Solution, names: &[&str], t: f64| {
            for name in names {
                let (got, want) = (sol.at(t, name).unwrap(), reference.at(t, name).unwrap());
                assert!(
                    (got - want).abs() <= 1e2 * tol,
                    "{method:?}, {name}: {got} against {want}"
                );
            }
        };
        let sol = ArmRecursive::default().simulate(0.0, 1.0, &options).unwrap();
        at(&sol, &arm, &["hand_x", "hand_y", "hand_z"], 1.0);
        let sol = DoublePendulumRecursive::default().simulate(0.0, 2.0, &options).unwrap();
        at(&sol, &pendulum, &["tip_x", "tip_y", "tip_z"], 2.0);
        let sol = RssrRecursive::default().simulate(0.0, 2.0, &options).unwrap();
        at(&sol, &four_bar, &["tip_y", "tip_z"], 2.0);
    }
    // Taylor at a tight tolerance.
    let tol = 1e-12;
    let taylor = Options::new().method(Method::Taylor).tolerance(tol);
    let sol = ArmRecursive::default().simulate(0.0, 1.0, &taylor).unwrap();
    assert_agree(&sol, &arm, &["hand_x", "hand_y", "hand_z"], &[0.5, 1.0], 1e2 * tol);
    let sol = DoublePendulumRecursive::default().simulate(0.0, 1.0, &taylor).unwrap();
    assert_agree(&sol, &pendulum, &["tip_x", "tip_y", "tip_z"], &[0.5, 1.0], 1e2 * tol);
}

in_both_formulations!(written_backwards, written_backwards_in_joint_coordinates, {
    // A block on a slide and a pendulum hung from it, both joints named
    // child first: the tree reaches each joint from its second frame. The
    // slide's axis (1, 0, 0.5) is in the block's axes, the hinge's (0, 1, 0)
    // in the bob's; the bob starts swinging at 1 rad/s, the block at rest
    // relative to its slide: the bob's centre moves at (0, 1, 0) × (0, 0, −0.5).
    let g = param(9.81);
    let ground = ground();
    let block = spatial_body(2.0, vec3(0.02, 0.03, 0.04), [0.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0]);
    let bob = spatial_body(
        1.0,
        vec3(0.01, 0.01, 0.002),
        [0.0, 0.3, -0.5],
        [1.0, 0.0, 0.0, 0.0],
        [-0.5, 0.0, 0.0],
        [0.0, 1.0, 0.0],
    );
    let slide =
        prismatic(block, vec3(0.0, 0.0, 0.0), ground, vec3(0.0, 0.0, 0.0), vec3(1.0, 0.0, 0.5));
    let hinge = revolute(bob, vec3(0.0, 0.0, 0.5), block, vec3(0.0, 0.3, 0.0), vec3(0.0, 1.0, 0.0));
    gravity(vec3(0.0, 0.0, -g));
});

#[test]
fn joints_the_tree_reaches_from_their_second_frame_match_the_global_formulation() {
    let tol = 1e-10;
    let global = tight::<WrittenBackwards>(2.0, tol);
    let recursive = tight::<WrittenBackwardsInJointCoordinates>(2.0, tol);
    assert!(global.initial_corrections().is_empty(), "{:?}", global.initial_corrections());
    let times = [0.0, 0.5, 1.0, 2.0];
    // Both bodies' coordinates and velocities, and the joints' coordinates
    // and rates.
    assert_eq!(same_values_by_name(&global, &recursive, &times, 1e-7), 2 * 13 + 2 * 2);
}

/// The rod hinged about world x, drawn hanging straight down, started at
/// 0.5 rad and 1 rad/s by its joint coordinate.
#[dae_model(scene = recursive)]
fn hinged_from_its_joint() {
    let g = param(9.81);
    let ground = ground();
    let rod = spatial_body(2.0, vec3(0.1, 0.2, 0.05), [0.0, 0.0, -0.5], [1.0, 0.0, 0.0, 0.0]);
    let hinge =
        revolute(ground, vec3(0.0, 0.0, 0.0), rod, vec3(0.0, 0.0, 0.5), vec3(1.0, 0.0, 0.0));
    gravity(vec3(0.0, 0.0, -g));
    init(hinge.q, 0.5);
    init(der(hinge.q), 1.0);
}

/// The same rod drawn at 0.5 rad, moving at 1 rad/s.
#[dae_model(scene = recursive)]
fn hinged_from_its_pose() {
    let g = param(9.81);
    let ground = ground();
    let rod = spatial_body(
        2.0,
        vec3(0.1, 0.2, 0.05),
        [0.0, 0.5 * sin(0.5), -0.5 * cos(0.5)],
        [cos(0.25), sin(0.25), 0.0, 0.0],
        [0.0, 0.5 * cos(0.5), 0.5 * sin(0.5)],
        [1.0, 0.0, 0.0],
    );
    let hinge =
        revolute(ground, vec3(0.0, 0.0, 0.0), rod, vec3(0.0, 0.0, 0.5), vec3(1.0, 0.0, 0.0));
    gravity(vec3(0.0, 0.0, -g));
}

#[test]
fn a_joint_coordinate_starts_where_init_says() {
    // The joint's zero is the pose drawn; `init` starts it elsewhere. The
    // two rods swing alike: the same body coordinates, the angle offset by
    // the 0.5 rad the second was drawn at.
    let opts = Options::new().method(Method::Dop853).tolerance(1e-12);
    let a = HingedFromItsJoint::default().simulate(0.0, 2.0, &opts).unwrap();
    let b = HingedFromItsPose::default().simulate(0.0, 2.0, &opts).unwrap();
    assert_eq!(a.at(0.0, "hinge.q").unwrap(), 0.5);
    assert_eq!(a.at(0.0, "der(hinge.q)").unwrap(), 1.0);
    for t in [0.3, 1.1, 2.0] {
        let (qa, qb): (f64, f64) = (a.at(t, "hinge.q").unwrap(), b.at(t, "hinge.q").unwrap());
        assert!((qa - (qb + 0.5)).abs() < 1e-10, "t = {t}: {qa} vs {qb} + 0.5");
        for c in ["rod.y", "rod.z", "rod.q0", "rod.q1", "rod.wx"] {
            let (u, v): (f64, f64) = (a.at(t, c).unwrap(), b.at(t, c).unwrap());
            assert!((u - v).abs() < 1e-10, "t = {t}: {c} {u} vs {v}");
        }
    }
}

/// A pendulum arm with a block sliding along it, a spring of the standard
/// library across the slide (on the joint's flange), and with `$damped`
/// a damper beside it.
macro_rules! slider_on_an_arm {
    ($name:ident, [$($attr:tt)*], $($damped:tt)*) => {
        #[dae_model($($attr)*)]
        fn $name() {
            let ground = ground();
            let arm = spatial_body(2.0, vec3(0.1, 0.1, 0.02), [0.0, 0.3, -0.4], [1.0, 0.0, 0.0, 0.0]);
            let block = spatial_body(1.0, vec3(0.01, 0.01, 0.01), [0.0, 0.3, -1.0], [1.0, 0.0, 0.0, 0.0]);
            let hinge = revolute(ground, vec3(0.0, 0.0, 0.0), arm, vec3(0.0, -0.3, 0.4), vec3(1.0, 0.0, 0.0));
            let slide = prismatic(arm, vec3(0.0, 0.0, -0.6), block, vec3(0.0, 0.0, 0.0), vec3(0.0, 0.0, -1.0));
            gravity(vec3(0.0, 0.0, -9.81));
            let spring = translational_spring(c = 40.0, s_rel0 = 0.1);
            let support = translational_fixed();
            connect(support.flange, spring.flange_a);
            connect(spring.flange_b, slide.flange);
            $($damped)*
        }
    };
}

slider_on_an_arm!(slider_arm_global, [],);
slider_on_an_arm!(slider_arm_recursive, [scene = recursive],);
slider_on_an_arm!(damped_slider_arm, [scene = recursive],
    let damper = translational_damper(3.0);
    connect(support.flange, damper.flange_a);
    connect(damper.flange_b, slide.flange);
);

#[test]
fn a_part_across_a_prismatic_joint_between_moving_bodies_acts_on_its_coordinate() {
    // In joint coordinates the flange's displacement is the slide's own
    // coordinate: the spring acts alike in both formulations, and a
    // damper's state is tied to the coordinate, its force d·q̇.
    let opts = Options::new().method(Method::Radau5).tolerance(1e-11);
    let global = SliderArmGlobal::default().simulate(0.0, 2.0, &opts).unwrap();
    let recursive = SliderArmRecursive::default().simulate(0.0, 2.0, &opts).unwrap();
    let names = ["block.x", "block.y", "block.z", "arm.y", "arm.z", "spring.f"];
    assert_agree(&global, &recursive, &names, &[0.5, 1.0, 2.0], 1e-7);
    let damped = DampedSliderArm::default().simulate(0.0, 2.0, &opts).unwrap();
    assert_eq!(
        <DampedSliderArm as Model>::INFO.states.len(),
        4,
        "{:?}",
        <DampedSliderArm as Model>::INFO.states
    );
    for t in [0.5, 1.0, 2.0] {
        let (f, rate): (f64, f64) =
            (damped.at(t, "damper.f").unwrap(), damped.at(t, "der(slide.q)").unwrap());
        assert!((f - 3.0 * rate).abs() <= 1e-12 * (1.0 + f.abs()), "t = {t}: {f} vs 3·{rate}");
    }
}
