use daegen::prelude::*;

/// A capacitor whose charge is a nonlinear function of its voltage.
#[component]
fn charge_capacitor() {
    let c0 = param(1.0);
    let p = pin();
    let n = pin();
    let q = state(0.0);
    let v = algebraic(0.0);
    v == p.v - n.v;
    p.i + n.i == 0.0;
    der(q) == p.i;
    q == c0 * v + 0.1 * v * v * v;
}

/// Two of them in parallel: their charges are tied through the voltage,
/// nonlinearly in it.
#[dae_model]
fn parallel_charges() {
    let source = constant_voltage(1.0);
    let r = resistor(1.0);
    let a = charge_capacitor(1.0);
    let b = charge_capacitor(2.0);
    let gnd = ground();
    connect(source.p, r.p);
    connect(r.n, a.p, b.p);
    connect(a.n, b.n, source.n, gnd.p);
}

fn main() {}
