//! The structural core's costs (`--structure`): what sorting the
//! equations costs a model's right-hand side against the same model
//! substituted by hand, how the expansion time grows with the number of
//! equations (against ModelingToolkit's reported times on networks of
//! that size), and the chemical Akzo Nobel problem, written as its authors
//! write it, against SUNDIALS' IDA. Writes `results/structure.md`.

use super::*;
use daegen::codegen::expand_dae_model;
use proc_macro2::TokenStream;
use std::hint::black_box;
use std::time::{Duration, Instant};

include!("../../tests/models/ladders.rs");
rc_ladders!(200);

/// Nanoseconds per `rhs` of `a` and of `b` at their initial states (moved
/// off zero), timed in alternation: the median of 21 rounds each.
pub(crate) fn rhs_ns<A: Model, B: Model>(a: &A, b: &B) -> (f64, f64) {
    fn state<M: Model>(m: &M) -> Vec<f64> {
        let mut y = vec![0.0; M::STATES];
        m.initial_state(&mut y);
        y.iter().enumerate().map(|(k, v)| v + 1e-3 * (k as f64 + 1.0)).collect()
    }
    fn batch<M: Model>(m: &M, y: &[f64], dy: &mut [f64], n: usize) -> f64 {
        let start = Instant::now();
        for _ in 0..n {
            let _ = black_box(m).rhs(black_box(0.0), black_box(y), dy);
            black_box(&dy);
        }
        start.elapsed().as_secs_f64() * 1e9 / n as f64
    }
    let (ya, yb) = (state(a), state(b));
    let (mut da, mut db) = (vec![0.0; A::STATES], vec![0.0; B::STATES]);
    // About 20 ms a batch.
    let n = (2e7 / batch(a, &ya, &mut da, 1000).max(1.0)) as usize;
    let (mut ta, mut tb) = (Vec::new(), Vec::new());
    for _ in 0..21 {
        ta.push(batch(a, &ya, &mut da, n));
        tb.push(batch(b, &yb, &mut db, n));
    }
    ta.sort_by(f64::total_cmp);
    tb.sort_by(f64::total_cmp);
    (ta[10], tb[10])
}

/// An RC ladder of `n` nodes with algebraic currents: 2n equations.
fn ladder_tokens(n: usize) -> TokenStream {
    let n = proc_macro2::Literal::usize_unsuffixed(n);
    quote::quote! {
        fn ladder() {
            const N: usize = #n;
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
        }
    }
}

/// An advection–reaction grid of `n` cells, species a and b flowing right
/// and reacting, a + b → 2b at the algebraic rate w = k·a·b of each cell,
/// the inflow an algebraic alias of the previous cell's outflow: 5n
/// equations (two differential, three algebraic a cell).
fn grid_tokens(n: usize) -> TokenStream {
    let n = proc_macro2::Literal::usize_unsuffixed(n);
    quote::quote! {
        fn grid() {
            const N: usize = #n;
            let k = param(1.0);
            let u = param(2.0);
            let a = state_array([1.0; N]);
            let b = state_array([0.01; N]);
            let w = algebraic_array([0.0; N]);
            let fa = algebraic_array([0.0; N]);
            let fb = algebraic_array([0.0; N]);
            for j in 0..N {
                w[j] == k * a[j] * b[j];
            }
            fa[0] == u;
            fb[0] == 0.0;
            for j in 1..N {
                fa[j] == u * a[j - 1];
                fb[j] == u * b[j - 1];
            }
            for j in 0..N {
                der(a[j]) == fa[j] - u * a[j] - w[j];
                der(b[j]) == fb[j] - u * b[j] + w[j];
            }
        }
    }
}

/// Seconds to expand `item` (the whole macro: analysis and emission), the
/// best of `repeats`.
pub(crate) fn expansion_seconds(item: &TokenStream, repeats: usize) -> f64 {
    (0..repeats)
        .map(|_| {
            let start = Instant::now();
            let out = expand_dae_model(TokenStream::new(), item.clone());
            black_box(out);
            start.elapsed().as_secs_f64()
        })
        .fold(f64::INFINITY, f64::min)
}

