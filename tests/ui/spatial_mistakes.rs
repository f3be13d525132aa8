use daegen::prelude::*;

/// A parallelogram with a third crank: Grübler's count says 12 − 12 = 0,
/// yet it moves; the third crank's rows follow from the others.
#[dae_model]
fn redundant_crank() {
    let ground = ground();
    let left = body(1.0, 0.1, [0.0, 0.5, 1.5707963267948966]);
    let right = body(1.0, 0.1, [2.0, 0.5, 1.5707963267948966]);
    let middle = body(1.0, 0.1, [1.0, 0.5, 1.5707963267948966]);
    let top = body(1.0, 0.5, [1.0, 1.0, 0.0]);
    revolute(ground, vec3(0.0, 0.0, 0.0), left, vec3(-0.5, 0.0, 0.0));
    revolute(ground, vec3(2.0, 0.0, 0.0), right, vec3(-0.5, 0.0, 0.0));
    revolute(left, vec3(0.5, 0.0, 0.0), top, vec3(-1.0, 0.0, 0.0));
    revolute(right, vec3(0.5, 0.0, 0.0), top, vec3(1.0, 0.0, 0.0));
    revolute(ground, vec3(1.0, 0.0, 0.0), middle, vec3(-0.5, 0.0, 0.0));
    let extra = revolute(middle, vec3(0.5, 0.0, 0.0), top, vec3(0.0, 0.0, 0.0));
}

/// A spatial four-bar with four parallel revolute joints: 18 coordinates,
/// 20 rows, and one degree of freedom.
#[dae_model]
fn spatial_four_bar() {
    let ground = ground();
    let crank = spatial_body(1.0, vec3(0.1, 0.1, 0.1), [0.0, 0.0, 0.5], [1.0, 0.0, 0.0, 0.0]);
    let coupler = spatial_body(1.0, vec3(0.1, 0.1, 0.1), [1.0, 0.0, 1.0], [1.0, 0.0, 0.0, 0.0]);
    let rocker = spatial_body(1.0, vec3(0.1, 0.1, 0.1), [2.0, 0.0, 0.5], [1.0, 0.0, 0.0, 0.0]);
    let y = vec3(0.0, 1.0, 0.0);
    revolute(ground, vec3(0.0, 0.0, 0.0), crank, vec3(0.0, 0.0, -0.5), y);
    revolute(crank, vec3(0.0, 0.0, 0.5), coupler, vec3(-1.0, 0.0, 0.0), y);
    revolute(coupler, vec3(1.0, 0.0, 0.0), rocker, vec3(0.0, 0.0, 0.5), y);
    let closing = revolute(rocker, vec3(0.0, 0.0, -0.5), ground, vec3(2.0, 0.0, 0.0), y);
}

/// Planar and spatial bodies in one scene.
#[dae_model]
fn mixed_scene() {
    let ground = ground();
    let a = body(1.0, 0.1, [0.0, -1.0, 0.0]);
    let b = spatial_body(1.0, vec3(0.1, 0.1, 0.1), [0.0, 0.0, -1.0], [1.0, 0.0, 0.0, 0.0]);
}

/// A spherical joint in a planar scene.
#[dae_model]
fn planar_spherical() {
    let ground = ground();
    let a = body(1.0, 0.1, [0.0, -1.0, 0.0]);
    spherical(ground, vec3(0.0, 0.0, 0.0), a, vec3(0.0, 1.0, 0.0));
}

/// A coordinate a body does not have.
#[dae_model]
fn unknown_coordinate() {
    let ground = ground();
    let a = spatial_body(1.0, vec3(0.1, 0.1, 0.1), [0.0, 0.0, -1.0], [1.0, 0.0, 0.0, 0.0]);
    spherical(ground, vec3(0.0, 0.0, 0.0), a, vec3(0.0, 0.0, 1.0));
    let h = output(a.theta);
}

/// An inertia of the wrong shape.
#[dae_model]
fn inertia_shape() {
    let ground = ground();
    let a = spatial_body(1.0, 0.1, [0.0, 0.0, -1.0], [1.0, 0.0, 0.0, 0.0]);
    spherical(ground, vec3(0.0, 0.0, 0.0), a, vec3(0.0, 0.0, 1.0));
}

fn main() {}
