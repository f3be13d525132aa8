use daegen::prelude::*;

#[dae_model]
fn model() {
    let x = state(1.0);
    let y = state(1.0);
    der(x) == -x;
    der(x) == -2.0 * x;
    der(y) == x - y;
}

fn main() {}
