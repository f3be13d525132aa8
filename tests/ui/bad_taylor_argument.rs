use daegen::prelude::*;

#[dae_model(taylor = 12)]
fn decay() {
    let x = state(1.0);
    der(x) == -x;
}

fn main() {}
