//! The DAE benchmarks (`--dae`): the price of the DAE forms against the
//! ODEs they reduce to, a scene in body and in joint coordinates,
//! and Robertson as an index-1 DAE against diffsol's mass-matrix BDF and
//! SUNDIALS' IDA. These
//! compare forms of one problem rather than sweep a registered model, so
//! they keep their own tables.

use super::*;
use std::time::{Duration, Instant};

fn mixed_error(got: &[f64], reference: &[f64]) -> f64 {
    got.iter().zip(reference).map(|(g, r)| (g - r).abs() / r.abs().max(1.0)).fold(0.0, f64::max)
}

/// Median wall time of `run` over repeats (after one warm-up), and its result.
fn time<T>(mut run: impl FnMut() -> T) -> (Duration, T) {
    let mut result = run();
    let mut times = Vec::new();
    let start = Instant::now();
    // Sub-millisecond runs on a shared 2-core machine vary by ±30% between
    // batches: take many repeats (at least 1 s or 200 runs) before the median.
    while times.len() < 200 && (times.len() < 5 || start.elapsed() < Duration::from_secs(1)) {
        let t = Instant::now();
        result = run();
        times.push(t.elapsed());
    }
    times.sort();
    (times[times.len() / 2], result)
}

/// One point of a work-precision curve.
#[derive(Clone, Debug)]
pub(crate) struct Point {
    pub(crate) tol: f64,
    pub(crate) error: f64,
    pub(crate) seconds: f64,
}

/// A peer's time at `error`, by log–log interpolation on its curve (None
/// outside the range it covers).
pub(crate) fn time_at_error(curve: &[Point], error: f64) -> Option<f64> {
    let mut pts: Vec<&Point> =
        curve.iter().filter(|p| p.error > 0.0 && p.error.is_finite()).collect();
    pts.sort_by(|a, b| b.error.total_cmp(&a.error));
    pts.windows(2).find_map(|w| {
        let (a, b) = (w[0], w[1]);
        if error <= a.error && error >= b.error {
            let s = (error.ln() - a.error.ln()) / (b.error.ln() - a.error.ln());
            Some((a.seconds.ln() + s * (b.seconds.ln() - a.seconds.ln())).exp())
        } else {
            None
        }
    })
}

/// One run of a pendulum form: the error in (x, y, u, v) at t = 10 against
/// Cash's recomputed reference, the time, and the steps taken.
fn pendulum_run<M: Model + Clone + Send + Sync + 'static>(
    model: &M,
    method: Method,
    tol: f64,
    formulation: Formulation,
    cartesian: &dyn Fn(&[f64]) -> [f64; 4],
) -> (Point, usize) {
    let options =
        Options::new().method(method).tolerance(tol).dense_output(false).formulation(formulation);
    let (d, sol) = time(|| model.simulate(0.0, 10.0, &options));
    let (error, steps) = match sol {
        Ok(sol) => {
            let got = cartesian(sol.state(sol.times().len() - 1).unwrap_or(&[0.0; 4]));
            (mixed_error(&got, &CASH_PENDULUM_AT_10[..4]), sol.stats().steps)
        }
        Err(_) => (f64::INFINITY, 0),
    };
    (Point { tol, error, seconds: d.as_secs_f64() }, steps)
}

