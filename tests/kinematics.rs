//! Kinematics in the model language (course notes §4.1): vectors and
//! rotation matrices expanded symbolically by the macro, checked against
//! the runtime's `daegen::runtime::kinematics` (itself tested against
//! identities and finite differences), and a spherical pendulum written
//! with vectors against its minimal-coordinate ODE.

use daegen::prelude::*;
use daegen::runtime::kinematics as k;
use daegen::runtime::nalgebra::{Matrix3, Vector3};

mod support;
use support::tight;

/// Each rotation constructor of the language applied to one vector `w`.
#[dae_model]
fn rotations() {
    let psi = param(0.3);
    let theta = param(-1.1);
    let phi = param(2.4);
    let wx = param(0.7);
    let wy = param(-0.2);
    let wz = param(1.3);
    let nx = param(1.0);
    let ny = param(2.0);
    let nz = param(-0.5);
    let w = vec3(wx, wy, wz);
    let n = vec3(nx, ny, nz);
    let q0 = param(0.5);
    let q1 = param(0.5);
    let q2 = param(-0.5);
    let q3 = param(0.5);
    let s = state(0.0);
    der(s) == 0.0;
    let euler = euler_313(psi, theta, phi) * w;
    let bryan = bryan_123(psi, theta, phi) * w;
    let rodrigues = axis_angle(n, theta) * w;
    let quaternion = quat_to_rot(q0, q1, q2, q3) * w;
    let primitives = rot_x(psi) * rot_y(theta) * rot_z(phi) * w;
    let round_trip = transpose(euler_313(psi, theta, phi)) * euler_313(psi, theta, phi) * w;
    let crossed = cross(n, w) - skew(n) * w;
    let e0 = output(euler[0]);
    let e1 = output(euler[1]);
    let e2 = output(euler[2]);
    let b0 = output(bryan[0]);
    let b1 = output(bryan[1]);
    let b2 = output(bryan[2]);
    let r0 = output(rodrigues[0]);
    let r1 = output(rodrigues[1]);
    let r2 = output(rodrigues[2]);
    let u0 = output(quaternion[0]);
    let u1 = output(quaternion[1]);
    let u2 = output(quaternion[2]);
    let p0 = output(primitives[0]);
    let p1 = output(primitives[1]);
    let p2 = output(primitives[2]);
    let t0 = output(round_trip[0]);
    let t1 = output(round_trip[1]);
    let t2 = output(round_trip[2]);
    let c0 = output(norm(crossed));
    let d0 = output(dot(n, w));
    let m12 = output(euler_313(psi, theta, phi)[1][2]);
}

#[test]
fn language_rotations_match_the_runtime_kinematics() {
    let sol = Rotations::default()
        .simulate(0.0, 1.0, &Options::new().method(Method::Rk4).step(0.5))
        .unwrap();
    let get = |names: [&str; 3]| Vector3::from_iterator(names.iter().map(|n| sol.last(n).unwrap()));
    let (psi, theta, phi) = (0.3, -1.1, 2.4);
    let w = Vector3::new(0.7, -0.2, 1.3);
    let n = Vector3::new(1.0, 2.0, -0.5);
    let cases: [([&str; 3], Matrix3<f64>); 5] = [
        (["e0", "e1", "e2"], k::euler_313(psi, theta, phi)),
        (["b0", "b1", "b2"], k::bryan_123(psi, theta, phi)),
        (["r0", "r1", "r2"], k::axis_angle(&n, theta)),
        (["u0", "u1", "u2"], k::quaternion_to_matrix([0.5, 0.5, -0.5, 0.5])),
        (["p0", "p1", "p2"], k::sequence([k::Axis::X, k::Axis::Y, k::Axis::Z], [psi, theta, phi])),
    ];
    for (names, r) in cases {
        let got = get(names);
        assert!((got - r * w).norm() <= 1e-15, "{names:?}: {got} vs {}", r * w);
    }
    assert!((get(["t0", "t1", "t2"]) - w).norm() <= 1e-15);
    assert!(sol.last("c0").unwrap() <= 1e-16);
    assert!((sol.last("d0").unwrap() - n.dot(&w)).abs() <= 1e-15);
    assert!((sol.last("m12").unwrap() - k::euler_313(psi, theta, phi)[(1, 2)]).abs() <= 1e-16);
}

