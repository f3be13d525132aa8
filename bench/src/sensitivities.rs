//! What forward sensitivities cost (`--sensitivities`,
//! `results/sensitivities.md`): a run of `<Model>Sensitivities` (the
//! states and n_p sensitivity columns) against a run of the model alone,
//! same method and tolerances, as time ratios; the targets are
//! ≤ 1 + 0.5·n_p for the implicit methods (which factor the base model's
//! matrix once for every column) and ≤ 1 + 0.3·n_p for Taylor. Robertson's
//! model with its rates as parameters and Lotka–Volterra are the tests'
//! (`main.rs`).

use crate::*;
use daegen_workprecision::mixed_error;

/// The median of `runs` timings of `run` (at least 5, more while under
/// half a second in all), and the steps of its last run.
fn median_seconds(run: &dyn Fn() -> usize) -> (f64, usize) {
    let mut times = Vec::new();
    let started = Instant::now();
    let mut steps = 0;
    while times.len() < 5 || (times.len() < 201 && started.elapsed().as_secs_f64() < 0.5) {
        let start = Instant::now();
        steps = run();
        times.push(start.elapsed().as_secs_f64());
    }
    times.sort_by(f64::total_cmp);
    (times[times.len() / 2], steps)
}

/// One row: the model alone and with its sensitivities, by `method` at
/// `tol` (atol = tol · `atol_factor`) from 0 to `t1`.
fn row<M, S>(
    text: &mut String,
    (name, model, with): (&str, M, S),
    (method, tol, atol_factor, t1): (Method, f64, f64, f64),
    (columns, controlled): (usize, bool),
    target: f64,
) where
    M: Model + Simulate,
    S: Model + Simulate,
{
    // The same direct linear solver for both (GMRES is not offered with
    // sensitivities).
    let options = Options::new()
        .method(method)
        .rtol(tol)
        .atol(tol * atol_factor)
        .linear_solver(LinearSolver::Direct);
    let alone =
        median_seconds(&|| model.simulate(0.0, t1, &options).map_or(0, |s| s.stats().steps));
    let options = options.sensitivity_error_control(controlled);
    let both = median_seconds(&|| with.simulate(0.0, t1, &options).map_or(0, |s| s.stats().steps));
    let ratio = both.0 / alone.0;
    let (goal, met) = match target {
        t if t.is_finite() => {
            (format!("≤ {t:.1}"), if ratio <= t { "yes" } else { "**no**" }.to_string())
        }
        _ => ("–".to_string(), "–".to_string()),
    };
    text.push_str(&format!(
        "| {name} | {method:?} | {tol:.0e} | {columns} | {} | {:.1} µs ({} steps) | {:.1} µs ({} steps) | {ratio:.2} | {goal} | {met} |\n",
        if controlled { "all" } else { "y only" },
        alone.0 * 1e6,
        alone.1,
        both.0 * 1e6,
        both.1,
    ));
}

