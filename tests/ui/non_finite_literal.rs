use daegen::prelude::*;

#[dae_model]
fn model() {
    let x = state(1.0);
    der(x) == -1e400 * x;
}

fn main() {}
