//! Sparse Jacobians against Jacobians derived by hand.

use daegen_codegen::{Graph, Id, SymbolId};

fn symbols(g: &mut Graph, states: &[&str], params: &[&str]) -> Vec<SymbolId> {
    for p in params {
        g.parameter(p).unwrap();
    }
    g.state_symbols(states).unwrap()
}

fn parse_all(g: &mut Graph, exprs: &[&str]) -> Vec<Id> {
    exprs.iter().map(|e| g.parse(e).unwrap()).collect()
}

#[test]
fn lorenz_jacobian_is_the_textbook_one() {
    let mut g = Graph::new();
    let s = symbols(&mut g, &["x", "y", "z"], &["sigma", "rho", "beta"]);
    let f = parse_all(&mut g, &["sigma*(y - x)", "x*(rho - z) - y", "x*y - beta*z"]);
    let j = g.jacobian(&f, &s).unwrap();
    let expected = [
        (0, 0, "-sigma"),
        (0, 1, "sigma"),
        (1, 0, "rho - z"),
        (1, 1, "-1"),
        (1, 2, "-x"),
        (2, 0, "y"),
        (2, 1, "x"),
        (2, 2, "-beta"),
    ];
    assert_eq!(j.entries.len(), expected.len(), "∂f0/∂z is structurally zero and must be absent");
    for (&(r, c, e), &(er, ec, text)) in j.entries.iter().zip(&expected) {
        assert_eq!((r, c), (er, ec));
        assert_eq!(e, g.parse(text).unwrap(), "J[{r}][{c}] = {}, expected {text}", g.show(e));
    }
}

#[test]
fn entries_that_cancel_are_dropped() {
    let mut g = Graph::new();
    let s = symbols(&mut g, &["x", "y"], &[]);
    // y appears in the written form but not in the value.
    let f = parse_all(&mut g, &["x + y - y", "x*y"]);
    let j = g.jacobian(&f, &s).unwrap();
    let pattern: Vec<(usize, usize)> = j.entries.iter().map(|e| (e.0, e.1)).collect();
    assert_eq!(pattern, [(0, 0), (1, 0), (1, 1)]);
}

#[test]
fn intermediates_are_differentiated_through() {
    let mut g = Graph::new();
    let s = symbols(&mut g, &["x", "y"], &[]);
    let r2 = g.parse("x^2 + y^2").unwrap();
    let r2 = g.intermediate("r2", r2).unwrap();
    let f = g.powi(r2, -1).unwrap();
    let j = g.jacobian(&[f], &s).unwrap();
    assert_eq!(j.entries.len(), 2);
    assert_eq!(g.show(j.entries[0].2).to_string(), "-2*x/r2^2");
    let want = g.parse("-2*y/r2^2").unwrap();
    assert_eq!(j.entries[1].2, want);
}

#[test]
fn jacobian_matches_central_differences_on_kepler() {
    // Planar Kepler problem: the gravity kernel r^(-3/2) that dominates N-body models.
    let mut g = Graph::new();
    let s = symbols(&mut g, &["q1", "q2", "p1", "p2"], &["mu"]);
    let f = parse_all(
        &mut g,
        &["p1", "p2", "-mu*q1*(q1^2 + q2^2)^(-3/2)", "-mu*q2*(q1^2 + q2^2)^(-3/2)"],
    );
    let j = g.jacobian(&f, &s).unwrap();
    let pattern: Vec<(usize, usize)> = j.entries.iter().map(|e| (e.0, e.1)).collect();
    assert_eq!(pattern, [(0, 2), (1, 3), (2, 0), (2, 1), (3, 0), (3, 1)]);
    let x = [0.4, -0.9, 0.3, 0.8, 1.3]; // q1 q2 p1 p2 mu
    let names = ["q1", "q2", "p1", "p2", "mu"];
    let at = |point: [f64; 5]| {
        let lookup: Vec<(&str, f64)> = names.iter().copied().zip(point).collect();
        f.iter().map(|&e| g.eval_named(e, &lookup)).collect::<Vec<f64>>()
    };
    for &(r, c, e) in &j.entries {
        let h = 1e-6;
        let (mut plus, mut minus) = (x, x);
        plus[c] += h;
        minus[c] -= h;
        let fd = (at(plus)[r] - at(minus)[r]) / (2.0 * h);
        let lookup: Vec<(&str, f64)> = names.iter().copied().zip(x).collect();
        let exact = g.eval_named(e, &lookup);
        assert!(
            (exact - fd).abs() < 1e-7 * exact.abs().max(1.0),
            "J[{r}][{c}] = {exact}, differences say {fd}"
        );
    }
}
