use daegen::prelude::*;

/// Two equations for `a` and `b` that say the same thing twice (the
/// second is twice the first but for its right side): the block they form
/// matches structurally and is singular.
#[dae_model]
fn singular_block() {
    let x = state(1.0);
    let a = algebraic(0.0);
    let b = algebraic(0.0);
    der(x) == -a - b;
    a + b == x;
    2.0 * a + 2.0 * b == 3.0 * x;
}

fn main() {}
