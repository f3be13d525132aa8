//! Equations in any order: aliases removed, the equations matched to the
//! unknowns they determine and sorted into blocks, each solved with what
//! the blocks before it determined. Models written as their physics reads
//! run like the same models substituted by hand.

use daegen::prelude::*;
use daegen::{BlockInfo, BlockSolution, StructureInfo};

mod support;
use support::harness::{adaptive_methods_for, kind, methods_for, Kind};

include!("models/stiff.rs");
akzo_nobel_model!();

include!("models/ladders.rs");
rc_ladders!(40);

#[test]
fn a_ladder_with_algebraic_currents_runs_as_its_substituted_ode() {
    const N: usize = 40;
    let t1 = 50.0;
    for method in adaptive_methods_for::<RcLadderWithCurrents>() {
        let opts = Options::new().method(method).tolerance(1e-10);
        let sorted = RcLadderWithCurrents::default().simulate(0.0, t1, &opts).unwrap();
        // The same ODE, its terms as substituted or grouped otherwise: the
        // same steps but where rounding tips one step's error test (one
        // step in 160 at most), the same states but for rounding, which
        // each run's error control keeps within its tolerance. Rounding
        // may also tip Auto's stiffness test near its bound, and with it a
        // hand-over (Dop853→Radau5 against Dop853→Radau5→Dop853): then
        // only the states are compared.
        let a = sorted.final_state();
        for by_hand in [
            RcLadderSubstituted::default().simulate(0.0, t1, &opts).unwrap(),
            RcLadderFactored::default().simulate(0.0, t1, &opts).unwrap(),
        ] {
            let (steps, by_hand_steps) = (sorted.stats().steps, by_hand.stats().steps);
            let same_methods = sorted.stats().method == by_hand.stats().method;
            assert!(
                steps.abs_diff(by_hand_steps) <= 1 || !same_methods,
                "{method:?}: {steps} and {by_hand_steps} steps"
            );
            let b = by_hand.final_state();
            let gap = a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max);
            assert!(gap <= 1e2 * 1e-10, "{method:?}: the two ladders differ by {gap:e}");
        }
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
    for method in adaptive_methods_for::<ResistiveLadder>() {
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
    // A stiff problem: the methods stable on it.
    for method in methods_for::<AkzoNobel>(|m| kind(m) == Kind::Stiff) {
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

/// A capacitor (1 F) discharging through a resistor and a diode in
/// series, written element by element: Kirchhoff's voltage law, Ohm's law,
/// the Shockley diode, and a wire (`vd == v_anode`). The algebraic block
/// in `i`, `vr`, `v_anode` is nonlinear; Newton iterates on `i` alone.
#[dae_model]
fn diode_discharge() {
    let r = param(10.0);
    let is = param(1e-9);
    let vt = param(0.025);
    let v = state(1.0);
    let i = algebraic(0.0);
    let vr = algebraic(0.0);
    let v_anode = algebraic(0.0);
    let vd = algebraic(0.0);
    der(v) == -i;
    v == vr + vd;
    vd == v_anode;
    vr == r * i;
    i == is * (exp(v_anode / vt) - 1.0);
}

/// The diode current at capacitor voltage `v`: the root of
/// i − Is (e^((v − R i)/Vt) − 1) by bisection on [0, v/R], where the left
/// side rises from negative to positive.
fn diode_current(v: f64, r: f64, is: f64, vt: f64) -> f64 {
    let f = |i: f64| i - is * (((v - r * i) / vt).exp() - 1.0);
    let (mut lo, mut hi) = (0.0, v / r);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if f(mid) > 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    0.5 * (lo + hi)
}

#[test]
fn a_torn_nonlinear_block_follows_an_independent_integration() {
    let m = DiodeDischarge::default();
    // The reference: classical RK4 on v' = −i(v) with 20 000 steps, the
    // current by bisection (error ~ (h/τ)⁴ with τ ≈ R C = 10: 1e-12).
    let (t1, n) = (20.0, 20_000);
    let h = t1 / n as f64;
    let mut v = 1.0;
    let rate = |v: f64| -diode_current(v, m.r, m.is, m.vt);
    for _ in 0..n {
        let k1 = rate(v);
        let k2 = rate(v + 0.5 * h * k1);
        let k3 = rate(v + 0.5 * h * k2);
        let k4 = rate(v + h * k3);
        v += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    }
    for method in adaptive_methods_for::<DiodeDischarge>() {
        let opts = Options::new().method(method).tolerance(1e-10);
        let sol = m.simulate(0.0, t1, &opts).unwrap();
        let got = sol.last("v").unwrap();
        assert!((got - v).abs() <= 1e-8, "{method:?}: v = {got}, reference {v}");
        // Every element's law holds in the solution's algebraic variables.
        let (i, vr, vd) =
            (sol.last("i").unwrap(), sol.last("vr").unwrap(), sol.last("vd").unwrap());
        assert!((got - vr - vd).abs() <= 1e-14, "Kirchhoff");
        assert!((vr - m.r * i).abs() <= 1e-14, "Ohm");
        let shockley = m.is * ((vd / m.vt).exp() - 1.0);
        assert!((i - shockley).abs() <= 1e-12 * i.abs().max(1e-9), "Shockley: {i} vs {shockley}");
    }
    assert_eq!(
        DiodeDischarge::INFO.structure,
        StructureInfo {
            aliases: 1,
            one_at_a_time: 1,
            blocks: &[BlockInfo { size: 3, solution: BlockSolution::Newton { tearing: 1 } }],
        }
    );
    let text = DiodeDischarge::default().describe();
    assert!(
        text.contains("structure: 1 alias removed, 1 equation solved one at a time, 1 block\n  block of 3 equations: nonlinear, Newton on 1 tearing variable"),
        "{text}"
    );
}

#[test]
fn describe_reports_the_blocks_before_and_after_tearing() {
    // The ladder's twelve node voltages: one linear block, constant
    // coefficients but for the parameters, solved at run time.
    let s = ResistiveLadder::INFO.structure;
    assert_eq!(s.aliases, 0);
    assert_eq!(s.blocks.len(), 1);
    assert_eq!(s.blocks[0].size, 12);
    // Akzo Nobel: y6 and the five rates, one at a time, no block.
    let s = AkzoNobel::INFO.structure;
    assert_eq!((s.aliases, s.one_at_a_time, s.blocks.len()), (0, 6, 0));
    // Kepler's radius from `r * r == x * x + y * y` pulls the forces that
    // divide by it into its Newton block; tearing leaves Newton `r`.
    let s = KeplerAnyOrder::INFO.structure;
    assert_eq!(s.blocks, &[BlockInfo { size: 3, solution: BlockSolution::Newton { tearing: 1 } }]);
    // Aliases only.
    let s = AliasChain::INFO.structure;
    assert_eq!((s.aliases, s.one_at_a_time, s.blocks.len()), (5, 1, 0));
    assert!(AliasChain::default().describe().contains("structure: 5 aliases removed"));
}

/// A resistive ladder heating up: its shunt conductances grow with the
/// dissipated energy `e`, so the node voltages form a linear block whose
/// coefficients depend on the state, and the power `u[0]² / r` that heats
/// it reads that block's first unknown squared.
#[dae_model]
fn heating_ladder() {
    const M: usize = 6;
    let r = param(1.0);
    let g = param(2.0);
    let vs = param(1.0);
    let e = state(0.0);
    let u = algebraic_array([0.0; M]);
    der(e) == u[0] * u[0] / r;
    (vs - u[0]) / r == u[0] * g * (1.0 + e) + (u[0] - u[1]) / r;
    for k in 1..M - 1 {
        (u[k - 1] - u[k]) / r == u[k] * g * (1.0 + e) + (u[k] - u[k + 1]) / r;
    }
    (u[M - 2] - u[M - 1]) / r == u[M - 1] * g * (1.0 + e);
}

/// The node voltages of [`HeatingLadder`] at energy `e`: its tridiagonal
/// Kirchhoff system solved by the Thomas algorithm.
fn heating_ladder_nodes(e: f64, m: usize, r: f64, g: f64, vs: f64) -> Vec<f64> {
    let shunt = g * (1.0 + e);
    // Row k: −u[k−1]/r + (2/r + shunt) u[k] − u[k+1]/r = (vs/r at k = 0);
    // the last row has one neighbour: (1/r + shunt).
    let diagonal: Vec<f64> =
        (0..m).map(|k| if k + 1 < m { 2.0 / r + shunt } else { 1.0 / r + shunt }).collect();
    let off = -1.0 / r;
    let mut rhs = vec![0.0; m];
    rhs[0] = vs / r;
    let (mut c, mut d) = (vec![0.0; m], vec![0.0; m]);
    c[0] = off / diagonal[0];
    d[0] = rhs[0] / diagonal[0];
    for k in 1..m {
        let denominator = diagonal[k] - off * c[k - 1];
        c[k] = off / denominator;
        d[k] = (rhs[k] - off * d[k - 1]) / denominator;
    }
    let mut u = vec![0.0; m];
    u[m - 1] = d[m - 1];
    for k in (0..m - 1).rev() {
        u[k] = d[k] - c[k] * u[k + 1];
    }
    u
}

#[test]
fn a_value_read_squared_from_a_run_time_block_is_solved_after_it() {
    let m = HeatingLadder::default();
    let rate = |e: f64| heating_ladder_nodes(e, 6, m.r, m.g, m.vs)[0].powi(2) / m.r;
    // The reference: RK4 with 4000 steps on e' = u0(e)²/r.
    let (t1, n) = (2.0, 4000);
    let h = t1 / n as f64;
    let mut e = 0.0;
    for _ in 0..n {
        let k1 = rate(e);
        let k2 = rate(e + 0.5 * h * k1);
        let k3 = rate(e + 0.5 * h * k2);
        let k4 = rate(e + h * k3);
        e += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    }
    for method in adaptive_methods_for::<HeatingLadder>() {
        let sol = m.simulate(0.0, t1, &Options::new().method(method).tolerance(1e-11)).unwrap();
        let got = sol.last("e").unwrap();
        assert!((got - e).abs() <= 1e-9, "{method:?}: e = {got}, reference {e}");
        let nodes = heating_ladder_nodes(got, 6, m.r, m.g, m.vs);
        for (k, node) in nodes.iter().enumerate() {
            let u = sol.last(&format!("u[{k}]")).unwrap();
            assert!((u - node).abs() <= 1e-13, "u[{k}] = {u}, Thomas gives {node}");
        }
    }
    // The six node voltages in one linear block, the power after it.
    let s = HeatingLadder::INFO.structure;
    assert_eq!(s.one_at_a_time, 1);
    assert_eq!(s.blocks.len(), 1);
    assert_eq!(s.blocks[0].size, 6);
    assert!(matches!(s.blocks[0].solution, BlockSolution::Symbolic | BlockSolution::Linear { .. }));
}

/// Fifty cells at quasi-steady state, each with its own quadratic
/// equation: `z[k]² == x[k]` gives `x' = −√x`, so
/// `x(t) = (√x0 − t/2)²`.
#[dae_model]
fn quasi_steady_cells() {
    const N: usize = 50;
    let x = state_array((0..N).map(|k| 1.0 + (k as f64) / 50.0));
    let z = algebraic_array([1.0; N]);
    for k in 0..N {
        der(x[k]) == -z[k];
        z[k] * z[k] == x[k];
    }
}

#[test]
fn independent_nonlinear_cells_are_solved_one_by_one() {
    for method in adaptive_methods_for::<QuasiSteadyCells>() {
        let opts = Options::new().method(method).tolerance(1e-10);
        let sol = QuasiSteadyCells::default().simulate(0.0, 1.0, &opts).unwrap();
        for k in 0..50 {
            let x0: f64 = 1.0 + k as f64 / 50.0;
            let exact = (x0.sqrt() - 0.5).powi(2);
            let x = sol.last(&format!("x[{k}]")).unwrap();
            assert!((x - exact).abs() <= 1e-8, "{method:?}: x[{k}] = {x}, exact {exact}");
            let z = sol.last(&format!("z[{k}]")).unwrap();
            assert!((z - exact.sqrt()).abs() <= 1e-8, "z[{k}] = {z}");
        }
    }
    // Fifty blocks of one equation, each its own Newton iteration.
    let s = QuasiSteadyCells::INFO.structure;
    assert_eq!(s.blocks.len(), 50);
    let one = BlockInfo { size: 1, solution: BlockSolution::Newton { tearing: 1 } };
    assert!(s.blocks.iter().all(|b| *b == one), "{:?}", s.blocks);
}
