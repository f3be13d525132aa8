use daegen::prelude::*;

// A Cardan joint whose cross axes are not perpendicular, and a universal
// joint given one axis.
#[dae_model]
fn skewed_cardan() {
    let ground = ground();
    let rod = spatial_body(1.0, vec3(0.1, 0.1, 0.01), [0.0, 0.0, -0.5], [1.0, 0.0, 0.0, 0.0]);
    universal(ground, vec3(0.0, 0.0, 0.0), rod, vec3(0.0, 0.0, 0.5), vec3(1.0, 0.0, 0.0), vec3(1.0, 1.0, 0.0));
    cylindrical(ground, vec3(0.0, 0.0, 0.0), rod, vec3(0.0, 0.0, 0.5), vec3(0.0, 0.0, 1.0), vec3(1.0, 0.0, 0.0));
    universal(ground, vec3(0.0, 0.0, 0.0), rod, vec3(0.0, 0.0, 0.5), vec3(1.0, 0.0, 0.0));
    gravity(vec3(0.0, 0.0, -9.81));
}

// Joints of space in a planar scene.
#[dae_model]
fn planar_scene() {
    let ground = ground();
    let rod = body(1.0, 0.1, [0.5, 0.0, 0.0]);
    cylindrical(ground, vec3(0.0, 0.0, 0.0), rod, vec3(-0.5, 0.0, 0.0), vec3(1.0, 0.0, 0.0));
    planar(ground, vec3(0.0, 0.0, 0.0), rod, vec3(-0.5, 0.0, 0.0), vec3(0.0, 0.0, 1.0));
    gravity(vec3(0.0, -9.81, 0.0));
}

fn main() {}