/// The slider-crank (global coordinates, 15 × 15 KKT system solved at each
/// evaluation) against its crank-angle ODE to t = 2, DOP853: the error in
/// the crank angle against the angle form at tol 1e-13, time per step.
fn slider_crank_against_ode() {
    println!("\n### Slider-crank to t = 2: global coordinates (DAE) against the crank-angle ODE, DOP853\n");
    println!("| tol | DAE error | DAE time (ms) | DAE steps | DAE µs/step | ODE error | ODE time (ms) | ODE steps | ODE µs/step | time ratio |");
    println!("|---|---|---|---|---|---|---|---|---|---|");
    let dae = SliderCrank::default();
    let probe = dae
        .simulate(0.0, 2.0, &Options::new().method(Method::Dop853))
        .expect("the slider-crank runs");
    let phi0 = probe.state(0).map_or(1.0, |s| s[4]);
    let ode = SliderCrankAngle { phi0, ..SliderCrankAngle::default() };
    let reference = ode
        .simulate(0.0, 2.0, &Options::new().method(Method::Dop853).tolerance(1e-13))
        .and_then(|s| s.last("phi"))
        .unwrap_or(f64::NAN);
    for tol in [1e-6, 1e-9, 1e-12] {
        let options = Options::new().method(Method::Dop853).tolerance(tol).dense_output(false);
        let (da, a) = time(|| dae.simulate(0.0, 2.0, &options));
        let (db, b) = time(|| ode.simulate(0.0, 2.0, &options));
        let (Ok(a), Ok(b)) = (a, b) else {
            println!("| {tol:.0e} | failed | | | | | | | | |");
            continue;
        };
        let ea = (a.last("theta1").unwrap_or(f64::NAN) - reference).abs();
        let eb = (b.last("phi").unwrap_or(f64::NAN) - reference).abs();
        let (sa, sb) = (a.stats().steps, b.stats().steps);
        println!(
            "| {tol:.0e} | {ea:.2e} | {:.3} | {sa} | {:.2} | {eb:.2e} | {:.3} | {sb} | {:.2} | {} |",
            da.as_secs_f64() * 1e3,
            da.as_secs_f64() * 1e6 / sa.max(1) as f64,
            db.as_secs_f64() * 1e3,
            db.as_secs_f64() * 1e6 / sb.max(1) as f64,
            ratio(da.as_secs_f64() / db.as_secs_f64())
        );
    }
}

/// The source of an n-rod chain scene, for timing the macro on it.
fn rod_chain_source(n: usize) -> String {
    let mut s = String::from("fn chain() { let g = param(9.81); let ground = ground();");
    for i in 0..n {
        s += &format!("let rod{i} = body(1.0, 1.0 / 12.0, [{}.5, 0.0, 0.0]);", i);
    }
    s += "revolute(ground, vec3(0.0, 0.0, 0.0), rod0, vec3(-0.5, 0.0, 0.0));";
    for i in 1..n {
        s += &format!("revolute(rod{}, vec3(0.5, 0.0, 0.0), rod{i}, vec3(-0.5, 0.0, 0.0));", i - 1);
    }
    s + "gravity(vec3(0.0, -g, 0.0)); }"
}

/// A ten-rod chain in body and in joint coordinates: macro
/// expansion time and generated size, and the run's cost per step.
fn formulations() {
    println!("\n### Ten-rod chain: body against joint coordinates (DOP853, tol 1e-8, t = 1)\n");
    println!(
        "| formulation | expansion (ms) | generated (kB) | states | run (ms) | steps | µs/step |"
    );
    println!("|---|---|---|---|---|---|---|");
    let source: proc_macro2::TokenStream = rod_chain_source(10).parse().expect("the chain parses");
    let options = Options::new().method(Method::Dop853).tolerance(1e-8).dense_output(false);
    for (name, attr) in [("global", "scene = global"), ("recursive", "scene = recursive")] {
        let attr: proc_macro2::TokenStream = attr.parse().expect("the attribute parses");
        let (expansion, tokens) =
            time(|| daegen::codegen::expand_dae_model(attr.clone(), source.clone()));
        let kb = tokens.to_string().len() as f64 / 1e3;
        let (run, steps, states) = if name == "global" {
            let (d, s) = time(|| RodChainGlobal::default().simulate(0.0, 1.0, &options));
            (d, s.map(|s| s.stats().steps).unwrap_or(0), RodChainGlobal::STATES)
        } else {
            let (d, s) = time(|| RodChainRecursive::default().simulate(0.0, 1.0, &options));
            (d, s.map(|s| s.stats().steps).unwrap_or(0), RodChainRecursive::STATES)
        };
        println!(
            "| {name} | {:.1} | {kb:.0} | {states} | {:.2} | {steps} | {:.1} |",
            expansion.as_secs_f64() * 1e3,
            run.as_secs_f64() * 1e3,
            run.as_secs_f64() * 1e6 / steps.max(1) as f64
        );
    }
}

