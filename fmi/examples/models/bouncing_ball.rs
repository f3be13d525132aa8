use daegen::prelude::*;

/// A ball dropped from 1 m that bounces with a coefficient of
/// restitution of 0.8.
#[dae_model]
pub fn bouncing_ball() {
    /// Gravity (m/s²).
    let g = param(9.81);
    /// Coefficient of restitution.
    let e = param(0.8);
    /// Height (m).
    let h = state(1.0);
    init(der(h), 0.0);
    der(der(h)) == -g;
    /// It hits the ground and bounces back.
    let bounce = event(h).falling().reinit(der(h), -e * pre(der(h)));
}
