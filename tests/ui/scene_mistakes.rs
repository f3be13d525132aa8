use daegen::prelude::*;

/// A body with nothing to hold the scene.
#[dae_model]
fn no_ground() {
    let bob = body(1.0, 0.1, [1.0, 0.0, 0.0]);
    gravity(vec3(0.0, -9.81, 0.0));
}

/// A joint to a body that was never declared.
#[dae_model]
fn unknown_body() {
    let ground = ground();
    let bob = body(1.0, 0.1, [1.0, 0.0, 0.0]);
    revolute(ground, vec3(0.0, 0.0, 0.0), bobb, vec3(-1.0, 0.0, 0.0));
}

/// A body where a number is needed.
#[dae_model]
fn body_as_number() {
    let ground = ground();
    let bob = body(1.0, 0.1, [1.0, 0.0, 0.0]);
    revolute(ground, vec3(0.0, 0.0, 0.0), bob, vec3(-1.0, 0.0, 0.0));
    let e = output(2.0 * bob);
}

/// A body pinned at two points: a structure, not a mechanism.
#[dae_model]
fn structure() {
    let ground = ground();
    let beam = body(1.0, 0.1, [0.5, 0.0, 0.0]);
    revolute(ground, vec3(0.0, 0.0, 0.0), beam, vec3(-0.5, 0.0, 0.0));
    revolute(ground, vec3(1.0, 0.0, 0.0), beam, vec3(0.5, 0.0, 0.0));
}

fn main() {}
