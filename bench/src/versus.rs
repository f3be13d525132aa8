//! Our Taylor method against heyoka, timed in alternation: heyoka runs in
//! another process, so the sweep times it seconds or minutes after us, and
//! on this shared machine the load moves sub-millisecond solves by ±40 %
//! in that time. Here each round times ours (median of repeats) and then
//! heyoka (median of `HEYOKA_REPEATS` solves in peer.py), and the ratio is
//! taken per round; the median over rounds is the figure.
//!
//! Equal tolerance is not equal error: our order follows the model's cost
//! (`runtime/src/methods/taylor/order.rs`), heyoka's the tolerance alone. So, as
//! against Dop853 below, heyoka's errors are first scanned on a grid of
//! tolerances four to a decade, and each round times it at the two whose
//! errors bracket ours, its time at our error interpolated log–log. Each
//! round also times ours at heyoka's own order (Jorba & Zou's, the same
//! steps as heyoka at the same tolerance) against heyoka at that
//! tolerance: the generated code's speed alone, without the order.
//!
//! Against `ode_solvers`' Dop853, in the same process, equal error is not
//! equal tolerance: its errors are first scanned on a grid of tolerances
//! four to a decade, and each round times ours and Dop853 at the two
//! tolerances whose errors bracket ours, its time at our error
//! interpolated log–log between them, as the sweep does.

use crate::peers::{array, field, OdeSolvers, Python, HEYOKA_REPEATS};
use daegen::prelude::*;
use daegen::runtime::taylor_order::jorba_zou_order;
use daegen_workprecision::{
    expansion_cost, function_operations, median_time, mixed_error, reference_values,
    taylor_jet_operations, Benchmark, Peer, PeerProblem, Record, Settings,
};

/// A peer's error on a grid of tolerances four a decade, 10^(−lo/4) to
/// 10^(−hi/4), from one solve each.
fn error_grid(
    lo: usize,
    hi: usize,
    error_at: impl Fn(f64) -> Result<f64, String>,
) -> Result<Vec<(f64, f64)>, String> {
    (lo..=hi).map(|j| 10f64.powf(-(j as f64) / 4.0)).map(|tol| Ok((tol, error_at(tol)?))).collect()
}

/// The two neighbouring tolerances of the grid whose errors bracket
/// `error`.
fn bracket(grid: &[(f64, f64)], error: f64) -> Option<[(f64, f64); 2]> {
    grid.windows(2).find(|w| w[0].1 >= error && error >= w[1].1).map(|w| [w[0], w[1]])
}

/// The peer's time at `error` from its times at the bracket's two
/// tolerances: log t linear in log error between them.
fn time_at_error(
    error: f64,
    [(_, err_a), (_, err_b)]: [(f64, f64); 2],
    time_a: f64,
    time_b: f64,
) -> f64 {
    let s = if err_a == err_b { 0.0 } else { (error / err_a).ln() / (err_b / err_a).ln() };
    (time_a.ln() + s * (time_b / time_a).ln()).exp()
}

/// One tolerance of one problem.
pub struct Row {
    pub problem: &'static str,
    pub tol: f64,
    /// Our time over heyoka's at our error, per round, sorted; empty when
    /// heyoka's grid does not reach our error.
    pub ratios: Vec<f64>,
    /// Ours at heyoka's order over heyoka at the same tolerance (the same
    /// steps), per round, sorted.
    pub same_order_ratios: Vec<f64>,
    pub ours_order: usize,
    pub ours_steps: usize,
    pub ours_error: f64,
    /// heyoka's two tolerances and errors around our error.
    pub bracket: Option<[(f64, f64); 2]>,
    /// Ours at heyoka's order, and heyoka, at this tolerance.
    pub same_order_steps: usize,
    pub same_order_error: f64,
    pub heyoka_steps: usize,
    pub heyoka_error: f64,
}

