//! Planar multibody scenes (course notes §4.2, body coordinates): bodies
//! with (x, y, θ) of their centres, joints as constraints with their
//! reactions as algebraic variables, the Newton–Euler equations written by
//! the macro. Checked against hand-written models and minimal-coordinate
//! ODEs.

use daegen::prelude::*;

mod support;
use support::{assert_agree, tight};

include!("models/slider_crank.rs");

include!("models/slider_crank_scene.rs");

#[test]
fn a_slider_crank_scene_matches_the_hand_written_model() {
    assert_eq!(<SliderCrankScene as Model>::INDEX, 3);
    let tol = 1e-10;
    let scene = tight::<SliderCrankScene>(2.0, tol);
    let hand = tight::<SliderCrank>(2.0, tol);
    assert_eq!(scene.degrees_of_freedom(), Some(1));
    for t in [0.0, 0.5, 1.0, 2.0] {
        let (a, b) = (scene.at(t, "crank.theta").unwrap(), hand.at(t, "theta1").unwrap());
        assert!((a - b).abs() <= 100.0 * tol, "t = {t}: scene θ {a}, hand-written {b}");
        let (a, b) = (scene.at(t, "slider.x").unwrap(), hand.at(t, "xs").unwrap());
        assert!((a - b).abs() <= 100.0 * tol, "t = {t}: scene xs {a}, hand-written {b}");
    }
    // The reactions are named: the pivot carries the crank's weight on average.
    assert!(scene.last("pivot[1]").unwrap().is_finite());
    let theta = scene.last("crank.theta").unwrap();
    assert!((scene.last("pin_x").unwrap() - 0.15 * theta.cos()).abs() <= 1e-12);
    assert!(scene.max_constraint_residual() <= 1e-12);
}

/// A four-bar linkage: ground pivots 3 apart, crank 1, coupler 3, rocker 2.5,
/// uniform rods swinging under gravity; one loop, one degree of freedom.
/// Started at the crank angle π/3 with the loop closed exactly (the coupler
/// and rocker poses from the circle intersection), so every formulation
/// starts from the same configuration.
macro_rules! four_bar_model {
    ($name:ident, $($attr:tt)*) => {
        #[dae_model($($attr)*)]
        fn $name() {
            let g = param(9.81);
            let ground = ground();
            let crank = body(
                1.0,
                1.0 / 12.0,
                [0.25, 0.4330127018922193, 1.0471975511965976],
            );
            let coupler = body(
                3.0,
                27.0 / 12.0,
                [1.758003825218467, 1.6829870771423172, 0.5759611339397936],
            );
            let rocker = body(
                2.5,
                2.5 * 6.25 / 12.0,
                [3.0080038252184673, 1.2499743752500978, 1.5643932228659467],
            );
            revolute(ground, vec3(0.0, 0.0, 0.0), crank, vec3(-0.5, 0.0, 0.0));
            revolute(crank, vec3(0.5, 0.0, 0.0), coupler, vec3(-1.5, 0.0, 0.0));
            revolute(coupler, vec3(1.5, 0.0, 0.0), rocker, vec3(1.25, 0.0, 0.0));
            revolute(ground, vec3(3.0, 0.0, 0.0), rocker, vec3(-1.25, 0.0, 0.0));
            gravity(vec3(0.0, -g, 0.0));
            let pin = position(crank, vec3(0.5, 0.0, 0.0));
            let crank_angle = output(atan2(pin[1], pin[0]));
        }
    };
}
four_bar_model!(four_bar, scene = global);

#[test]
fn a_four_bar_linkage_has_one_degree_of_freedom_and_keeps_its_energy() {
    let tol = 1e-10;
    let sol = tight::<FourBar>(3.0, tol);
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
        assert!((energy(t) - e0).abs() <= 1e-7 * e0.abs(), "t = {t}: {} vs {e0}", energy(t));
    }
    // It moves: the crank turns.
    assert!((sol.last("crank.theta").unwrap() - sol.at(0.0, "crank.theta").unwrap()).abs() > 0.1);
}

