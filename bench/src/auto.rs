//! `Method::Auto` against the best of the single methods it chooses among
//! (DOPRI5, DOP853, RADAU5, RODAS5P) on every reference problem, stiff and
//! non-stiff, at equal tolerance; and an explicit pair on a stiff problem
//! until its stiffness error, with the peak memory of the run.
//!
//! Each tolerance is timed in rounds, every method once per round (median
//! of repeats), so the machine's load moves all of them alike; the figure
//! is the median over rounds of Auto's time over the fastest single
//! method's in that round. A single method that fails (an explicit pair on
//! a stiff problem stops with `Error::Stiff`) takes no part.

use crate::*;
use daegen_workprecision::{median_time, mixed_error, Settings};
use std::time::Duration;

/// The Oregonator (IVP test set `orego`).
#[dae_model]
fn orego() {
    let y1 = state(1.0);
    let y2 = state(2.0);
    let y3 = state(3.0);
    der(y1) == 77.27 * (y2 + y1 * (1.0 - 8.375e-6 * y1 - y2));
    der(y2) == (y3 - (1.0 + y1) * y2) / 77.27;
    der(y3) == 0.161 * (y1 - y3);
}

/// Published at t = 360 (test set orego.f; reference-problems.md §12a).
const OREGO_AT_360: [f64; 3] = [0.1000814870318523e1, 0.1228178521549917e4, 0.1320554942846706e3];

const METHODS: [Method; 4] = [Method::Dopri5, Method::Dop853, Method::Radau5, Method::Rodas5P];

/// One problem at one tolerance.
struct Row {
    problem: &'static str,
    tol: f64,
    /// The fastest single method (by its median over rounds).
    best: Method,
    /// Auto's time over the fastest single method's, per round, sorted.
    ratios: Vec<f64>,
    auto_time: f64,
    auto_error: f64,
    best_error: f64,
    chain: &'static str,
}

/// Times Auto and the single methods on `M` from 0 to `t1` in `rounds`.
fn compare<M: Model + Clone + Send + Sync + 'static>(
    model: M,
    problem: &'static str,
    t1: f64,
    reference: &[f64],
    atol_factor: f64,
    rounds: usize,
) -> Vec<Row> {
    let settings = Settings {
        min_repeats: 3,
        max_repeats: 100,
        budget: Duration::from_millis(100),
        tightest: 0.0,
        rounds: 1,
    };
    let mut rows = Vec::new();
    for tol in [1e-4, 1e-6, 1e-8, 1e-10] {
        eprint!("\r\x1b[2Kauto: {problem} at {tol:e}");
        let options = |m: Method| Options::new().method(m).rtol(tol).atol(tol * atol_factor);
        let run = |m: Method| model.simulate(0.0, t1, &options(m));
        let error = |s: &Solution| mixed_error(s.final_state(), reference);
        // The single methods that finish.
        let finishing: Vec<Method> = METHODS.into_iter().filter(|&m| run(m).is_ok()).collect();
        let Ok(auto) = run(Method::Auto) else {
            eprintln!("\nauto: {problem} at {tol:e} failed");
            continue;
        };
        if finishing.is_empty() {
            continue;
        }
        let mut times = vec![Vec::new(); finishing.len()];
        let (mut ratios, mut auto_times) = (Vec::new(), Vec::new());
        for _ in 0..rounds {
            let (a, _) = median_time(&settings, || run(Method::Auto));
            let singles: Vec<f64> =
                finishing.iter().map(|&m| median_time(&settings, || run(m)).0).collect();
            for (k, t) in singles.iter().enumerate() {
                times[k].push(*t);
            }
            ratios.push(a / singles.iter().copied().fold(f64::INFINITY, f64::min));
            auto_times.push(a);
        }
        let median = |v: &mut Vec<f64>| {
            v.sort_by(f64::total_cmp);
            v[v.len() / 2]
        };
        let best = (0..finishing.len())
            .min_by(|&a, &b| {
                median(&mut times[a].clone()).total_cmp(&median(&mut times[b].clone()))
            })
            .map(|k| finishing[k])
            .unwrap_or(Method::Radau5);
        let best_error = run(best).map(|s| error(&s)).unwrap_or(f64::NAN);
        ratios.sort_by(f64::total_cmp);
        rows.push(Row {
            problem,
            tol,
            best,
            auto_time: median(&mut auto_times),
            ratios,
            auto_error: error(&auto),
            best_error,
            chain: auto.stats().method,
        });
    }
    rows
}

/// An explicit pair on Robertson to t = 1e5, in a child process so its
/// peak memory is its own: steps, time, peak resident memory and the end.
pub fn stiff_probe(method: &str, detect: bool) {
    let method = if method == "Dop853" { Method::Dop853 } else { Method::Dopri5 };
    let options = Options::new().method(method).stiffness_detection(detect);
    let start = std::time::Instant::now();
    let result = Robertson::default().simulate(0.0, 1e5, &options);
    let seconds = start.elapsed().as_secs_f64();
    let (steps, outcome) = match &result {
        Ok(s) => (s.stats().steps, "reached t = 1e5".to_string()),
        Err(e) => (
            e.partial_solution().map_or(0, |s| s.stats().steps),
            match e {
                Error::Stiff { t, onset, .. } => {
                    format!("Error::Stiff at t = {t:.3e} (stiff from {onset:.3e})")
                }
                Error::MaxSteps { t, .. } => format!("Error::MaxSteps at t = {t:.1}"),
                other => format!("{other}"),
            },
        ),
    };
    let peak_kb = std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM:"))
                .and_then(|l| l.split_whitespace().nth(1))
                .and_then(|v| v.parse::<f64>().ok())
        })
        .unwrap_or(f64::NAN);
    println!("{steps}\t{seconds}\t{peak_kb}\t{outcome}");
}

