//! Large stiff problems (`--large`, `results/large.md`): the Brusselator
//! in one space dimension (1000 states, banded) and in two (2048 states,
//! sparse), written with loops in the model language. For each: the
//! macro's expansion time and rustc's on the generated code, a reference
//! from RADAU5 at rtol 1e-11 checked against CVODE at the same tolerance
//! (the run fails where they differ by more than 1e-6),
//! and RADAU5 against CVODE (band LU or KLU, the Jacobian the macro
//! generated), RADAU5 from rtol 1e-4 to 1e-8 and CVODE on to 1e-11, the
//! ratio at matched error.

use super::*;
use crate::dae::{time_at_error, Point};

/// The Brusselator in one space dimension (Hairer & Wanner II, §IV.1,
/// problem BRUS): u′ = 1 + u²v − 4u + α(N+1)² u_xx, v′ = 3u − u²v +
/// α(N+1)² v_xx on N = 500 interior points x_i = i/(N+1), u = 1 and v = 3
/// on the boundary, from u = 1 + sin(2πx), v = 3, to t = 10. Each point's
/// u and v side by side, as Hairer and Wanner order them, so that the
/// Jacobian is a band of width 2 on either side.
#[dae_model(bench = Bench::until(10.0).methods([Radau5]).tolerances(4, 8))]
fn brusselator_1d() {
    const N: usize = 500;
    const PI: f64 = 3.141592653589793;
    let alpha = param(0.02);
    let w = state_array((0..2 * N).map(|k| {
        if k % 2 == 0 {
            1.0 + sin(2.0 * PI * ((k / 2 + 1) as f64) / ((N + 1) as f64))
        } else {
            3.0
        }
    }));
    let c = alpha * (((N + 1) * (N + 1)) as f64);
    for i in 0..N {
        let u = w[2 * i];
        let v = w[2 * i + 1];
        let u_left = if i == 0 { 1.0 } else { w[2 * i - 2] };
        let v_left = if i == 0 { 3.0 } else { w[2 * i - 1] };
        let u_right = if i + 1 == N { 1.0 } else { w[2 * i + 2] };
        let v_right = if i + 1 == N { 3.0 } else { w[2 * i + 3] };
        der(w[2 * i]) == 1.0 + u * u * v - 4.0 * u + c * (u_left - 2.0 * u + u_right);
        der(w[2 * i + 1]) == 3.0 * u - u * u * v + c * (v_left - 2.0 * v + v_right);
    }
}

/// The Brusselator in two space dimensions (Hairer & Wanner II, §IV.10,
/// BRUSS-2D): u′ = 1 + u²v − 4.4u + α Δu + f, v′ = 3.4u − u²v + α Δv,
/// α = 0.1, on a 32 × 32 grid of [0, 1]² (Δx = 1/31, periodic
/// neighbours, as SciMLBenchmarks discretise it), from u = 22 y(1 − y)^1.5,
/// v = 27 x(1 − x)^1.5, to t = 11.5; the forcing f = 5 in the disc of
/// radius 0.1 about (0.3, 0.6) from t = 1.1 on (`forcing`, set by the run).
#[dae_model(bench = Bench::until(11.5).methods([Radau5]).tolerances(4, 8))]
fn brusselator_2d() {
    const N: usize = 32;
    let alpha = param(0.1);
    let forcing = param(0.0);
    let u = state_array((0..N * N).map(|k| {
        22.0 * (((k % N) as f64) / ((N - 1) as f64))
            * (1.0 - ((k % N) as f64) / ((N - 1) as f64)).powf(1.5)
    }));
    let v = state_array((0..N * N).map(|k| {
        27.0 * (((k - k % N) / N) as f64 / ((N - 1) as f64))
            * (1.0 - ((k - k % N) / N) as f64 / ((N - 1) as f64)).powf(1.5)
    }));
    let c = alpha * (((N - 1) * (N - 1)) as f64);
    for i in 0..N {
        for j in 0..N {
            let k = i * N + j;
            let up = ((i + 1) % N) * N + j;
            let down = ((i + N - 1) % N) * N + j;
            let right = i * N + (j + 1) % N;
            let left = i * N + (j + N - 1) % N;
            let x = (i as f64) / ((N - 1) as f64);
            let y = (j as f64) / ((N - 1) as f64);
            let f =
                if (x - 0.3) * (x - 0.3) + (y - 0.6) * (y - 0.6) <= 0.01 { forcing } else { 0.0 };
            let uuv = u[k] * u[k] * v[k];
            der(u[k])
                == 1.0 + uuv - 4.4 * u[k]
                    + c * (u[up] + u[down] + u[left] + u[right] - 4.0 * u[k])
                    + f;
            der(v[k]) == 3.4 * u[k] - uuv + c * (v[up] + v[down] + v[left] + v[right] - 4.0 * v[k]);
        }
    }
}

