use daegen::prelude::*;

/// Three equations for two currents: one of them is one too many.
#[dae_model]
fn over_determined() {
    let v = state(1.0);
    let i1 = algebraic(0.0);
    let i2 = algebraic(0.0);
    der(v) == -i1 - i2;
    2.0 * i1 == v;
    3.0 * i2 == v;
    i1 * i2 == v * v / 6.0;
}

/// A current that no equation determines: the loop equation for `i3` is
/// missing, and the node equation alone cannot fix both `i2` and `i3`.
#[dae_model]
fn under_determined() {
    let v = state(1.0);
    let i1 = algebraic(0.0);
    let i2 = algebraic(0.0);
    let i3 = algebraic(0.0);
    der(v) == -i1;
    i1 == v;
    i1 == 2.0 * i2 + 3.0 * i3;
}

fn main() {}
