use daegen::prelude::*;

/// A joint's coordinates are states only with `scene = recursive`.
#[dae_model]
fn global_start() {
    let ground = ground();
    let rod = spatial_body(2.0, vec3(0.1, 0.2, 0.05), [0.0, 0.0, -0.5], [1.0, 0.0, 0.0, 0.0]);
    let hinge = revolute(ground, vec3(0.0, 0.0, 0.0), rod, vec3(0.0, 0.0, 0.5), vec3(1.0, 0.0, 0.0));
    gravity(vec3(0.0, 0.0, -9.81));
    init(hinge.q, 0.5);
}

/// A coordinate the joint does not have.
#[dae_model(scene = recursive)]
fn unknown_coordinate() {
    let ground = ground();
    let rod = spatial_body(2.0, vec3(0.1, 0.2, 0.05), [0.0, 0.0, -0.5], [1.0, 0.0, 0.0, 0.0]);
    let hinge = revolute(ground, vec3(0.0, 0.0, 0.0), rod, vec3(0.0, 0.0, 0.5), vec3(1.0, 0.0, 0.0));
    gravity(vec3(0.0, 0.0, -9.81));
    init(hinge.angle, 0.5);
}

fn main() {}
