use daegen::prelude::*;

#[dae_model(taylor = 2)]
fn angle() {
    let x = state(0.5);
    der(x) == asin(x);
}

fn main() {}
