use daegen::prelude::*;

/// A slider-crank mechanism as a scene: a crank on a revolute joint to
/// the ground, a rod of fixed length to a slider on a horizontal
/// prismatic joint, falling under gravity from rough poses that
/// initialization closes.
#[dae_model]
pub fn slider_crank() {
    /// Crank length (m).
    let r = param(0.15);
    /// Rod length (m).
    let l = param(0.4);
    /// Crank mass (kg).
    let m1 = param(1.0);
    /// Slider mass (kg).
    let m2 = param(0.5);
    /// Gravity (m/s²).
    let g = param(9.81);
    let ground = ground();
    let crank = body(m1, m1 * r * r / 12.0, [0.04, 0.06, 1.0]);
    let slider = body(m2, 1.0, [0.45, 0.0, 0.0]);
    revolute(ground, vec3(0.0, 0.0, 0.0), crank, vec3(-0.5 * r, 0.0, 0.0));
    distance(crank, vec3(0.5 * r, 0.0, 0.0), slider, vec3(0.0, 0.0, 0.0), l);
    prismatic(ground, vec3(0.0, 0.0, 0.0), slider, vec3(0.0, 0.0, 0.0), vec3(1.0, 0.0, 0.0));
    gravity(vec3(0.0, -g, 0.0));
    let pin = position(crank, vec3(0.5 * r, 0.0, 0.0));
    /// The crank pin's horizontal position (m).
    let pin_x = output(pin[0]);
}
