//! Large stiff problems (`--large`, `results/large.md`): the Brusselator
//! in one space dimension (1000 states, banded) and in two (2048 states,
//! sparse), and SUNDIALS' diurnal kinetics example on a 50 × 50 grid (5000
//! states, where CVODE runs GMRES), written with loops in the model
//! language. For each: the
//! macro's expansion time and rustc's on the generated code, a reference
//! from RADAU5 at rtol 1e-11 checked against CVODE at the same tolerance
//! (the run fails where they differ by more than 1e-6),
//! and RADAU5 and RODAS5P (with the LU the pattern calls for, and RODAS5P
//! with GMRES as well) against CVODE and IDA (band LU, KLU or GMRES, the
//! Jacobian the macro generated), ours from rtol 1e-3 to 1e-8 and theirs
//! on to 1e-11, the ratios at matched error.

use super::*;
use crate::dae::{time_at_error, Point};

/// The Brusselator in one space dimension (Hairer & Wanner II, §IV.1,
/// problem BRUS): u′ = 1 + u²v − 4u + α(N+1)² u_xx, v′ = 3u − u²v +
/// α(N+1)² v_xx on N = 500 interior points x_i = i/(N+1), u = 1 and v = 3
/// on the boundary, from u = 1 + sin(2πx), v = 3, to t = 10. Each point's
/// u and v side by side, as Hairer and Wanner order them, so that the
/// Jacobian is a band of width 2 on either side.
#[dae_model(bench = Bench::until(10.0).methods([Radau5, Rodas5P]).tolerances(4, 8))]
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
#[dae_model(bench = Bench::until(11.5).methods([Radau5, Rodas5P]).tolerances(4, 8), sensitivities = [alpha])]
pub(crate) fn brusselator_2d() {
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

/// SUNDIALS' cvDiurnal example (`cvDiurnal_kry.c`, after Hindmarsh &
/// Byrne's ozone problem): two species c1 (oxygen singlet) and c2 (ozone)
/// in a 20 km × 20 km vertical slice of the atmosphere (y from 30 to 50
/// km), with horizontal diffusion K_h = 4e-6, advection V = 1e-3 along x,
/// vertical diffusion K_v(y) = 1e-8·exp(y/5), and the diurnal kinetics
/// (rates q3, q4 = exp(−a/sin ωt) while the sun is up, 0 at night),
/// discretised as the example does (central differences, zero flux at the
/// edges by mirroring) on a 50 × 50 grid instead of its 10 × 10: 5000
/// states, each cell's two species side by side, to t = 86400 s (one day).
/// The night is a phase of its own (`daylight = 0`), where the rates are 0.
#[dae_model( bench = Bench::until(86400.0).methods([Radau5, Rodas5P]).tolerances(4, 8))]
fn diurnal() {
    const M: usize = 50;
    const PI: f64 = 3.141592653589793;
    let daylight = param(1.0);
    let t = time();
    // c1 = 1e6·α(x)β(y), c2 = 1e12·α(x)β(y), α(x) = 1 − a² + a⁴/2 with
    // a = (x − 10)/10, β likewise in b = (y − 40)/10.
    let c = state_array((0..2 * M * M).map(|k| {
        (if k % 2 == 0 { 1.0e6 } else { 1.0e12 })
            * (1.0 - (((k / 2) % M) as f64 * 20.0 / ((M - 1) as f64) / 10.0 - 1.0).powi(2)
                + 0.5 * (((k / 2) % M) as f64 * 20.0 / ((M - 1) as f64) / 10.0 - 1.0).powi(4))
            * (1.0 - (((k / 2) / M) as f64 * 20.0 / ((M - 1) as f64) / 10.0 - 1.0).powi(2)
                + 0.5 * (((k / 2) / M) as f64 * 20.0 / ((M - 1) as f64) / 10.0 - 1.0).powi(4))
    }));
    // By day sin ωt; by night 1, where the rates are switched off.
    let sun = daylight * sin(PI / 43200.0 * t) + (1.0 - daylight);
    let q3 = daylight * exp(-22.62 / sun);
    let q4 = daylight * exp(-7.601 / sun);
    let dx = 20.0 / ((M - 1) as f64);
    let dy = 20.0 / ((M - 1) as f64);
    for jy in 0..M {
        for jx in 0..M {
            let k = jy * M + jx;
            let down = if jy == 0 { k + M } else { k - M };
            let up = if jy + 1 == M { k - M } else { k + M };
            let left = if jx == 0 { k + 1 } else { k - 1 };
            let right = if jx + 1 == M { k - 1 } else { k + 1 };
            let y_down = 30.0 + ((jy as f64) - 0.5) * dy;
            let k_down = 1.0e-8 / (dy * dy) * exp(0.2 * y_down);
            let k_up = 1.0e-8 / (dy * dy) * exp(0.2 * (y_down + dy));
            let kh = 4.0e-6 / (dx * dx);
            let va = 1.0e-3 / (2.0 * dx);
            let c1 = c[2 * k];
            let c2 = c[2 * k + 1];
            let qq1 = 1.63e-16 * c1 * 3.7e16;
            let qq2 = 4.66e-16 * c1 * c2;
            let qq3 = q3 * 3.7e16;
            let qq4 = q4 * c2;
            der(c[2 * k])
                == k_up * (c[2 * up] - c1) - k_down * (c1 - c[2 * down])
                    + kh * (c[2 * right] - 2.0 * c1 + c[2 * left])
                    + va * (c[2 * right] - c[2 * left])
                    - qq1
                    - qq2
                    + 2.0 * qq3
                    + qq4;
            der(c[2 * k + 1])
                == k_up * (c[2 * up + 1] - c2) - k_down * (c2 - c[2 * down + 1])
                    + kh * (c[2 * right + 1] - 2.0 * c2 + c[2 * left + 1])
                    + va * (c[2 * right + 1] - c[2 * left + 1])
                    + qq1
                    - qq2
                    - qq4;
        }
    }
}

/// A large problem: its model's run from its initial state to the end, in
/// phases where a parameter switches (the 2-D forcing), by one of ours or
/// by CVODE with `linear`.
struct Large<M: Benchmark> {
    /// (phase end, the model during the phase).
    phases: Vec<(f64, M)>,
    linear: sundials::cvode::Linear,
    /// atol = rtol · this (cvDiurnal's floor of 100: concentrations of 1e6
    /// and 1e12 that fall to nothing at night).
    atol_factor: f64,
}

impl<M: Benchmark> Large<M> {
    fn ours(
        &self,
        (method, linear): (Method, LinearSolver),
        tol: f64,
    ) -> Option<(Vec<f64>, usize)> {
        let atol = tol * self.atol_factor;
        let options = Options::new()
            .method(method)
            .linear_solver(linear)
            .rtol(tol)
            .atol(atol)
            .dense_output(false);
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

    fn ida(&self, tol: f64) -> Option<(Vec<f64>, usize)> {
        self.by_sundials(tol, sundials::ida_structured::solve)
    }

    fn cvode(&self, tol: f64) -> Option<(Vec<f64>, usize)> {
        self.by_sundials(tol, sundials::cvode::solve)
    }

    /// The phases one after the other by a SUNDIALS integrator (CVODE's or
    /// IDA's `solve`), each from where the last ended.
    fn by_sundials<'s>(&'s self, tol: f64, solve: Solve<'s, M>) -> Option<(Vec<f64>, usize)> {
        let mut y = vec![0.0; M::STATES];
        self.phases[0].1.initial_state(&mut y);
        let (mut t, mut steps) = (0.0, 0);
        for (end, model) in &self.phases {
            let mut system = sundials::structured::ModelSystem(model);
            let atol = tol * self.atol_factor;
            let (next, counts) = solve(&mut system, t, &y, *end, (tol, atol), self.linear)?;
            y = next;
            steps += counts.steps;
            t = *end;
        }
        Some((y, steps))
    }
}

/// A SUNDIALS integrator's `solve` on a model's phase.
type Solve<'m, M> = fn(
    &mut sundials::structured::ModelSystem<'m, M>,
    f64,
    &[f64],
    f64,
    (f64, f64),
    sundials::cvode::Linear,
) -> Option<(Vec<f64>, sundials::cvode::Counts)>;

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

