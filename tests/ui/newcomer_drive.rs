use daegen::prelude::*;

/// A speed drive whose controller's set point is left unconnected.
#[dae_model]
fn set_point_left_open() {
    let gnd = ground();
    let supply = signal_voltage();
    let winding = resistor(0.5);
    connect(supply.p, winding.p);
    let motor = emf(k = 0.05);
    connect(winding.n, motor.p);
    connect(supply.n, motor.n, gnd.p);
    let rotor = inertia(j = 1e-3);
    connect(motor.flange, rotor.flange_a);
    let friction = damper(d = 1e-4);
    let housing = fixed();
    connect(friction.flange_b, housing.flange);
    let sensor = speed_sensor();
    connect(rotor.flange_b, friction.flange_a, sensor.flange);
    let controller = pi_controller(kp = 0.02, ki = 0.5);
    connect(sensor.w, controller.u_m);
    connect(controller.y, supply.u);
}

/// A misspelt parameter: one message, none on the names declared below
/// that read the part.
#[dae_model]
fn misspelt_parameter() {
    let rotor = inertia(jj = 1.0, w0 = 10.0);
    let spring = spring(c = 100.0);
    connect(rotor.flange_a, spring.flange_a);
    let housing = fixed();
    connect(spring.flange_b, housing.flange);
    let e_kin = output(0.5 * rotor.w * rotor.w);
    let e_stored = output(50.0 * spring.phi_rel * spring.phi_rel);
    let e_total = output(e_kin + e_stored);
}

/// The last connection joins two outputs: it is the one at fault.
#[dae_model]
fn two_outputs_joined_last() {
    let controller = pi_controller();
    let reference = constant(1.0);
    connect(reference.y, controller.u_s);
    let feedback = gain(2.0);
    connect(feedback.y, controller.u_m);
    connect(controller.y, feedback.u);
    connect(reference.y, feedback.y);
}

/// A part that hands its input on to a gain inside it.
#[component]
fn doubled() {
    let u = real_input();
    let y = real_output();
    let k = gain(2.0);
    connect(u, k.u);
    connect(k.y, y);
}

/// Its input is connected inside it, not from outside.
#[dae_model]
fn input_connected_only_inside_its_part() {
    let d = doubled();
    let x = integrator();
    connect(d.y, x.u);
}

fn main() {}