/// A double pendulum of two uniform rods (mass 1, length 1) released
/// horizontal, as a scene; each rod's body x axis points from its upper
/// hinge down the rod, so its angle is θ − π/2 for θ from the vertical.
/// `double_rod_model!(name, (attributes) { statements })` adds
/// `statements` (loads, outputs) to it.
macro_rules! double_rod_model {
    ($name:ident, ($($attr:tt)*) { $($statements:tt)* }) => {
        #[dae_model($($attr)*)]
        fn $name() {
            let g = param(9.81);
            let ground = ground();
            let upper = body(1.0, 1.0 / 12.0, [0.5, 0.0, 0.0]);
            let lower = body(1.0, 1.0 / 12.0, [1.5, 0.0, 0.0]);
            revolute(ground, vec3(0.0, 0.0, 0.0), upper, vec3(-0.5, 0.0, 0.0));
            revolute(upper, vec3(0.5, 0.0, 0.0), lower, vec3(-0.5, 0.0, 0.0));
            gravity(vec3(0.0, -g, 0.0));
            $($statements)*
        }
    };
    ($name:ident, $($attr:tt)*) => {
        double_rod_model!($name, ($($attr)*) {
            let upper_angle = output(position(upper, vec3(0.5, 0.0, 0.0))[0]);
        });
    };
}
double_rod_model!(double_rod_scene, scene = global);

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
    let sol = tight::<DoubleRodScene>(2.0, tol);
    let reference = tight::<DoubleRodAngles>(2.0, 1e-13);
    assert_eq!(sol.degrees_of_freedom(), Some(2));
    let half_pi = std::f64::consts::FRAC_PI_2;
    for t in [0.5, 1.0, 2.0] {
        for (body, angle) in [("upper", "a"), ("lower", "b")] {
            let got = sol.at(t, &format!("{body}.theta")).unwrap() + half_pi;
            let want = reference.at(t, angle).unwrap();
            assert!((got - want).abs() <= 1000.0 * tol, "t = {t}: {body} {got} vs {want}");
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
    spring(ground, vec3(0.0, 0.0, 0.0), block, vec3(0.0, 0.0, 0.0), 40.0, 1.0, 2.0);
    gravity(vec3(0.0, -g, 0.0));
}

#[test]
fn a_spring_damper_in_a_scene_gives_the_damped_oscillation() {
    assert_eq!(<HangingBlock as Model>::INDEX, 0);
    let tol = 1e-11;
    let sol = HangingBlock::default()
        .simulate(0.0, 3.0, &Options::new().method(Method::Dop853).tolerance(tol))
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
        assert!((got - want).abs() <= 100.0 * tol, "t = {t}: {got} vs {want}");
        assert!(sol.at(t, "block.x").unwrap().abs() <= 1e-15);
    }
}

include!("models/rod_chain.rs");
rod_chain_model!(ten_rod_chain, scene = global);
rod_chain_model!(ten_rod_chain_recursive, scene = recursive);

