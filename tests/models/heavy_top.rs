/// A heavy symmetric top about a fixed point, its attitude a quaternion
/// state (|q| = 1 projected onto after each step) and its body rates ω:
/// q' = ½ (−q_v·ω, q0 ω + q_v × ω), I ω' + ω × I ω = l e3 × Rᵀ(−m g ẑ).
#[dae_model(taylor = 1)]
fn heavy_top() {
    let a = param(1.0);
    let c = param(0.5);
    let mgl = param(1.0);
    let q = quaternion_state([0.9689124217106447, 0.24740395925452294, 0.0, 0.0]);
    let w = state_array([0.0, 0.5, 5.0]);
    let qv = vec3(q[1], q[2], q[3]);
    let omega = vec3(w[0], w[1], w[2]);
    der(q[0]) == -0.5 * dot(qv, omega);
    vec3(der(q[1]), der(q[2]), der(q[3])) == 0.5 * (q[0] * omega + cross(qv, omega));
    let r = quat_to_rot(q[0], q[1], q[2], q[3]);
    let down = transpose(r) * vec3(0.0, 0.0, -1.0);
    let inertia = mat3(a, 0.0, 0.0, 0.0, a, 0.0, 0.0, 0.0, c);
    let torque = mgl * cross(vec3(0.0, 0.0, 1.0), down);
    inertia * vec3(der(w[0]), der(w[1]), der(w[2])) == torque - cross(omega, inertia * omega);
    /// Kinetic plus potential energy, conserved.
    let energy = output(0.5 * dot(omega, inertia * omega) + mgl * r[2][2]);
    /// Angular momentum about the vertical, conserved.
    let lz = output((r * inertia * omega)[2]);
}
