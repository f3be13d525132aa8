//! Kepler's problem with eccentricity 0.9 over ten orbits, by the adaptive
//! Taylor method, against its exact solution from Kepler's equation; the
//! orbit is written as CSV and drawn as SVG.
//!
//! Run: `cargo run --release --example kepler`

use daegen::prelude::*;
use daegen_workprecision::Series;

#[path = "support/output.rs"]
mod output;

include!("../tests/models/kepler.rs");
kepler_model!(taylor = 1);

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let t1 = 20.0 * std::f64::consts::PI;
    println!("Kepler e = 0.9, ten orbits (t = 20π), exact solution by Kepler's equation\n");
    println!("  method     tol      steps   error at t1   energy drift");
    for (method, tol) in [
        (Method::Dop853, 1e-10),
        (Method::Taylor, 1e-10),
        (Method::Taylor, 1e-15),
    ] {
        let opts = Options::new().method(method).rtol(tol).atol(tol);
        let sol = Kepler::default().simulate(0.0, t1, &opts)?;
        let exact = kepler_exact(t1);
        let error = sol
            .final_state()
            .iter()
            .zip(exact)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        let e0 = sol.at(0.0, "energy")?;
        let drift = (sol.last("energy")? - e0).abs();
        println!(
            "  {:8} {tol:7.0e}  {:6}   {error:10.2e}   {drift:10.2e}",
            format!("{method:?}"),
            sol.stats().steps
        );
    }
    // One orbit, sampled evenly, against the exact ellipse.
    let opts = Options::new()
        .method(Method::Taylor)
        .rtol(1e-12)
        .atol(1e-12);
    let sol = Kepler::default().simulate(0.0, 2.0 * std::f64::consts::PI, &opts)?;
    let mut rows = Vec::new();
    let (mut numeric, mut exact) = (Vec::new(), Vec::new());
    for k in 0..=400 {
        let t = 2.0 * std::f64::consts::PI * k as f64 / 400.0;
        let (x, y) = (sol.at(t, "q1")?, sol.at(t, "q2")?);
        let e = kepler_exact(t);
        rows.push(vec![t, x, y, e[0], e[1]]);
        numeric.push((x, y));
        exact.push((e[0], e[1]));
    }
    output::write(
        "kepler",
        &["t", "q1", "q2", "q1_exact", "q2_exact"],
        &rows,
        ("Kepler e = 0.9: one orbit", "q1", "q2"),
        &[
            Series {
                name: "Taylor, tol 1e-12",
                points: numeric,
            },
            Series {
                name: "exact",
                points: exact,
            },
        ],
    )?;
    Ok(())
}