/// Writes results/sensitivities.md.
pub fn sensitivities_section() {
    let mut text = format!(
        "# What sensitivities cost\n\nMachine: {}. Written by `cd bench && cargo run --release -- --sensitivities` (bench/src/sensitivities.rs). Each time is the median of at least five runs; the ratio is the run with the sensitivities (states and n_p columns; in the error test with the states, or left out of it by `Options::sensitivity_error_control(false)`) over the model alone, same method and tolerance. Targets: 1 + 0.5·n_p for the implicit methods, 1 + 0.3·n_p for Taylor; the explicit pairs have none (their cost is (1 + n_p) right-hand sides of the base model's size, at best).\n\n| model | method | tol | n_p | error test | alone | with sensitivities | ratio | target | met |\n|---|---|---|---|---|---|---|---|---|---|\n",
        machine()
    );
    let lv = (
        "Lotka–Volterra to t = 10",
        LotkaVolterra::default(),
        LotkaVolterra::default().with_sensitivities(),
    );
    for tol in [1e-8, 1e-12] {
        for method in [Method::Dopri5, Method::Dop853] {
            for controlled in [true, false] {
                let setting = (method, tol, 1.0, 10.0);
                row(&mut text, lv.clone(), setting, (4, controlled), f64::INFINITY);
            }
        }
        for controlled in [true, false] {
            let setting = (Method::Taylor, tol, 1.0, 10.0);
            row(&mut text, lv.clone(), setting, (4, controlled), 1.0 + 0.3 * 4.0);
        }
    }
    let rober = (
        "Robertson to t = 1e5",
        RobertsonRates::default(),
        RobertsonRates::default().with_sensitivities(),
    );
    for tol in [1e-6, 1e-9] {
        for method in [Method::Radau5, Method::Rodas5P] {
            for controlled in [true, false] {
                let setting = (method, tol, 1e-6, 1e5);
                row(&mut text, rober.clone(), setting, (3, controlled), 1.0 + 0.5 * 3.0);
            }
        }
    }
    // A grid whose sparse LU (with its fill-in) dominates a step: the
    // columns share it, and only their vector work is added. The grid
    // lives with the large problems, built with SUNDIALS.
    #[cfg(feature = "sundials")]
    {
        let grid = crate::large::Brusselator2d { forcing: 5.0, ..Default::default() };
        let bruss =
            ("Brusselator 2-D, 32 × 32, forced, to t = 11.5", grid, grid.with_sensitivities());
        for method in [Method::Radau5, Method::Rodas5P] {
            for controlled in [true, false] {
                let setting = (method, 1e-6, 1.0, 11.5);
                row(&mut text, bruss.clone(), setting, (1, controlled), 1.0 + 0.5 * 1.0);
            }
        }
    }
    versus_cvodes(&mut text);
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("results/sensitivities.md");
    if let Err(e) = std::fs::write(&path, &text) {
        eprintln!("cannot write {}: {e}", path.display());
    }
    print!("{text}");
}

/// Robertson's end time and absolute tolerance factor in the comparison
/// with CVODES (as the cost rows above).
const ROBERTSON_END: f64 = 1e5;
const ROBERTSON_ATOL: f64 = 1e-6;
const CVODES_TOLERANCES: [f64; 8] = [1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12];
/// Ours: CVODES reaches their errors at its tighter tolerances.
const OUR_TOLERANCES: [f64; 6] = [1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10];

/// One CVODES run as the peer prints it.
struct CvodesRun {
    rtol: f64,
    sensitivities: bool,
    seconds: f64,
    steps: usize,
    values: Vec<f64>,
}

/// The number after `"key": ` in a line of the peer's JSON.
fn json_number(line: &str, key: &str) -> Option<f64> {
    let rest = &line[line.find(&format!("\"{key}\": "))? + key.len() + 4..];
    rest.split([',', '}']).next()?.trim().parse().ok()
}

/// The peer's runs: built (its own workspace, `peers/cvodes`) and run as a
/// program, or why not.
fn cvodes_runs() -> Result<Vec<CvodesRun>, String> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("peers/cvodes");
    let built = Command::new("cargo")
        .args(["build", "--release", "-q"])
        .current_dir(&dir)
        .status()
        .map_err(|e| format!("cannot run cargo: {e}"))?;
    if !built.success() {
        return Err(
            "the CVODES peer did not build (peers/install-sundials.sh installs CVODES)".into()
        );
    }
    let program =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("target/cvodes-peer/release/daegen-cvodes-peer");
    let mut args = vec![format!("{ROBERTSON_END:e}"), format!("{ROBERTSON_ATOL:e}")];
    args.extend(CVODES_TOLERANCES.iter().map(|t| format!("{t:e}")));
    let out = Command::new(&program)
        .args(&args)
        .output()
        .map_err(|e| format!("cannot run the CVODES peer: {e}"))?;
    let text = String::from_utf8_lossy(&out.stdout);
    let mut runs = Vec::new();
    for line in text.lines() {
        let values = line
            .split("\"values\": [")
            .nth(1)
            .and_then(|v| v.split(']').next())
            .map(|v| v.split(',').filter_map(|x| x.trim().parse().ok()).collect())
            .unwrap_or_default();
        runs.push(CvodesRun {
            rtol: json_number(line, "rtol").ok_or("a line without its tolerance")?,
            sensitivities: line.contains("\"sensitivities\": true"),
            seconds: json_number(line, "seconds").ok_or("a line without its time")?,
            steps: json_number(line, "steps").unwrap_or(0.0) as usize,
            values,
        });
    }
    Ok(runs)
}

/// y(t1) followed by the scaled sensitivities k_j·∂y/∂k_j, column by
/// column: all of order 0.01–1 at t = 1e5, so one mixed error measures them.
fn scaled(values: &[f64]) -> Vec<f64> {
    let rates = [0.04, 3.0e7, 1.0e4];
    values.iter().enumerate().map(|(i, v)| if i < 3 { *v } else { v * rates[i / 3 - 1] }).collect()
}