#[test]
fn a_ten_rod_chain_keeps_its_constraints_and_energy() {
    let sol = tight::<TenRodChain>(1.0, 1e-9);
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

// The same scenes in joint coordinates (relative joint coordinates).

// The double rod scene, recursive: two joint angles, no constraint.
double_rod_model!(double_rod_recursive, scene = recursive);

#[test]
fn the_recursive_double_rod_is_an_ode_in_its_joint_angles() {
    assert_eq!(<DoubleRodRecursive as Model>::INDEX, 0);
    assert_eq!(DoubleRodRecursive::INFO.states.len(), 4);
    let tol = 1e-11;
    let sol = tight::<DoubleRodRecursive>(2.0, tol);
    let reference = tight::<DoubleRodAngles>(2.0, 1e-13);
    for t in [0.5, 1.0, 2.0] {
        // θ_upper − π/2 is the first joint angle; the second is relative.
        let (q1, q2) = (sol.at(t, "revolute1.q").unwrap(), sol.at(t, "revolute2.q").unwrap());
        let (a, b) = (reference.at(t, "a").unwrap(), reference.at(t, "b").unwrap());
        let half_pi = std::f64::consts::FRAC_PI_2;
        assert!((q1 + half_pi - a).abs() <= 1000.0 * tol, "t = {t}: {q1} vs {a}");
        assert!((q1 + q2 + half_pi - b).abs() <= 1000.0 * tol, "t = {t}: {} vs {b}", q1 + q2);
        // Outputs read body coordinates, rewritten in joint angles.
        assert!((sol.at(t, "upper_angle").unwrap() - a.sin()).abs() <= 1000.0 * tol);
    }
}

// The four-bar, recursive: three joint angles on the tree, the fourth joint
// cut (two constraint rows).
four_bar_model!(four_bar_recursive, scene = recursive);

#[test]
fn the_recursive_four_bar_matches_the_global_one() {
    assert_eq!(<FourBarRecursive as Model>::INDEX, 3);
    let tol = 1e-10;
    let recursive = tight::<FourBarRecursive>(3.0, tol);
    let global = tight::<FourBar>(3.0, tol);
    assert_eq!(recursive.degrees_of_freedom(), Some(1));
    for t in [0.0, 1.0, 2.0, 3.0] {
        // The crank turns over: compare the angles modulo 2π.
        let a = recursive.at(t, "crank_angle").unwrap();
        let b = global.at(t, "crank.theta").unwrap();
        let d = (a - b).rem_euclid(std::f64::consts::TAU);
        let d = d.min(std::f64::consts::TAU - d);
        assert!(d <= 1000.0 * tol, "t = {t}: recursive {a}, global {b}");
    }
}

// The slider-crank in body and in joint coordinates from the same exact
// start (θ = 1): in joint coordinates the crank angle and the slide are
// the states and the massless rod is the cut joint.
macro_rules! slider_crank_from_rest {
    ($name:ident, $($attr:tt)*) => {
        slider_crank_scene!($name, ($($attr)*),
            crank: ([0.04052267294011048, 0.06311032386059223, 1.0]),
            slider: ([0.4606087109312288, 0.0, 0.0]),
            { let slider_x = output(position(slider, vec3(0.0, 0.0, 0.0))[0]); });
    };
}
slider_crank_from_rest!(slider_crank_global, scene = global);
slider_crank_from_rest!(slider_crank_recursive, scene = recursive);

#[test]
fn the_slider_crank_agrees_in_both_formulations() {
    // Recursive: two joint coordinates, one cut row; global: six, five rows.
    assert_eq!(SliderCrankRecursive::INFO.states.len(), 4);
    assert_eq!(SliderCrankGlobal::INFO.states.len(), 12);
    let tol = 1e-10;
    let a = tight::<SliderCrankRecursive>(2.0, tol);
    let b = tight::<SliderCrankGlobal>(2.0, tol);
    assert_agree(&a, &b, &["slider_x"], &[0.0, 0.5, 1.0, 2.0], 100.0 * tol);
    assert_eq!(a.degrees_of_freedom(), Some(1));
}

#[test]
fn the_ten_rod_chain_agrees_in_both_formulations() {
    assert_eq!(TenRodChainRecursive::INFO.states.len(), 20);
    let a = tight::<TenRodChain>(0.5, 1e-10);
    let b = tight::<TenRodChainRecursive>(0.5, 1e-10);
    assert_agree(&a, &b, &["tip_x", "tip_y"], &[0.1, 0.25, 0.5], 1e-6);
}

/// Loads in both formulations: the double rod pulled by a spring–damper
/// from a wall point to the lower rod's tip, and a torque on the upper rod.
macro_rules! sprung_double_rod {
    ($name:ident, $($attr:tt)*) => {
        double_rod_model!($name, ($($attr)*) {
            spring(ground, vec3(2.5, -1.0, 0.0), lower, vec3(0.5, 0.0, 0.0), 30.0, 0.5, 0.8);
            torque(upper, 0.7);
            let tip = position(lower, vec3(0.5, 0.0, 0.0));
            let tip_x = output(tip[0]);
            let tip_y = output(tip[1]);
        });
    };
}
sprung_double_rod!(sprung_global, scene = global);
sprung_double_rod!(sprung_recursive, scene = recursive);

#[test]
fn springs_and_torques_agree_in_both_formulations() {
    let tol = 1e-10;
    let a = tight::<SprungGlobal>(2.0, tol);
    let b = tight::<SprungRecursive>(2.0, tol);
    assert_agree(&a, &b, &["tip_x", "tip_y"], &[0.5, 1.0, 2.0], 1000.0 * tol);
}

// The slider-crank started moving: the crank at θ = 1 turning at ω = 2,
// its centre and the slider with the velocities that follow (ẋ_s =
// −r ω sin θ − r² ω sin θ cos θ / √(l² − r² sin² θ)). The recursive
// formulation turns them into joint rates.
macro_rules! slider_crank_moving {
    ($name:ident, $($attr:tt)*) => {
        slider_crank_scene!($name, ($($attr)*),
            crank: (
                [0.5 * r * cos(1.0), 0.5 * r * sin(1.0), 1.0],
                [-r * sin(1.0), r * cos(1.0), 2.0]
            ),
            slider: (
                [r * cos(1.0) + sqrt(l * l - r * r * sin(1.0) * sin(1.0)), 0.0, 0.0],
                [
                    -2.0 * r * sin(1.0)
                        - 2.0 * r * r * sin(1.0) * cos(1.0)
                            / sqrt(l * l - r * r * sin(1.0) * sin(1.0)),
                    0.0,
                    0.0,
                ]
            ),
            {
                let slider_x = output(slider.x);
                let crank_rate = output(der(crank.theta));
            });
    };
}
slider_crank_moving!(moving_crank_global, scene = global);
slider_crank_moving!(moving_crank_recursive, scene = recursive);

#[test]
fn initial_body_velocities_become_joint_rates_in_the_recursive_formulation() {
    let tol = 1e-10;
    let a = tight::<MovingCrankRecursive>(1.0, tol);
    let b = tight::<MovingCrankGlobal>(1.0, tol);
    assert!((a.at(0.0, "crank_rate").unwrap() - 2.0).abs() <= 1e-15);
    let times = [0.0, 0.25, 0.5, 1.0];
    assert_agree(&a, &b, &["slider_x", "crank_rate"], &times, 1000.0 * tol);
}

/// A bent pendulum: a second rod welded at 0.5 rad to the first one's end.
/// In joint coordinates the welded rod adds nothing: one angle, two states.
macro_rules! bent_pendulum {
    ($name:ident, $($attr:tt)*) => {
        #[dae_model($($attr)*)]
        fn $name() {
            let g = param(9.81);
            let ground = ground();
            let upper = body(1.0, 1.0 / 12.0, [0.5, 0.0, 0.0]);
            let lower = body(
                0.5,
                0.5 / 12.0,
                [1.0 + 0.5 * cos(0.5), 0.5 * sin(0.5), 0.5],
            );
            revolute(ground, vec3(0.0, 0.0, 0.0), upper, vec3(-0.5, 0.0, 0.0));
            fixed(upper, vec3(0.5, 0.0, 0.0), lower, vec3(-0.5, 0.0, 0.0));
            gravity(vec3(0.0, -g, 0.0));
            let tip = position(lower, vec3(0.5, 0.0, 0.0));
            let tip_x = output(tip[0]);
            let tip_y = output(tip[1]);
        }
    };
}
bent_pendulum!(bent_global, scene = global);
bent_pendulum!(bent_recursive, scene = recursive);

#[test]
fn a_welded_body_adds_no_joint_coordinate_and_both_formulations_agree() {
    assert_eq!(BentRecursive::INFO.states.len(), 2);
    assert_eq!(BentGlobal::INFO.states.len(), 12);
    let tol = 1e-10;
    let a = tight::<BentGlobal>(2.0, tol);
    let b = tight::<BentRecursive>(2.0, tol);
    assert_eq!(a.degrees_of_freedom(), Some(1));
    assert_agree(&a, &b, &["tip_x", "tip_y"], &[0.5, 1.0, 2.0], 1000.0 * tol);
}

/// A pendulum whose hinge names the ground second (`revolute(rod, .., ground,
/// ..)`): joint coordinates reach the joint from its second frame.
macro_rules! hinge_written_backwards {
    ($name:ident, $($attr:tt)*) => {
        #[dae_model($($attr)*)]
        fn $name() {
            let ground = ground();
            let rod = body(1.0, 1.0 / 12.0, [0.5 * cos(-0.3), 0.5 * sin(-0.3), -0.3]);
            let hinge = revolute(rod, vec3(-0.5, 0.0, 0.0), ground, vec3(0.0, 0.0, 0.0));
            gravity(vec3(0.0, -9.81, 0.0));
        }
    };
}
hinge_written_backwards!(backwards_global, scene = global);
hinge_written_backwards!(backwards_recursive, scene = recursive);

/// Every name the two solutions share agrees at `times` within `tol`.
fn same_values_by_name(a: &Solution, b: &Solution, times: &[f64], tol: f64) -> usize {
    let shared: Vec<&str> = a.names().into_iter().filter(|n| b.names().contains(n)).collect();
    assert_agree(a, b, &shared, times, tol);
    shared.len()
}

/// Both formulations answer to the same names: body coordinates add each
/// revolute and prismatic joint's coordinate `joint.q` (θ_b − θ_a, or the
/// slide along the axis) and its rate as outputs, joint coordinates each
/// body's `body.x`, `body.y`, `body.theta` and their rates.
#[test]
fn both_formulations_answer_to_the_same_names() {
    let tol = 1e-10;
    let times = [0.0, 0.5, 1.0, 2.0];

    let global = tight::<SliderCrankGlobal>(2.0, tol);
    let recursive = tight::<SliderCrankRecursive>(2.0, tol);
    let shared = same_values_by_name(&global, &recursive, &times, 1e-7);
    // Six body coordinates and their rates, two joint coordinates and their
    // rates, the rod's multiplier and the output.
    assert_eq!(shared, 12 + 4 + 2, "{:?}", recursive.names());
    // The crank's joint angle is its body angle (the ground does not turn).
    let q = global.column("pivot.q").unwrap();
    assert_eq!(q, global.column("crank.theta").unwrap());

    let global = tight::<FourBar>(2.0, tol);
    let recursive = tight::<FourBarRecursive>(2.0, tol);
    // Three bodies' coordinates and rates, four joints' coordinates and
    // rates (the cut joint's from the body poses), the cut joint's two
    // multipliers and the output.
    assert_eq!(same_values_by_name(&global, &recursive, &times, 1e-6), 18 + 8 + 2 + 1);

    let global = tight::<BackwardsGlobal>(2.0, tol);
    let recursive = tight::<BackwardsRecursive>(2.0, tol);
    assert_eq!(same_values_by_name(&global, &recursive, &times, 1e-7), 6 + 2);
    // θ_ground − θ_rod: the opposite of the rod's angle.
    for t in times {
        let (q, theta) =
            (recursive.at(t, "hinge.q").unwrap(), recursive.at(t, "rod.theta").unwrap());
        assert!((q + theta).abs() <= 1e-12, "t = {t}: {q} {theta}");
    }
}

/// Kinetic plus potential energy of planar bodies `(name, mass, inertia)`
/// under gravity g = 9.81 at time `t`, from their coordinates and rates.
fn energy_of(sol: &Solution, bodies: &[(&str, f64, f64)], t: f64) -> f64 {
    bodies
        .iter()
        .map(|&(b, m, inertia)| {
            let v = |c: &str| sol.at(t, &format!("der({b}.{c})")).unwrap();
            0.5 * m * (v("x").powi(2) + v("y").powi(2))
                + 0.5 * inertia * v("theta").powi(2)
                + m * 9.81 * sol.at(t, &format!("{b}.y")).unwrap()
        })
        .sum()
}

/// Over a thousand Taylor steps at tolerance 1e-15: the largest
/// |E − E(0)| at the steps over the largest |potential energy| on the way
/// (E's scale), the number of steps, and the tape's order.
fn taylor_energy_drift<M: Model + Simulate>(
    model: M,
    t1: f64,
    bodies: &[(&str, f64, f64)],
) -> (f64, usize, usize) {
    let opts = Options::new().method(Method::Taylor).tolerance(1e-15);
    let sol = model.simulate(0.0, t1, &opts).unwrap();
    let e0 = energy_of(&sol, bodies, 0.0);
    let (mut drift, mut scale) = (0.0f64, 0.0f64);
    for &t in sol.times() {
        drift = drift.max((energy_of(&sol, bodies, t) - e0).abs());
        let potential: f64 =
            bodies.iter().map(|&(b, m, _)| m * 9.81 * sol.at(t, &format!("{b}.y")).unwrap()).sum();
        scale = scale.max(potential.abs());
    }
    assert!(sol.max_constraint_residual() <= 1e-12);
    (drift / scale, sol.stats().steps, sol.stats().taylor_order)
}

/// Energy is kept to rounding: each step's state carries errors of ε·|E|
/// (ε = 2.2e-16) that add up like a random walk, ε·√N of E's scale after
/// N steps (7e-15 after 1000); the largest drift along the way passes four
/// times that with probability 2·P(Z > 4) ≈ 6e-5 (reflection principle).
fn energy_drift_bound(steps: usize) -> f64 {
    4.0 * f64::EPSILON * (steps as f64).sqrt()
}

/// The double rod in body coordinates solves its 10 × 10 KKT system at run
/// time; the Taylor method solves it order by order with one LU a step, and
/// keeps the energy over a thousand steps (E(0) = 0, released horizontal;
/// the potential energy reaches −29 J on the way).
#[test]
fn taylor_keeps_the_double_rod_scenes_energy_over_a_thousand_steps() {
    assert_eq!(<DoubleRodScene as Model>::TAYLOR_TAPE, daegen::Availability::Available);
    let rods = [("upper", 1.0, 1.0 / 12.0), ("lower", 1.0, 1.0 / 12.0)];
    assert_taylor_keeps_energy(DoubleRodScene::default(), 25.0, &rods);
    assert_taylor_follows_dop853(DoubleRodScene::default(), &["lower.x", "lower.y", "upper.theta"]);
}

/// Over ≥ 1000 Taylor steps the energy drifts by at most
/// [`energy_drift_bound`].
fn assert_taylor_keeps_energy<M: Model + Simulate>(model: M, t1: f64, bodies: &[(&str, f64, f64)]) {
    let (drift, steps, order) = taylor_energy_drift(model, t1, bodies);
    assert!(steps >= 1000, "{steps} steps");
    assert!(
        drift <= energy_drift_bound(steps),
        "relative energy drift {drift:e} over {steps} steps of order {order}"
    );
}

/// Taylor at 1e-15 and DOP853 at 1e-13 agree to 1e-10 on `names` over 2 s.
fn assert_taylor_follows_dop853<M: Model + Simulate>(model: M, names: &[&str]) {
    let taylor = Options::new().method(Method::Taylor).tolerance(1e-15);
    let dop853 = Options::new().method(Method::Dop853).tolerance(1e-13);
    let a = model.simulate(0.0, 2.0, &taylor).unwrap();
    let b = model.simulate(0.0, 2.0, &dop853).unwrap();
    assert_agree(&a, &b, names, &[0.5, 1.0, 2.0], 1e-10);
}

#[test]
fn taylor_keeps_the_slider_cranks_energy_over_a_thousand_steps() {
    // The crank r = 0.15 of mass 1 and the slider of mass 0.5 on the x axis.
    let bodies = [("crank", 1.0, 0.15 * 0.15 / 12.0), ("slider", 0.5, 1.0)];
    assert_taylor_keeps_energy(SliderCrankGlobal::default(), 20.0, &bodies);
    assert_taylor_keeps_energy(SliderCrankScene::default(), 20.0, &bodies);
    assert_taylor_follows_dop853(SliderCrankGlobal::default(), &["slider_x", "crank.theta"]);
}

/// Ten coupled rods: a 10 × 10 mass matrix (recursive) or a KKT system
/// (global) solved at run time, order by order on the Taylor tape, in
/// agreement with DOP853 in both formulations. Released from rest with
/// every joint angle zero, the joint angles' series at the start vanish at
/// the orders ≡ 3, 0 (mod 4): at orders 16 (tolerances 1e-10 and 1e-11)
/// the last two coefficients are zero, which must not read as an infinite
/// radius of convergence.
#[test]
fn taylor_runs_the_ten_rod_chain_in_both_formulations() {
    let dop853 = Options::new().method(Method::Dop853).tolerance(1e-13);
    let reference = TenRodChainRecursive::default().simulate(0.0, 1.0, &dop853).unwrap();
    for tol in [1e-10, 1e-13] {
        let taylor = Options::new().method(Method::Taylor).tolerance(tol);
        let global = TenRodChain::default().simulate(0.0, 1.0, &taylor).unwrap();
        let recursive = TenRodChainRecursive::default().simulate(0.0, 1.0, &taylor).unwrap();
        assert!(recursive.stats().steps >= 20, "{} steps", recursive.stats().steps);
        let bound = 1e3 * tol;
        assert_agree(&global, &reference, &["tip_x", "tip_y"], &[0.25, 0.5, 1.0], bound);
        assert_agree(&recursive, &reference, &["tip_x", "tip_y"], &[0.25, 0.5, 1.0], bound);
    }
}

/// At a dead centre of the slider-crank (crank and rod in line, θ = 0)
/// the KKT system is regular, and the accelerations, solved symbolically,
/// divide only by its determinant: finite, and those of the crank's
/// Lagrange equation there (ω²-free: the slider is at rest, so the crank
/// turns freely, θ'' = −g·m·r/2 / I_pivot·cos θ).
#[test]
fn the_slider_crank_accelerations_are_finite_at_dead_centre() {
    let model = SliderCrankGlobal::default();
    let (r, l, m1, g) = (model.r, model.l, model.m1, model.g);
    let omega = 1.0;
    let mut y = vec![0.0; <SliderCrankGlobal as Model>::STATES];
    let names = SliderCrankGlobal::INFO.states;
    let mut set = |name: &str, v: f64| {
        let i = names.iter().position(|n| *n == name).unwrap();
        y[i] = v;
    };
    // Crank centre at (r/2, 0) turning at ω about the origin; the pin at
    // (r, 0); the slider at rest at (r + l, 0).
    set("crank.x", 0.5 * r);
    set("der(crank.y)", 0.5 * r * omega);
    set("der(crank.theta)", omega);
    set("slider.x", r + l);
    let mut dy = vec![0.0; y.len()];
    model.rhs(0.0, &y, &mut dy).unwrap();
    assert!(dy.iter().all(|v| v.is_finite()), "{dy:?}");
    // The slider at rest at the dead centre does not resist: the crank
    // swings as a rod about its end, θ'' = −(m g r/2) cos θ / (m r²/3).
    let i = names.iter().position(|n| *n == "der(crank.theta)").unwrap();
    let want = -(m1 * g * 0.5 * r) / (m1 * r * r / 3.0);
    assert!((dy[i] - want).abs() <= 1e-9 * want.abs(), "θ'' = {} against {want}", dy[i]);
}
