//! Taylor's final error against heyoka's at equal tolerance: both take
//! Jorba & Zou's truncation for a tolerance, but our order follows the
//! model's cost, so the same tolerance runs at another order and step.
//! Each problem is solved at every tolerance of a grid four a decade, by
//! us and by heyoka (peer.py, one solve each), and the table lists the
//! errors and their ratio.
//!
//! At the tightest tolerances rounding, not truncation, sets both errors,
//! and one solve's error is a draw: the table gives, at the last
//! tolerance, the spread of ours over Jorba & Zou's order and the six
//! above it (each with their step, so a truncation at or below heyoka's).

use crate::peers::{array, field, Python};
use daegen::prelude::*;
use daegen_workprecision::{mixed_error, reference_values, Benchmark};

/// One problem at one tolerance.
pub struct Row {
    pub problem: &'static str,
    pub tol: f64,
    pub order: usize,
    pub steps: usize,
    pub error: f64,
    pub heyoka_steps: usize,
    pub heyoka_error: f64,
}

/// Our errors at one tolerance over a range of given orders.
pub struct Spread {
    pub problem: &'static str,
    pub tol: f64,
    pub orders: (usize, usize),
    pub least: f64,
    pub largest: f64,
}

/// `M` with `Method::Taylor` and heyoka at the tolerances 10^(−j/4),
/// j = `lo` ..= `hi`, and the spread of our errors at the last.
pub fn taylor_error<M: Benchmark>(lo: usize, hi: usize) -> Result<(Vec<Row>, Spread), String> {
    let bench = M::bench();
    let peer = bench.peer.ok_or("no peer problem")?;
    let reference = reference_values::<M>(&bench)?;
    let heyoka = Python { solver: "heyoka" };
    let model = M::default();
    let mut rows = Vec::new();
    for j in lo..=hi {
        let tol = 10f64.powf(-(j as f64) / 4.0);
        eprint!("\r\x1b[2K{} Taylor and heyoka at {tol:.1e}", M::NAME);
        let atol = tol * bench.atol_factor;
        let options =
            Options::new().method(Method::Taylor).rtol(tol).atol(atol).dense_output(false);
        let sol = model.simulate(0.0, bench.t_end, &options).map_err(|e| e.to_string())?;
        let text = heyoka.call(peer, tol, (bench.atol_factor != 1.0).then_some(atol), 1)?;
        let heyoka_error = field(&text, "max_mixed_err")
            .or_else(|| array(&text, "y_end").map(|y| mixed_error(&y, &reference)))
            .unwrap_or(f64::NAN);
        rows.push(Row {
            problem: M::NAME,
            tol,
            order: sol.stats().taylor_order,
            steps: sol.stats().steps,
            error: mixed_error(sol.final_state(), &reference),
            heyoka_steps: field(&text, "steps").unwrap_or(f64::NAN) as usize,
            heyoka_error,
        });
    }
    let tol = 10f64.powf(-(hi as f64) / 4.0);
    let p0 = daegen::runtime::taylor_order::jorba_zou_order(tol);
    let options = Options::new()
        .method(Method::Taylor)
        .rtol(tol)
        .atol(tol * bench.atol_factor)
        .dense_output(false);
    let mut spread =
        Spread { problem: M::NAME, tol, orders: (p0, p0 + 6), least: f64::INFINITY, largest: 0.0 };
    for p in p0..=p0 + 6 {
        let sol = model
            .simulate(0.0, bench.t_end, &options.taylor_order(p))
            .map_err(|e| e.to_string())?;
        let error = mixed_error(sol.final_state(), &reference);
        spread.least = spread.least.min(error);
        spread.largest = spread.largest.max(error);
    }
    Ok((rows, spread))
}

/// Per problem: the ratios' geometric mean and largest, how many
/// tolerances end with our error above heyoka's, and the spread of ours at
/// the last tolerance; then every row.
pub fn markdown(rows: &[Row], spreads: &[Spread]) -> String {
    let mut s = String::from(
        "# Taylor's error against heyoka's at equal tolerance\n\nEach problem at tolerances four a decade, `Method::Taylor` (the order it picks) and heyoka (peer.py, Jorba & Zou's order), one solve each; the error is the sweep's mixed error at the end time. Ratio = our error / heyoka's. The last column: at the last tolerance, where rounding sets the error, ours at Jorba & Zou's order and the six above it (their step, so a truncation at or below heyoka's), least and largest error, against heyoka's there.\n\n| problem | tolerances | ratio: geometric mean | least | largest (at tol) | ours above heyoka's | our steps / heyoka's | rounding: ours at orders p₀ … p₀ + 6 (heyoka's) |\n|---|---|---|---|---|---|---|---|\n",
    );
    let mut problems: Vec<&str> = rows.iter().map(|r| r.problem).collect();
    problems.dedup();
    for p in &problems {
        let rs: Vec<&Row> = rows.iter().filter(|r| r.problem == *p).collect();
        let ratios: Vec<f64> = rs.iter().map(|r| r.error / r.heyoka_error).collect();
        let mean = (ratios.iter().map(|r| r.ln()).sum::<f64>() / ratios.len() as f64).exp();
        let least = ratios.iter().copied().fold(f64::INFINITY, f64::min);
        let (at, largest) = rs
            .iter()
            .zip(&ratios)
            .max_by(|a, b| a.1.total_cmp(b.1))
            .map(|(r, &x)| (r.tol, x))
            .unwrap_or((0.0, 0.0));
        let above = ratios.iter().filter(|&&r| r > 1.0).count();
        let steps = rs.iter().map(|r| r.steps).sum::<usize>() as f64
            / rs.iter().map(|r| r.heyoka_steps).sum::<usize>() as f64;
        let spread = spreads.iter().find(|x| x.problem == *p).map_or("—".into(), |x| {
            let heyoka = rs.last().map_or(f64::NAN, |r| r.heyoka_error);
            format!(
                "{:.0e}, orders {}–{}: {:.1e} … {:.1e} ({heyoka:.1e})",
                x.tol, x.orders.0, x.orders.1, x.least, x.largest
            )
        });
        s.push_str(&format!(
            "| {p} | {:.0e} … {:.0e} | {mean:.2} | {least:.2} | {largest:.2} ({at:.1e}) | {above} of {} | {steps:.2} | {spread} |\n",
            rs[0].tol,
            rs[rs.len() - 1].tol,
            rs.len()
        ));
    }
    s.push_str("\n| problem | tol | our order, steps, error | heyoka's order, steps, error | ratio |\n|---|---|---|---|---|\n");
    for r in rows {
        s.push_str(&format!(
            "| {} | {:.1e} | {}, {}, {:.1e} | {}, {}, {:.1e} | {:.2} |\n",
            r.problem,
            r.tol,
            r.order,
            r.steps,
            r.error,
            daegen::runtime::taylor_order::jorba_zou_order(r.tol),
            r.heyoka_steps,
            r.heyoka_error,
            r.error / r.heyoka_error
        ));
    }
    s
}
