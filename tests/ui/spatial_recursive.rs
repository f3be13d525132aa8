use daegen::prelude::*;

/// The recursive formulation is planar.
#[dae_model(scene = recursive)]
fn recursive_top() {
    let ground = ground();
    let top = spatial_body(1.0, vec3(0.1, 0.1, 0.1), [0.0, 0.0, 1.0], [1.0, 0.0, 0.0, 0.0]);
    spherical(ground, vec3(0.0, 0.0, 0.0), top, vec3(0.0, 0.0, -1.0));
}

fn main() {}
