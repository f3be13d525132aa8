//! Van der Pol's oscillator with ε = 1e-6 (the IVP test set's `vdpol`), a
//! stiff problem: RADAU5 with the generated Jacobian reaches the published
//! solution at t = 2; an explicit method would need millions of steps.
//!
//! Run: `cargo run --release --example van_der_pol`

use daegen::prelude::*;
use daegen_workprecision::Series;

#[path = "support/output.rs"]
mod output;

include!("../tests/models/stiff.rs");
van_der_pol_model!();

fn main() -> Result<(), Box<dyn std::error::Error>> {
    println!("Van der Pol, ε = 1e-6, to t = 2 (published reference: IVP test set vdpol)\n");
    println!("  tol      steps  rejected  Jacobians   |y1 − ref|   |y2 − ref| / |ref|");
    for tol in [1e-4, 1e-6, 1e-8, 1e-10] {
        let opts = Options::new().method(Method::Radau5).rtol(tol).atol(tol);
        let sol = VanDerPol::default().simulate(0.0, 2.0, &opts)?;
        let y = sol.final_state();
        let s = sol.stats();
        println!(
            "  {tol:7.0e}  {:5}  {:8}  {:9}   {:10.2e}   {:10.2e}",
            s.steps,
            s.rejected,
            s.jacobian_evals,
            (y[0] - VDP_AT_2[0]).abs(),
            (y[1] - VDP_AT_2[1]).abs() / VDP_AT_2[1].abs()
        );
    }
    // A longer run, sampled on the collocation polynomials.
    let opts = Options::new().method(Method::Radau5).rtol(1e-8).atol(1e-8);
    let sol = VanDerPol::default().simulate(0.0, 3.0, &opts)?;
    let rows: Vec<Vec<f64>> = (0..=600)
        .map(|k| {
            let t = 3.0 * k as f64 / 600.0;
            Ok(vec![t, sol.at(t, "y1")?, sol.at(t, "y2")?])
        })
        .collect::<Result<_, daegen::Error>>()?;
    let y1 = rows.iter().map(|r| (r[0], r[1])).collect();
    output::write(
        "van_der_pol",
        &["t", "y1", "y2"],
        &rows,
        ("Van der Pol, ε = 1e-6 (RADAU5, tol 1e-8)", "t", "y1"),
        &[Series {
            name: "y1",
            points: y1,
        }],
    )?;
    Ok(())
}