/// One spatial scene in one formulation: DOP853 from 0 to `t1` at `tol`,
/// the run's median time, its steps and the outputs `names` at the end.
fn spatial_run<M: Simulate + Default>(
    t1: f64,
    tol: f64,
    names: &[&str],
) -> (Duration, usize, Vec<f64>) {
    let options = Options::new().method(Method::Dop853).tolerance(tol).dense_output(false);
    let (run, result) = time(|| M::default().simulate(0.0, t1, &options));
    match result {
        Ok(sol) => {
            let end = names.iter().map(|n| sol.last(n).unwrap_or(f64::NAN)).collect();
            (run, sol.stats().steps, end)
        }
        Err(_) => (run, 0, vec![f64::NAN; names.len()]),
    }
}

/// The spatial scenes in body and in joint coordinates: the
/// macro's expansion time, the generated code's size and rustc's time on
/// it, and the run's cost per step by DOP853 at tol 1e-10, with the end
/// error against joint coordinates at 1e-13.
fn spatial_formulations() {
    println!("\n### Spatial scenes: body against joint coordinates (DOP853, tol 1e-10)\n");
    println!("Expansion: median of 5; rustc (release): the faster of 2 (one above a minute). Error: max over the outputs at the end against joint coordinates at tol 1e-13.\n");
    println!("| scene | formulation | states | expansion (ms) | generated (kB) | rustc (s) | run (ms) | steps | µs/step | error |");
    println!("|---|---|---|---|---|---|---|---|---|---|");
    let file = include_str!("../../tests/models/spatial_chains.rs");
    type Run = fn(f64) -> (Duration, usize, Vec<f64>);
    let scenes: [(&str, &str, f64, [&str; 3], Run, Run, usize, usize); 3] = [
        (
            "double pendulum (2 spherical)",
            "spatial_double_pendulum",
            2.0,
            ["tip_x", "tip_y", "tip_z"],
            |tol| {
                spatial_run::<SpatialDoublePendulumGlobal>(2.0, tol, &["tip_x", "tip_y", "tip_z"])
            },
            |tol| {
                spatial_run::<SpatialDoublePendulumRecursive>(
                    2.0,
                    tol,
                    &["tip_x", "tip_y", "tip_z"],
                )
            },
            SpatialDoublePendulumGlobal::STATES,
            SpatialDoublePendulumRecursive::STATES,
        ),
        (
            "four-bar loop (RSSR)",
            "rssr_loop",
            2.0,
            ["tip_y", "tip_z", "tip_z"],
            |tol| spatial_run::<RssrLoopGlobal>(2.0, tol, &["tip_y", "tip_z", "tip_z"]),
            |tol| spatial_run::<RssrLoopRecursive>(2.0, tol, &["tip_y", "tip_z", "tip_z"]),
            RssrLoopGlobal::STATES,
            RssrLoopRecursive::STATES,
        ),
        (
            "seven-joint arm",
            "seven_joint_arm",
            1.0,
            ["hand_x", "hand_y", "hand_z"],
            |tol| spatial_run::<SevenJointArmGlobal>(1.0, tol, &["hand_x", "hand_y", "hand_z"]),
            |tol| spatial_run::<SevenJointArmRecursive>(1.0, tol, &["hand_x", "hand_y", "hand_z"]),
            SevenJointArmGlobal::STATES,
            SevenJointArmRecursive::STATES,
        ),
    ];
    for (scene, macro_name, t1, _, global, recursive, global_states, recursive_states) in scenes {
        let (_, _, reference) = recursive(1e-13);
        let Some(source) = crate::tape_cost::macro_model_source(file, macro_name, macro_name)
        else {
            println!("| {scene} | source not found | | | | | | | | |");
            continue;
        };
        for (formulation, attr, run, states) in [
            ("global", "", global, global_states),
            ("recursive", "scene = recursive", recursive, recursive_states),
        ] {
            eprint!("\r\x1b[2Kspatial formulations: {scene}, {formulation}");
            let cost = daegen_workprecision::expansion_cost(&source, attr, 5);
            let (expansion, kb, rustc) = match &cost {
                Ok(c) => {
                    let name = format!("{macro_name}_{formulation}");
                    // A second compile only where the first was short
                    // enough for the machine's load to matter.
                    let mut rustc = f64::INFINITY;
                    for k in 0..2 {
                        if let Ok(s) = rustc_seconds(&c.code, &format!("{name}{k}")) {
                            rustc = rustc.min(s);
                        }
                        if rustc > 60.0 {
                            break;
                        }
                    }
                    (c.seconds * 1e3, c.bytes as f64 / 1e3, rustc)
                }
                Err(_) => (f64::NAN, f64::NAN, f64::NAN),
            };
            let (time_taken, steps, end) = run(1e-10);
            let error = end.iter().zip(&reference).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
            println!(
                "| {scene}, t = {t1} | {formulation} | {states} | {expansion:.1} | {kb:.0} | {rustc:.2} | {:.2} | {steps} | {:.1} | {error:.1e} |",
                time_taken.as_secs_f64() * 1e3,
                time_taken.as_secs_f64() * 1e6 / steps.max(1) as f64
            );
        }
    }
    eprintln!();
}

