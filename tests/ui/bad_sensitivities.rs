use daegen::prelude::*;

// A state where a parameter belongs, a name that is neither, and an
// initial value of no state.
#[dae_model(sensitivities = [x, k2, init(z)])]
fn decay() {
    let k = param(0.7);
    let x = state(2.0);
    der(x) == -k * x;
}

/// An algebraic equation solved by Newton at run time: its sensitivities
/// are not generated.
#[dae_model(sensitivities = [k])]
fn square_root_decay() {
    let k = param(1.0);
    let y = state(1.0);
    let z = algebraic(0.9);
    der(y) == -k * z;
    z * z == y;
}

fn main() {}
