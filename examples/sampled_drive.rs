//! A DC drive under a digital speed controller: the motor (armature
//! resistance and inductance, EMF, rotor inertia, friction) is continuous,
//! the PI controller runs every millisecond and holds its voltage between
//! samples, the speed profile comes from a table (a trapezoid: ramp up,
//! hold, ramp down), and a brake engages, by an event, once the drive has
//! come back to rest. Every controller instant is stepped to exactly and
//! every corner of the profile too; the run prints the speed following
//! the profile, the voltage held, and the instants, and writes CSV and SVG
//! under `target/example-output/`.
//!
//! Run: `cargo run --release --example sampled_drive`

use daegen::prelude::*;
use std::path::PathBuf;

/// The drive: a sampled PI on the motor's speed, the set point an input.
#[dae_model]
fn sampled_drive() {
    /// Speed profile (rad/s).
    let profile = input(0.0);
    let supply = signal_voltage();
    let armature = resistor(0.5);
    let winding = inductor(1e-3);
    let motor = emf(0.05);
    let rotor = inertia(2e-4);
    let friction = damper(1e-4);
    let housing = fixed();
    let tacho = speed_sensor();
    let controller = sampled_pi(kp = 0.05, ki = 2.0, period = 1e-3);
    let gnd = ground();
    connect(supply.p, armature.p);
    connect(armature.n, winding.p);
    connect(winding.n, motor.p);
    connect(motor.n, supply.n, gnd.p);
    connect(motor.flange, rotor.flange_a, tacho.flange);
    let brake = signal_torque();
    connect(rotor.flange_b, friction.flange_a, brake.flange);
    connect(friction.flange_b, housing.flange);
    connect(tacho.w, controller.u_m);
    connect(controller.y, supply.u);
    controller.u_s == profile;
    /// The brake: engaged once the profile is back at zero and the drive
    /// slower than 1 rad/s, a viscous torque from then on.
    let braked = discrete(false);
    let stopping = event(1.0 - tacho.w + 100.0 * profile).rising().reinit(braked, true);
    brake.u == if braked { -0.05 * tacho.w } else { 0.0 };
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let profile = Input::linear(&[0.0, 0.2, 0.6, 0.8], &[0.0, 100.0, 100.0, 0.0])?;
    let drive = SampledDrive { profile, ..SampledDrive::default() };
    let info = <SampledDrive as Model>::INFO;
    println!("inputs: {:?}, discrete values: {:?}", info.inputs, info.discrete);
    for clock in info.clocks {
        println!("clock {} sets {:?}", clock.name, clock.resets);
    }
    let opts = Options::new().rtol(1e-8).atol(1e-8);
    let sol = drive.simulate(0.0, 1.0, &opts)?;
    let grid: Vec<f64> = (0..=10).map(|k| 0.1 * k as f64).collect();
    let names = ["profile", "tacho.w", "controller.y", "winding.i"];
    println!("{}", sol.sample(&names, &grid)?);
    let jumps = sol.jumps();
    let samples = jumps.iter().filter(|j| j.triggers.contains(&"controller.sample")).count();
    println!(
        "{} controller instants, the first at t = {}, the last at t = {}",
        samples,
        jumps[0].t,
        jumps[jumps.len() - 1].t
    );
    for t in [0.2, 0.6, 0.8] {
        println!("profile corner at t = {t}: a step ends there: {}", sol.times().contains(&t));
    }
    if let Ok(times) = sol.event_times("stopping") {
        println!("brake engaged at t = {:?}", times);
    }
    println!("{} steps of {}", sol.stats().steps, sol.stats().method);
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target/example-output");
    std::fs::create_dir_all(&dir)?;
    sol.write_csv(std::fs::File::create(dir.join("sampled_drive.csv"))?, &names)?;
    daegen::plot::time_series(&sol, &["profile", "tacho.w"], dir.join("sampled_drive.svg"))?;
    println!("wrote sampled_drive.csv and sampled_drive.svg in {}", dir.display());
    Ok(())
}