/// A spherical pendulum written with vectors: `m r'' = −λ r + m g`,
/// `|r| = l` (an index-3 DAE, three equations from one vector equation).
#[dae_model]
fn spherical_pendulum() {
    let m = param(1.0);
    let l = param(1.0);
    let g = param(9.81);
    let x = state(0.8414709848078965);
    let y = state(0.0);
    let z = state(-0.5403023058681398);
    init(der(x), 0.0);
    init(der(y), 1.682941969615793);
    init(der(z), 0.0);
    let lambda = algebraic(0.0);
    let r = vec3(x, y, z);
    let gravity = vec3(0.0, 0.0, -g);
    m * vec3(der(der(x)), der(der(y)), der(der(z))) == -lambda * r + m * gravity;
    constraint(dot(r, r) - l * l);
    /// Angular momentum about the vertical, conserved.
    let lz = output(m * cross(r, vec3(der(x), der(y), der(z)))[2]);
}

/// Its minimal coordinates: θ from the downward vertical, φ about it:
/// θ'' = sin θ cos θ φ'² − (g/l) sin θ, φ'' = −2 θ' φ' cos θ / sin θ.
#[dae_model]
fn spherical_pendulum_angles() {
    let l = param(1.0);
    let g = param(9.81);
    let theta = state(1.0);
    let phi = state(0.0);
    init(der(theta), 0.0);
    init(der(phi), 2.0);
    der(der(theta)) == sin(theta) * cos(theta) * der(phi) * der(phi) - g / l * sin(theta);
    der(der(phi)) == -2.0 * der(theta) * der(phi) * cos(theta) / sin(theta);
}

#[test]
fn a_spherical_pendulum_written_with_vectors_follows_its_angles() {
    assert_eq!(<SphericalPendulum as Model>::INDEX, 3);
    let tol = 1e-10;
    let sol = tight::<SphericalPendulum>(3.0, tol);
    let reference = tight::<SphericalPendulumAngles>(3.0, 1e-13);
    for t in [0.5, 1.0, 3.0] {
        let (theta, phi) = (reference.at(t, "theta").unwrap(), reference.at(t, "phi").unwrap());
        let want = [theta.sin() * phi.cos(), theta.sin() * phi.sin(), -theta.cos()];
        for (name, w) in ["x", "y", "z"].iter().zip(want) {
            let got = sol.at(t, name).unwrap();
            assert!((got - w).abs() <= 100.0 * tol, "t = {t}: {name} = {got}, from the angles {w}");
        }
    }
    // L_z = m l² sin²θ φ' = sin²(1) · 2 at the start, conserved.
    let lz0 = 2.0 * 1f64.sin().powi(2);
    assert!((sol.last("lz").unwrap() - lz0).abs() <= 100.0 * tol);
    assert!(sol.max_constraint_residual() <= 1e-12);
}

include!("models/heavy_top.rs");

