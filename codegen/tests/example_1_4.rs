//! Course notes, Example 1.4: `y' = x*y + x`, `y(0) = 1`, exact solution
//! `y = 2*exp(x²/2) - 1`. The economic Taylor scheme's D1..D4 (notes §1.3.1)
//! must be the ones the notes derive by hand, agree with the derivatives of
//! the exact solution, and give a method of order p.

use daegen_codegen::{economic_taylor_derivatives, Graph, Id, SymbolId};

struct Problem {
    g: Graph,
    x: SymbolId,
    y: SymbolId,
    d: Vec<Id>,
}

fn problem(order: usize) -> Problem {
    let mut g = Graph::new();
    let x = g.time("x").unwrap();
    let y = g.state("y").unwrap();
    let (x, y) = (g.as_symbol(x).unwrap(), g.as_symbol(y).unwrap());
    let f = g.parse("x*y + x").unwrap();
    let d = economic_taylor_derivatives(&mut g, x, &[y], &[f], order).unwrap();
    Problem { g, x, y, d: d.into_iter().map(|v| v[0]).collect() }
}

/// `[y, y', y'', ...]` of the exact solution at `x`.
fn exact_derivatives(x: f64) -> [f64; 5] {
    let e = (x * x / 2.0).exp();
    [
        2.0 * e - 1.0,
        2.0 * x * e,
        2.0 * (1.0 + x * x) * e,
        2.0 * (3.0 * x + x.powi(3)) * e,
        2.0 * (3.0 + 6.0 * x * x + x.powi(4)) * e,
    ]
}

impl Problem {
    /// `[y', ..., y^(p)]` by the scheme: D_k evaluated with y^(j) from D_j.
    fn derivatives_at(&self, x: f64, y: f64) -> Vec<f64> {
        let mut known = vec![y];
        for &dk in &self.d {
            let value = |s: SymbolId| {
                if s == self.x {
                    return x;
                }
                match self.g.symbol(s).kind {
                    daegen_codegen::SymbolKind::State => known[0],
                    daegen_codegen::SymbolKind::Derivative { order, .. } => known[order as usize],
                    _ => f64::NAN,
                }
            };
            let v = self.g.eval(&[dk], &value)[0];
            known.push(v);
        }
        known.split_off(1)
    }

    /// The economic Taylor scheme from 0 to 1 in `n` steps.
    fn integrate(&self, n: usize) -> f64 {
        let h = 1.0 / n as f64;
        let mut y = 1.0;
        for k in 0..n {
            let ds = self.derivatives_at(k as f64 * h, y);
            let mut term = 1.0;
            for (j, d) in ds.iter().enumerate() {
                term *= h / (j + 1) as f64;
                y += term * d;
            }
        }
        y
    }
}

#[test]
fn derivatives_are_those_of_the_notes() {
    let mut p = problem(4);
    let expected = [
        "x*y + x",
        "y + x*der(y) + 1",
        "2*der(y) + x*der(der(y))",
        "3*der(der(y)) + x*der(der(der(y)))",
    ];
    for (k, text) in expected.iter().enumerate() {
        let want = p.g.parse(text).unwrap();
        assert_eq!(p.d[k], want, "D{}: got `{}`, the notes have `{text}`", k + 1, p.g.show(p.d[k]));
    }
    let _ = p.y;
}

#[test]
fn derivatives_match_the_exact_solution() {
    let p = problem(4);
    for x in [0.0, 0.3, 1.0, 1.7] {
        let exact = exact_derivatives(x);
        let ds = p.derivatives_at(x, exact[0]);
        for (k, d) in ds.iter().enumerate() {
            let want = exact[k + 1];
            assert!(
                (d - want).abs() <= 1e-13 * want.abs().max(1.0),
                "x = {x}, y^({}) = {d}, exact {want}",
                k + 1
            );
        }
    }
}

#[test]
fn the_scheme_converges_with_order_p() {
    let y1 = exact_derivatives(1.0)[0];
    for order in 1..=4 {
        let p = problem(order);
        let (coarse, fine) = (p.integrate(40), p.integrate(80));
        let rate = ((coarse - y1).abs() / (fine - y1).abs()).log2();
        assert!((rate - order as f64).abs() < 0.15, "order {order}: observed rate {rate:.3}");
    }
}
