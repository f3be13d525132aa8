use daegen::prelude::*;

/// 201 algebraic unknowns on a ring, each equation quadratic in both of
/// its neighbours: no equation determines a variable explicitly, so
/// Newton would iterate on all of them at once.
#[dae_model]
fn quadratic_ring() {
    const N: usize = 201;
    let x = state_array([1.0; N]);
    let z = algebraic_array([1.0; N]);
    for k in 0..N {
        der(x[k]) == -z[k];
        z[k] * z[k] + z[(k + 1) % N] * z[(k + 1) % N] == 2.0 * x[k];
    }
}

fn main() {}
