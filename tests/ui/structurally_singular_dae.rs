use daegen::prelude::*;

/// Three equations for the two unknowns `der(x)` and `a`: the constraint's
/// derivative `der(x) == 0` competes with the other two.
#[dae_model]
fn overdetermined() {
    let x = state(1.0);
    let a = algebraic(0.0);
    der(x) == a;
    a == x;
    constraint(x - 1.0);
}

/// `b` appears in no equation that is left for it.
#[dae_model]
fn underdetermined() {
    let x = state(1.0);
    let a = algebraic(0.0);
    let b = algebraic(0.0);
    der(x) == a + b;
    constraint(x - 1.0);
}

fn main() {}
