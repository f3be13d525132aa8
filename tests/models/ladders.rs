// RC ladders written three ways, shared by tests/structure.rs and the
// benchmark (`include!`d): a source `vs` behind `r`, then N sections of a
// capacitor to ground and a resistor to the next node. The ODEs are
// macros so each includer chooses the size: `rc_ladders!(40);`.

#[allow(unused_macros)]
macro_rules! rc_ladders {
    ($n:literal) => {
/// The ladder written as a circuit is read: Kirchhoff's current law at
/// each node first, then Ohm's law for each resistor's current, the
/// currents algebraic.
#[dae_model]
fn rc_ladder_with_currents() {
    const N: usize = $n;
    let r = param(1.0);
    let c = param(1.0);
    let vs = param(1.0);
    let v = state_array([0.0; N]);
    let i = algebraic_array([0.0; N]);
    for k in 0..N - 1 {
        c * der(v[k]) == i[k] - i[k + 1];
    }
    c * der(v[N - 1]) == i[N - 1];
    r * i[0] == vs - v[0];
    for k in 1..N {
        r * i[k] == v[k - 1] - v[k];
    }
    /// The voltage across each resistor.
    let drop = output_array((0..N).map(|k| r * i[k]));
}

/// The ladder with the currents substituted by hand, term for term:
/// `(i[k] − i[k+1]) / c` with `i[k] = (v[k−1] − v[k]) / r`.
#[dae_model]
fn rc_ladder_substituted() {
    const N: usize = $n;
    let r = param(1.0);
    let c = param(1.0);
    let vs = param(1.0);
    let v = state_array([0.0; N]);
    der(v[0]) == ((vs - v[0]) / r - (v[0] - v[1]) / r) / c;
    for k in 1..N - 1 {
        der(v[k]) == ((v[k - 1] - v[k]) / r - (v[k] - v[k + 1]) / r) / c;
    }
    der(v[N - 1]) == ((v[N - 2] - v[N - 1]) / r) / c;
}

/// The ladder as an ODE simplified by hand: each node's two currents over
/// one common `r c`.
#[dae_model]
fn rc_ladder_factored() {
    const N: usize = $n;
    let r = param(1.0);
    let c = param(1.0);
    let vs = param(1.0);
    let v = state_array([0.0; N]);
    der(v[0]) == ((vs - v[0]) - (v[0] - v[1])) / (r * c);
    for k in 1..N - 1 {
        der(v[k]) == ((v[k - 1] - v[k]) - (v[k] - v[k + 1])) / (r * c);
    }
    der(v[N - 1]) == (v[N - 2] - v[N - 1]) / (r * c);
}
    };
}
