//! The main job: a pendulum at large amplitudes, written in the model
//! language, integrated with RK4, its swings timed by an event on θ, and
//! checked against its exact period
//! T = 4 √(l/g) K(sin(θ₀/2)) (K the complete elliptic integral of the first
//! kind, computed here by the arithmetic–geometric mean).
//!
//! The same pendulum is then run as the contract's index-3 DAE in Cartesian
//! coordinates (x² + y² = l², the multiplier λ as an algebraic variable),
//! with its swings timed by an event on x and its constraint drift shown.
//!
//! Last, one swing at 170° is printed as a table, written as CSV, and
//! drawn as a time series and a phase portrait (SVG), all under
//! `target/example-output/`.
//!
//! Run: `cargo run --release --example pendulum`

use daegen::prelude::*;
use std::path::PathBuf;

/// Planar pendulum in its angle θ (the contract's pendulum, as an ODE).
#[dae_model]
fn pendulum() {
    /// Length (m).
    let l = param(1.0);
    /// Gravity (m/s²).
    let g = param(9.81);
    /// Initial angle (rad).
    let theta0 = param(1.0);
    let theta = state(theta0);
    der(der(theta)) == -g / l * sin(theta);
    /// Energy per unit mass (J/kg), conserved.
    let energy = output(0.5 * l * l * der(theta) * der(theta) - g * l * cos(theta));
    /// The bob passes under the pivot.
    let swing = event(theta);
}

// tests/models/items.rs holds the same pendulum for the tests; an example
// is read alone, so it writes its model out.
/// The contract's pendulum: an index-3 DAE in Cartesian coordinates.
#[dae_model]
fn pendulum_dae() {
    let m = param(1.0);
    let l = param(1.0);
    let g = param(9.81);
    let x0 = param(0.8414709848078965);
    let y0 = param(-0.5403023058681398);
    let x = state(x0);
    let y = state(y0);
    let u = state(0.0);
    let v = state(0.0);
    let lambda = algebraic(0.0);
    der(x) == u;
    der(y) == v;
    m * der(u) == -lambda * x;
    m * der(v) == -lambda * y - m * g;
    constraint(x * x + y * y - l * l);
    /// The bob passes under the pivot.
    let under_the_pivot = event(x);
}

/// K(k) = π / (2 AGM(1, √(1 - k²))).
fn elliptic_k(k: f64) -> f64 {
    let (mut a, mut b) = (1.0f64, (1.0 - k * k).sqrt());
    // Quadratic convergence: 30 rounds reach the last bit even for k → 1;
    // a tolerance test could cycle in the last bit forever.
    for _ in 0..30 {
        (a, b) = ((a + b) / 2.0, (a * b).sqrt());
    }
    std::f64::consts::PI / (2.0 * a)
}

/// The period from the crossings of the vertical: two per period.
fn period(crossings: &[f64]) -> f64 {
    match crossings {
        [first, .., last] if crossings.len() >= 3 => {
            (last - first) / ((crossings.len() - 1) as f64 / 2.0)
        }
        _ => f64::NAN,
    }
}

/// Where the example writes its files: `target/example-output/`.
fn output_dir() -> std::io::Result<PathBuf> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target/example-output");
    std::fs::create_dir_all(&dir)?;
    Ok(dir)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    println!("Pendulum, l = 1 m, g = 9.81 m/s², RK4 with h = 1e-4 s, 4 periods per amplitude\n");
    println!("  θ₀ (deg)   period (s)          exact (s)           rel. error   small-angle (s)   energy drift / gl");
    for degrees in [5.0, 30.0, 60.0, 90.0, 120.0, 150.0, 170.0, 179.0] {
        let theta0 = f64::to_radians(degrees);
        let model = Pendulum { theta0, ..Pendulum::default() };
        let exact = 4.0 * (model.l / model.g).sqrt() * elliptic_k((theta0 / 2.0).sin());
        let sol =
            model.simulate(0.0, 4.0 * exact, &Options::new().method(Method::Rk4).step(1e-4))?;
        let period = period(&sol.event_times("swing")?);
        let e0 = -model.g * model.l * theta0.cos();
        // Relative to g·l, the energy scale (E₀ itself is 0 at 90°).
        let drift = (sol.last("energy")? - e0).abs() / (model.g * model.l);
        let small = 2.0 * std::f64::consts::PI * (model.l / model.g).sqrt();
        println!(
            "  {degrees:8.1}   {period:.15}   {exact:.15}   {:10.2e}   {small:.6}          {drift:.1e}",
            (period - exact).abs() / exact
        );
    }
    println!("\nThe period grows without bound as θ₀ → 180°, where the small-angle formula fails.");

    println!(
        "\nThe same pendulum as an index-{} DAE in x, y, u, v, λ (DOP853, tol 1e-10, projected each step)\n",
        <PendulumDae as Model>::INDEX
    );
    println!(
        "  θ₀ (deg)   period (s)          rel. error   max |x² + y² − l²|   λ at the bottom (N)"
    );
    for degrees in [5.0, 60.0, 120.0, 170.0] {
        let theta0 = f64::to_radians(degrees);
        let model = PendulumDae { x0: theta0.sin(), y0: -theta0.cos(), ..PendulumDae::default() };
        let exact = 4.0 * (model.l / model.g).sqrt() * elliptic_k((theta0 / 2.0).sin());
        let opts = Options::new().method(Method::Dop853).tolerance(1e-10);
        let sol = model.simulate(0.0, 4.0 * exact, &opts)?;
        let crossings = sol.event_times("under_the_pivot")?;
        let period = period(&crossings);
        // At the bottom the rod carries the weight and the centripetal force.
        let bottom = crossings.first().copied().unwrap_or(f64::NAN);
        let lambda = sol.at(bottom, "lambda")? * model.l;
        println!(
            "  {degrees:8.1}   {period:.15}   {:10.2e}   {:18.1e}   {lambda:.6} (exact {:.6})",
            (period - exact).abs() / exact,
            sol.max_constraint_residual(),
            model.m * model.g * (3.0 - 2.0 * theta0.cos()),
        );
    }

    // One swing at 170°, through RK4's cubic Hermite interpolant.
    let model = Pendulum { theta0: f64::to_radians(170.0), ..Pendulum::default() };
    let sol = model.simulate(0.0, 6.0, &Options::new().method(Method::Rk4).step(1e-3))?;
    let grid: Vec<f64> = (0..=12).map(|k| 0.5 * k as f64).collect();
    println!("\nθ₀ = 170°, RK4 with h = 1e-3 s:\n");
    println!("{}", sol.sample(&["theta", "der(theta)", "energy"], &grid)?);
    let dir = output_dir()?;
    let csv = std::fs::File::create(dir.join("pendulum.csv"))?;
    sol.write_csv(csv, &sol.names())?;
    daegen::plot::time_series(&sol, &["theta", "der(theta)"], dir.join("pendulum.svg"))?;
    daegen::plot::phase_portrait(&sol, "theta", "der(theta)", dir.join("pendulum-phase.svg"))?;
    println!("\nwrote pendulum.csv, pendulum.svg and pendulum-phase.svg in {}", dir.display());
    Ok(())
}
