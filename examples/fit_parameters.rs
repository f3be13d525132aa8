//! Fits the four rates of a Lotka–Volterra model to noisy observations by
//! Levenberg–Marquardt, with the Jacobian of the residuals from the
//! model's forward sensitivities (`#[dae_model(sensitivities = [..])]`):
//! one run per iteration gives the residuals and all their derivatives.
//!
//! Run: `cargo run --release --example fit_parameters`.

use daegen::prelude::*;

/// Prey x and predators y: x′ = a·x − b·x·y, y′ = c·x·y − d·y.
#[dae_model(sensitivities = [a, b, c, d])]
fn lotka_volterra() {
    /// Prey growth rate.
    let a = param(1.0);
    /// Predation rate.
    let b = param(1.0);
    /// Predator growth per prey eaten.
    let c = param(1.0);
    /// Predator death rate.
    let d = param(1.0);
    let x = state(10.0);
    let y = state(5.0);
    der(x) == a * x - b * x * y;
    der(y) == c * x * y - d * y;
}

const NAMES: [&str; 4] = ["a", "b", "c", "d"];

fn with_rates(p: &[f64; 4]) -> LotkaVolterra {
    LotkaVolterra { a: p[0], b: p[1], c: p[2], d: p[3] }
}

/// Residuals (model − data) at the observation times, and their Jacobian
/// with respect to the rates (row-major, 4 columns), from one run.
fn residuals(
    p: &[f64; 4],
    times: &[f64],
    data: &[(f64, f64)],
) -> Result<(Vec<f64>, Vec<f64>), Error> {
    let options = Options::new().method(Method::Dop853).tolerance(1e-10);
    let sol = with_rates(p).with_sensitivities().simulate(0.0, times[times.len() - 1], &options)?;
    let (mut r, mut jacobian) = (Vec::new(), Vec::new());
    for (&t, &(x, y)) in times.iter().zip(data) {
        for (state, observed) in [("x", x), ("y", y)] {
            r.push(sol.at(t, state)? - observed);
            for name in NAMES {
                jacobian.push(sol.sensitivity(t, state, name)?);
            }
        }
    }
    Ok((r, jacobian))
}

/// Solves the 4 × 4 system `a·x = b` by Gaussian elimination.
fn solve4(mut a: [[f64; 4]; 4], mut b: [f64; 4]) -> Option<[f64; 4]> {
    daegen::runtime::linalg::solve_in_place(&mut a, &mut b).then_some(b)
}

fn main() -> Result<(), Error> {
    let truth = [1.5, 1.0, 1.0, 3.0];
    // Observations every 0.2 time units to t = 4 (about two cycles), with
    // 2 % noise from a fixed pseudo-random sequence (a linear congruential
    // generator).
    let times: Vec<f64> = (1..=20).map(|k| 0.2 * k as f64).collect();
    let exact = with_rates(&truth).simulate(0.0, 4.0, &Options::new().tolerance(1e-12))?;
    let mut seed: u64 = 2026;
    let mut noise = || {
        seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        ((seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 0.04
    };
    let mut data = Vec::new();
    for &t in &times {
        let (x, y) = (exact.at(t, "x")?, exact.at(t, "y")?);
        data.push((x * (1.0 + noise()), y * (1.0 + noise())));
    }

    // Levenberg–Marquardt (Marquardt 1963): (JᵀJ + λ·diag(JᵀJ)) δ = −Jᵀr,
    // λ shrunk after a step that lowers the sum of squares, grown otherwise.
    // A start 13–20 % off (over many cycles the sum of squares of an
    // oscillator has other minima: the fit would need a closer start).
    let mut p = [1.3, 0.85, 1.15, 2.6];
    let mut lambda = 1e-3;
    let (mut r, mut jacobian) = residuals(&p, &times, &data)?;
    let mut cost: f64 = r.iter().map(|v| v * v).sum();
    println!("iteration   sum of squares   λ          a        b        c        d");
    println!(
        "{:>9}   {cost:>14.6e}   {lambda:<9.1e}  {:.5}  {:.5}  {:.5}  {:.5}",
        0, p[0], p[1], p[2], p[3]
    );
    for iteration in 1..=50 {
        let mut jtj = [[0.0; 4]; 4];
        let mut jtr = [0.0; 4];
        for (row, ri) in jacobian.chunks(4).zip(&r) {
            for i in 0..4 {
                jtr[i] += row[i] * ri;
                for j in 0..4 {
                    jtj[i][j] += row[i] * row[j];
                }
            }
        }
        let mut damped = jtj;
        (0..4).for_each(|i| damped[i][i] += lambda * jtj[i][i]);
        let Some(step) = solve4(damped, jtr.map(|v| -v)) else { break };
        let trial = [p[0] + step[0], p[1] + step[1], p[2] + step[2], p[3] + step[3]];
        let accepted = match residuals(&trial, &times, &data) {
            Ok((r_new, j_new)) => {
                let new_cost: f64 = r_new.iter().map(|v| v * v).sum();
                if new_cost < cost {
                    let relative = (cost - new_cost) / cost;
                    (p, r, jacobian, cost) = (trial, r_new, j_new, new_cost);
                    lambda = (lambda / 10.0).max(1e-12);
                    Some(relative)
                } else {
                    lambda *= 10.0;
                    None
                }
            }
            // Rates that make the run fail: a shorter step next time.
            Err(_) => {
                lambda *= 10.0;
                None
            }
        };
        println!(
            "{iteration:>9}   {cost:>14.6e}   {lambda:<9.1e}  {:.5}  {:.5}  {:.5}  {:.5}",
            p[0], p[1], p[2], p[3]
        );
        if accepted.is_some_and(|relative| relative < 1e-10) {
            break;
        }
    }
    println!("\nrate   fitted    truth");
    for (k, name) in NAMES.iter().enumerate() {
        println!("{name:<5}  {:.5}  {:.5}", p[k], truth[k]);
    }
    Ok(())
}
