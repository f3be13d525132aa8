use daegen::prelude::*;

/// Both states have their own equations: a constraint between them has no
/// unknown left to determine, whatever it says.
#[dae_model]
fn redundant() {
    let x = state(0.0);
    let y = state(0.0);
    der(x) == 1.0;
    der(y) == 1.0;
    constraint(x - y);
}

/// Its derivative along the dynamics, 2 - 1, is a non-zero constant.
#[dae_model]
fn contradictory() {
    let t = time();
    let x = state(0.0);
    der(x) == 2.0;
    constraint(x - t);
}

/// Differentiating never reaches an unknown.
#[dae_model]
fn never_determines() {
    let x = state(1.0);
    let y = state(1.0);
    der(x) == -x;
    der(y) == -y;
    constraint(x * x - y);
}

fn main() {}
