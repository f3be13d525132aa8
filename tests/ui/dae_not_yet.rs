use daegen::prelude::*;

/// The contract's pendulum, an index-3 DAE: not supported yet.
#[dae_model]
fn pendulum() {
    let l = param(1.0);
    let x = state(1.0);
    let y = state(0.0);
    let u = state(0.0);
    let v = state(0.0);
    let lambda = algebraic(0.0);
    der(x) == u;
    der(y) == v;
    der(u) == -lambda * x;
    der(v) == -lambda * y - 9.81;
    constraint(x * x + y * y - l * l);
}

fn main() {}
