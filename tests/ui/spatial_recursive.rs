use daegen::prelude::*;

/// In joint coordinates a body starts where its joint places it:
/// the top's joint point is 0.1 m below the pivot.
#[dae_model(scene = recursive)]
fn recursive_top() {
    let ground = ground();
    let top = spatial_body(1.0, vec3(0.1, 0.1, 0.1), [0.0, 0.0, 1.0], [1.0, 0.0, 0.0, 0.0]);
    spherical(ground, vec3(0.0, 0.0, 0.0), top, vec3(0.0, 0.0, -0.9));
}

/// And it starts moving as its joint moves it: turning at 1 rad/s about
/// the hinge, the bob's centre moves at (−0.5, 0, 0), not (0.5, 0, 0).
#[dae_model(scene = recursive)]
fn recursive_swing() {
    let ground = ground();
    let bob = spatial_body(
        1.0,
        vec3(0.01, 0.01, 0.002),
        [0.0, 0.0, -0.5],
        [1.0, 0.0, 0.0, 0.0],
        [0.5, 0.0, 0.0],
        [0.0, 1.0, 0.0],
    );
    let hinge = revolute(ground, vec3(0.0, 0.0, 0.0), bob, vec3(0.0, 0.0, 0.5), vec3(0.0, 1.0, 0.0));
}

fn main() {}
