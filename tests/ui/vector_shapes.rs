use daegen::prelude::*;

/// Vectors and matrices where they do not fit.
#[dae_model]
fn shapes() {
    let theta = param(0.5);
    let x = state(1.0);
    let r = vec3(x, 0.0, 0.0);
    let bad_sum = r + rot_z(theta);
    der(x) == r;
    let bad_product = r * r;
    let bad_axis = axis_angle(theta, theta);
    let bad_sequence = rot_seq("zzx", theta, theta, theta);
    let bad_rates = omega_seq("zxz", theta, theta, theta);
}

fn main() {}