/// The generated code and a function that runs the model, as a user's
/// crate has it: without a caller rustc leaves the model's methods (and
/// the runtime's generic code for them) uncompiled.
fn with_a_caller(code: &str, name: &str) -> String {
    let ty: String = name
        .split('_')
        .map(|part| {
            let mut chars = part.chars();
            chars.next().map_or(String::new(), |c| c.to_uppercase().chain(chars).collect())
        })
        .collect();
    format!(
        "{code}\npub fn run() -> f64 {{ use ::daegen::prelude::*; <{ty} as Model>::STATES as f64 + {ty}::default().simulate(0.0, 1.0, &Options::new()).map_or(f64::NAN, |s| s.final_state()[0]) }}\n"
    )
}

/// One problem's section of the report.
fn report<M: Benchmark>(title: &str, problem: &Large<M>, failed_checks: &mut usize) -> String {
    let mut text = format!("\n### {title}\n\n");
    eprintln!("large: {title}: expanding");
    let expansion = daegen_workprecision::expansion_cost(M::SOURCE, M::ATTRIBUTES, 3);
    let (expand, rustc) = match &expansion {
        Ok(cost) => {
            eprintln!("large: {title}: rustc");
            let rustc = rustc_seconds(&with_a_caller(&cost.code, M::NAME), M::NAME)
                .map_or_else(|e| format!("rustc failed: {e}"), |s| format!("{s:.1} s"));
            (format!("{:.2} s ({:.1} MB of code)", cost.seconds, cost.bytes as f64 / 1e6), rustc)
        }
        Err(e) => (format!("failed: {e}"), "–".into()),
    };
    let (ml, mu) = sundials::cvode::bandwidths(M::JACOBIAN.pattern());
    text.push_str(&format!(
        "{} states, {} Jacobian non-zeros (bandwidths {ml} below, {mu} above). Macro expansion {expand}; rustc -C opt-level=3 on the generated code and a function that runs it {rustc}.\n\n",
        M::STATES,
        M::JACOBIAN.pattern().len()
    ));
    eprintln!("large: {title}: reference");
    let reference = problem.ours((Method::Radau5, LinearSolver::Direct), 1e-11).map(|(y, _)| y);
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
    // CVODE down to 1e-11, so that its curve reaches our errors.
    let tols: Vec<f64> = (3..=11).map(|k| 10f64.powi(-k)).collect();
    let methods = [
        (Method::Radau5, LinearSolver::Direct),
        (Method::Rodas5P, LinearSolver::Direct),
        (Method::Rodas5P, LinearSolver::Krylov),
    ];
    let mut ours: Vec<Vec<(Point, usize)>> = vec![Vec::new(); methods.len()];
    let (mut theirs, mut ida) = (Vec::new(), Vec::new());
    for &tol in &tols {
        eprintln!("large: {title}: tol {tol:.0e}");
        if tol >= 1e-8 {
            for (runs, &method) in ours.iter_mut().zip(&methods) {
                let (s, out) = timed(|| problem.ours(method, tol));
                let error = out.as_ref().map_or(f64::INFINITY, |o| mixed(&o.0, &reference));
                runs.push((Point { tol, error, seconds: s }, out.map_or(0, |o| o.1)));
            }
        }
        let (s, out) = timed(|| problem.cvode(tol));
        let error = out.as_ref().map_or(f64::INFINITY, |o| mixed(&o.0, &reference));
        theirs.push((Point { tol, error, seconds: s }, out.map_or(0, |o| o.1)));
        let (s, out) = timed(|| problem.ida(tol));
        let error = out.as_ref().map_or(f64::INFINITY, |o| mixed(&o.0, &reference));
        ida.push((Point { tol, error, seconds: s }, out.map_or(0, |o| o.1)));
    }
    let curve: Vec<Point> = theirs.iter().map(|(p, _)| p.clone()).collect();
    let ida_curve: Vec<Point> = ida.iter().map(|(p, _)| p.clone()).collect();
    let linear = problem.linear;
    text.push_str(&format!(
        "| tol | RADAU5 error | time | steps | RODAS5P error | time | steps | RODAS5P GMRES error | time | steps | CVODE ({linear:?}) error | time | steps | IDA error | time | steps | RADAU5 / CVODE | RODAS5P / CVODE | RODAS5P GMRES / CVODE | best / CVODE | best / IDA |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
    ));
    for (k, ((q, qs), (d, ds))) in theirs.iter().zip(&ida).enumerate() {
        let mut cells = String::new();
        let (mut ratios, mut ida_ratios) = (Vec::new(), Vec::new());
        for runs in &ours {
            match runs.get(k) {
                Some((p, ps)) => {
                    cells.push_str(&format!("{:.1e} | {:.3} s | {ps} | ", p.error, p.seconds));
                    ratios.push(time_at_error(&curve, p.error).map(|t| p.seconds / t));
                    ida_ratios.push(time_at_error(&ida_curve, p.error).map(|t| p.seconds / t));
                }
                None => cells.push_str("| | | "),
            }
        }
        let ratio = |r: Option<f64>| r.map_or("–".into(), |r| format!("{r:.2}×"));
        let mut ratio_cells: Vec<String> = ratios.iter().map(|&r| ratio(r)).collect();
        ratio_cells.resize(ours.len(), String::new());
        let best = ratios.iter().flatten().copied().reduce(f64::min);
        let best_ida = ida_ratios.iter().flatten().copied().reduce(f64::min);
        text.push_str(&format!(
            "| {:.0e} | {cells}{:.1e} | {:.3} s | {qs} | {:.1e} | {:.3} s | {ds} | {} | {} | {} |\n",
            q.tol,
            q.error,
            q.seconds,
            d.error,
            d.seconds,
            ratio_cells.join(" | "),
            best.map_or(String::new(), |b| format!("{b:.2}×")),
            best_ida.map_or(String::new(), |b| format!("{b:.2}×")),
        ));
    }
    text
}

