use daegen::prelude::*;

#[dae_model(taylor = 12)]
fn decay() {
    let x = state(1.0);
    der(x) == -x;
}

#[dae_model(taylor = 2, unroll = [1, 19])]
fn growth() {
    let x = state(1.0);
    der(x) == x;
}

#[dae_model(unroll = 19)]
fn logistic() {
    let x = state(0.5);
    der(x) == x * (1.0 - x);
}

#[dae_model(order = 3)]
fn cubic() {
    let x = state(0.5);
    der(x) == x * x * x;
}

fn main() {}