/// `rounds` alternating timings of `M` with `Method::Taylor` and heyoka at
/// each tolerance; an error when the model has no peer problem or heyoka
/// is missing.
pub fn versus_heyoka<M: Benchmark>(tolerances: &[f64], rounds: usize) -> Result<Vec<Row>, String> {
    let bench = M::bench();
    let peer = bench.peer.ok_or("no peer problem")?;
    let reference = reference_values::<M>(&bench)?;
    let heyoka = Python { solver: "heyoka" };
    let atol = |tol: f64| (bench.atol_factor != 1.0).then_some(tol * bench.atol_factor);
    // peer.py's own error where it has the reference; else ours.
    let heyoka_error = |text: &str| {
        field(text, "max_mixed_err")
            .or_else(|| array(text, "y_end").map(|y| mixed_error(&y, &reference)))
            .unwrap_or(f64::NAN)
    };
    let heyoka_time = |tol: f64| -> Result<f64, String> {
        let text = heyoka.call(peer, tol, atol(tol), HEYOKA_REPEATS)?;
        field(&text, "solve_s").ok_or_else(|| "peer.py printed no solve_s".to_string())
    };
    eprint!("\r\x1b[2K{} heyoka's errors on the grid", M::NAME);
    let grid =
        error_grid(36, 64, |tol| Ok(heyoka_error(&heyoka.call(peer, tol, atol(tol), 1)?)))?;
    let model = M::default();
    let settings = Settings::default();
    let mut rows = Vec::new();
    for &tol in tolerances {
        let options = Options::new()
            .method(Method::Taylor)
            .rtol(tol)
            .atol(tol * bench.atol_factor)
            .dense_output(false);
        let same_order = options.taylor_order(jorba_zou_order(tol));
        let run = |o: &Options| model.simulate(0.0, bench.t_end, o).map_err(|e| e.to_string());
        let (sol, same) = (run(&options)?, run(&same_order)?);
        let text = heyoka.call(peer, tol, atol(tol), 1)?;
        let ours_error = mixed_error(sol.final_state(), &reference);
        let mut row = Row {
            problem: M::NAME,
            tol,
            ratios: Vec::new(),
            same_order_ratios: Vec::new(),
            ours_order: sol.stats().taylor_order,
            ours_steps: sol.stats().steps,
            ours_error,
            bracket: bracket(&grid, ours_error),
            same_order_steps: same.stats().steps,
            same_order_error: mixed_error(same.final_state(), &reference),
            heyoka_steps: field(&text, "steps").unwrap_or(f64::NAN) as usize,
            heyoka_error: heyoka_error(&text),
        };
        for round in 0..rounds {
            eprint!("\r\x1b[2K{} Taylor vs heyoka {tol:.0e}, round {}", M::NAME, round + 1);
            let (ours, _) = median_time(&settings, || run(&options));
            let (ours_same, _) = median_time(&settings, || run(&same_order));
            row.same_order_ratios.push(ours_same / heyoka_time(tol)?);
            if let Some(b @ [(tol_a, _), (tol_b, _)]) = row.bracket {
                let theirs = time_at_error(ours_error, b, heyoka_time(tol_a)?, heyoka_time(tol_b)?);
                row.ratios.push(ours / theirs);
            }
        }
        row.ratios.sort_by(f64::total_cmp);
        row.same_order_ratios.sort_by(f64::total_cmp);
        rows.push(row);
    }
    Ok(rows)
}

/// The rows as a markdown table.
pub fn markdown(rows: &[Row], rounds: usize) -> String {
    let mut s = format!(
        "# Taylor vs heyoka, timed in alternation\n\n{rounds} rounds per tolerance; each round: our median solve time, then heyoka's (median of {HEYOKA_REPEATS} solves) at the two tolerances of its grid (four a decade) whose errors bracket ours, interpolated log–log to our error; then ours at heyoka's order (Jorba & Zou's, the same steps) against heyoka at the same tolerance. Ratio = ours / heyoka's per round.\n\n| problem | tol | our order, steps, error | heyoka tolerances (errors) | ratio at equal error | at heyoka's order: steps ours / heyoka, errors ours / heyoka | ratio at the same order |\n|---|---|---|---|---|---|---|\n"
    );
    for r in rows {
        let bracket = bracket_cell(r.bracket);
        let ratio = ratio_cell(&r.ratios).unwrap_or_else(|| "—".into());
        let same = ratio_cell(&r.same_order_ratios).unwrap_or_else(|| "—".into());
        s.push_str(&format!(
            "| {} | {:.0e} | {}, {}, {:.1e} | {bracket} | {ratio} | {} / {}, {:.1e} / {:.1e} | {same} |\n",
            r.problem, r.tol, r.ours_order, r.ours_steps, r.ours_error, r.same_order_steps, r.heyoka_steps, r.same_order_error, r.heyoka_error
        ));
    }
    s
}

/// The peer's two tolerances (and errors) around ours, or why there are
/// none.
fn bracket_cell(bracket: Option<[(f64, f64); 2]>) -> String {
    match bracket {
        Some([(ta, ea), (tb, eb)]) => format!("{ta:.1e} ({ea:.1e}), {tb:.1e} ({eb:.1e})"),
        None => "our error out of its reach".into(),
    }
}

