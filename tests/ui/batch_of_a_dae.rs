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

fn main() {}
