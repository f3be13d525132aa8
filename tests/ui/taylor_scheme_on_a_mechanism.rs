use daegen::prelude::*;

// A double rod in body coordinates solves its KKT system at run time: the
// economic scheme (`taylor = p`) and unrolled jets need closed-form
// derivatives; `Method::Taylor` runs it without either.
#[dae_model(taylor = 2)]
fn double_rod() {
    let ground = ground();
    let upper = body(1.0, 1.0 / 12.0, [0.5, 0.0, 0.0]);
    revolute(ground, vec3(0.0, 0.0, 0.0), upper, vec3(-0.5, 0.0, 0.0));
    let lower = body(1.0, 1.0 / 12.0, [1.5, 0.0, 0.0]);
    revolute(upper, vec3(0.5, 0.0, 0.0), lower, vec3(-0.5, 0.0, 0.0));
    gravity(vec3(0.0, -9.81, 0.0));
}

#[dae_model(unroll = [8])]
fn double_rod_unrolled() {
    gravity(vec3(0.0, -9.81, 0.0));
    let ground = ground();
    let upper = body(2.0, 2.0 / 12.0, [0.0, -0.5, 0.0]);
    let lower = body(1.0, 1.0 / 12.0, [0.0, -1.5, 0.0]);
    revolute(ground, vec3(0.0, 0.0, 0.0), upper, vec3(0.0, 0.5, 0.0));
    revolute(upper, vec3(0.0, -0.5, 0.0), lower, vec3(0.0, 0.5, 0.0));
}

fn main() {}