#[test]
fn a_heavy_top_with_quaternions_conserves_energy_and_unit_norm() {
    assert_eq!(HeavyTop::CONSTRAINTS.len(), 1, "the quaternion's unit norm");
    let tol = 1e-15;
    let opts = Options::new().method(Method::Taylor).tolerance(tol);
    let sol = HeavyTop::default().simulate(0.0, 450.0, &opts).unwrap();
    let steps = sol.times().len();
    let (e0, l0) = (sol.at(0.0, "energy").unwrap(), sol.at(0.0, "lz").unwrap());
    let (mut energy, mut momentum, mut norm) = (0.0f64, 0.0f64, 0.0f64);
    for k in 0..steps {
        let s = sol.state(k).unwrap();
        let t = sol.times()[k];
        energy = energy.max((sol.at(t, "energy").unwrap() - e0).abs());
        momentum = momentum.max((sol.at(t, "lz").unwrap() - l0).abs());
        norm = norm.max((s[..4].iter().map(|x| x * x).sum::<f64>() - 1.0).abs());
    }
    // Measured over 1021 steps (the order chosen for the model's cost,
    // `runtime/src/methods/taylor/order.rs`): 1.8e-15, 2.2e-15 and 2.2e-16.
    assert!(steps >= 1000, "{steps} steps");
    assert!(energy <= 1e-12 * e0.abs().max(1.0), "energy drift {energy:e}");
    assert!(momentum <= 1e-12 * l0.abs().max(1.0), "L_z drift {momentum:e}");
    assert!(norm <= 1e-15, "|q|² − 1 = {norm:e}");
    // ω3 of a symmetric top is constant.
    let w3: Vec<f64> = (0..steps).map(|k| sol.state(k).unwrap()[6]).collect();
    assert!(w3.iter().all(|w| (w - 5.0).abs() <= 1e-12));
}

/// An oscillator whose first integral is declared an invariant: explicit
/// Euler spirals outwards (|z|² grows by 1 + h² per step) unless projected.
#[dae_model]
fn projected_oscillator() {
    let x = state(1.0);
    let v = state(0.0);
    der(x) == v;
    der(v) == -x;
    invariant(x * x + v * v - 1.0);
}

#[test]
fn a_declared_invariant_is_kept_by_projection() {
    let sol = ProjectedOscillator::default()
        .simulate(0.0, 10.0, &Options::new().method(Method::Euler).step(1e-2))
        .unwrap();
    for k in 0..sol.times().len() {
        let s = sol.state(k).unwrap();
        assert!((s[0] * s[0] + s[1] * s[1] - 1.0).abs() <= 1e-15);
    }
    // Projection keeps the radius, not the phase: Euler's phase error stays
    // first order (|x(10) − cos 10| within 10 h).
    assert!((sol.last("x").unwrap() - 10f64.cos()).abs() <= 0.1);
    assert_eq!(<ProjectedOscillator as Model>::INDEX, 0);
    assert!(sol.stats().formulation.contains("invariants"));
}

/// Any axis sequence, its inverse, and the body angular velocity of angle
/// and quaternion states (course notes §4.1.2, §4.1.4).
#[dae_model]
fn rates() {
    let a = state(0.3);
    let b = state(-0.8);
    let c = state(1.9);
    init(der(a), 0.7);
    init(der(b), -1.3);
    init(der(c), 0.4);
    der(der(a)) == 0.0;
    der(der(b)) == 0.0;
    der(der(c)) == 0.0;
    let q = quaternion_state([0.5, 0.5, -0.5, 0.5]);
    der(q[0]) == 0.1 * q[1];
    der(q[1]) == -0.1 * q[0];
    der(q[2]) == 0.3 * q[3];
    der(q[3]) == -0.3 * q[2];
    let w = vec3(0.7, -0.2, 1.3);
    let rotated = rot_seq("zyz", a, b, c) * w;
    let back = inverse_rot_seq("zyz", a, b, c) * rotated;
    let omega = omega_seq("yxz", a, b, c);
    let omega_q = omega_quat(q[0], q[1], q[2], q[3]);
    let r0 = output(rotated[0]);
    let r1 = output(rotated[1]);
    let r2 = output(rotated[2]);
    let back_error = output(norm(back - w));
    let w0 = output(omega[0]);
    let w1 = output(omega[1]);
    let w2 = output(omega[2]);
    let v0 = output(omega_q[0]);
    let v1 = output(omega_q[1]);
    let v2 = output(omega_q[2]);
}

