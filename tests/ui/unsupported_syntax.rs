use daegen::prelude::*;

#[dae_model]
fn model() {
    let x = state(1.0);
    let y = state(1.0);
    let f = |a: f64| a * 2.0;
    let g = f(x, y);
    let s = x.sin();
    let branch = if x == 0.0 { x } else { -x };
    x = 2.0;
    der(x) == -x;
    der(y) == -y;
}

fn main() {}
