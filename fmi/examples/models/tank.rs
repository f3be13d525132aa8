use daegen::prelude::*;

/// A tank drained through an orifice (Torricelli), filled by an inflow
/// the importer sets.
#[dae_model]
pub fn tank() {
    /// Outflow coefficient (m^2.5/s).
    let k = param(0.5);
    /// Inflow (m³/s), from outside.
    let q = input(0.2);
    /// Level (m).
    let h = state(1.0);
    der(h) == q - k * sqrt(h);
    /// Outflow (m³/s).
    let outflow = output(k * sqrt(h));
}
