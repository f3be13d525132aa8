use daegen::prelude::*;

#[dae_model]
fn model() {
    let x = state(1.0);
    let y = state(0.0);
    der(x) == sine(y);
    der(y) == atan2(x);
}

fn main() {}
