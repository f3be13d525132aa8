//! Hybrid models against heyoka (`--hybrid`): a bouncing ball to its 20th
//! bounce (an event that resets the speed) and a PI controller sampled at
//! 1 kHz for a second (a clock), each at several tolerances, timed here
//! and by `peers/hybrid.py` in one run, with the error of each against the
//! exact result (the geometric series of the bounce times; the
//! zero-order-hold recursion of the sampled loop). heyoka has events with
//! callbacks but no clocks: its users step to each instant from Python,
//! which the second row's time includes. Writes `results/hybrid.md`.

use super::*;
use daegen_workprecision::median_time;

/// The ball of the tests: dropped from 10 m, restitution 0.8.
#[dae_model]
fn ball() {
    let e = param(0.8);
    let h = state(10.0);
    der(der(h)) == -9.81;
    let bounce = event(h).falling().reinit(der(h), -e * pre(der(h)));
}

/// x' = −2x + 3u under a PI controller sampled every millisecond.
#[dae_model]
fn sampled_pi_1khz() {
    let h = param(1e-3);
    let x = state(0.0);
    let u = discrete(0.0);
    let integral = discrete(0.0);
    der(x) == -2.0 * x + 3.0 * u;
    let sample = every(h)
        .reinit(integral, integral + 1.5 * h * (1.0 - x))
        .reinit(u, 0.8 * (1.0 - x) + integral);
}

const BOUNCES: usize = 20;
const SAMPLES: usize = 1000;

include!("../../tests/support/impact_times.rs");

/// The bounce times of the ball dropped from 10 m (restitution 0.8).
fn bounce_times() -> Vec<f64> {
    impact_times(10.0, 9.81, 0.8, BOUNCES)
}

/// x at 1 s from the zero-order-hold recursion: with u held over a
/// sample, x_{k+1} = φ x_k + (3/2)(1 − φ) u_k, φ = e^{−2h}.
fn sampled_x_end() -> f64 {
    let h = 1e-3f64;
    let phi = (-2.0 * h).exp();
    let (mut x, mut integral) = (0.0f64, 0.0f64);
    for _ in 0..SAMPLES {
        let e = 1.0 - x;
        integral += 1.5 * h * e;
        let u = 0.8 * e + integral;
        x = phi * x + 1.5 * (1.0 - phi) * u;
    }
    x
}

/// The largest relative error of `got` against `want`.
fn worst(got: &[f64], want: &[f64]) -> f64 {
    if got.len() != want.len() {
        return f64::INFINITY;
    }
    got.iter().zip(want).map(|(a, b)| ((a - b) / b).abs()).fold(0.0, f64::max)
}

/// heyoka's times and results at `tol`: (ball seconds, bounce times,
/// sampled seconds, x at the end).
fn heyoka(tol: f64) -> Result<(f64, Vec<f64>, f64, f64), String> {
    let script = concat!(env!("CARGO_MANIFEST_DIR"), "/peers/hybrid.py");
    let out = Command::new("python3")
        .arg(script)
        .args(["--tol", &format!("{tol:e}")])
        .output()
        .map_err(|e| format!("python3 not found: {e}"))?;
    if !out.status.success() {
        let stderr = String::from_utf8_lossy(&out.stderr);
        return Err(format!("not run: {}", stderr.lines().last().unwrap_or("").trim()));
    }
    let json = String::from_utf8_lossy(&out.stdout).to_string();
    let number = |name: &str, from: usize| -> Option<f64> {
        let at = json[from..].find(&format!("\"{name}\": "))? + from + name.len() + 4;
        json[at..].split([',', '}']).next()?.trim().parse().ok()
    };
    let ball_at = json.find("\"ball\"").ok_or("no ball")?;
    let pi_at = json.find("\"sampled_pi\"").ok_or("no sampled_pi")?;
    let times_at = json.find("\"bounce_times\": [").ok_or("no bounce times")? + 17;
    let times_end = times_at + json[times_at..].find(']').ok_or("unterminated")?;
    let times: Vec<f64> =
        json[times_at..times_end].split(',').filter_map(|s| s.trim().parse().ok()).collect();
    match (number("seconds", ball_at), number("seconds", pi_at), number("x_end", pi_at)) {
        (Some(b), Some(p), Some(x)) => Ok((b, times, p, x)),
        _ => Err(format!("unreadable output: {json}")),
    }
}

/// Writes results/hybrid.md.
pub fn hybrid_section() -> String {
    let settings = Settings::default();
    let exact_times = bounce_times();
    let exact_x = sampled_x_end();
    let t_ball = exact_times[BOUNCES - 1] + 0.01;
    let mut text = format!(
        "# Hybrid models\n\nMachine: {}. Written by `cd bench && cargo run --release -- --hybrid` (bench/src/hybrid.rs, peers/hybrid.py). Time: the median of the runs in the budget here, heyoka's fastest of 21 (its integrator built before the clock starts, its Python callback or loop included); error: the largest relative error of the 20 bounce times against their geometric series, and of x(1) against the zero-order-hold recursion. Ratio: ours over heyoka's.\n\n| problem | tol | method | time | error | heyoka time | heyoka error | ratio |\n|---|---|---|---|---|---|---|---|\n",
        machine()
    );
    for tol in [1e-6, 1e-9, 1e-12] {
        eprintln!("hybrid: tol {tol:e}");
        let peer = heyoka(tol);
        for method in [Method::Taylor, Method::Dop853, Method::Auto] {
            let opts = Options::new().method(method).tolerance(tol);
            let (seconds, times) = median_time(&settings, || {
                Ball::default().simulate(0.0, t_ball, &opts).map(|s| s.event_times("bounce"))
            });
            let error = match times {
                Ok(Ok(times)) => worst(&times, &exact_times),
                _ => f64::INFINITY,
            };
            let (peer_time, peer_error, ratio) = match &peer {
                Ok((s, times, _, _)) => (
                    format!("{:.1} µs", s * 1e6),
                    format!("{:.1e}", worst(times, &exact_times)),
                    format!("{:.2}×", seconds / s),
                ),
                Err(e) => (e.clone(), String::new(), String::new()),
            };
            text.push_str(&format!(
                "| ball, {BOUNCES} bounces | {tol:.0e} | {} | {:.1} µs | {error:.1e} | {peer_time} | {peer_error} | {ratio} |\n",
                method.name(),
                seconds * 1e6
            ));
        }
        for method in [Method::Taylor, Method::Dop853, Method::Auto] {
            let opts = Options::new().method(method).tolerance(tol).output_times(vec![1.0]);
            let (seconds, x) = median_time(&settings, || {
                SampledPi1khz::default().simulate(0.0, 1.0, &opts).and_then(|s| s.last("x"))
            });
            let error = x.map_or(f64::INFINITY, |x| ((x - exact_x) / exact_x).abs());
            let (peer_time, peer_error, ratio) = match &peer {
                Ok((_, _, s, x)) => (
                    format!("{:.0} µs", s * 1e6),
                    format!("{:.1e}", ((x - exact_x) / exact_x).abs()),
                    format!("{:.2}×", seconds / s),
                ),
                Err(e) => (e.clone(), String::new(), String::new()),
            };
            text.push_str(&format!(
                "| PI at 1 kHz, {SAMPLES} samples | {tol:.0e} | {} | {:.0} µs | {error:.1e} | {peer_time} | {peer_error} | {ratio} |\n",
                method.name(),
                seconds * 1e6
            ));
        }
    }
    text
}