/// The ten-rod chain by the Taylor method, which solves its 10 × 10 mass
/// matrix (recursive) or 30 + 20 KKT system (global) order by order with
/// one LU a step, against DOP853, at tight tolerances: error in the tip's
/// height at t = 1 against DOP853 at 1e-14, time and cost per step.
fn taylor_on_the_chain() {
    println!("\n### Ten-rod chain by the Taylor method against DOP853 (t = 1)\n");
    println!("| formulation | method | tol | tip error | run (ms) | steps | µs/step |");
    println!("|---|---|---|---|---|---|---|");
    let reference = RodChainRecursive::default()
        .simulate(0.0, 1.0, &Options::new().method(Method::Dop853).tolerance(1e-14))
        .ok()
        .and_then(|s| s.last("tip_y").ok())
        .unwrap_or(f64::NAN);
    for tol in [1e-10, 1e-13] {
        for (name, method) in [("DOP853", Method::Dop853), ("Taylor", Method::Taylor)] {
            let options = Options::new().method(method).tolerance(tol).dense_output(false);
            for formulation in ["global", "recursive"] {
                let (run, result) = if formulation == "global" {
                    time(|| RodChainGlobal::default().simulate(0.0, 1.0, &options))
                } else {
                    time(|| RodChainRecursive::default().simulate(0.0, 1.0, &options))
                };
                let Ok(sol) = result else {
                    println!("| {formulation} | {name} | {tol:.0e} | failed | | | |");
                    continue;
                };
                let error = (sol.last("tip_y").unwrap_or(f64::NAN) - reference).abs();
                let steps = sol.stats().steps;
                println!(
                    "| {formulation} | {name} | {tol:.0e} | {error:.1e} | {:.2} | {steps} | {:.1} |",
                    run.as_secs_f64() * 1e3,
                    run.as_secs_f64() * 1e6 / steps.max(1) as f64
                );
            }
        }
    }
}

