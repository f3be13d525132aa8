use daegen::prelude::*;

#[dae_model]
fn decay() {
    let k = param(1.0);
    let x = state(1.0);
    der(x) == -k * y;
}

fn main() {
    // Only the mistake in the model is reported: the type and its fields exist.
    let m = Decay { k: 2.0 };
    let _ = m.simulate(0.0, 1.0, &Options::new());
}
