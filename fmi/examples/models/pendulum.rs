use daegen::prelude::*;

/// A point mass on a massless rod in Cartesian coordinates: an index-3
/// DAE, the rod's force λ its algebraic variable.
#[dae_model]
pub fn pendulum() {
    /// Mass (kg).
    let m = param(1.0);
    /// Rod length (m).
    let l = param(1.0);
    /// Gravity (m/s²).
    let g = param(9.81);
    /// Horizontal position (m).
    let x = state(1.0);
    /// Vertical position (m).
    let y = state(0.0);
    /// Horizontal velocity (m/s).
    let u = state(0.0);
    /// Vertical velocity (m/s).
    let v = state(0.0);
    /// Rod force over length (N/m).
    let lambda = algebraic(0.0);
    der(x) == u;
    der(y) == v;
    m * der(u) == -lambda * x;
    m * der(v) == -lambda * y - m * g;
    constraint(x * x + y * y - l * l);
    /// Total energy (J), kept by the exact solution.
    let energy = output(0.5 * m * (u * u + v * v) + m * g * y);
}
