// A chain of six bodies on revolute joints in body coordinates: its
// generated code would pass 2 MB, so the model is refused with the
// advice to use joint coordinates (which the same chain takes in 0.1 MB).
use daegen::prelude::*;

#[dae_model]
fn six_bars() {
    let ground = ground();
    gravity(vec3(0.0, 0.0, -9.81));
    let b0 = spatial_body(1.0, vec3(0.1, 0.1, 0.02), [0.0, 0.0, -0.5], [1.0, 0.0, 0.0, 0.0]);
    let b1 = spatial_body(1.0, vec3(0.1, 0.1, 0.02), [0.0, 0.0, -1.5], [1.0, 0.0, 0.0, 0.0]);
    let b2 = spatial_body(1.0, vec3(0.1, 0.1, 0.02), [0.0, 0.0, -2.5], [1.0, 0.0, 0.0, 0.0]);
    let b3 = spatial_body(1.0, vec3(0.1, 0.1, 0.02), [0.0, 0.0, -3.5], [1.0, 0.0, 0.0, 0.0]);
    let b4 = spatial_body(1.0, vec3(0.1, 0.1, 0.02), [0.0, 0.0, -4.5], [1.0, 0.0, 0.0, 0.0]);
    let b5 = spatial_body(1.0, vec3(0.1, 0.1, 0.02), [0.0, 0.0, -5.5], [1.0, 0.0, 0.0, 0.0]);
    let j0 = revolute(ground, vec3(0.0, 0.0, 0.0), b0, vec3(0.0, 0.0, 0.5), vec3(0.0, 1.0, 0.0));
    let j1 = revolute(b0, vec3(0.0, 0.0, -0.5), b1, vec3(0.0, 0.0, 0.5), vec3(1.0, 0.0, 0.0));
    let j2 = revolute(b1, vec3(0.0, 0.0, -0.5), b2, vec3(0.0, 0.0, 0.5), vec3(0.0, 1.0, 0.0));
    let j3 = revolute(b2, vec3(0.0, 0.0, -0.5), b3, vec3(0.0, 0.0, 0.5), vec3(1.0, 0.0, 0.0));
    let j4 = revolute(b3, vec3(0.0, 0.0, -0.5), b4, vec3(0.0, 0.0, 0.5), vec3(0.0, 1.0, 0.0));
    let j5 = revolute(b4, vec3(0.0, 0.0, -0.5), b5, vec3(0.0, 0.0, 0.5), vec3(1.0, 0.0, 0.0));
}

fn main() {}
