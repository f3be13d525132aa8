use daegen::prelude::*;

#[dae_model]
fn model() {
    let x = state(1.0);
    der(x) == x * ln(0.0) + sqrt(-1.0);
}

fn main() {}
