use daegen::prelude::*;

/// A point on the unit circle whose constraint force is left out of the
/// dynamics: the constraint has nothing to determine.
#[dae_model]
fn lonely_multiplier() {
    let x = state(1.0);
    let y = state(0.0);
    let lambda = algebraic(1.0);
    der(x) == -y;
    der(y) == x;
    constraint(x * x + y * y - 1.0);
}

fn main() {}
