use daegen::prelude::*;

/// 201 concentrations at quasi-steady state, each quadratic in itself:
/// no equation determines its variable explicitly, so Newton would
/// iterate on all of them at once.
#[dae_model]
fn quasi_steady_grid() {
    const N: usize = 201;
    let x = state_array([1.0; N]);
    let z = algebraic_array([1.0; N]);
    for k in 0..N {
        der(x[k]) == -z[k];
        z[k] * z[k] == x[k];
    }
}

fn main() {}
