//! Our Taylor method against heyoka, timed in alternation: heyoka runs in
//! another process, so the sweep times it seconds or minutes after us, and
//! on this shared machine the load moves sub-millisecond solves by ±40 %
//! in that time. Here each round times ours (median of repeats) and then
//! heyoka (median of `HEYOKA_REPEATS` solves in peer.py), and the ratio is taken per
//! round; the median over rounds is the figure. Both take the same steps
//! at the same tolerance (same order, same step rule), so equal tolerance
//! is equal error; the table shows both errors to confirm it.

use crate::peers::{field, Python, HEYOKA_REPEATS};
use daegen::prelude::*;
use daegen_workprecision::{median_time, mixed_error, reference_values, Benchmark, Settings};

/// One tolerance of one problem.
pub struct Row {
    pub problem: &'static str,
    pub tol: f64,
    /// Our time over heyoka's, per round, sorted.
    pub ratios: Vec<f64>,
    pub ours_error: f64,
    pub heyoka_error: f64,
    pub ours_steps: usize,
    pub heyoka_steps: usize,
}

/// `rounds` alternating timings of `M` with `Method::Taylor` and heyoka at
/// each tolerance; an error when the model has no peer problem or heyoka
/// is missing.
pub fn versus_heyoka<M: Benchmark>(tolerances: &[f64], rounds: usize) -> Result<Vec<Row>, String> {
    let bench = M::bench();
    let peer = bench.peer.ok_or("no peer problem")?;
    let reference = reference_values::<M>(&bench)?;
    let heyoka = Python { solver: "heyoka" };
    let model = M::default();
    let settings = Settings::default();
    let mut rows = Vec::new();
    for &tol in tolerances {
        let options = Options::new()
            .method(Method::Taylor)
            .rtol(tol)
            .atol(tol * bench.atol_factor)
            .dense_output(false);
        let mut row = Row {
            problem: M::NAME,
            tol,
            ratios: Vec::new(),
            ours_error: f64::NAN,
            heyoka_error: f64::NAN,
            ours_steps: 0,
            heyoka_steps: 0,
        };
        for round in 0..rounds {
            eprint!(
                "\r\x1b[2K{} Taylor vs heyoka {tol:.0e}, round {}",
                M::NAME,
                round + 1
            );
            let (ours, sol) = median_time(&settings, || model.simulate(0.0, bench.t_end, &options));
            let sol = sol.map_err(|e| e.to_string())?;
            let text = heyoka.call(peer, tol, None, HEYOKA_REPEATS)?;
            let theirs = field(&text, "solve_s").ok_or("peer.py printed no solve_s")?;
            row.ratios.push(ours / theirs);
            row.ours_error = mixed_error(sol.final_state(), &reference);
            row.ours_steps = sol.stats().steps;
            row.heyoka_error = field(&text, "max_mixed_err").unwrap_or(f64::NAN);
            row.heyoka_steps = field(&text, "steps").unwrap_or(f64::NAN) as usize;
        }
        row.ratios.sort_by(f64::total_cmp);
        rows.push(row);
    }
    Ok(rows)
}

/// The rows as a markdown table.
pub fn markdown(rows: &[Row], rounds: usize) -> String {
    let mut s = format!(
        "# Taylor vs heyoka, timed in alternation\n\n{rounds} rounds per tolerance; each round: our median solve time, then heyoka's (median of {HEYOKA_REPEATS} solves); ratio = ours / heyoka's per round.\n\n| problem | tol | median ratio (range) | steps ours / heyoka | error ours / heyoka |\n|---|---|---|---|---|\n"
    );
    for r in rows {
        let (Some(first), Some(median), Some(last)) = (
            r.ratios.first(),
            r.ratios.get(r.ratios.len() / 2),
            r.ratios.last(),
        ) else {
            continue;
        };
        s.push_str(&format!(
            "| {} | {:.0e} | {median:.2}× ({first:.2}–{last:.2}) | {} / {} | {:.1e} / {:.1e} |\n",
            r.problem, r.tol, r.ours_steps, r.heyoka_steps, r.ours_error, r.heyoka_error
        ));
    }
    s
}
