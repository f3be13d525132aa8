//! Work-precision benchmarks: daegen's methods against peer solvers in one
//! run, as time ratios at equal error.
//!
//! Run: `cargo run --release --manifest-path bench/Cargo.toml`
//! (add `--no-python` to skip SciPy and heyoka).
//!
//! Non-stiff (Kepler e = 0.9 over ten orbits, Arenstorf over one period):
//! our DOPRI5 and DOP853 against the `ode_solvers` crate's and SciPy's,
//! and our Taylor method against heyoka's.
//! Stiff (Van der Pol ε = 1e-6, Robertson to 1e11, HIRES): our RADAU5
//! against the `diffsol` crate's BDF and TR-BDF2 (its SDIRK) and SciPy's
//! Radau and BDF (through ../shared/peers/peer.py).
//! Errors are max |y − ref| / max(1, |ref|) at the end, against exact or
//! published references (../shared/notes/reference-problems.md).
//! `ode_solvers` 0.6.2 runs the same algorithms with the same controller,
//! but its final value (read from its dense output) is unreliable, so it is
//! also compared at equal tolerance. A missing peer is reported as missing.

use daegen::prelude::*;
use std::process::Command;
use std::time::{Duration, Instant};

include!("../../tests/models/kepler.rs");
include!("../../tests/models/arenstorf.rs");
// The orders unrolled are those of the tolerances 1e-4 … 1e-15.
kepler_model!(
    taylor = 1,
    unroll = [6, 7, 8, 10, 11, 12, 13, 14, 15, 16, 18, 19]
);
arenstorf_model!(
    taylor = 1,
    unroll = [6, 7, 8, 10, 11, 12, 13, 14, 15, 16, 18, 19]
);

/// Lorenz, σ = 10, ρ = 28, β = 8/3 (peer.py's `lorenz`).
#[dae_model(taylor = 1, unroll = [12, 15, 19])]
fn lorenz() {
    let x = state(1.0);
    let y = state(0.0);
    let z = state(0.0);
    der(x) == 10.0 * (y - x);
    der(y) == x * (28.0 - z) - y;
    der(z) == x * y - 8.0 / 3.0 * z;
}

include!("../../tests/models/outer_solar_system.rs");
// Orders 12, 15 and 19 are those of tolerances 1e-9, 1e-12 and 1e-15.
outer_solar_system_model!(taylor = 1, unroll = [12, 15, 19]);

include!("../../tests/models/stiff.rs");
include!("../../tests/models/pendulum.rs");
include!("../../tests/models/slider_crank.rs");
include!("../../tests/models/rod_chain.rs");
rod_chain_model!(rod_chain_global, scene = global);
rod_chain_model!(rod_chain_recursive, scene = recursive);
cash_pendulum_model!(
    taylor = 1,
    unroll = [6, 7, 8, 10, 11, 12, 13, 14, 15, 16, 18, 19]
);

/// The outer solar system at t = 20 000 days in the model's state order
/// (x, y, z of the six bodies, then u, v, w): the recomputed 38-digit
/// reference of reference-problems.md §11a.
const OSS_REFERENCE: [f64; 36] = [
    0.12333221241422682,
    -0.7717783718781831,
    3.905129228943534,
    -17.49283446453391,
    18.05146500280488,
    37.2859494487057,
    -0.05861680898736033,
    4.610553890044759,
    -8.565631984033054,
    4.343534522694276,
    22.146025676860077,
    -10.728138680006204,
    -0.028723538220436225,
    1.9942337301316608,
    -3.706141337200349,
    2.148260692500113,
    8.61348200303968,
    -14.554583801118437,
    1.21536081089604e-05,
    -0.007523187121658664,
    0.004869814448954702,
    -0.0010774480286725038,
    -0.0025198369859314694,
    0.0014396172428636,
    -2.0358519838216773e-06,
    -0.0009504715666775789,
    0.0020114478852441033,
    -0.003648047365938506,
    0.0017408452383549818,
    0.002172144522421196,
    -1.159628992553582e-06,
    -0.00022431528198097166,
    0.0006211500161960769,
    -0.0015825685372962699,
    0.0007751962528747769,
    0.0002455229146265932,
];

