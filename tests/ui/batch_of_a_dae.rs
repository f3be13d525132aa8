use daegen::prelude::*;

/// A pendulum in Cartesian coordinates: a DAE, which lanes do not step.
#[dae_model(batch = 4)]
fn pendulum() {
    let x = state(1.0);
    let y = state(0.0);
    let u = state(0.0);
    let v = state(0.0);
    let lambda = algebraic(0.0);
    der(x) == u;
    der(y) == v;
    der(u) == -lambda * x;
    der(v) == -lambda * y - 9.81;
    constraint(x * x + y * y - 1.0);
}

/// A batch of one member is no batch.
#[dae_model(batch = 1)]
fn decay() {
    let x = state(1.0);
    der(x) == -x;
}

fn main() {}
