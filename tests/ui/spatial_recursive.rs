use daegen::prelude::*;

/// In the recursive formulation a body starts where its joint places it:
/// the top's joint point is 0.1 m below the pivot.
#[dae_model(scene = recursive)]
fn recursive_top() {
    let ground = ground();
    let top = spatial_body(1.0, vec3(0.1, 0.1, 0.1), [0.0, 0.0, 1.0], [1.0, 0.0, 0.0, 0.0]);
    spherical(ground, vec3(0.0, 0.0, 0.0), top, vec3(0.0, 0.0, -0.9));
}

fn main() {}