/// `median× (least–largest)` of sorted ratios, if there are any.
fn ratio_cell(ratios: &[f64]) -> Option<String> {
    let (first, median, last) = (ratios.first()?, ratios.get(ratios.len() / 2)?, ratios.last()?);
    Some(format!("{median:.2}× ({first:.2}–{last:.2})"))
}

/// One tolerance of one problem against `ode_solvers`' Dop853.
pub struct Dop853Row {
    pub problem: &'static str,
    pub tol: f64,
    /// Our time over Dop853's at our error, per round, sorted; empty when
    /// Dop853 does not reach our error on the grid.
    pub ratios: Vec<f64>,
    /// Our method, "Taylor" or "DOP853".
    pub method: &'static str,
    /// Taylor's order (0 for DOP853).
    pub ours_order: usize,
    pub ours_error: f64,
    /// Dop853's two tolerances and errors around ours.
    pub bracket: Option<[(f64, f64); 2]>,
    /// Floating-point operations of our solve and of Dop853's at our
    /// error (see [`Work`]), when the generated code could be counted.
    pub work: Option<(f64, f64)>,
    /// Our median solve time over the rounds, in seconds.
    pub ours_seconds: f64,
}

/// The arithmetic a solve does, counted in the generated code
/// (`daegen_workprecision::function_operations`) and in the methods'
/// tableaus: what separates a method that wins by doing less from one
/// that wins by doing the same faster.
struct Work {
    /// Operations of one right-hand side.
    rhs: f64,
    /// The model's generated code, for its jets.
    code: String,
    /// States.
    n: f64,
}

impl Work {
    /// A DOP853 solve (ours or `ode_solvers`'): its right-hand sides and,
    /// per step tried, the stage sums and error estimate of
    /// `dop853::operations_per_state`.
    fn dop853(&self, rhs_evals: usize, steps_tried: usize) -> f64 {
        let per_state = daegen::runtime::dop853::operations_per_state() as f64;
        rhs_evals as f64 * self.rhs + steps_tried as f64 * self.n * per_state
    }

    /// A Taylor solve at an unrolled order: per step its jet and its state
    /// update; None for the interpreted tape.
    fn taylor(&self, order: usize, steps: usize) -> Option<f64> {
        let jet = taylor_jet_operations(&self.code, order)? as f64;
        let update = daegen::runtime::taylor::update_operations_per_state(order) as f64;
        Some(steps as f64 * (jet + self.n * update))
    }
}

/// `rounds` alternating timings of `M` with `Method::Taylor` and
/// `ode_solvers`' Dop853 at our error, per tolerance.
pub fn versus_dop853<M: Benchmark>(
    tolerances: &[f64],
    rounds: usize,
) -> Result<Vec<Dop853Row>, String> {
    ours_versus_dop853::<M>(Method::Taylor, tolerances, rounds)
}

/// [`versus_dop853`] with our DOP853 instead: the same method on both
/// sides, timed in alternation (the sweep times them minutes apart).
pub fn dop853_versus_dop853<M: Benchmark>(
    tolerances: &[f64],
    rounds: usize,
) -> Result<Vec<Dop853Row>, String> {
    ours_versus_dop853::<M>(Method::Dop853, tolerances, rounds)
}

