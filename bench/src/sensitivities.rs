//! What forward sensitivities cost (`--sensitivities`,
//! `results/sensitivities.md`): a run of `<Model>Sensitivities` (the
//! states and n_p sensitivity columns) against a run of the model alone,
//! same method and tolerances, as time ratios; the targets are
//! ≤ 1 + 0.5·n_p for the implicit methods (which factor the base model's
//! matrix once for every column) and ≤ 1 + 0.3·n_p for Taylor. Robertson's
//! model with its rates as parameters is the tests' (`main.rs`).

use crate::*;

/// Lotka–Volterra, x′ = a·x − b·x·y, y′ = c·x·y − d·y (non-stiff), with
/// the sensitivities to its four rates.
#[dae_model(sensitivities = [a, b, c, d])]
fn lotka_volterra() {
    let a = param(1.5);
    let b = param(1.0);
    let c = param(1.0);
    let d = param(3.0);
    let x = state(10.0);
    let y = state(5.0);
    der(x) == a * x - b * x * y;
    der(y) == c * x * y - d * y;
}

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
    let options = Options::new().method(method).rtol(tol).atol(tol * atol_factor);
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
        row(&mut text, lv.clone(), (Method::Taylor, tol, 1.0, 10.0), (4, true), 1.0 + 0.3 * 4.0);
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
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("results/sensitivities.md");
    if let Err(e) = std::fs::write(&path, &text) {
        eprintln!("cannot write {}: {e}", path.display());
    }
    print!("{text}");
}
