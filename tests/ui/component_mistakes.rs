use daegen::prelude::*;

/// A parameter the part does not have.
#[dae_model]
fn wrong_parameter_name() {
    let gnd = ground();
    let r1 = resistor(rr = 100.0);
    connect(r1.n, gnd.p);
    let c1 = capacitor(1e-3, 0.0, 5.0);
    connect(r1.p, c1.p);
    connect(r1.n, c1.n);
}

/// A pin joined to a flange.
#[dae_model]
fn kinds_that_do_not_match() {
    let gnd = ground();
    let r1 = resistor(1.0);
    connect(r1.n, gnd.p);
    let j = inertia(1.0);
    connect(r1.p, j.flange_a);
    connect(r1.p, r1.q);
}

/// Parts declared in a loop.
#[dae_model]
fn parts_in_a_loop() {
    for k in 0..3 {
        let r = resistor(1.0);
    }
    let r1 = resistor(1.0);
    let gnd = ground();
    connect(r1.p, gnd.p);
}

/// A misspelt part: a name no part has, though it is like a library
/// part's, is fetched as the user's own part (the user's parts come
/// first), and the compiler says there is none.
#[dae_model]
fn misspelt_part() {
    let r1 = resistr(1.0);
    let gnd = ground();
    connect(r1.p, gnd.p);
}

/// A part with a mistake in its body: reported where it is defined.
#[component]
fn leaky_part() {
    let p = pin();
    let n = pin();
    p.i + n.i == 0.0;
    p.v - n.v == leakage * p.i;
}

/// Arguments and a return type, as a Rust function would have.
#[component]
fn resistor_with_arguments(r: f64) -> f64 {
    let p = pin();
    let n = pin();
    p.v - n.v == r * p.i;
    p.i + n.i == 0.0;
}

/// Two outputs joined: a signal has one source.
#[dae_model]
fn two_sources_for_one_signal() {
    let a = constant(1.0);
    let b = constant(2.0);
    let g = gain(2.0);
    let x = integrator();
    connect(a.y, b.y, g.u);
    connect(g.y, x.u);
}

fn main() {}
