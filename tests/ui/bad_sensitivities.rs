use daegen::prelude::*;

// A state where a parameter belongs, a name that is neither, and an
// initial value of no state.
#[dae_model(sensitivities = [x, k2, init(z)])]
fn decay() {
    let k = param(0.7);
    let x = state(2.0);
    der(x) == -k * x;
}

/// Sensitivities of a DAE are not generated yet.
#[dae_model(sensitivities = [l])]
fn pendulum() {
    let l = param(1.0);
    let x = state(1.0);
    let y = state(0.0);
    let lambda = algebraic(0.0);
    der(der(x)) == -lambda * x;
    der(der(y)) == -lambda * y - 9.81;
    constraint(x * x + y * y - l * l);
}

fn main() {}
