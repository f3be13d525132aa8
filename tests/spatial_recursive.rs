//! The recursive formulation of spatial scenes (joint coordinates, mass
//! matrix by the composite-rigid-body algorithm, bias forces by recursive
//! Newton–Euler) against the global formulation of the same scenes.

use daegen::prelude::*;

mod support;
use support::{assert_agree, tight};

include!("models/spatial_chains.rs");

spatial_double_pendulum!(double_pendulum_global,);
spatial_double_pendulum!(double_pendulum_recursive, scene = recursive);

#[test]
fn the_spatial_double_pendulum_matches_the_global_formulation() {
    let tol = 1e-10;
    let global = tight::<DoublePendulumGlobal>(2.0, tol);
    let recursive = tight::<DoublePendulumRecursive>(2.0, tol);
    println!("{:?}", recursive.names());
    let times = [0.0, 0.5, 1.0, 1.5, 2.0];
    assert_agree(&global, &recursive, &["tip_x", "tip_y", "tip_z"], &times, 1e-7);
}

rssr_loop!(rssr_global,);
rssr_loop!(rssr_recursive, scene = recursive);
seven_joint_arm!(arm_global,);
seven_joint_arm!(arm_recursive, scene = recursive);

#[test]
fn probe() {
    let tol = 1e-10;
    for (g, r, names) in [
        (tight::<DoublePendulumGlobal>(2.0, tol), tight::<DoublePendulumRecursive>(2.0, tol), ["tip_x", "tip_y", "tip_z"]),
        (tight::<RssrGlobal>(2.0, tol), tight::<RssrRecursive>(2.0, tol), ["tip_y", "tip_z", "tip_z"]),
        (tight::<ArmGlobal>(1.0, tol), tight::<ArmRecursive>(1.0, tol), ["hand_x", "hand_y", "hand_z"]),
    ] {
        println!("states g {} r {}; steps g {} r {}; dof {:?} {:?}", g.names().len(), r.names().len(), g.stats().steps, r.stats().steps, g.degrees_of_freedom(), r.degrees_of_freedom());
        for t in [0.25, 0.5, 1.0, 2.0] {
            if t > *g.times().last().unwrap() { continue; }
            let a: Vec<f64> = names.iter().map(|n| g.at(t, n).unwrap()).collect();
            let b: Vec<f64> = names.iter().map(|n| r.at(t, n).unwrap()).collect();
            println!("t {t}: {a:?} diff {:?}", a.iter().zip(&b).map(|(x, y)| x - y).collect::<Vec<_>>());
        }
    }
}