/// A large problem: its model's run from its initial state to the end, in
/// phases where a parameter switches (the 2-D forcing), by RADAU5 or by
/// CVODE with `linear`.
struct Large<M: Benchmark> {
    /// (phase end, the model during the phase).
    phases: Vec<(f64, M)>,
    linear: sundials::cvode::Linear,
}

impl<M: Benchmark> Large<M> {
    fn ours(&self, tol: f64) -> Option<(Vec<f64>, usize)> {
        let options = Options::new().method(Method::Radau5).rtol(tol).atol(tol).dense_output(false);
        let mut y = vec![0.0; M::STATES];
        self.phases[0].1.initial_state(&mut y);
        let (mut t, mut steps) = (0.0, 0);
        for (end, model) in &self.phases {
            let sol = model.simulate_from(t, &y, *end, &options).ok()?;
            y = sol.final_state().to_vec();
            steps += sol.stats().steps;
            t = *end;
        }
        Some((y, steps))
    }

    fn cvode(&self, tol: f64) -> Option<(Vec<f64>, usize)> {
        let mut y = vec![0.0; M::STATES];
        self.phases[0].1.initial_state(&mut y);
        let (mut t, mut steps) = (0.0, 0);
        for (end, model) in &self.phases {
            let mut system = sundials::structured::ModelSystem(model);
            let (next, counts) =
                sundials::cvode::solve(&mut system, t, &y, *end, (tol, tol), self.linear)?;
            y = next;
            steps += counts.steps;
            t = *end;
        }
        Some((y, steps))
    }
}

/// The median time of `run` over three runs, or more while they take
/// under a second in all (up to 51: a 1-D solve takes 20 ms, and three of
/// them on this shared machine vary by half), and its answer.
fn timed(run: impl Fn() -> Option<(Vec<f64>, usize)>) -> (f64, Option<(Vec<f64>, usize)>) {
    let mut times = Vec::new();
    let mut answer = None;
    let started = Instant::now();
    while times.len() < 3 || (times.len() < 51 && started.elapsed().as_secs_f64() < 1.0) {
        let start = Instant::now();
        answer = run();
        times.push(start.elapsed().as_secs_f64());
    }
    times.sort_by(f64::total_cmp);
    (times[times.len() / 2], answer)
}

/// max |a − b| / max(1, |b|).
fn mixed(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, r)| (x - r).abs() / r.abs().max(1.0)).fold(0.0, f64::max)
}