/// Ours and CVODES with forward sensitivities on Robertson, at matched
/// error in the states and the scaled sensitivities.
fn versus_cvodes(text: &mut String) {
    text.push_str("\n## Against CVODES\n\nRobertson to t = 1e5 with the sensitivities to k1, k2, k3, atol = 1e-6·rtol. CVODES (BDF, staggered corrector, dense LU with the analytic Jacobian and analytic sensitivity right-hand sides, tolerances estimated from p̄ = k, sensitivities in the error test: its example `cvsRoberts_FSA_dns`) runs as its own program (bench/peers/cvodes: CVODE and CVODES export the same symbols). Error: max |v − ref| / max(1, |ref|) over y(t1) and the scaled sensitivities k_j·∂y_i/∂k_j (−0.79 … 0.79); reference: RADAU5 at rtol 1e-12, atol 1e-20. Ratio: our time over CVODES's at our error, its curve interpolated log–log (–: outside the errors it reached). CVODES's own cost of the sensitivities is its time with them over its time without, same tolerance.\n\n");
    let runs = match cvodes_runs() {
        Ok(runs) if !runs.is_empty() => runs,
        Ok(_) => {
            text.push_str("The CVODES peer printed nothing.\n");
            return;
        }
        Err(why) => {
            text.push_str(&format!("No comparison: {why}.\n"));
            return;
        }
    };
    let model = RobertsonRates::default().with_sensitivities();
    let tight = Options::new().method(Method::Radau5).rtol(1e-12).atol(1e-20);
    let Some(reference) =
        model.simulate(0.0, ROBERTSON_END, &tight).ok().map(|s| scaled(s.final_state()))
    else {
        text.push_str("No comparison: the reference run failed.\n");
        return;
    };
    let cvodes: Vec<Record> = runs
        .iter()
        .filter(|r| r.sensitivities)
        .map(|r| Record {
            problem: "Robertson".into(),
            method: "CVODES".into(),
            tol: r.rtol,
            error: mixed_error(&scaled(&r.values), &reference),
            seconds: r.seconds,
            steps: r.steps,
            rejected: 0,
            rhs_evals: 0,
            jacobian_evals: 0,
        })
        .collect();
    let curve: Vec<&Record> = cvodes.iter().collect();
    text.push_str("| solver | rtol | error | time | steps | ratio to CVODES | own cost of the sensitivities |\n|---|---|---|---|---|---|---|\n");
    for r in &cvodes {
        let alone = runs.iter().find(|a| !a.sensitivities && a.rtol == r.tol);
        let own = alone.map_or("–".into(), |a| format!("{:.2}×", r.seconds / a.seconds));
        text.push_str(&format!(
            "| CVODES | {:.0e} | {:.1e} | {:.1} µs | {} | – | {own} |\n",
            r.tol,
            r.error,
            r.seconds * 1e6,
            r.steps
        ));
    }
    let base = RobertsonRates::default();
    for method in [Method::Radau5, Method::Rodas5P] {
        for tol in OUR_TOLERANCES {
            let options = Options::new().method(method).rtol(tol).atol(tol * ROBERTSON_ATOL);
            let run = || model.simulate(0.0, ROBERTSON_END, &options).ok();
            let (seconds, _) = median_seconds(&|| run().map_or(0, |s| s.stats().steps));
            let (alone, _) = median_seconds(&|| {
                base.simulate(0.0, ROBERTSON_END, &options).map_or(0, |s| s.stats().steps)
            });
            let Some(sol) = run() else {
                text.push_str(&format!(
                    "| daegen {method:?} | {tol:.0e} | failed | – | – | – | – |\n"
                ));
                continue;
            };
            let error = mixed_error(&scaled(sol.final_state()), &reference);
            let ratio = daegen_workprecision::time_at_error(&curve, error)
                .map_or("–".into(), |t| format!("{:.2}×", seconds / t));
            text.push_str(&format!(
                "| daegen {method:?} | {tol:.0e} | {error:.1e} | {:.1} µs | {} | {ratio} | {:.2}× |\n",
                seconds * 1e6,
                sol.stats().steps,
                seconds / alone
            ));
        }
    }
}
