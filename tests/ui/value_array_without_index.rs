use daegen::prelude::*;

#[dae_model]
fn springs() {
    let k = [1.0, 2.0];
    let x = state(1.0);
    der(x) == -k * x;
}

fn main() {}
