//! A servo press built from parts of four domains, as in Modelica: a DC
//! motor (armature resistance and inductance, EMF, rotor inertia, a
//! component of its own), a 20:1 gear turning the crank of a slider-crank
//! scene, a PI speed controller driving the motor's voltage through a
//! voltage source, and the armature's resistor heating up against the
//! air. No equation says what is an input: the macro flattens the parts,
//! writes Kirchhoff's equations of the connections, eliminates the states
//! the connections tie (the EMF's and the rotor's angles are the crank's
//! through the gear) and sorts what is left. The run prints the crank's
//! speed settling at the set point under gravity's pull on the slider, the
//! motor's current and the armature's temperature, and writes CSV and SVG
//! under `target/example-output/`.
//!
//! Run: `cargo run --release --example servo_press`

use daegen::prelude::*;
use std::path::PathBuf;

/// A DC motor whose armature resistance heats with its temperature,
/// between the pins `p` and `n`, driving the flange `shaft`, losing its
/// heat through `heat`.
#[component]
fn hot_motor() {
    /// Armature resistance at 20 °C (Ω).
    let r = param(0.8);
    /// Armature inductance (H).
    let l = param(2e-3);
    /// Motor constant (V s/rad).
    let k = param(0.06);
    /// Rotor inertia (kg m²).
    let j = param(2e-5);
    let p = pin();
    let n = pin();
    let shaft = flange();
    let heat = heat_port();
    // From the pin `p` through the armature to the shaft.
    let armature = heating_resistor(r = r, alpha = 0.0039);
    connect(p, armature.p);
    connect(armature.heat_port, heat);
    let winding = inductor(l);
    connect(armature.n, winding.p);
    let emf = emf(k);
    connect(winding.n, emf.p);
    connect(emf.n, n);
    let rotor = inertia(j);
    connect(emf.flange, rotor.flange_a);
    connect(rotor.flange_b, shaft);
}

/// The press: the motor at 100 rad/s of crank speed ×20, a crank of
/// 0.15 m turning a 0.4 m rod and a 0.5 kg slider.
#[dae_model(scene = recursive)]
fn servo_press() {
    let r = param(0.15);
    let l = param(0.4);
    let ground = ground();
    let crank = body(1.0, r * r / 12.0, [0.5 * r * cos(1.0), 0.5 * r * sin(1.0), 1.0]);
    let slider =
        body(0.5, 1.0, [r * cos(1.0) + sqrt(l * l - r * r * sin(1.0) * sin(1.0)), 0.0, 0.0]);
    let pivot = revolute(ground, vec3(0.0, 0.0, 0.0), crank, vec3(-0.5 * r, 0.0, 0.0));
    let rod = distance(crank, vec3(0.5 * r, 0.0, 0.0), slider, vec3(0.0, 0.0, 0.0), l);
    prismatic(ground, vec3(0.0, 0.0, 0.0), slider, vec3(0.0, 0.0, 0.0), vec3(1.0, 0.0, 0.0));
    gravity(vec3(0.0, -9.81, 0.0));
    // Drive: the set point in motor rad/s, the controller, the source.
    let set_point = constant(100.0);
    let controller = limited_pi(kp = 0.05, ki = 1.0, y_max = 24.0, y_min = -24.0, k_aw = 20.0);
    let tacho = speed_sensor();
    let supply = signal_voltage();
    let motor = hot_motor();
    let gear = ideal_gear(20.0);
    connect(set_point.y, controller.u_s);
    connect(tacho.w, controller.u_m);
    connect(controller.y, supply.u);
    connect(supply.p, motor.p);
    connect(supply.n, motor.n, ground.p);
    connect(motor.shaft, gear.flange_a, tacho.flange);
    connect(gear.flange_b, pivot.flange);
    // Thermal: the motor's body and the air around it.
    let housing = heat_capacitor(c = 30.0, t0 = 293.15);
    let air = convection(0.4);
    let room = fixed_temperature(293.15);
    connect(motor.heat, housing.port, air.solid);
    connect(air.fluid, room.port);
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let model = ServoPress::default();
    let info = <ServoPress as Model>::INFO;
    println!("Servo press from {} parts:", info.components.len());
    for c in info.components {
        let depth = c.path.matches('.').count();
        println!("  {:indent$}{} ({})", "", c.path, c.part, indent = 2 * depth);
    }
    println!("states: {}\n", info.states.join(", "));
    let opts = Options::new().rtol(1e-8).atol(1e-8);
    let sol = model.simulate(0.0, 3.0, &opts)?;
    let grid: Vec<f64> = (0..=12).map(|k| 0.25 * k as f64).collect();
    let names = ["tacho.w", "der(pivot.q)", "motor.winding.i", "controller.y", "housing.t"];
    println!("{}", sol.sample(&names, &grid)?);
    println!("{} steps of {}", sol.stats().steps, sol.stats().method);
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target/example-output");
    std::fs::create_dir_all(&dir)?;
    sol.write_csv(std::fs::File::create(dir.join("servo_press.csv"))?, &names)?;
    daegen::plot::time_series(&sol, &["tacho.w", "controller.y"], dir.join("servo_press.svg"))?;
    println!("wrote servo_press.csv and servo_press.svg in {}", dir.display());
    Ok(())
}