/// One problem's section of the report.
fn report<M: Benchmark>(title: &str, problem: &Large<M>, failed_checks: &mut usize) -> String {
    let mut text = format!("\n### {title}\n\n");
    eprintln!("large: {title}: expanding");
    let expansion = daegen_workprecision::expansion_cost(M::SOURCE, M::ATTRIBUTES, 3);
    let (expand, rustc) = match &expansion {
        Ok(cost) => {
            eprintln!("large: {title}: rustc");
            let rustc = rustc_seconds(&cost.code, M::NAME)
                .map_or_else(|e| format!("rustc failed: {e}"), |s| format!("{s:.1} s"));
            (format!("{:.2} s ({:.1} MB of code)", cost.seconds, cost.bytes as f64 / 1e6), rustc)
        }
        Err(e) => (format!("failed: {e}"), "–".into()),
    };
    let (ml, mu) = sundials::cvode::bandwidths(M::JACOBIAN_PATTERN);
    text.push_str(&format!(
        "{} states, {} Jacobian non-zeros (bandwidths {ml} below, {mu} above). Macro expansion {expand}; rustc -C opt-level=3 on the generated code {rustc}.\n\n",
        M::STATES,
        M::JACOBIAN_PATTERN.len()
    ));
    eprintln!("large: {title}: reference");
    let reference = problem.ours(1e-11).map(|(y, _)| y);
    let check = problem.cvode(1e-11).map(|(y, _)| y);
    let Some(reference) = reference else {
        text.push_str("RADAU5 at 1e-11 failed: no reference (check FAILED).\n");
        *failed_checks += 1;
        return text;
    };
    // The check: two methods of different families, each at 1e-11, agree
    // to 1e-6 (mixed error), or the reference is not one.
    let difference = check.map_or(f64::INFINITY, |c| mixed(&c, &reference));
    let agrees = difference <= 1e-6;
    if !agrees {
        *failed_checks += 1;
    }
    text.push_str(&format!(
        "Reference: RADAU5 at rtol = atol = 1e-11; CVODE ({:?}) at 1e-11 differs from it by {difference:.1e} (check, ≤ 1e-6: {}).\n\n",
        problem.linear,
        if agrees { "passed" } else { "FAILED" }
    ));
    // CVODE down to 1e-11, so that its curve reaches RADAU5's errors.
    let tols: Vec<f64> = (4..=11).map(|k| 10f64.powi(-k)).collect();
    let mut ours = Vec::new();
    let mut theirs = Vec::new();
    for &tol in &tols {
        eprintln!("large: {title}: tol {tol:.0e}");
        if tol >= 1e-8 {
            let (s, out) = timed(|| problem.ours(tol));
            let error = out.as_ref().map_or(f64::INFINITY, |o| mixed(&o.0, &reference));
            ours.push((Point { tol, error, seconds: s }, out.map_or(0, |o| o.1)));
        }
        let (s, out) = timed(|| problem.cvode(tol));
        let error = out.as_ref().map_or(f64::INFINITY, |o| mixed(&o.0, &reference));
        theirs.push((Point { tol, error, seconds: s }, out.map_or(0, |o| o.1)));
    }
    let curve: Vec<Point> = theirs.iter().map(|(p, _)| p.clone()).collect();
    text.push_str(&format!(
        "| tol | RADAU5 error | RADAU5 time | steps | CVODE ({:?}) error | CVODE time | steps | RADAU5 / CVODE at RADAU5's error |\n|---|---|---|---|---|---|---|---|\n",
        problem.linear
    ));
    for (k, (q, qs)) in theirs.iter().enumerate() {
        let (ours_text, ratio) = match ours.get(k) {
            Some((p, ps)) => (
                format!("{:.1e} | {:.3} s | {ps}", p.error, p.seconds),
                time_at_error(&curve, p.error)
                    .map_or("–".into(), |t| format!("{:.2}×", p.seconds / t)),
            ),
            None => ("| |".to_string(), String::new()),
        };
        text.push_str(&format!(
            "| {:.0e} | {ours_text} | {:.1e} | {:.3} s | {qs} | {ratio} |\n",
            q.tol, q.error, q.seconds
        ));
    }
    text
}

/// Writes results/large.md.
pub fn large_section() {
    let mut text = format!(
        "# Large stiff problems\n\nMachine: {}. Written by `cd bench && cargo run --release -- --large` (bench/src/large.rs). Times are medians of three solves or more (up to 51 while they take under a second in all); errors max |y − ref| / max(1, |ref|) at the end. Ratio: RADAU5's time over CVODE's at RADAU5's error, CVODE's curve interpolated log–log (–: outside the errors CVODE reached).\n",
        machine()
    );
    let bruss_1d = Large {
        phases: vec![(10.0, Brusselator1d::default())],
        linear: sundials::cvode::Linear::Band,
    };
    let mut failed_checks = 0;
    text.push_str(&report("Brusselator 1-D, N = 500, to t = 10", &bruss_1d, &mut failed_checks));
    let off = Brusselator2d::default();
    let bruss_2d = Large {
        phases: vec![(1.1, off), (11.5, Brusselator2d { forcing: 5.0, ..off })],
        linear: sundials::cvode::Linear::Klu,
    };
    text.push_str(&report("Brusselator 2-D, 32 × 32, to t = 11.5", &bruss_2d, &mut failed_checks));
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("results/large.md");
    if let Err(e) = std::fs::write(&path, &text) {
        eprintln!("cannot write {}: {e}", path.display());
    }
    print!("{text}");
    if failed_checks > 0 {
        eprintln!("large: {failed_checks} reference check(s) failed: RADAU5 and CVODE disagree");
        std::process::exit(1);
    }
}
