use daegen::prelude::*;

/// A mode that leaves the rate undetermined.
#[dae_model]
fn half_mode() {
    let x = state(1.0);
    let y = algebraic(0.0);
    let on = discrete(true);
    der(x) == -y;
    if on {
        y == x;
    }
}

/// The Taylor scheme asked of a model that reads an input.
#[dae_model(taylor = 2)]
fn driven() {
    let u = input(0.0);
    let x = state(0.0);
    der(x) == u - x;
}

/// Sensitivities across a reset.
#[dae_model(sensitivities = [e])]
fn bouncing() {
    let e = param(0.8);
    let h = state(1.0);
    der(der(h)) == -9.81;
    let bounce = event(h).falling().reinit(der(h), -e * pre(der(h)));
}

/// An input in a constraint the index reduction differentiates.
#[dae_model]
fn prescribed() {
    let s = input(0.0);
    let x = state(0.0);
    let f = algebraic(0.0);
    der(der(x)) == f;
    constraint(x - s);
}

/// An integer mode set to a value not known at compile time.
#[dae_model]
fn shifting() {
    let v = state(0.0);
    let force = algebraic(0.0);
    let gear = discrete(1);
    der(v) == force;
    if gear == 1 {
        force == 2.0;
    } else {
        force == 1.0;
    }
    let up = event(v - 1.0).rising().reinit(gear, gear + 1.0);
}

fn main() {}
