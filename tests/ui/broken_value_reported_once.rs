use daegen::prelude::*;

/// One mistake, one error: `hand` is not defined because `tip` is not a
/// body, and its uses stay quiet.
#[dae_model]
fn arm() {
    let ground = ground();
    let tip = 1.0;
    let link = spatial_body(1.0, vec3(0.1, 0.1, 0.1), [0.0, 0.0, -0.5], [1.0, 0.0, 0.0, 0.0]);
    spherical(ground, vec3(0.0, 0.0, 0.0), link, vec3(0.0, 0.0, 0.5));
    let hand = position(tip, vec3(0.0, 0.0, 0.0));
    let hand_x = output(hand[0]);
    let reach = hand[2] * 2.0;
    let depth = output(reach);
}

fn main() {}
