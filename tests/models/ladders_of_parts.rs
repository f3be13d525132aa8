// An RC ladder from the library's parts, and the same ladder written
// flat: shared by the component tests and the benchmark.

/// `rc_ladder_of_parts!(Name, N)`: a source charging N RC sections in
/// series, each a resistor and a capacitor to ground, from the library;
/// every resistor reads the model's `r` and every capacitor its `c`.
macro_rules! rc_ladder_of_parts {
    ($name:ident, $n:literal) => {
        #[dae_model]
        fn $name() {
            const N: usize = $n;
            let r = param(1.0);
            let c = param(1.0);
            let source = constant_voltage(1.0);
            let resistors = [resistor(r); N];
            let capacitors = [capacitor(c); N];
            let gnd = ground();
            connect(source.p, resistors[0].p);
            connect(source.n, gnd.p);
            for k in 0..N {
                connect(resistors[k].n, capacitors[k].p);
                connect(capacitors[k].n, gnd.p);
                if k + 1 < N {
                    connect(resistors[k].n, resistors[k + 1].p);
                }
            }
        }
    };
}

/// `rc_ladder_of_tunable_parts!(Name, N)`: the same ladder with each
/// part's own value, a parameter of its own (`resistors_3_r`).
macro_rules! rc_ladder_of_tunable_parts {
    ($name:ident, $n:literal) => {
        #[dae_model]
        fn $name() {
            const N: usize = $n;
            let source = constant_voltage(1.0);
            let resistors = [resistor(1.0); N];
            let capacitors = [capacitor(1.0); N];
            let gnd = ground();
            connect(source.p, resistors[0].p);
            connect(source.n, gnd.p);
            for k in 0..N {
                connect(resistors[k].n, capacitors[k].p);
                connect(capacitors[k].n, gnd.p);
                if k + 1 < N {
                    connect(resistors[k].n, resistors[k + 1].p);
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
