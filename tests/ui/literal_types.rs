use daegen::prelude::*;

/// Literals of the wrong type, each reported once.
#[dae_model]
fn literals() {
    let x = state("1.0");
    let y = state(true);
    let k = param("fast");
    der(x) == 'c';
    der(y) == k * x;
}

fn main() {}
