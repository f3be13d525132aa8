use daegen::prelude::*;

/// A first-order plant x' = −a x + b u under a PI controller sampled every
/// `h`, its output held between samples (a zero-order hold): a clock.
#[dae_model]
pub fn sampled_pi() {
    /// Plant pole (1/s).
    let a = param(2.0);
    /// Plant gain.
    let b = param(3.0);
    /// Proportional gain.
    let kp = param(0.8);
    /// Integral gain (1/s).
    let ki = param(1.5);
    /// Set point.
    let r = param(1.0);
    /// Sampling period (s).
    let h = param(0.1);
    /// Plant output.
    let x = state(0.0);
    /// The controller's output, held between samples.
    let u = discrete(0.0);
    /// The integral of the error, summed at the samples.
    let integral = discrete(0.0);
    der(x) == -a * x + b * u;
    /// The controller reads x and sets u.
    let sample =
        every(h).reinit(integral, integral + ki * h * (r - x)).reinit(u, kp * (r - x) + integral);
}
