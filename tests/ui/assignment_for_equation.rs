use daegen::prelude::*;

#[dae_model]
fn decay() {
    let k = param(2.0);
    let x = state(1.0);
    der(x) = -k * x;
}

fn main() {}
