use daegen::prelude::*;

#[dae_model]
fn model() {
    let x = state(1.0);
    let y = state(1.0);
    der(x) + der(y) == -x;
}

fn main() {}
