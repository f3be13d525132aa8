use daegen::prelude::*;

#[dae_model]
fn oscillator() {
    let omega = param(2.0);
    let x = state(1.0);
    der(der(x)) == -omgea * omgea * x;
}

fn main() {}