/// Akzo Nobel to t = 180 by `method` at `tol` (atol 1e-4·tol): the error
/// against the test set's reference (relative, y1 … y6) and the time.
fn akzo_point(method: Method, tol: f64) -> dae::Point {
    let model = AkzoNobel::default();
    let options = Options::new().method(method).rtol(tol).atol(1e-4 * tol);
    let mut best = Duration::MAX;
    let mut error = f64::INFINITY;
    let start = Instant::now();
    while start.elapsed() < Duration::from_millis(500) {
        let t = Instant::now();
        let sol = model.simulate(0.0, 180.0, &options);
        best = best.min(t.elapsed());
        error = match sol {
            Ok(sol) => {
                let got: Vec<f64> = ["y1", "y2", "y3", "y4", "y5", "y6"]
                    .iter()
                    .map(|n| sol.last(n).unwrap_or(f64::NAN))
                    .collect();
                relative(&got, &AKZO_NOBEL_AT_180)
            }
            Err(_) => f64::INFINITY,
        };
    }
    dae::Point { tol, error, seconds: best.as_secs_f64() }
}

fn relative(got: &[f64], reference: &[f64]) -> f64 {
    got.iter().zip(reference).map(|(g, r)| ((g - r) / r).abs()).fold(0.0, f64::max)
}

/// IDA on Akzo Nobel as the test set states it, F(t, y, y′) = 0 with y6
/// algebraic, the iteration matrix by forward differences of F (what IDA
/// does itself without one).
#[cfg(feature = "sundials")]
fn ida_akzo(tol: f64) -> dae::Point {
    use crate::sundials::ida::{solve, Residual};
    let f = |y: &[f64], dy: &mut [f64]| {
        let (k1, k2, k3, k4, kbig, kla, ks, po2, hen) =
            (18.7, 0.58, 0.09, 0.42, 34.4, 3.3, 115.83, 0.9, 737.0);
        let r1 = k1 * y[0].powi(4) * y[1].max(0.0).sqrt();
        let r2 = k2 * y[2] * y[3];
        let r3 = k2 / kbig * y[0] * y[4];
        let r4 = k3 * y[0] * y[3] * y[3];
        let r5 = k4 * y[5] * y[5] * y[1].max(0.0).sqrt();
        let fin = kla * (po2 / hen - y[1]);
        dy[0] = -2.0 * r1 + r2 - r3 - r4;
        dy[1] = -0.5 * r1 - r4 - 0.5 * r5 + fin;
        dy[2] = r1 - r2 + r3;
        dy[3] = -r2 + r3 - 2.0 * r4;
        dy[4] = r2 - r3 + r5;
        dy[5] = ks * y[0] * y[3] - y[5];
    };
    let residual = |_t: f64, y: &[f64], yp: &[f64], r: &mut [f64]| {
        f(y, r);
        for k in 0..5 {
            r[k] = yp[k] - r[k];
        }
    };
    let iteration_matrix = |_t: f64, cj: f64, y: &[f64], _yp: &[f64], j: &mut [f64]| {
        let (mut base, mut moved) = ([0.0; 6], [0.0; 6]);
        f(y, &mut base);
        let mut z = [0.0; 6];
        z.copy_from_slice(y);
        for c in 0..6 {
            let h = 1e-8 * y[c].abs().max(1e-6);
            z[c] = y[c] + h;
            f(&z, &mut moved);
            z[c] = y[c];
            for r in 0..6 {
                // F = y′ − f for the differential rows, f for the last.
                let d = (moved[r] - base[r]) / h;
                j[r * 6 + c] = if r < 5 { -d + if r == c { cj } else { 0.0 } } else { d };
            }
        }
    };
    let y0 = [0.444, 0.00123, 0.0, 0.007, 0.0, 115.83 * 0.444 * 0.007];
    let mut yp0 = [0.0; 6];
    f(&y0, &mut yp0);
    yp0[5] = 0.0;
    let dae = Residual {
        y0: &y0,
        yp0: &yp0,
        differential: &[1.0, 1.0, 1.0, 1.0, 1.0, 0.0],
        residual: &residual,
        iteration_matrix: &iteration_matrix,
    };
    let mut best = Duration::MAX;
    let mut error = f64::INFINITY;
    let start = Instant::now();
    while start.elapsed() < Duration::from_millis(500) {
        let t = Instant::now();
        let out = solve(&dae, 180.0, tol, 1e-4 * tol);
        best = best.min(t.elapsed());
        error = out.map_or(f64::INFINITY, |(y, _)| relative(&y, &AKZO_NOBEL_AT_180));
    }
    dae::Point { tol, error, seconds: best.as_secs_f64() }
}

