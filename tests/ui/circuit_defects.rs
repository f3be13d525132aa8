use daegen::prelude::*;

/// A circuit no ground holds: its node voltages are free by a constant.
#[dae_model]
fn no_ground() {
    let source = constant_voltage(10.0);
    let r1 = resistor(100.0);
    let c1 = capacitor(1e-3);
    connect(source.p, r1.p);
    connect(r1.n, c1.p);
    connect(c1.n, source.n);
}

/// Two ideal voltage sources across the same nodes.
#[dae_model]
fn sources_in_parallel() {
    let a = constant_voltage(10.0);
    let b = constant_voltage(12.0);
    let c1 = capacitor(1e-3);
    let r1 = resistor(1.0);
    let gnd = ground();
    connect(a.p, b.p, r1.p);
    connect(r1.n, c1.p);
    connect(a.n, b.n, c1.n, gnd.p);
}

/// A spring between two torques: nothing holds its angles, only their
/// difference is fixed.
#[dae_model]
fn floating_flange() {
    let j = inertia(1.0);
    let brake = damper(0.1);
    let housing = fixed();
    let s = spring(10.0);
    let left = torque_source(1.0);
    let right = torque_source(-1.0);
    connect(j.flange_b, brake.flange_a);
    connect(brake.flange_b, housing.flange);
    connect(left.flange, s.flange_a);
    connect(s.flange_b, right.flange);
}

fn main() {}