fn mixed_error(got: &[f64], reference: &[f64]) -> f64 {
    got.iter()
        .zip(reference)
        .map(|(g, r)| (g - r).abs() / r.abs().max(1.0))
        .fold(0.0, f64::max)
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
struct Point {
    tol: f64,
    error: f64,
    seconds: f64,
}

/// A peer's time at `error`, by log–log interpolation on its curve (None
/// outside the range it covers).
fn time_at_error(curve: &[Point], error: f64) -> Option<f64> {
    let mut pts: Vec<&Point> = curve
        .iter()
        .filter(|p| p.error > 0.0 && p.error.is_finite())
        .collect();
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

fn ours<M: Model + Clone + Send + Sync + 'static>(
    model: &M,
    t1: f64,
    method: Method,
    tol: f64,
    atol: f64,
    reference: &[f64],
) -> Point {
    // The Taylor method keeps no dense output here, like heyoka's
    // `propagate_until` it is compared with; the explicit pairs keep theirs,
    // like `ode_solvers` (which samples it) and SciPy.
    let options = Options::new()
        .method(method)
        .rtol(tol)
        .atol(atol)
        .dense_output(method != Method::Taylor);
    ours_with(model, t1, &options, tol, reference)
}

/// The Taylor method in the compact layout (the tape interpreted).
fn ours_compact<M: Model + Clone + Send + Sync + 'static>(
    model: &M,
    t1: f64,
    tol: f64,
    reference: &[f64],
) -> Point {
    let options = Options::new()
        .method(Method::Taylor)
        .rtol(tol)
        .atol(tol)
        .dense_output(false)
        .taylor_compact(true);
    ours_with(model, t1, &options, tol, reference)
}

fn ours_with<M: Model + Clone + Send + Sync + 'static>(
    model: &M,
    t1: f64,
    options: &Options,
    tol: f64,
    reference: &[f64],
) -> Point {
    let (d, sol) = time(|| model.simulate(0.0, t1, options));
    let error = match sol {
        Ok(sol) => mixed_error(sol.state(sol.times().len() - 1).unwrap_or(&[]), reference),
        Err(_) => f64::INFINITY,
    };
    Point {
        tol,
        error,
        seconds: d.as_secs_f64(),
    }
}

mod peers {
    use super::{mixed_error, time, Point};
    use ode_solvers::{Dop853, Dopri5, System, Vector4};

    struct Kepler;
    impl System<f64, Vector4<f64>> for Kepler {
        fn system(&self, _t: f64, y: &Vector4<f64>, dy: &mut Vector4<f64>) {
            let r3 = (y[0] * y[0] + y[1] * y[1]).powf(1.5);
            dy[0] = y[2];
            dy[1] = y[3];
            dy[2] = -y[0] / r3;
            dy[3] = -y[1] / r3;
        }
    }

    struct Arenstorf;
    impl System<f64, Vector4<f64>> for Arenstorf {
        fn system(&self, _t: f64, y: &Vector4<f64>, dy: &mut Vector4<f64>) {
            let mu = 0.012277471;
            let mup = 1.0 - mu;
            let d1 = ((y[0] + mu).powi(2) + y[1] * y[1]).powf(1.5);
            let d2 = ((y[0] - mup).powi(2) + y[1] * y[1]).powf(1.5);
            dy[0] = y[2];
            dy[1] = y[3];
            dy[2] = y[0] + 2.0 * y[3] - mup * (y[0] + mu) / d1 - mu * (y[0] - mup) / d2;
            dy[3] = y[1] - 2.0 * y[2] - mup * y[1] / d1 - mu * y[1] / d2;
        }
    }

