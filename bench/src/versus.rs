//! Our Taylor method against heyoka, timed in alternation: heyoka runs in
//! another process, so the sweep times it seconds or minutes after us, and
//! on this shared machine the load moves sub-millisecond solves by ±40 %
//! in that time. Here each round times ours (median of repeats) and then
//! heyoka (median of `HEYOKA_REPEATS` solves in peer.py), and the ratio is taken per
//! round; the median over rounds is the figure. Both take the same steps
//! at the same tolerance (same order, same step rule), so equal tolerance
//! is equal error; the table shows both errors to confirm it.
//!
//! Against `ode_solvers`' Dop853, in the same process, equal error is not
//! equal tolerance: its errors are first scanned on a grid of tolerances
//! four to a decade, and each round times ours and Dop853 at the two
//! tolerances whose errors bracket ours, its time at our error
//! interpolated log–log between them, as the sweep does.

use crate::peers::{array, field, OdeSolvers, Python, HEYOKA_REPEATS};
use daegen::prelude::*;
use daegen_workprecision::{
    median_time, mixed_error, reference_values, Benchmark, Peer, PeerProblem, Settings,
};

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
            // peer.py's own error where it has the reference; else ours.
            row.heyoka_error = field(&text, "max_mixed_err")
                .or_else(|| array(&text, "y_end").map(|y| mixed_error(&y, &reference)))
                .unwrap_or(f64::NAN);
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
        let Some(ratio) = ratio_cell(&r.ratios) else {
            continue;
        };
        s.push_str(&format!(
            "| {} | {:.0e} | {ratio} | {} / {} | {:.1e} / {:.1e} |\n",
            r.problem, r.tol, r.ours_steps, r.heyoka_steps, r.ours_error, r.heyoka_error
        ));
    }
    s
}

/// `median× (least–largest)` of sorted ratios, if there are any.
fn ratio_cell(ratios: &[f64]) -> Option<String> {
    let (first, median, last) = (
        ratios.first()?,
        ratios.get(ratios.len() / 2)?,
        ratios.last()?,
    );
    Some(format!("{median:.2}× ({first:.2}–{last:.2})"))
}

/// One tolerance of one problem against `ode_solvers`' Dop853.
pub struct Dop853Row {
    pub problem: &'static str,
    pub tol: f64,
    /// Our time over Dop853's at our error, per round, sorted; empty when
    /// Dop853 does not reach our error on the grid.
    pub ratios: Vec<f64>,
    pub ours_error: f64,
    /// Dop853's two tolerances and errors around ours.
    pub bracket: Option<[(f64, f64); 2]>,
}

/// `rounds` alternating timings of `M` with `Method::Taylor` and
/// `ode_solvers`' Dop853 at our error, per tolerance.
pub fn versus_dop853<M: Benchmark>(
    tolerances: &[f64],
    rounds: usize,
) -> Result<Vec<Dop853Row>, String> {
    let bench = M::bench();
    let reference = reference_values::<M>(&bench)?;
    let model = M::default();
    let rhs = |t: f64, y: &[f64], dy: &mut [f64]| {
        if model.rhs(t, y, dy).is_err() {
            dy.iter_mut().for_each(|v| *v = f64::NAN);
        }
    };
    let no_jacobian = |_: f64, _: &[f64], j: &mut [f64]| j.iter_mut().for_each(|v| *v = f64::NAN);
    let mut y0 = vec![0.0; M::STATES];
    model.initial_state(&mut y0);
    let problem = PeerProblem {
        name: M::NAME,
        peer: bench.peer,
        y0,
        t_end: bench.t_end,
        tolerances: Vec::new(),
        atol_factor: bench.atol_factor,
        stiff: false,
        nonstiff: true,
        reference: &reference,
        rhs: &rhs,
        jacobian: &no_jacobian,
    };
    let dop853 = OdeSolvers { dop853: true };
    let settings = Settings::default();
    let once = Settings {
        min_repeats: 1,
        max_repeats: 1,
        ..Settings::default()
    };
    // Dop853's error on the grid 1e-8 … 1e-16, four tolerances a decade.
    let grid: Vec<(f64, f64)> = (32..=64)
        .map(|j| 10f64.powf(-(j as f64) / 4.0))
        .map(|tol| Ok((tol, dop853.run(&problem, tol, &once)?.error)))
        .collect::<Result<_, String>>()?;
    let mut rows = Vec::new();
    for &tol in tolerances {
        let options = Options::new()
            .method(Method::Taylor)
            .rtol(tol)
            .atol(tol * bench.atol_factor)
            .dense_output(false);
        let sol = model
            .simulate(0.0, bench.t_end, &options)
            .map_err(|e| e.to_string())?;
        let ours_error = mixed_error(sol.final_state(), &reference);
        let bracket = grid
            .windows(2)
            .find(|w| w[0].1 >= ours_error && ours_error >= w[1].1)
            .map(|w| [w[0], w[1]]);
        let mut row = Dop853Row {
            problem: M::NAME,
            tol,
            ratios: Vec::new(),
            ours_error,
            bracket,
        };
        if let Some([(tol_a, err_a), (tol_b, err_b)]) = bracket {
            for round in 0..rounds {
                eprint!(
                    "\r\x1b[2K{} Taylor vs Dop853 {tol:.0e}, round {}",
                    M::NAME,
                    round + 1
                );
                let (ours, _) =
                    median_time(&settings, || model.simulate(0.0, bench.t_end, &options));
                let time_a = dop853.run(&problem, tol_a, &settings)?.seconds;
                let time_b = dop853.run(&problem, tol_b, &settings)?.seconds;
                // log t linear in log error between the two tolerances.
                let s = if err_a == err_b {
                    0.0
                } else {
                    (ours_error / err_a).ln() / (err_b / err_a).ln()
                };
                let theirs = (time_a.ln() + s * (time_b / time_a).ln()).exp();
                row.ratios.push(ours / theirs);
            }
            row.ratios.sort_by(f64::total_cmp);
        }
        rows.push(row);
    }
    Ok(rows)
}

/// The Dop853 rows as a markdown table.
pub fn dop853_markdown(rows: &[Dop853Row], rounds: usize) -> String {
    let mut s = format!(
        "# Taylor vs ode_solvers Dop853, timed in alternation at equal error\n\n{rounds} rounds per tolerance; each round: our median solve time, then Dop853's at the two tolerances of its grid (four a decade) whose errors bracket ours, interpolated log–log to our error; ratio = ours / Dop853's per round.\n\n| problem | tol | our error | Dop853 tolerances (errors) | median ratio (range) |\n|---|---|---|---|---|\n"
    );
    for r in rows {
        let bracket = match r.bracket {
            Some([(ta, ea), (tb, eb)]) => format!("{ta:.1e} ({ea:.1e}), {tb:.1e} ({eb:.1e})"),
            None => "our error out of its reach".into(),
        };
        let ratio = ratio_cell(&r.ratios).unwrap_or_else(|| "—".into());
        s.push_str(&format!(
            "| {} | {:.0e} | {:.1e} | {bracket} | {ratio} |\n",
            r.problem, r.tol, r.ours_error
        ));
    }
    s
}
