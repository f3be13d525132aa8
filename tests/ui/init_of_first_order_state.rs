use daegen::prelude::*;

#[dae_model]
fn model() {
    let x = state(1.0);
    init(der(x), 0.5);
    der(x) == -x;
}

fn main() {}
