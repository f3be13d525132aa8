use daegen::prelude::*;

/// Van der Pol's oscillator, x'' = μ(1 − x²)x' − x.
#[dae_model]
pub fn van_der_pol() {
    /// Damping (1).
    let mu = param(1.0);
    /// Position.
    let x = state(2.0);
    init(der(x), 0.0);
    der(der(x)) == mu * (1.0 - x * x) * der(x) - x;
    /// Energy-like, x² + x'².
    let energy = output(x * x + der(x) * der(x));
}