    /// `ode_solvers` on "kepler" or "arenstorf": (`dop853`, tol) → point.
    /// Its dense output is sampled every t1/1000: with one sample spanning
    /// many steps (dx = t1) its final value is wrong (seen with 0.6.2), and
    /// dx = 0 does not terminate.
    pub fn ode_solvers(
        problem: &str,
        dop853: bool,
        y0: [f64; 4],
        t1: f64,
        tol: f64,
        reference: &[f64],
    ) -> Point {
        let y0 = Vector4::new(y0[0], y0[1], y0[2], y0[3]);
        let run = || -> Option<Vec<f64>> {
            macro_rules! go {
                ($system:expr) => {{
                    if dop853 {
                        let mut s = Dop853::new($system, 0.0, t1, t1 / 1000.0, y0, tol, tol);
                        s.integrate().ok()?;
                        s.y_out().last().map(|v| v.iter().copied().collect())
                    } else {
                        let mut s = Dopri5::new($system, 0.0, t1, t1 / 1000.0, y0, tol, tol);
                        s.integrate().ok()?;
                        s.y_out().last().map(|v| v.iter().copied().collect())
                    }
                }};
            }
            if problem == "kepler" {
                go!(Kepler)
            } else {
                go!(Arenstorf)
            }
        };
        let (d, y) = time(run);
        let error = y.map_or(f64::INFINITY, |y| mixed_error(&y, reference));
        Point {
            tol,
            error,
            seconds: d.as_secs_f64(),
        }
    }
}

mod diffsol_peer {
    use super::{mixed_error, time, Point};
    use diffsol::{NalgebraLU, NalgebraMat, OdeBuilder, OdeSolverMethod};
    type M = NalgebraMat<f64>;
    type LS = NalgebraLU<f64>;