/// Writes results/large.md.
pub fn large_section() {
    let mut text = format!(
        "# Large stiff problems\n\nMachine: {}. Written by `cd bench && cargo run --release -- --large` (bench/src/large.rs). Times are medians of three solves or more (up to 51 while they take under a second in all); errors max |y − ref| / max(1, |ref|) at the end. Ratios: our method's time over CVODE's (IDA's) at our method's error, the peer's curve interpolated log–log (–: outside the errors it reached); best: the lowest of ours. IDA integrates the same system as y′ − f = 0 with the same linear solver as CVODE.\n",
        machine()
    );
    let bruss_1d = Large {
        phases: vec![(10.0, Brusselator1d::default())],
        linear: sundials::cvode::Linear::Band,
        atol_factor: 1.0,
    };
    let mut failed_checks = 0;
    text.push_str(&report("Brusselator 1-D, N = 500, to t = 10", &bruss_1d, &mut failed_checks));
    let off = Brusselator2d::default();
    let bruss_2d = Large {
        phases: vec![(1.1, off), (11.5, Brusselator2d { forcing: 5.0, ..off })],
        linear: sundials::cvode::Linear::Klu,
        atol_factor: 1.0,
    };
    text.push_str(&report("Brusselator 2-D, 32 × 32, to t = 11.5", &bruss_2d, &mut failed_checks));
    let day = Diurnal::default();
    let diurnal = Large {
        phases: vec![(43200.0, day), (86400.0, Diurnal { daylight: 0.0 })],
        linear: sundials::cvode::Linear::Gmres { block: 2 },
        atol_factor: 100.0,
    };
    text.push_str(&report(
        "cvDiurnal, 2 species on 50 × 50, to t = 86400 s",
        &diurnal,
        &mut failed_checks,
    ));
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
