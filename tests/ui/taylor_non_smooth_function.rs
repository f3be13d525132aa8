use daegen::prelude::*;

#[dae_model(taylor = 2)]
fn bounce() {
    let x = state(0.5);
    der(x) == -abs(x);
}

fn main() {}