/// `rounds` alternating timings of `M` with `method` and `ode_solvers`'
/// Dop853 at our error, per tolerance.
fn ours_versus_dop853<M: Benchmark>(
    method: Method,
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
    let work = expansion_cost(M::SOURCE, M::ATTRIBUTES, 1).ok().and_then(|cost| {
        Some(Work {
            rhs: function_operations(&cost.code, "rhs")? as f64,
            code: cost.code,
            n: M::STATES as f64,
        })
    });
    let dop853 = OdeSolvers { dop853: true };
    let settings = Settings::default();
    let once = Settings { min_repeats: 1, max_repeats: 1, ..Settings::default() };
    // Dop853's error on the grid 1e-8 … 1e-16, four tolerances a decade,
    // and its runs there for their work.
    let runs: Vec<Record> = (32..=64)
        .map(|j| dop853.run(&problem, 10f64.powf(-(j as f64) / 4.0), &once))
        .collect::<Result<_, _>>()?;
    let grid: Vec<(f64, f64)> = runs.iter().map(|r| (r.tol, r.error)).collect();
    let run_at = |tol: f64| runs.iter().find(|r| r.tol == tol);
    let mut rows = Vec::new();
    for &tol in tolerances {
        let options = Options::new()
            .method(method.clone())
            .rtol(tol)
            .atol(tol * bench.atol_factor)
            .dense_output(false);
        let sol = model.simulate(0.0, bench.t_end, &options).map_err(|e| e.to_string())?;
        let ours_error = mixed_error(sol.final_state(), &reference);
        let mut row = Dop853Row {
            method: match method {
                Method::Taylor => "Taylor",
                _ => "DOP853",
            },
            problem: M::NAME,
            tol,
            ratios: Vec::new(),
            ours_order: sol.stats().taylor_order,
            ours_error,
            bracket: bracket(&grid, ours_error),
            work: None,
            ours_seconds: f64::NAN,
        };
        // Our arithmetic and Dop853's at our error, interpolated log–log
        // between the bracket's two runs as its time is.
        if let (Some(w), Some(b @ [(tol_a, _), (tol_b, _)])) = (&work, row.bracket) {
            let stats = sol.stats();
            let ours = match method {
                Method::Taylor => w.taylor(stats.taylor_order, stats.steps),
                _ => Some(w.dop853(stats.rhs_evals, stats.steps + stats.rejected)),
            };
            let theirs =
                |tol: f64| run_at(tol).map(|r| w.dop853(r.rhs_evals, r.steps + r.rejected));
            if let (Some(ours), Some(a), Some(b_work)) = (ours, theirs(tol_a), theirs(tol_b)) {
                row.work = Some((ours, time_at_error(ours_error, b, a, b_work)));
            }
        }
        if let Some(b @ [(tol_a, _), (tol_b, _)]) = row.bracket {
            let mut times = Vec::new();
            for round in 0..rounds {
                eprint!("\r\x1b[2K{} {method:?} vs Dop853 {tol:.0e}, round {}", M::NAME, round + 1);
                let (ours, _) =
                    median_time(&settings, || model.simulate(0.0, bench.t_end, &options));
                let time_a = dop853.run(&problem, tol_a, &settings)?.seconds;
                let time_b = dop853.run(&problem, tol_b, &settings)?.seconds;
                row.ratios.push(ours / time_at_error(ours_error, b, time_a, time_b));
                times.push(ours);
            }
            row.ratios.sort_by(f64::total_cmp);
            times.sort_by(f64::total_cmp);
            row.ours_seconds = times[times.len() / 2];
        }
        rows.push(row);
    }
    Ok(rows)
}

/// The Dop853 rows as a markdown table.
pub fn dop853_markdown(rows: &[Dop853Row], rounds: usize) -> String {
    let method = rows.first().map_or("Taylor", |r| r.method);
    let mut s = format!(
        "# {method} vs ode_solvers Dop853, timed in alternation at equal error\n\n{rounds} rounds per tolerance; each round: our median solve time, then Dop853's at the two tolerances of its grid (four a decade) whose errors bracket ours, interpolated log–log to our error; ratio = ours / Dop853's per round.\n\nArithmetic: the floating-point operations of a solve, counted in the generated code (a jet or right-hand side; loops by their trips) and in the methods' updates (DOP853's stage sums and error estimate over the tableau's nonzero coefficients, per step tried; Taylor's Horner sums and norms), Dop853's interpolated to our error as its time is. Operations per second = arithmetic ratio / time ratio: how much faster than Dop853's our code computes (ours in Gop/s after it, an FMA one operation). To be k× faster, a method doing r× Dop853's arithmetic must compute r·k× as fast.\n\n| problem | tol | our order, error | Dop853 tolerances (errors) | median ratio (range) | arithmetic, ours / Dop853's | our operations per second / Dop853's (ours) |\n|---|---|---|---|---|---|---|\n"
    );
    for r in rows {
        let bracket = bracket_cell(r.bracket);
        let ratio = ratio_cell(&r.ratios).unwrap_or_else(|| "—".into());
        let order = match r.ours_order {
            0 => "—".to_string(),
            p => p.to_string(),
        };
        let median = r.ratios.get(r.ratios.len() / 2);
        let (arithmetic, rate) = match (r.work, median) {
            (Some((ours, theirs)), Some(time)) => (
                format!("{ours:.2e} / {theirs:.2e} = {:.2}", ours / theirs),
                format!("{:.1}× ({:.1} Gop/s)", ours / theirs / time, ours / r.ours_seconds / 1e9),
            ),
            _ => ("—".into(), "—".into()),
        };
        s.push_str(&format!(
            "| {} | {:.0e} | {order}, {:.1e} | {bracket} | {ratio} | {arithmetic} | {rate} |\n",
            r.problem, r.tol, r.ours_error
        ));
    }
    s
}
