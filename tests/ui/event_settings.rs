use daegen::prelude::*;

#[dae_model]
fn ball() {
    let height = state(10.0);
    der(der(height)) == -9.81;
    let bounce = event(height).sideways();
    let both = event(height).rising().falling();
    let arg = event(height).terminal(true);
    event(height).terminal();
}

fn main() {}
