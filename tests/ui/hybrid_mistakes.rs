use daegen::prelude::*;

#[dae_model]
fn switched() {
    let h = state(1.0);
    let z = algebraic(0.0);
    let on = discrete(true);
    der(der(h)) == -9.81;
    z == 2.0 * h;
    der(on) == 1.0;
    let early = pre(h) + 1.0;
    let reset_z = event(h).falling().reinit(z, 0.0);
    let one_argument = event(h).falling().reinit(der(h));
    let silent = every(0.1);
    let backwards = every(-0.1).reinit(on, false);
    event(h).rising();
    let ticks = output(silent);
    let gear = discrete(1);
    let pull = output(if gear == 2 { 1.0 } else { 0.0 });
    if on {
        let extra = state(0.0);
        der(extra) == 1.0;
    }
}

fn main() {}
