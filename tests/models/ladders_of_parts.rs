// An RC ladder from the library's parts, and the same ladder written
// flat: shared by the component tests and the benchmark.

/// `rc_ladder_of_parts!(Name, N, { declarations }, r, c)`: a source
/// charging N RC sections in series, each a resistor `resistor(r)` and a
/// capacitor `capacitor(c)` to ground, from the library: with `r` and `c`
/// the model's parameters, every part reads them; with numbers, each part
/// has its own (`resistors_3_r`).
macro_rules! rc_ladder_of_parts {
    ($name:ident, $n:literal, { $($declarations:tt)* }, $r:expr, $c:expr) => {
        #[dae_model]
        fn $name() {
            const N: usize = $n;
            $($declarations)*
            let source = constant_voltage(1.0);
            let resistors = [resistor($r); N];
            let capacitors = [capacitor($c); N];
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
