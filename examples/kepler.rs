//! Kepler's problem with eccentricity 0.9 over ten orbits, by the adaptive
//! Taylor method against DOP853, both checked against the exact solution
//! from Kepler's equation: steps, error and energy drift at each
//! tolerance. One orbit is then printed as a table, written as CSV and
//! drawn (q2 against q1) as SVG under `target/example-output/`.
//!
//! Run: `cargo run --release --example kepler`

use daegen::prelude::*;
use std::f64::consts::PI;
use std::path::PathBuf;

// tests/models/kepler.rs holds the same orbit for the tests; an example is
// read alone, so it writes its model out.
/// The two-body problem in the plane, in units where the period is 2π,
/// started at the pericentre of an orbit of eccentricity e.
#[dae_model]
fn kepler() {
    /// Eccentricity.
    let e = param(0.9);
    /// Position (the centre of attraction at the origin).
    let q1 = state(1.0 - e);
    let q2 = state(0.0);
    /// Momentum.
    let p1 = state(0.0);
    let p2 = state(sqrt((1.0 + e) / (1.0 - e)));
    let r3 = (q1 * q1 + q2 * q2).powf(-1.5);
    der(q1) == p1;
    der(q2) == p2;
    der(p1) == -q1 * r3;
    der(p2) == -q2 * r3;
    /// Energy, −1/2 on this orbit.
    let energy = output(0.5 * (p1 * p1 + p2 * p2) - (q1 * q1 + q2 * q2).powf(-0.5));
}

/// The exact state at time t: the eccentric anomaly E from Kepler's
/// equation E − e sin E = t by Newton's method.
fn exact(t: f64, e: f64) -> [f64; 4] {
    let mut big_e = t + e * t.sin();
    for _ in 0..50 {
        big_e -= (big_e - e * big_e.sin() - t) / (1.0 - e * big_e.cos());
    }
    let (s, c) = big_e.sin_cos();
    let w = (1.0 - e * e).sqrt();
    [c - e, w * s, -s / (1.0 - e * c), w * c / (1.0 - e * c)]
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let model = Kepler::default();
    let t1 = 20.0 * PI;
    println!("Kepler e = 0.9, ten orbits (t = 20π), against Kepler's equation\n");
    println!("  method   tol      steps   f evals   max error at t1   energy drift");
    for tol in [1e-8, 1e-11, 1e-14] {
        for method in [Method::Dop853, Method::Taylor] {
            let opts = Options::new().method(method).tolerance(tol);
            let sol = model.simulate(0.0, t1, &opts)?;
            let error = sol
                .final_state()
                .iter()
                .zip(exact(t1, model.e))
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            let drift = (sol.last("energy")? + 0.5).abs();
            let stats = sol.stats();
            // A Taylor step evaluates the tape once per order.
            let evals = if method == Method::Taylor {
                format!("{} × order {}", stats.rhs_evals, stats.taylor_order)
            } else {
                stats.rhs_evals.to_string()
            };
            println!(
                "  {:7}  {tol:7.0e}  {:6}   {evals:14}  {error:10.2e}   {drift:10.2e}",
                format!("{method:?}"),
                stats.steps
            );
        }
    }

    // One orbit at 64 times, from the Taylor polynomials of the steps.
    let times: Vec<f64> = (0..=64).map(|k| 2.0 * PI * k as f64 / 64.0).collect();
    let opts = Options::new().method(Method::Taylor).tolerance(1e-12).output_times(times);
    let sol = model.simulate(0.0, 2.0 * PI, &opts)?;
    let worst = sol
        .times()
        .iter()
        .enumerate()
        .map(|(k, &t)| {
            let y = sol.state(k).unwrap_or(&[]);
            y.iter().zip(exact(t, model.e)).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max)
        })
        .fold(0.0, f64::max);
    println!("\nOne orbit, Taylor with tol 1e-12, every eighth of 64 output times:\n");
    let eighth: Vec<f64> = sol.times().iter().step_by(8).copied().collect();
    println!("{}", sol.sample(&["q1", "q2", "energy"], &eighth)?);
    println!("\nlargest error at the 64 output times: {worst:.1e}");
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target/example-output");
    std::fs::create_dir_all(&dir)?;
    sol.write_csv(std::fs::File::create(dir.join("kepler.csv"))?, &sol.names())?;
    daegen::plot::phase_portrait(&sol, "q1", "q2", dir.join("kepler.svg"))?;
    println!("wrote kepler.csv and kepler.svg in {}", dir.display());
    Ok(())
}
