//! Van der Pol's oscillator as an FMU: `cargo fmu --example van_der_pol_fmu`
//! (or `cargo run -p daegen-fmi --bin cargo-fmu -- --example
//! van_der_pol_fmu`) writes `target/fmu/van_der_pol_fmu.fmu` (FMI 3.0)
//! and `target/fmu/van_der_pol_fmu_fmi2.fmu` (FMI 2.0).

use daegen::prelude::*;

/// Van der Pol's oscillator, x'' = μ(1 − x²)x' − x.
#[dae_model]
fn van_der_pol() {
    /// Damping (1).
    let mu = param(1.0);
    /// Position.
    let x = state(2.0);
    init(der(x), 0.0);
    der(der(x)) == mu * (1.0 - x * x) * der(x) - x;
    /// Energy-like, x² + x'².
    let energy = output(x * x + der(x) * der(x));
}

daegen_fmi::export_fmu!(VanDerPol);