    /// diffsol's BDF (`sdirk` false) or TR-BDF2 (`sdirk` true) on one of
    /// the stiff problems, with hand-written Jacobian-vector products.
    pub fn run(
        problem: &str,
        sdirk: bool,
        t1: f64,
        tol: f64,
        atol: f64,
        reference: &[f64],
    ) -> Point {
        macro_rules! solve {
            ($n:expr, $rhs:expr, $jv:expr, $init:expr) => {{
                let run = || -> Option<Vec<f64>> {
                    let p = OdeBuilder::<M>::new()
                        .rtol(tol)
                        .atol([atol])
                        .rhs_implicit($rhs, $jv)
                        .init($init, $n)
                        .build()
                        .ok()?;
                    if sdirk {
                        let mut s = p.tr_bdf2::<LS>().ok()?;
                        s.solve(t1).ok()?;
                        Some((0..$n).map(|i| s.state().y[i]).collect())
                    } else {
                        let mut s = p.bdf::<LS>().ok()?;
                        s.solve(t1).ok()?;
                        Some((0..$n).map(|i| s.state().y[i]).collect())
                    }
                };
                let (d, y) = time(run);
                Point {
                    tol,
                    error: y.map_or(f64::INFINITY, |y| mixed_error(&y, reference)),
                    seconds: d.as_secs_f64(),
                }
            }};
        }
        match problem {
            "vdpol" => solve!(
                2,
                |x, _p, _t, y| {
                    y[0] = x[1];
                    y[1] = ((1.0 - x[0] * x[0]) * x[1] - x[0]) / 1e-6;
                },
                |x, _p, _t, v, y| {
                    y[0] = v[1];
                    y[1] = ((-2.0 * x[0] * x[1] - 1.0) * v[0] + (1.0 - x[0] * x[0]) * v[1]) / 1e-6;
                },
                |_p, _t, y| {
                    y[0] = 2.0;
                    y[1] = 0.0;
                }
            ),
            "robertson" => solve!(
                3,
                |x, _p, _t, y| {
                    y[0] = -0.04 * x[0] + 1e4 * x[1] * x[2];
                    y[1] = 0.04 * x[0] - 1e4 * x[1] * x[2] - 3e7 * x[1] * x[1];
                    y[2] = 3e7 * x[1] * x[1];
                },
                |x, _p, _t, v, y| {
                    y[0] = -0.04 * v[0] + 1e4 * v[1] * x[2] + 1e4 * x[1] * v[2];
                    y[1] = 0.04 * v[0] - 1e4 * v[1] * x[2] - 1e4 * x[1] * v[2] - 6e7 * x[1] * v[1];
                    y[2] = 6e7 * x[1] * v[1];
                },
                |_p, _t, y| {
                    y[0] = 1.0;
                    y[1] = 0.0;
                    y[2] = 0.0;
                }
            ),
            _ => solve!(
                8,
                |x, _p, _t, y| {
                    y[0] = -1.71 * x[0] + 0.43 * x[1] + 8.32 * x[2] + 0.0007;
                    y[1] = 1.71 * x[0] - 8.75 * x[1];
                    y[2] = -10.03 * x[2] + 0.43 * x[3] + 0.035 * x[4];
                    y[3] = 8.32 * x[1] + 1.71 * x[2] - 1.12 * x[3];
                    y[4] = -1.745 * x[4] + 0.43 * x[5] + 0.43 * x[6];
                    y[5] = -280.0 * x[5] * x[7] + 0.69 * x[3] + 1.71 * x[4] - 0.43 * x[5]
                        + 0.69 * x[6];
                    y[6] = 280.0 * x[5] * x[7] - 1.81 * x[6];
                    y[7] = -280.0 * x[5] * x[7] + 1.81 * x[6];
                },
                |x, _p, _t, v, y| {
                    y[0] = -1.71 * v[0] + 0.43 * v[1] + 8.32 * v[2];
                    y[1] = 1.71 * v[0] - 8.75 * v[1];
                    y[2] = -10.03 * v[2] + 0.43 * v[3] + 0.035 * v[4];
                    y[3] = 8.32 * v[1] + 1.71 * v[2] - 1.12 * v[3];
                    y[4] = -1.745 * v[4] + 0.43 * v[5] + 0.43 * v[6];
                    let nl = 280.0 * (v[5] * x[7] + x[5] * v[7]);
                    y[5] = -nl + 0.69 * v[3] + 1.71 * v[4] - 0.43 * v[5] + 0.69 * v[6];
                    y[6] = nl - 1.81 * v[6];
                    y[7] = -nl + 1.81 * v[6];
                },
                |_p, _t, y| {
                    for i in 0..8 {
                        y[i] = 0.0;
                    }
                    y[0] = 1.0;
                    y[7] = 0.0057;
                }
            ),
        }
    }
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
    let options = Options::new()
        .method(method)
        .rtol(tol)
        .atol(tol)
        .dense_output(false)
        .formulation(formulation);
    let (d, sol) = time(|| model.simulate(0.0, 10.0, &options));
    let (error, steps) = match sol {
        Ok(sol) => {
            let got = cartesian(sol.state(sol.times().len() - 1).unwrap_or(&[0.0; 4]));
            (
                mixed_error(&got, &CASH_PENDULUM_AT_10[..4]),
                sol.stats().steps,
            )
        }
        Err(_) => (f64::INFINITY, 0),
    };
    (
        Point {
            tol,
            error,
            seconds: d.as_secs_f64(),
        },
        steps,
    )
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
    let ode = SliderCrankAngle {
        phi0,
        ..SliderCrankAngle::default()
    };
    let reference = ode
        .simulate(
            0.0,
            2.0,
            &Options::new()
                .method(Method::Dop853)
                .rtol(1e-13)
                .atol(1e-13),
        )
        .and_then(|s| s.last("phi"))
        .unwrap_or(f64::NAN);
    for tol in [1e-6, 1e-9, 1e-12] {
        let options = Options::new()
            .method(Method::Dop853)
            .rtol(tol)
            .atol(tol)
            .dense_output(false);
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
        s += &format!(
            "revolute(rod{}, vec3(0.5, 0.0, 0.0), rod{i}, vec3(-0.5, 0.0, 0.0));",
            i - 1
        );
    }
    s + "gravity(vec3(0.0, -g, 0.0)); }"
}

