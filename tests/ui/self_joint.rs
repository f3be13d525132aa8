use daegen::prelude::*;

/// A joint from a body to itself.
#[dae_model]
fn self_joint() {
    let ground = ground();
    let bar = body(1.0, 0.1, [0.5, 0.0, 0.0]);
    revolute(ground, vec3(0.0, 0.0, 0.0), bar, vec3(-0.5, 0.0, 0.0));
    revolute(bar, vec3(0.5, 0.0, 0.0), bar, vec3(-0.5, 0.0, 0.0));
}

fn main() {}
