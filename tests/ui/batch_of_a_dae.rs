use daegen::prelude::*;

/// x' = −x², through an algebraic variable: a DAE, which lanes do not step.
#[dae_model(batch = 4)]
fn squared_decay() {
    let x = state(1.0);
    let z = algebraic(1.0);
    der(x) == -z;
    0.0 == z - x * x;
}

/// A batch of one member is no batch.
#[dae_model(batch = 1)]
fn decay() {
    let x = state(1.0);
    der(x) == -x;
}

/// A bouncing ball: its members' events differ, which lanes do not follow.
#[dae_model(batch = 4)]
fn balls() {
    let h = state(1.0);
    der(der(h)) == -9.81;
    let bounce = event(h).falling().reinit(der(h), -0.8 * pre(der(h)));
}

/// Driven by an input.
#[dae_model(batch = 4)]
fn driven() {
    let u = input(0.0);
    let x = state(1.0);
    der(x) == u - x;
}

fn main() {}
