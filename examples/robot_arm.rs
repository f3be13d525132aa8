//! A UR5 arm from its URDF, moved by a joint-space PD controller from its
//! zero configuration (stretched out, horizontal) to a target pose, under
//! gravity. Each joint's controller is a spring-damper of the standard
//! library across the joint's flange, set to the joint's target:
//! τ = −K (q − q*) − D q̇, no gravity compensation (so the arm sags a
//! little below the target). Run by RADAU5 and by the Taylor method; the
//! path of the end effector (the origin of `tool0`, the link the file
//! welds to the last one) is printed and plotted to
//! `target/example-output/`, and the two methods' ends compared.
//!
//! Run: `cargo run --release --example robot_arm`

use daegen::prelude::*;
use std::path::PathBuf;

/// The UR5 under a PD controller on every joint.
#[dae_model(scene = recursive)]
fn ur5_pd() {
    urdf("tests/robots/ur5.urdf");
    gravity(vec3(0.0, 0.0, -9.81));
    /// Stiffness of each joint's controller (N m/rad).
    let k = param(300.0);
    /// Damping of each joint's controller (N m s/rad).
    let d = param(60.0);
    let base = fixed();
    let pan = spring_damper(c = k, d = d, phi_rel0 = 0.8);
    let lift = spring_damper(c = k, d = d, phi_rel0 = -1.0);
    let elbow = spring_damper(c = k, d = d, phi_rel0 = 1.2);
    let wrist_1 = spring_damper(c = k, d = d, phi_rel0 = -0.5);
    let wrist_2 = spring_damper(c = k, d = d, phi_rel0 = 0.3);
    let wrist_3 = spring_damper(c = k, d = d, phi_rel0 = 0.0);
    connect(
        base.flange,
        pan.flange_a,
        lift.flange_a,
        elbow.flange_a,
        wrist_1.flange_a,
        wrist_2.flange_a,
        wrist_3.flange_a,
    );
    connect(pan.flange_b, shoulder_pan_joint.flange);
    connect(lift.flange_b, shoulder_lift_joint.flange);
    connect(elbow.flange_b, elbow_joint.flange);
    connect(wrist_1.flange_b, wrist_1_joint.flange);
    connect(wrist_2.flange_b, wrist_2_joint.flange);
    connect(wrist_3.flange_b, wrist_3_joint.flange);
    /// The end effector's position, world x (m).
    let tool_x = output(tool0[0]);
    /// Its y (m).
    let tool_y = output(tool0[1]);
    /// Its z (m).
    let tool_z = output(tool0[2]);
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let arm = Ur5Pd::default();
    let path = ["tool_x", "tool_y", "tool_z"];
    let grid: Vec<f64> = (0..=10).map(|k| 0.2 * k as f64).collect();
    let mut ends = Vec::new();
    for method in [Method::Radau5, Method::Taylor] {
        let opts = Options::new().method(method).tolerance(1e-9);
        let started = std::time::Instant::now();
        let sol = arm.simulate(0.0, 2.0, &opts)?;
        let seconds = started.elapsed().as_secs_f64();
        println!("{method:?}: {} steps in {:.1} ms", sol.stats().steps, seconds * 1e3);
        println!("{}", sol.sample(&path, &grid)?);
        let end: Vec<f64> = path.iter().map(|n| sol.last(n)).collect::<Result<_, _>>()?;
        ends.push(end);
        if method == Method::Radau5 {
            let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target/example-output");
            std::fs::create_dir_all(&dir)?;
            sol.write_csv(std::fs::File::create(dir.join("robot_arm.csv"))?, &path)?;
            daegen::plot::time_series(&sol, &path, dir.join("robot_arm.svg"))?;
            println!("wrote robot_arm.csv and robot_arm.svg in {}", dir.display());
        }
    }
    let gap = ends[0].iter().zip(&ends[1]).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
    println!("the end effector at t = 2 s: {:?}; RADAU5 and Taylor agree to {gap:.1e} m", ends[0]);
    Ok(())
}
