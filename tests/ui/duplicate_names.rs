use daegen::prelude::*;

#[dae_model]
fn model() {
    let m = param(1.0);
    let m = state(0.0);
    let x = state(1.0);
    der(x) == -x;
}

fn main() {}