/// The whole section, as markdown.
pub fn structure_section() -> String {
    let mut out = String::from("# Equations in any order: what the sorting costs\n\n");
    out.push_str(&format!("Machine: {}.\n\n", machine()));
    // The right-hand side, sorted against substituted by hand.
    out.push_str("## Right-hand side, sorted against substituted by hand\n\n");
    out.push_str(
        "Nanoseconds per `rhs` at the initial state (median of 21 alternated rounds).\n\n",
    );
    out.push_str("| model | sorted (ns) | by hand (ns) | ratio |\n|---|---|---|---|\n");
    let (a, b) = rhs_ns(&AkzoNobel::default(), &AkzoNobelByHand::default());
    out.push_str(&format!("| Akzo Nobel (y6 algebraic) | {a:.1} | {b:.1} | {:.3}× |\n", a / b));
    let (a, b) = rhs_ns(&RcLadderWithCurrents::default(), &RcLadderSubstituted::default());
    out.push_str(&format!(
        "| RC ladder, 200 nodes, algebraic currents (by hand: the currents substituted) | {a:.1} | {b:.1} | {:.3}× |\n",
        a / b
    ));
    let (a, b) = rhs_ns(&RcLadderWithCurrents::default(), &RcLadderFactored::default());
    out.push_str(&format!(
        "| RC ladder, 200 nodes, algebraic currents (by hand: factored, `((v[k−1] − v[k]) − (v[k] − v[k+1])) / (r c)`) | {a:.1} | {b:.1} | {:.3}× |\n\n",
        a / b
    ));
    out.push_str(
        "The sorted model's right-hand side is the equations with the currents \
         substituted: what it costs beyond the model substituted by hand is the \
         first ladder row. The factored form does fewer operations in each node's \
         row of the index-table loop a grid's rows are rolled into (4 against 6: \
         `(i[k] − i[k+1]) / c` recomputes both currents in the loop); factoring \
         changes the rounding, so the macro leaves it to the user.\n\n",
    );
    // Expansion time.
    out.push_str("## Expansion time against the number of equations\n\n");
    out.push_str(
        "The whole macro (lowering, aliases, matching, sorting, emission), called as a \
         library, best of 3. ModelingToolkit's users report `mtkcompile` not finishing after \
         20 hours on 5,000–6,000 equations (its tracker, #3919) and `structural_simplify` taking \
         471 s on a 1,100-unknown reaction network (#3557).\n\n",
    );
    out.push_str("| network | cells or nodes | equations | expansion (s) | µs per equation |\n|---|---|---|---|---|\n");
    for (name, sizes, per, tokens) in [
        (
            "RC ladder, algebraic currents",
            &[250usize, 500, 1000, 2000, 3000][..],
            2,
            ladder_tokens as fn(usize) -> TokenStream,
        ),
        (
            "advection–reaction grid, algebraic rates and fluxes",
            &[100, 220, 400, 800, 1200][..],
            5,
            grid_tokens,
        ),
    ] {
        for &n in sizes {
            eprint!("\r\x1b[2Kexpanding {name} of {n}");
            let s = expansion_seconds(&tokens(n), 3);
            let equations = per * n;
            out.push_str(&format!(
                "| {name} | {n} | {equations} | {s:.2} | {:.0} |\n",
                s * 1e6 / equations as f64
            ));
        }
    }
    // Akzo Nobel against IDA.
    out.push_str("\n## Akzo Nobel, as its authors write it, against IDA\n\n");
    out.push_str(
        "To t = 180, atol = 1e-4·rtol; the relative error of y1 … y6 against the test set's \
         reference; the best time of the runs in half a second. IDA integrates the test \
         set's residual with y6 algebraic.\n\n",
    );
    out.push_str("| solver | tol | error | time (ms) |\n|---|---|---|---|\n");
    let tols = [1e-4, 1e-6, 1e-8, 1e-10];
    for (name, method) in [("daegen RADAU5", Method::Radau5), ("daegen RODAS5P", Method::Rodas5P)] {
        for &tol in &tols {
            let p = akzo_point(method, tol);
            out.push_str(&format!(
                "| {name} | {tol:.0e} | {:.2e} | {:.3} |\n",
                p.error,
                p.seconds * 1e3
            ));
        }
    }
    #[cfg(feature = "sundials")]
    for &tol in &tols {
        let p = ida_akzo(tol);
        out.push_str(&format!(
            "| IDA (dense) | {tol:.0e} | {:.2e} | {:.3} |\n",
            p.error,
            p.seconds * 1e3
        ));
    }
    #[cfg(not(feature = "sundials"))]
    out.push_str("\nIDA: not built (the `sundials` feature is off).\n");
    eprintln!("\r\x1b[2Kdone");
    out
}
