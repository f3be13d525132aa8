//! Robertson's chemical kinetics (the IVP test set's `rober`), a classic
//! stiff problem: reaction rates from 0.04 to 3e7, time scales from 1e-5
//! to 1e11. RADAU5 with the generated Jacobian integrates to t = 1e11 and
//! meets the published reference there; DOP853 stops with an error that
//! says the problem turned stiff and what to use. The solution at every
//! decade is printed, written as CSV and drawn against log10 t as SVG
//! under `target/example-output/`.
//!
//! Run: `cargo run --release --example robertson`

use daegen::plot::{line_chart_svg, Series};
use daegen::prelude::*;
use std::path::PathBuf;

/// Three species, A → B (slow), B + B → C + B (fast), B + C → A + C.
#[dae_model]
fn robertson() {
    let k1 = param(0.04);
    let k2 = param(3e7);
    let k3 = param(1e4);
    let y1 = state(1.0);
    let y2 = state(0.0);
    let y3 = state(0.0);
    der(y1) == -k1 * y1 + k3 * y2 * y3;
    der(y2) == k1 * y1 - k3 * y2 * y3 - k2 * y2 * y2;
    der(y3) == k2 * y2 * y2;
    /// y1 + y2 + y3, conserved (= 1).
    let total = output(y1 + y2 + y3);
}

/// The IVP test set's reference at t = 1e11 (`rober.f`, RADAU in quadruple
/// precision, rtol = atol = 1.1e-18).
const REFERENCE: [f64; 3] = [0.2083340149701255e-07, 0.8333360770334713e-13, 0.9999999791665050];

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let model = Robertson::default();
    let t1 = 1e11;
    // y2 falls to 1e-13: its absolute tolerance must lie far below that.
    let radau = Options::new().method(Method::Radau5).rtol(1e-10).atol(1e-20);
    let decades: Vec<f64> = std::iter::once(0.0).chain((-5..=11).map(|k| 10f64.powi(k))).collect();
    let sol = model.simulate(0.0, t1, &radau.output_times(decades))?;
    println!("Robertson to t = 1e11, RADAU5, rtol 1e-10, atol 1e-20\n");
    println!("{}", sol.table(&["y1", "y2", "y3", "total"])?);
    let stats = sol.stats();
    println!(
        "\n{} steps, {} rejected, {} Jacobians",
        stats.steps, stats.rejected, stats.jacobian_evals
    );
    println!("at t = 1e11, relative deviation from the published reference:");
    for (k, name) in ["y1", "y2", "y3"].iter().enumerate() {
        let deviation = (sol.last(name)? - REFERENCE[k]).abs() / REFERENCE[k];
        println!("  {name}: {deviation:.1e}");
    }

    match model.simulate(0.0, t1, &Options::new().method(Method::Dop853).rtol(1e-6).atol(1e-10)) {
        Err(e) => println!("\nDOP853 on the same problem:\n  {e}"),
        Ok(s) => println!("\nDOP853 finished in {} steps", s.stats().steps),
    }

    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target/example-output");
    std::fs::create_dir_all(&dir)?;
    sol.write_csv(std::fs::File::create(dir.join("robertson.csv"))?, &sol.names())?;
    // Against log10 t, y2 scaled by 1e4 to share the axis.
    let curve = |name: &str, scale: f64| -> Result<Vec<(f64, f64)>, daegen::Error> {
        let values = sol.column(name)?;
        Ok(sol.times().iter().zip(values).skip(1).map(|(t, v)| (t.log10(), scale * v)).collect())
    };
    let series = [
        Series { name: "y1", points: curve("y1", 1.0)? },
        Series { name: "1e4 · y2", points: curve("y2", 1e4)? },
        Series { name: "y3", points: curve("y3", 1.0)? },
    ];
    let svg = line_chart_svg("Robertson (RADAU5)", "log10 t", "concentration", &series)?;
    std::fs::write(dir.join("robertson.svg"), svg)?;
    println!("\nwrote robertson.csv and robertson.svg in {}", dir.display());
    Ok(())
}
