use daegen::prelude::*;

#[dae_model]
fn model() {
    let x = state(1.0);
    let v = state(0.0);
    der(x) == x;
}

fn main() {}
