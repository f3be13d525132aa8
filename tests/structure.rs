//! Equations in any order: aliases removed, the equations matched to the
//! unknowns they determine and sorted into blocks, each solved with what
//! the blocks before it determined. Models written as their physics reads
//! run like the same models substituted by hand.

use daegen::prelude::*;

mod support;

include!("models/stiff.rs");
akzo_nobel_model!();

/// An RC ladder: a source `vs` behind `r`, then N sections of a capacitor
/// to ground and a resistor to the next node, written as a circuit is
/// read: Ohm's law for each resistor's current, Kirchhoff's current law at
/// each node, in that order.
#[dae_model]
fn rc_ladder_with_currents() {
    const N: usize = 40;
    let r = param(1.0);
    let c = param(1.0);
    let vs = param(1.0);
    let v = state_array([0.0; N]);
    let i = algebraic_array([0.0; N]);
    // Kirchhoff first: the capacitor of node k takes what flows in less
    // what flows on.
    for k in 0..N - 1 {
        c * der(v[k]) == i[k] - i[k + 1];
    }
    c * der(v[N - 1]) == i[N - 1];
    // Then Ohm.
    r * i[0] == vs - v[0];
    for k in 1..N {
        r * i[k] == v[k - 1] - v[k];
    }
    let drop = output_array((0..N).map(|k| r * i[k]));
}

/// The same ladder substituted by hand: an ODE in the node voltages.
#[dae_model]
fn rc_ladder_substituted() {
    const N: usize = 40;
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

#[test]
fn a_ladder_with_algebraic_currents_runs_as_its_substituted_ode() {
    const N: usize = 40;
    let t1 = 50.0;
    for method in [Method::Dopri5, Method::Radau5, Method::Rodas5P, Method::Auto] {
        let opts = Options::new().method(method).tolerance(1e-10);
        let sorted = RcLadderWithCurrents::default().simulate(0.0, t1, &opts).unwrap();
        let by_hand = RcLadderSubstituted::default().simulate(0.0, t1, &opts).unwrap();
        // The same ODE, its terms grouped otherwise: the same steps, the
        // same states but for rounding, which each run's error control
        // keeps within its tolerance.
        assert_eq!(sorted.stats().steps, by_hand.stats().steps, "{method:?}");
        let (a, b) = (sorted.final_state(), by_hand.final_state());
        let gap = a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max);
        assert!(gap <= 1e2 * 1e-10, "{method:?}: the two ladders differ by {gap:e}");
        // Each current is readable, and it is Ohm's: (v[k-1] − v[k]) / r.
        for k in 1..N {
            let current = sorted.last(&format!("i[{k}]")).unwrap();
            let ohm = a[k - 1] - a[k];
            assert!((current - ohm).abs() <= 1e-14, "i[{k}] = {current}, Ohm gives {ohm}");
            let drop = sorted.last(&format!("drop[{k}]")).unwrap();
            assert!((drop - ohm).abs() <= 1e-14);
        }
    }
    assert_eq!(RcLadderWithCurrents::INFO.algebraics.len(), N);
    assert_eq!(RcLadderWithCurrents::INFO.algebraics[3], "i[3]");
}

/// A resistive ladder of M nodes between a source and a capacitor: every
/// node voltage is algebraic, fixed by Kirchhoff's law at all nodes at once
/// (one linear block of M unknowns), and the capacitor sees the Thévenin
/// equivalent of the whole ladder.
#[dae_model]
fn resistive_ladder() {
    const M: usize = 12;
    let r = param(1.0);
    let r_shunt = param(2.0);
    let c = param(1.0);
    let vs = param(1.0);
    let v = state(0.0);
    let u = algebraic_array([0.0; M]);
    c * der(v) == (u[M - 1] - v) / r;
    (vs - u[0]) / r == u[0] / r_shunt + (u[0] - u[1]) / r;
    for k in 1..M - 1 {
        (u[k - 1] - u[k]) / r == u[k] / r_shunt + (u[k] - u[k + 1]) / r;
    }
    (u[M - 2] - u[M - 1]) / r == u[M - 1] / r_shunt + (u[M - 1] - v) / r;
}