/// The index-3 pendulum as a DAE (index-1 form with projection) against
/// its angle ODE, same method and tolerance: the price of the DAE form.
fn dae_against_ode() {
    println!("\n### Cash's index-3 pendulum to t = 10: the DAE form against the angle ODE\n");
    println!("| method | tol | DAE error | DAE time (ms) | DAE steps | DAE µs/step | ODE error | ODE time (ms) | ODE steps | ODE µs/step | time ratio |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    let dae = CashPendulum::default();
    let ode = CashPendulumAngle::default();
    for (name, method, formulation) in [
        ("DOP853", Method::Dop853, Formulation::IndexOneProjected),
        ("Taylor", Method::Taylor, Formulation::IndexOneProjected),
        ("RADAU5", Method::Radau5, Formulation::IndexOneProjected),
        ("RADAU5, GGL form", Method::Radau5, Formulation::MassMatrix),
    ] {
        for tol in [1e-6, 1e-9, 1e-12] {
            let (a, sa) =
                pendulum_run(&dae, method, tol, formulation, &|s| [s[0], s[1], s[2], s[3]]);
            let (b, sb) = pendulum_run(&ode, method, tol, Formulation::IndexOneProjected, &|s| {
                let (theta, omega) = (s[0], s[1]);
                [theta.cos(), theta.sin(), -omega * theta.sin(), omega * theta.cos()]
            });
            let per_step = |p: &Point, n: usize| p.seconds * 1e6 / n.max(1) as f64;
            println!(
                "| {name} | {tol:.0e} | {:.2e} | {:.3} | {sa} | {:.2} | {:.2e} | {:.3} | {sb} | {:.2} | {} |",
                a.error,
                a.seconds * 1e3,
                per_step(&a, sa),
                b.error,
                b.seconds * 1e3,
                per_step(&b, sb),
                ratio(a.seconds / b.seconds)
            );
        }
    }
}

/// diffsol's BDF on Robertson as an index-1 DAE with the singular mass
/// matrix diag(1, 1, 0), its documented way of solving DAEs.
fn diffsol_robertson_dae(tol: f64, atol: f64) -> Point {
    use diffsol::{NalgebraLU, NalgebraMat, OdeBuilder, OdeSolverMethod};
    let run = || -> Option<Vec<f64>> {
        let p = OdeBuilder::<NalgebraMat<f64>>::new()
            .rtol(tol)
            .atol([atol])
            .rhs_implicit(
                |x, _p, _t, y| {
                    y[0] = -0.04 * x[0] + 1e4 * x[1] * x[2];
                    y[1] = 0.04 * x[0] - 1e4 * x[1] * x[2] - 3e7 * x[1] * x[1];
                    y[2] = x[0] + x[1] + x[2] - 1.0;
                },
                |x, _p, _t, v, y| {
                    y[0] = -0.04 * v[0] + 1e4 * v[1] * x[2] + 1e4 * x[1] * v[2];
                    y[1] = 0.04 * v[0] - 1e4 * v[1] * x[2] - 1e4 * x[1] * v[2] - 6e7 * x[1] * v[1];
                    y[2] = v[0] + v[1] + v[2];
                },
            )
            .mass(|v, _p, _t, beta, y| {
                y[0] = v[0] + beta * y[0];
                y[1] = v[1] + beta * y[1];
                y[2] = beta * y[2];
            })
            .init(
                |_p, _t, y| {
                    y[0] = 1.0;
                    y[1] = 0.0;
                    y[2] = 0.0;
                },
                3,
            )
            .build()
            .ok()?;
        let mut s = p.bdf::<NalgebraLU<f64>>().ok()?;
        s.solve(1e11).ok()?;
        Some((0..3).map(|i| s.state().y[i]).collect())
    };
    let (d, y) = time(run);
    Point {
        tol,
        error: y.map_or(f64::INFINITY, |y| mixed_error(&y, &ROBER_AT_1E11)),
        seconds: d.as_secs_f64(),
    }
}

/// IDA's BDF on Robertson as the index-1 DAE F = (y1′ − f1, y2′ − f2,
/// y1 + y2 + y3 − 1), y3 algebraic, its residual and iteration matrix
/// written out as in SUNDIALS' own example `idaRoberts_dns`.
#[cfg(feature = "sundials")]
fn ida_robertson_dae(tol: f64, atol: f64) -> Point {
    use crate::sundials::ida::{solve, Residual};
    let residual = |_t: f64, y: &[f64], yp: &[f64], r: &mut [f64]| {
        r[0] = yp[0] - (-0.04 * y[0] + 1e4 * y[1] * y[2]);
        r[1] = yp[1] - (0.04 * y[0] - 1e4 * y[1] * y[2] - 3e7 * y[1] * y[1]);
        r[2] = y[0] + y[1] + y[2] - 1.0;
    };
    let iteration_matrix = |_t: f64, cj: f64, y: &[f64], _yp: &[f64], j: &mut [f64]| {
        j.copy_from_slice(&[
            0.04 + cj,
            -1e4 * y[2],
            -1e4 * y[1],
            -0.04,
            1e4 * y[2] + 6e7 * y[1] + cj,
            1e4 * y[1],
            1.0,
            1.0,
            1.0,
        ]);
    };
    let dae = Residual {
        y0: &[1.0, 0.0, 0.0],
        yp0: &[-0.04, 0.04, 0.0],
        differential: &[1.0, 1.0, 0.0],
        residual: &residual,
        iteration_matrix: &iteration_matrix,
    };
    let (d, out) = time(|| solve(&dae, 1e11, tol, atol));
    Point {
        tol,
        error: out.map_or(f64::INFINITY, |(y, _)| mixed_error(&y, &ROBER_AT_1E11)),
        seconds: d.as_secs_f64(),
    }
}

fn ratio(r: f64) -> String {
    if r < 0.1 {
        format!("{r:.1e}×")
    } else {
        format!("{r:.2}×")
    }
}

fn report(problem: &str, ours: &[(&str, Vec<Point>)], peers: &[(&str, Option<Vec<Point>>)]) {
    println!("\n### {problem}\n");
    println!(
        "| method | tol | error | time (ms) | vs {} |",
        peers.iter().map(|p| p.0).collect::<Vec<_>>().join(" | vs ")
    );
    println!("|---|---|---|---|{}", "---|".repeat(peers.len()));
    for (name, curve) in ours {
        for p in curve {
            let ratios: Vec<String> = peers
                .iter()
                .map(|(_, peer)| match peer {
                    None => "missing".to_string(),
                    Some(c) => time_at_error(c, p.error)
                        .map_or("–".to_string(), |t| ratio(p.seconds / t)),
                })
                .collect();
            println!(
                "| {name} | {:.0e} | {:.2e} | {:.3} | {} |",
                p.tol,
                p.error,
                p.seconds * 1e3,
                ratios.join(" | ")
            );
        }
    }
    for (name, peer) in peers {
        match peer {
            None => println!("\n{name}: missing (not installed)"),
            Some(c) => {
                let pts: Vec<String> = c
                    .iter()
                    .map(|p| format!("{:.0e}: {:.2e} in {:.3} ms", p.tol, p.error, p.seconds * 1e3))
                    .collect();
                println!("\n{name}: {}", pts.join("; "));
            }
        }
    }
}

/// The DAE forms: the pendulum against its ODE, Robertson's index-1 DAE
/// against diffsol's mass-matrix BDF. `--dae-only` runs just this.
pub fn dae_section(stiff_tols: &[f64]) {
    dae_against_ode();
    slider_crank_against_ode();
    formulations();
    spatial_formulations();
    taylor_on_the_chain();
    let rd = RobertsonDae::default();
    let rober_dae_ours = vec![(
        "daegen RADAU5 (index-1 DAE, y3 solved symbolically)",
        stiff_tols
            .iter()
            .map(|&t| {
                let options = Options::new().method(Method::Radau5).rtol(t).atol(1e-6 * t);
                let (d, sol) = time(|| rd.simulate(0.0, 1e11, &options));
                let error = match sol {
                    Ok(sol) => {
                        let got: Vec<f64> = ["y1", "y2", "y3"]
                            .iter()
                            .map(|n| sol.last(n).unwrap_or(f64::NAN))
                            .collect();
                        mixed_error(&got, &ROBER_AT_1E11)
                    }
                    Err(_) => f64::INFINITY,
                };
                Point { tol: t, error, seconds: d.as_secs_f64() }
            })
            .collect(),
    )];
    #[allow(unused_mut)]
    let mut rober_dae_peers = vec![(
        "diffsol BDF (mass matrix)",
        Some(stiff_tols.iter().map(|&t| diffsol_robertson_dae(t, 1e-6 * t)).collect()),
    )];
    #[cfg(feature = "sundials")]
    rober_dae_peers.push((
        "IDA BDF (dense)",
        Some(stiff_tols.iter().map(|&t| ida_robertson_dae(t, 1e-6 * t)).collect()),
    ));
    report(
        "Robertson as an index-1 DAE to t = 1e11, atol = 1e-6·rtol",
        &rober_dae_ours,
        &rober_dae_peers,
    );
}
