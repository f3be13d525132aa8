use daegen::prelude::*;

/// Course notes Example 2.2: E = [1 1; 0 0], A = [0 1; 0 0], c = (t, 1).
#[dae_model]
fn example_2_2() {
    let t = time();
    let y = state_array([0.0, 0.0]);
    der(y[0]) + der(y[1]) + y[1] == t;
    0.0 == 1.0;
}

fn main() {}
