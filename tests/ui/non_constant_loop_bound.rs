use daegen::prelude::*;

#[dae_model]
fn model() {
    let n = param(3.0);
    let q = state_array([1.0, 2.0, 3.0]);
    for i in 0..n {
        der(q[i]) == -q[i];
    }
}

fn main() {}
