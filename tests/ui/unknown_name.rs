use daegen::prelude::*;

#[dae_model]
fn pendulum() {
    let lambda = param(1.0);
    let x = state(1.0);
    der(x) == -lamda * x;
}

fn main() {}
