use daegen::prelude::*;

#[dae_model]
fn model() {
    let k = param(2.0);
    let x = state(1.0);
    der(x) == der(k) + der(2.0) + der(x * x);
}

fn main() {}
