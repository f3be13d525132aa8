//! How a model finds the parts it calls: the user's own first, then the
//! standard library. A part of the user's whose name is like a library
//! part's (`conductor_g` beside `conductor`, `ideal_gear_s` beside
//! `ideal_gear`) is the user's, never a misspelling.

use daegen::prelude::*;

/// A conductance between two pins: `i = g v`.
#[component]
fn conductor_g() {
    let g = param(1.0);
    let p = pin();
    let n = pin();
    p.i + n.i == 0.0;
    p.i == g * (p.v - n.v);
}

/// A rotational damper written by the user, `tau = d w_rel`.
#[component]
fn my_damper() {
    let d = param(1.0);
    let flange_a = flange();
    let flange_b = flange();
    let phi_rel = state(0.0).avoid();
    phi_rel == flange_b.phi - flange_a.phi;
    flange_b.tau == d * der(phi_rel);
    flange_a.tau == -d * der(phi_rel);
}

/// 2 V on C = 0.5 F through a conductance of 4 S: `v = 2 (1 − e^(−8t))`.
#[dae_model]
fn conductance_charging() {
    let source = constant_voltage(2.0);
    let g = conductor_g(4.0);
    let c = capacitor(0.5);
    let gnd = ground();
    connect(source.p, g.p);
    connect(g.n, c.p);
    connect(c.n, source.n, gnd.p);
}

/// A rotor at 3 rad/s braked by the user's damper: `w = 3 e^(−t/2)`.
#[dae_model]
fn braked_rotor() {
    let rotor = inertia(j = 2.0, w0 = 3.0);
    let brake = my_damper(1.0);
    let housing = fixed();
    connect(rotor.flange_b, brake.flange_a);
    connect(brake.flange_b, housing.flange);
}

#[test]
fn a_part_named_like_a_library_part_is_the_users() {
    let opts = Options::new().rtol(1e-10).atol(1e-12);
    let charging = ConductanceCharging::default().simulate(0.0, 1.0, &opts).unwrap();
    let braked = BrakedRotor::default().simulate(0.0, 4.0, &opts).unwrap();
    for &t in &[0.1f64, 0.5, 1.0] {
        let v: f64 = charging.at(t, "c.v").unwrap();
        assert!((v - 2.0 * (1.0 - (-8.0 * t).exp())).abs() < 1e-8, "t = {t}: v = {v}");
        let w: f64 = braked.at(4.0 * t, "rotor.w").unwrap();
        assert!((w - 3.0 * (-2.0 * t).exp()).abs() < 1e-8, "t = {}: w = {w}", 4.0 * t);
    }
}