/// `--auto`: both tables, written to `results/auto.md`.
pub fn auto_section() {
    let rounds = 5;
    let mut rows = Vec::new();
    rows.extend(compare(
        Kepler::default(),
        "kepler (e = 0.9, 10 orbits)",
        20.0 * std::f64::consts::PI,
        &kepler_exact(20.0 * std::f64::consts::PI),
        1.0,
        rounds,
    ));
    rows.extend(compare(
        Arenstorf::default(),
        "arenstorf (one period)",
        ARENSTORF_T,
        &ARENSTORF_Y0,
        1.0,
        rounds,
    ));
    rows.extend(compare(Lorenz::default(), "lorenz (t = 20)", 20.0, &LORENZ_AT_20, 1.0, rounds));
    rows.extend(compare(
        OuterSolarSystem::default(),
        "outer solar system (20 000 days)",
        20000.0,
        &OSS_REFERENCE,
        1.0,
        rounds,
    ));
    let filter = LowPass::default();
    let exact = [low_pass_exact(1.0, filter.tau, filter.omega)];
    rows.extend(compare(
        filter,
        "low-pass filter (τ = 2e-4, 5 Hz, t = 1)",
        1.0,
        &exact,
        1.0,
        rounds,
    ));
    let rc = LowPass { tau: 1e-4, omega: 2.0 * std::f64::consts::PI };
    let exact = [low_pass_exact(2.0, rc.tau, rc.omega)];
    rows.extend(compare(rc, "RC circuit (RC = 1e-4, 1 Hz, t = 2)", 2.0, &exact, 1.0, rounds));
    rows.extend(compare(
        VanDerPol::default(),
        "van der Pol (ε = 1e-6, t = 2)",
        2.0,
        &VDP_AT_2,
        1.0,
        rounds,
    ));
    rows.extend(compare(
        Robertson::default(),
        "robertson (t = 1e11, atol = 1e-6·rtol)",
        1e11,
        &ROBER_AT_1E11,
        1e-6,
        rounds,
    ));
    rows.extend(compare(Hires::default(), "hires", 321.8122, &HIRES_AT_END, 1.0, rounds));
    rows.extend(compare(Orego::default(), "orego (t = 360)", 360.0, &OREGO_AT_360, 1.0, rounds));
    eprintln!("\r\x1b[2Kauto: explicit pairs on Robertson");
    let mut text = format!(
        "# `Method::Auto` against the single methods\n\nMachine: {}. Written by `cd bench && cargo run --release -- --auto` (bench/src/auto.rs).\n\n",
        machine()
    );
    text.push_str("## Auto against the best single method\n\nAt equal tolerance (rtol = atol = tol, Robertson atol = 1e-6·tol), the single methods being DOPRI5, DOP853, RADAU5 and RODAS5P (those `Auto` chooses among; an explicit pair that stops with `Error::Stiff` takes no part). Time ratio: Auto's median solve over the fastest single method's, per round of all methods, median (range) over 5 rounds. Errors are max |y − ref| / max(1, |ref|) at the end against the published or exact solution. Goal: ≤ 2×.\n\n| problem | tol | Auto ran | Auto time | best single | ratio (range) | Auto error | best's error |\n|---|---|---|---|---|---|---|---|\n");
    for r in &rows {
        let (lo, mid, hi) =
            (r.ratios[0], r.ratios[r.ratios.len() / 2], r.ratios[r.ratios.len() - 1]);
        text.push_str(&format!(
            "| {} | {:.0e} | {} | {:.3} ms | {:?} | {}{mid:.2}× ({lo:.2}–{hi:.2}){} | {:.1e} | {:.1e} |\n",
            r.problem,
            r.tol,
            r.chain,
            r.auto_time * 1e3,
            r.best,
            if mid > 2.0 { "**" } else { "" },
            if mid > 2.0 { "**" } else { "" },
            r.auto_error,
            r.best_error,
        ));
    }
    let within = rows.iter().filter(|r| r.ratios[r.ratios.len() / 2] <= 2.0).count();
    text.push_str(&format!("\n{within} of {} rows within 2×.\n", rows.len()));
    text.push_str("\n## An explicit pair on a stiff problem\n\nRobertson from t = 0 to 1e5 at the default tolerances (rtol 1e-6, atol 1e-9), each run in a child process: its steps, time and peak resident memory (VmHWM, the whole process). With stiffness detection (the default) the pair stops with `Error::Stiff`; without it (`Options::stiffness_detection(false)`), as before, it runs into the 10⁷-step limit.\n\n| method | stiffness detection | steps | time | peak memory | end |\n|---|---|---|---|---|---|\n");
    let exe = std::env::current_exe().expect("the benchmark's own path");
    for method in ["Dopri5", "Dop853"] {
        for detect in [true, false] {
            let out = std::process::Command::new(&exe)
                .args(["--stiff-probe", method, if detect { "on" } else { "off" }])
                .output();
            let line = out
                .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
                .unwrap_or_default();
            let f: Vec<&str> = line.split('\t').collect();
            if f.len() == 4 {
                let seconds: f64 = f[1].parse().unwrap_or(f64::NAN);
                let peak: f64 = f[2].parse().unwrap_or(f64::NAN);
                text.push_str(&format!(
                    "| {method} | {} | {} | {:.3} s | {:.1} MB | {} |\n",
                    if detect { "on" } else { "off" },
                    f[0],
                    seconds,
                    peak / 1024.0,
                    f[3]
                ));
            }
        }
    }
    let out = Path::new(env!("CARGO_MANIFEST_DIR")).join("results").join("auto.md");
    let _ = std::fs::write(&out, &text);
    eprintln!("\r\x1b[2Kdone");
    println!("{text}");
}
