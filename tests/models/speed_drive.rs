// The speed drive, shared by the component tests and the benchmark (through
// tests/models/drives.rs) and by the FMU tests and examples (`#[path]`).

// Already in scope where the file is `include!`d.
#[allow(unused_imports)]
use daegen::prelude::*;

/// A DC motor under a PI speed controller, built from the standard
/// library's parts across the electrical, mechanical and control
/// domains and a motor from a crate of components, with viscous friction
/// and a load torque of 0.02 N m from t = 0.3 s.
#[dae_model]
pub fn speed_drive() {
    let reference = constant(100.0);
    let controller = pi_controller(kp = 0.02, ki = 0.5);
    let sensor = speed_sensor();
    let supply = signal_voltage();
    let motor = daegen_parts_example::dc_motor(l = 0.5e-3, k = 0.05, j = 1e-4);
    let friction = damper(1e-5);
    let housing = fixed();
    let load = signal_torque();
    let load_torque = step(height = -0.02, start_time = 0.3);
    let gnd = ground();
    connect(reference.y, controller.u_s);
    connect(sensor.w, controller.u_m);
    connect(controller.y, supply.u);
    connect(supply.p, motor.p);
    connect(supply.n, motor.n, gnd.p);
    connect(motor.shaft, friction.flange_a, sensor.flange, load.flange);
    connect(friction.flange_b, housing.flange);
    connect(load_torque.y, load.u);
}