/// A ten-rod chain in the global and the recursive formulation: macro
/// expansion time and generated size, and the run's cost per step.
fn formulations() {
    println!(
        "\n### Ten-rod chain: global against recursive formulation (DOP853, tol 1e-8, t = 1)\n"
    );
    println!(
        "| formulation | expansion (ms) | generated (kB) | states | run (ms) | steps | µs/step |"
    );
    println!("|---|---|---|---|---|---|---|");
    let source: proc_macro2::TokenStream = rod_chain_source(10).parse().expect("the chain parses");
    let options = Options::new()
        .method(Method::Dop853)
        .rtol(1e-8)
        .atol(1e-8)
        .dense_output(false);
    for (name, attr) in [
        ("global", "scene = global"),
        ("recursive", "scene = recursive"),
    ] {
        let attr: proc_macro2::TokenStream = attr.parse().expect("the attribute parses");
        let (expansion, tokens) =
            time(|| daegen::codegen::expand_dae_model(attr.clone(), source.clone()));
        let kb = tokens.to_string().len() as f64 / 1e3;
        let (run, steps, states) = if name == "global" {
            let (d, s) = time(|| RodChainGlobal::default().simulate(0.0, 1.0, &options));
            (
                d,
                s.map(|s| s.stats().steps).unwrap_or(0),
                RodChainGlobal::STATES,
            )
        } else {
            let (d, s) = time(|| RodChainRecursive::default().simulate(0.0, 1.0, &options));
            (
                d,
                s.map(|s| s.stats().steps).unwrap_or(0),
                RodChainRecursive::STATES,
            )
        };
        println!(
            "| {name} | {:.1} | {kb:.0} | {states} | {:.2} | {steps} | {:.1} |",
            expansion.as_secs_f64() * 1e3,
            run.as_secs_f64() * 1e3,
            run.as_secs_f64() * 1e6 / steps.max(1) as f64
        );
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
            let (a, sa) = pendulum_run(&dae, method, tol, formulation, &|s| {
                [s[0], s[1], s[2], s[3]]
            });
            let (b, sb) = pendulum_run(&ode, method, tol, Formulation::IndexOneProjected, &|s| {
                let (theta, omega) = (s[0], s[1]);
                [
                    theta.cos(),
                    theta.sin(),
                    -omega * theta.sin(),
                    omega * theta.cos(),
                ]
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

/// SciPy or heyoka through peer.py: `None` when Python or the package is missing.
fn python_peer(problem: &str, solver: &str, tol: f64, atol: Option<f64>) -> Option<Point> {
    let script = concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/peers/peer.py");
    let mut cmd = Command::new("python3");
    cmd.arg(script)
        .arg(problem)
        .arg("--solver")
        .arg(solver)
        .arg("--tol")
        .arg(format!("{tol:e}"))
        .arg("--repeat")
        .arg("5");
    if let Some(a) = atol {
        cmd.arg("--atol").arg(format!("{a:e}"));
    }
    let out = cmd.output().ok()?;
    let text = String::from_utf8_lossy(&out.stdout);
    let field = |name: &str| -> Option<f64> {
        let i = text.find(&format!("\"{name}\""))?;
        let rest = &text[i + name.len() + 3..];
        let end = rest.find([',', '}'])?;
        rest[..end].trim().parse().ok()
    };
    Some(Point {
        tol,
        // Problems without a reference (Lorenz) report no error.
        error: field("max_mixed_err").unwrap_or(f64::NAN),
        seconds: field("solve_s")?,
    })
}

fn ratio(r: f64) -> String {
    if r < 0.1 {
        format!("{r:.1e}×")
    } else {
        format!("{r:.2}×")
    }
}

/// Our time over the peer's at the same tolerance, for peers whose final
/// values cannot be trusted for an equal-error comparison.
fn report_equal_tolerance(
    problem: &str,
    ours: &[(&str, Vec<Point>)],
    peers: &[(&str, Vec<Point>)],
) {
    println!("\n{problem}, at equal tolerance (same algorithm and controller defaults):\n");
    for ((name, curve), (peer, peer_curve)) in ours.iter().zip(peers) {
        let cells: Vec<String> = curve
            .iter()
            .zip(peer_curve)
            .map(|(p, q)| format!("{:.0e}: {}", p.tol, ratio(p.seconds / q.seconds)))
            .collect();
        println!("- {name} / {peer}: {}", cells.join(", "));
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
                    .map(|p| {
                        format!(
                            "{:.0e}: {:.2e} in {:.3} ms",
                            p.tol,
                            p.error,
                            p.seconds * 1e3
                        )
                    })
                    .collect();
                println!("\n{name}: {}", pts.join("; "));
            }
        }
    }
}

fn main() {
    let python = !std::env::args().any(|a| a == "--no-python");
    if std::env::args().any(|a| a == "--dae-only") {
        dae_section(&(4..=10).map(|k| 10f64.powi(-k)).collect::<Vec<_>>());
        return;
    }
    let collect_python = |problem: &str,
                          solver: &str,
                          tols: &[f64],
                          atol: &dyn Fn(f64) -> Option<f64>|
     -> Option<Vec<Point>> {
        if !python {
            return None;
        }
        tols.iter()
            .map(|&t| python_peer(problem, solver, t, atol(t)))
            .collect()
    };
    let nonstiff_tols: Vec<f64> = (4..=12).map(|k| 10f64.powi(-k)).collect();
    let taylor_tols: Vec<f64> = (4..=15).map(|k| 10f64.powi(-k)).collect();

    // Non-stiff.
    let kepler_t1 = 20.0 * std::f64::consts::PI;
    let kepler_ref = kepler_exact(kepler_t1);
    let k = Kepler::default();
    let kepler_ours = vec![
        (
            "daegen DOPRI5",
            nonstiff_tols
                .iter()
                .map(|&t| ours(&k, kepler_t1, Method::Dopri5, t, t, &kepler_ref))
                .collect(),
        ),
        (
            "daegen DOP853",
            nonstiff_tols
                .iter()
                .map(|&t| ours(&k, kepler_t1, Method::Dop853, t, t, &kepler_ref))
                .collect(),
        ),
        (
            "daegen Taylor",
            taylor_tols
                .iter()
                .map(|&t| ours(&k, kepler_t1, Method::Taylor, t, t, &kepler_ref))
                .collect(),
        ),
        (
            "daegen Taylor (compact)",
            taylor_tols
                .iter()
                .map(|&t| ours_compact(&k, kepler_t1, t, &kepler_ref))
                .collect(),
        ),
    ];
    eprintln!("kepler: ours done");
    let k0 = kepler_exact(0.0);
    let kepler_peers = vec![
        (
            "ode_solvers Dopri5",
            Some(
                nonstiff_tols
                    .iter()
                    .map(|&t| peers::ode_solvers("kepler", false, k0, kepler_t1, t, &kepler_ref))
                    .collect(),
            ),
        ),
        (
            "ode_solvers Dop853",
            Some(
                nonstiff_tols
                    .iter()
                    .map(|&t| peers::ode_solvers("kepler", true, k0, kepler_t1, t, &kepler_ref))
                    .collect(),
            ),
        ),
        (
            "SciPy DOP853",
            collect_python("kepler", "DOP853", &nonstiff_tols, &|_| None),
        ),
        (
            "heyoka",
            collect_python("kepler", "heyoka", &taylor_tols, &|_| None),
        ),
    ];
    report(
        "Kepler e = 0.9, ten orbits (t = 20π), exact reference",
        &kepler_ours,
        &kepler_peers,
    );
    let equal = |i: usize| kepler_peers[i].1.clone().unwrap_or_default();
    report_equal_tolerance(
        "Kepler",
        &kepler_ours[..2],
        &[
            ("ode_solvers Dopri5", equal(0)),
            ("ode_solvers Dop853", equal(1)),
        ],
    );

    let a = Arenstorf::default();
    let aren_ours = vec![
        (
            "daegen DOPRI5",
            nonstiff_tols
                .iter()
                .map(|&t| ours(&a, ARENSTORF_T, Method::Dopri5, t, t, &ARENSTORF_Y0))
                .collect(),
        ),
        (
            "daegen DOP853",
            nonstiff_tols
                .iter()
                .map(|&t| ours(&a, ARENSTORF_T, Method::Dop853, t, t, &ARENSTORF_Y0))
                .collect(),
        ),
        (
            "daegen Taylor",
            taylor_tols
                .iter()
                .map(|&t| ours(&a, ARENSTORF_T, Method::Taylor, t, t, &ARENSTORF_Y0))
                .collect(),
        ),
        (
            "daegen Taylor (compact)",
            taylor_tols
                .iter()
                .map(|&t| ours_compact(&a, ARENSTORF_T, t, &ARENSTORF_Y0))
                .collect(),
        ),
    ];
    let aren_peers = vec![
        (
            "ode_solvers Dopri5",
            Some(
                nonstiff_tols
                    .iter()
                    .map(|&t| {
                        peers::ode_solvers(
                            "arenstorf",
                            false,
                            ARENSTORF_Y0,
                            ARENSTORF_T,
                            t,
                            &ARENSTORF_Y0,
                        )
                    })
                    .collect(),
            ),
        ),
        (
            "ode_solvers Dop853",
            Some(
                nonstiff_tols
                    .iter()
                    .map(|&t| {
                        peers::ode_solvers(
                            "arenstorf",
                            true,
                            ARENSTORF_Y0,
                            ARENSTORF_T,
                            t,
                            &ARENSTORF_Y0,
                        )
                    })
                    .collect(),
            ),
        ),
        (
            "SciPy DOP853",
            collect_python("arenstorf", "DOP853", &nonstiff_tols, &|_| None),
        ),
        (
            "heyoka",
            collect_python("arenstorf", "heyoka", &taylor_tols, &|_| None),
        ),
    ];
    report(
        "Arenstorf, one period, back to the start",
        &aren_ours,
        &aren_peers,
    );
    let equal = |i: usize| aren_peers[i].1.clone().unwrap_or_default();
    report_equal_tolerance(
        "Arenstorf",
        &aren_ours[..2],
        &[
            ("ode_solvers Dopri5", equal(0)),
            ("ode_solvers Dop853", equal(1)),
        ],
    );

    // The outer solar system over 20 000 days (the tolerances).
    let oss_tols = [1e-9, 1e-12, 1e-15];
    let oss = OuterSolarSystem::default();
    let oss_ours = vec![
        (
            "daegen DOP853",
            oss_tols[..2]
                .iter()
                .map(|&t| ours(&oss, 20000.0, Method::Dop853, t, t, &OSS_REFERENCE))
                .collect(),
        ),
        (
            "daegen Taylor",
            oss_tols
                .iter()
                .map(|&t| ours(&oss, 20000.0, Method::Taylor, t, t, &OSS_REFERENCE))
                .collect(),
        ),
        (
            "daegen Taylor (compact)",
            oss_tols
                .iter()
                .map(|&t| ours_compact(&oss, 20000.0, t, &OSS_REFERENCE))
                .collect(),
        ),
    ];
    let oss_peers = vec![
        (
            "SciPy DOP853",
            collect_python("outer_solar_system", "DOP853", &oss_tols[..2], &|_| None),
        ),
        (
            "heyoka",
            collect_python("outer_solar_system", "heyoka", &oss_tols, &|_| None),
        ),
    ];
    report(
        "Outer solar system (GNI), 20 000 days, recomputed reference",
        &oss_ours,
        &oss_peers,
    );

    // Lorenz to t = 20: chaotic, so no reference; the two Taylor codes share
    // the order and step rules, so equal tolerance is equal work.
    let lorenz_tols = [1e-9, 1e-12, 1e-15];
    let lorenz_ours = vec![(
        "daegen Taylor",
        lorenz_tols
            .iter()
            .map(|&t| ours(&Lorenz::default(), 20.0, Method::Taylor, t, t, &[]))
            .collect(),
    )];
    if let Some(heyoka) = collect_python("lorenz", "heyoka", &lorenz_tols, &|_| None) {
        report_equal_tolerance("Lorenz to t = 20", &lorenz_ours, &[("heyoka", heyoka)]);
    }

    // Stiff.
    let stiff_tols: Vec<f64> = (4..=10).map(|k| 10f64.powi(-k)).collect();
    let v = VanDerPol::default();
    let vdp_ours = vec![(
        "daegen RADAU5",
        stiff_tols
            .iter()
            .map(|&t| ours(&v, 2.0, Method::Radau5, t, t, &VDP_AT_2))
            .collect(),
    )];
    let vdp_peers = vec![
        (
            "diffsol BDF",
            Some(
                stiff_tols
                    .iter()
                    .map(|&t| diffsol_peer::run("vdpol", false, 2.0, t, t, &VDP_AT_2))
                    .collect(),
            ),
        ),
        (
            "diffsol TR-BDF2",
            Some(
                stiff_tols
                    .iter()
                    .map(|&t| diffsol_peer::run("vdpol", true, 2.0, t, t, &VDP_AT_2))
                    .collect(),
            ),
        ),
        (
            "SciPy Radau",
            collect_python("vdpol", "Radau", &stiff_tols, &|_| None),
        ),
        (
            "SciPy BDF",
            collect_python("vdpol", "BDF", &stiff_tols, &|_| None),
        ),
    ];
    report(
        "Van der Pol ε = 1e-6 to t = 2 (test set vdpol)",
        &vdp_ours,
        &vdp_peers,
    );

    let r = Robertson::default();
    let rober_ours = vec![(
        "daegen RADAU5",
        stiff_tols
            .iter()
            .map(|&t| ours(&r, 1e11, Method::Radau5, t, 1e-6 * t, &ROBER_AT_1E11))
            .collect(),
    )];
    let rober_peers = vec![
        (
            "diffsol BDF",
            Some(
                stiff_tols
                    .iter()
                    .map(|&t| {
                        diffsol_peer::run("robertson", false, 1e11, t, 1e-6 * t, &ROBER_AT_1E11)
                    })
                    .collect(),
            ),
        ),
        (
            "diffsol TR-BDF2",
            Some(
                stiff_tols
                    .iter()
                    .map(|&t| {
                        diffsol_peer::run("robertson", true, 1e11, t, 1e-6 * t, &ROBER_AT_1E11)
                    })
                    .collect(),
            ),
        ),
        (
            "SciPy Radau",
            collect_python("robertson_1e11", "Radau", &stiff_tols, &|t| Some(1e-6 * t)),
        ),
        (
            "SciPy BDF",
            collect_python("robertson_1e11", "BDF", &stiff_tols, &|t| Some(1e-6 * t)),
        ),
    ];
    report(
        "Robertson to t = 1e11 (test set rober), atol = 1e-6·rtol",
        &rober_ours,
        &rober_peers,
    );

    let h = Hires::default();
    let hires_ours = vec![(
        "daegen RADAU5",
        stiff_tols
            .iter()
            .map(|&t| ours(&h, 321.8122, Method::Radau5, t, t, &HIRES_AT_END))
            .collect(),
    )];
    let hires_peers = vec![
        (
            "diffsol BDF",
            Some(
                stiff_tols
                    .iter()
                    .map(|&t| diffsol_peer::run("hires", false, 321.8122, t, t, &HIRES_AT_END))
                    .collect(),
            ),
        ),
        (
            "diffsol TR-BDF2",
            Some(
                stiff_tols
                    .iter()
                    .map(|&t| diffsol_peer::run("hires", true, 321.8122, t, t, &HIRES_AT_END))
                    .collect(),
            ),
        ),
        (
            "SciPy Radau",
            collect_python("hires", "Radau", &stiff_tols, &|_| None),
        ),
        (
            "SciPy BDF",
            collect_python("hires", "BDF", &stiff_tols, &|_| None),
        ),
    ];
    report(
        "HIRES to t = 321.8122 (test set hires)",
        &hires_ours,
        &hires_peers,
    );

    dae_section(&stiff_tols);
}

/// The DAE forms: the pendulum against its ODE, Robertson's index-1 DAE
/// against diffsol's mass-matrix BDF. `--dae-only` runs just this.
fn dae_section(stiff_tols: &[f64]) {
    dae_against_ode();
    slider_crank_against_ode();
    formulations();
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
                Point {
                    tol: t,
                    error,
                    seconds: d.as_secs_f64(),
                }
            })
            .collect(),
    )];
    let rober_dae_peers = vec![(
        "diffsol BDF (mass matrix)",
        Some(
            stiff_tols
                .iter()
                .map(|&t| diffsol_robertson_dae(t, 1e-6 * t))
                .collect(),
        ),
    )];
    report(
        "Robertson as an index-1 DAE to t = 1e11, atol = 1e-6·rtol",
        &rober_dae_ours,
        &rober_dae_peers,
    );
}
