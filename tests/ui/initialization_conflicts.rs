use daegen::prelude::*;

/// Two capacitors in parallel discharging through a resistor, each given
/// a start: the connections make their voltages one.
#[dae_model]
fn two_starts_for_one_voltage() {
    let gnd = ground();
    let c1 = capacitor(1.0);
    init(c1.v, 0.0);
    let c2 = capacitor(2.0);
    init(c2.v, 1.0);
    let r = resistor(1.0);
    connect(c1.p, c2.p, r.p);
    connect(c1.n, c2.n, r.n, gnd.p);
}

/// A steady start asked of a state whose start is fixed.
#[dae_model]
fn steady_but_fixed() {
    let x = state(1.0).fixed();
    der(x) == 1.0 - x;
    initial(der(x) == 0.0);
}

/// Two initial equations for the one state they can move.
#[dae_model]
fn two_equations_for_one_start() {
    let x = state(1.0);
    let y = state(0.0).fixed();
    der(x) == y - x;
    der(y) == -y;
    initial(der(x) == 0.0);
    initial(x == 2.0);
}

fn main() {}