#[test]
fn sequences_and_angular_velocities_in_the_language_match_the_runtime() {
    use k::Axis::*;
    let sol = Rates::default()
        .simulate(0.0, 0.5, &Options::new().method(Method::Rk4).step(0.25))
        .unwrap();
    let (angles, rates) = ([0.3, -0.8, 1.9], [0.7, -1.3, 0.4]);
    let at0 = |n: &str| sol.at(0.0, n).unwrap();
    let w = Vector3::new(0.7, -0.2, 1.3);
    let want = k::sequence([Z, Y, Z], angles) * w;
    let got = Vector3::new(at0("r0"), at0("r1"), at0("r2"));
    assert!((got - want).norm() <= 1e-15);
    assert!(at0("back_error") <= 1e-15);
    let want = k::angular_velocity([Y, X, Z], angles, rates);
    let got = Vector3::new(at0("w0"), at0("w1"), at0("w2"));
    assert!((got - want).norm() <= 1e-15, "{got} vs {want}");
    let q = [0.5, 0.5, -0.5, 0.5];
    let q_dot = [0.1 * q[1], -0.1 * q[0], 0.3 * q[3], -0.3 * q[2]];
    let want = k::quaternion_angular_velocity(q, q_dot);
    let got = Vector3::new(at0("v0"), at0("v1"), at0("v2"));
    assert!((got - want).norm() <= 1e-15, "{got} vs {want}");
}

/// Transforms and natural coordinates in the language.
#[dae_model]
fn frames() {
    let alpha = param(0.4);
    let s = state(0.0);
    der(s) == 0.0;
    let r = rot_seq("zxy", alpha, 0.3, -1.2);
    let p = vec3(0.5, -0.1, 2.0);
    let xb = homogeneous(vec3(0.3, -0.7, 1.1));
    let xw = transform(r, p) * xb;
    let back = inverse_transform(r, p) * xw;
    let p1 = vec3(0.5, -0.2, 0.0);
    let p2 = vec3(0.5 + 2.0 * cos(alpha), -0.2 + 2.0 * sin(alpha), 0.0);
    let frame = planar_frame(p1, p2) * vec3(1.0, 2.0, 3.0);
    // Three points of a body turned by r, in natural coordinates: the
    // second along its x axis, the third in its x–y plane.
    let q1 = vec3(0.2, 0.1, -0.3);
    let q2 = q1 + r * vec3(2.0, 0.0, 0.0);
    let q3 = q1 + r * vec3(0.5, 3.0, 0.0);
    let spatial = natural_frame(q1, q2, q3) - r;
    let n = output(
        norm(spatial * vec3(1.0, 0.0, 0.0))
            + norm(spatial * vec3(0.0, 1.0, 0.0))
            + norm(spatial * vec3(0.0, 0.0, 1.0)),
    );
    let x0 = output(xw[0]);
    let x1 = output(xw[1]);
    let x2 = output(xw[2]);
    let x3 = output(xw[3]);
    let b = output(norm(vec3(back[0], back[1], back[2]) - vec3(0.3, -0.7, 1.1)));
    let f0 = output(frame[0]);
    let f1 = output(frame[1]);
    let f2 = output(frame[2]);
}

#[test]
fn transforms_and_natural_coordinates_in_the_language_match_the_runtime() {
    use k::Axis::*;
    let sol = Frames::default()
        .simulate(0.0, 0.5, &Options::new().method(Method::Rk4).step(0.25))
        .unwrap();
    let at = |n: &str| sol.last(n).unwrap();
    let r = k::sequence([Z, X, Y], [0.4, 0.3, -1.2]);
    let p = Vector3::new(0.5, -0.1, 2.0);
    let want = p + r * Vector3::new(0.3, -0.7, 1.1);
    let got = Vector3::new(at("x0"), at("x1"), at("x2"));
    assert!((got - want).norm() <= 1e-15 && at("x3") == 1.0);
    assert!(at("b") <= 1e-15);
    let want = k::rot_z(0.4) * Vector3::new(1.0, 2.0, 3.0);
    let got = Vector3::new(at("f0"), at("f1"), at("f2"));
    assert!((got - want).norm() <= 1e-15, "{got} vs {want}");
    // The frame of three points is the body's rotation, to rounding.
    assert!(at("n") <= 1e-14, "natural_frame − R: {:e}", at("n"));
    // The frame of three points is the body's rotation, to rounding.
    assert!(at("n") <= 1e-14, "natural_frame − R: {:e}", at("n"));
}
