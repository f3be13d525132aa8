// An RC ladder from the library's parts, and the same ladder written
// flat: shared by the component tests and the benchmark.

/// `rc_ladder_of_parts!(Name, N)`: a source charging N RC sections in
/// series, each a resistor and a capacitor to ground, from the library.
macro_rules! rc_ladder_of_parts {
    ($name:ident, $n:literal) => {
        #[dae_model]
        fn $name() {
            const N: usize = $n;
            let source = constant_voltage(1.0);
            let r = [resistor(1.0); N];
            let c = [capacitor(1.0); N];
            let gnd = ground();
            connect(source.p, r[0].p);
            connect(source.n, gnd.p);
            for k in 0..N {
                connect(r[k].n, c[k].p);
                connect(c[k].n, gnd.p);
                if k + 1 < N {
                    connect(r[k].n, r[k + 1].p);
                }
            }
        }
    };
}

/// `rc_ladder_flat!(Name, N)`: the same ladder written flat: the node
/// voltages, each current by Ohm's law.
macro_rules! rc_ladder_flat {
    ($name:ident, $n:literal) => {
        #[dae_model]
        fn $name() {
            const N: usize = $n;
            let r = param(1.0);
            let c = param(1.0);
            let vs = param(1.0);
            let v = state_array([0.0; N]);
            for k in 0..N {
                let left = if k == 0 { vs } else { v[k - 1] };
                let right = if k + 1 < N { (v[k] - v[k + 1]) / r } else { 0.0 };
                c * der(v[k]) == (left - v[k]) / r - right;
            }
        }
    };
}
