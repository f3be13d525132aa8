use daegen::prelude::*;

/// The pendulum with its constraint force left out of the dynamics: the
/// constraint has nothing to determine.
#[dae_model]
fn lonely_multiplier() {
    let x = state(1.0);
    let y = state(0.0);
    let u = state(0.0);
    let v = state(1.0);
    let lambda = algebraic(1.0);
    der(x) == u;
    der(y) == v;
    der(u) == -x;
    der(v) == -y - 1.0;
    constraint(x * x + y * y - 1.0);
}

fn main() {}