/// The Thévenin equivalent the capacitor of [`ResistiveLadder`] sees: a
/// source behind a resistor, folded node by node from the source
/// (series `r`, then the node's shunt in parallel).
fn thevenin(m: usize, r: f64, r_shunt: f64, vs: f64) -> (f64, f64) {
    let parallel = |a: f64, b: f64| a * b / (a + b);
    let (mut v, mut rt) = (vs, r);
    for _ in 0..m {
        // The node's shunt divides the voltage and parallels the resistance.
        v *= r_shunt / (rt + r_shunt);
        rt = parallel(rt, r_shunt) + r;
    }
    (v, rt)
}

#[test]
fn a_linear_block_of_node_voltages_gives_the_thevenin_response() {
    let (vth, rth) = thevenin(12, 1.0, 2.0, 1.0);
    let model = ResistiveLadder::default();
    for method in [Method::Dopri5, Method::Dop853, Method::Radau5, Method::Rodas5P] {
        for tol in [1e-6, 1e-9] {
            let opts = Options::new().method(method).tolerance(tol);
            let sol = model.simulate(0.0, 3.0, &opts).unwrap();
            let exact = vth * (1.0 - (-3.0 / (rth * model.c)).exp());
            let v = sol.last("v").unwrap();
            assert!((v - exact).abs() <= 1e2 * tol, "{method:?} at {tol:e}: {v} against {exact}");
        }
    }
}

/// Aliases in a chain, written in any order: `d` is `x` through three of
/// them, and `e` is a parameter's value.
#[dae_model]
fn alias_chain() {
    let k = param(2.0);
    let x = state(1.0);
    let a = algebraic(0.0);
    let b = algebraic(0.0);
    let c = algebraic(0.0);
    let d = algebraic(0.0);
    let e = algebraic(0.0);
    der(x) == -e * d;
    d + a == 0.0;
    a == b;
    b == -c;
    c == x;
    e == k;
}

#[test]
fn alias_chains_leave_every_name_readable() {
    let opts = Options::new().method(Method::Dop853).tolerance(1e-12);
    let sol = AliasChain::default().simulate(0.0, 1.0, &opts).unwrap();
    // x' = −k x: x = e^(−2t).
    let x = (-2.0f64).exp();
    assert!((sol.last("x").unwrap() - x).abs() <= 1e-11);
    for (name, value) in [("a", -x), ("b", -x), ("c", x), ("d", x), ("e", 2.0)] {
        let got = sol.last(name).unwrap();
        assert!((got - value).abs() <= 1e-11, "{name} = {got}, not {value}");
    }
    assert_eq!(AliasChain::INFO.algebraics, &["a", "b", "c", "d", "e"]);
}

/// Kepler's problem with its force written before the positions it reads,
/// and the radius an algebraic variable defined last.
#[dae_model]
fn kepler_any_order() {
    let fx = algebraic(0.0);
    let fy = algebraic(0.0);
    let r = algebraic(1.0);
    let x = state(0.1);
    let y = state(0.0);
    der(der(x)) == fx;
    der(der(y)) == fy;
    fx * r * r * r == -x;
    fy * r * r * r == -y;
    init(der(y), sqrt(1.9 / 0.1));
    r * r == x * x + y * y;
}

#[test]
fn equations_in_any_order_with_a_nonlinear_definition() {
    // e = 0.9 from the pericentre: after one period (2π) the orbit returns.
    let opts = Options::new().method(Method::Dop853).tolerance(1e-11);
    let sol = KeplerAnyOrder::default().simulate(0.0, 2.0 * std::f64::consts::PI, &opts).unwrap();
    let (x, y) = (sol.last("x").unwrap(), sol.last("y").unwrap());
    assert!((x - 0.1).abs() <= 1e-6 && y.abs() <= 1e-6, "({x}, {y}) after one period");
    let r = sol.last("r").unwrap();
    assert!((r - (x * x + y * y).sqrt()).abs() <= 1e-12);
}

#[test]
fn akzo_nobel_as_its_authors_write_it_meets_the_reference() {
    let model = AkzoNobel::default();
    for method in [Method::Radau5, Method::Rodas5P, Method::Auto] {
        for tol in [1e-6, 1e-8, 1e-10] {
            let opts = Options::new().method(method).rtol(tol).atol(1e-4 * tol);
            let sol = model.simulate(0.0, 180.0, &opts).unwrap();
            let y = sol.final_state();
            let y6 = sol.last("y6").unwrap();
            let got = [y[0], y[1], y[2], y[3], y[4], y6];
            let error = support::mixed_error(&got, &AKZO_NOBEL_AT_180, 0.0);
            assert!(error <= 1e3 * tol, "{method:?} at {tol:e}: relative error {error:e}");
        }
    }
}
