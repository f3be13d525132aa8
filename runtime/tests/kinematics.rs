//! Rigid-body kinematics (course notes §4.1): identities of the
//! constructors, round trips of the inverse problems, singular
//! configurations reported, and rates against finite differences.

use daegen_runtime::kinematics::*;
use nalgebra::{Matrix3, Vector3};
use std::f64::consts::PI;

const ALL_SEQUENCES: [[Axis; 3]; 12] = {
    use Axis::*;
    [
        [X, Y, Z],
        [X, Z, Y],
        [Y, X, Z],
        [Y, Z, X],
        [Z, X, Y],
        [Z, Y, X],
        [X, Y, X],
        [X, Z, X],
        [Y, X, Y],
        [Y, Z, Y],
        [Z, X, Z],
        [Z, Y, Z],
    ]
};

/// Deterministic angles in (−π, π) (a linear congruential sequence).
fn angles(count: usize) -> Vec<[f64; 3]> {
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = || {
        state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        ((state >> 11) as f64 / (1u64 << 53) as f64) * 2.0 * PI - PI
    };
    (0..count).map(|_| [next(), next(), next()]).collect()
}

fn close(a: &Matrix3<f64>, b: &Matrix3<f64>, tol: f64) -> bool {
    (a - b).abs().max() <= tol
}

fn proper(axes: [Axis; 3]) -> bool {
    axes[0] == axes[2]
}

#[test]
fn every_constructor_gives_a_rotation() {
    for u in angles(50) {
        let n = Vector3::new(u[0], u[1], u[2]);
        let q = [u[0], u[1], u[2], 0.3];
        let mut all = vec![
            rot_x(u[0]),
            rot_y(u[1]),
            rot_z(u[2]),
            euler_313(u[0], u[1], u[2]),
            bryan_123(u[0], u[1], u[2]),
            axis_angle(&n, u[0]),
            quaternion_to_matrix(q),
        ];
        all.extend(ALL_SEQUENCES.iter().map(|&axes| sequence(axes, u)));
        for r in all {
            assert!(close(&(r * r.transpose()), &Matrix3::identity(), 1e-14));
            assert!((r.determinant() - 1.0).abs() <= 1e-14);
            assert!(is_rotation(&r, 1e-12));
        }
    }
    // Not rotations: a reflection, a shear.
    assert!(!is_rotation(&Matrix3::new(1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, -1.0), 1e-12));
    assert!(!is_rotation(&Matrix3::new(1.0, 0.1, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0), 1e-12));
}

#[test]
fn sequences_are_products_of_primitives_and_inverses_are_transposes() {
    for u in angles(20) {
        assert_eq!(euler_313(u[0], u[1], u[2]), rot_z(u[2]) * rot_x(u[1]) * rot_z(u[0]));
        assert_eq!(
            euler_313(u[0], u[1], u[2]),
            sequence([Axis::Z, Axis::X, Axis::Z], [u[2], u[1], u[0]])
        );
        assert_eq!(
            bryan_123(u[0], u[1], u[2]),
            sequence([Axis::Z, Axis::Y, Axis::X], [u[2], u[1], u[0]])
        );
        for axes in ALL_SEQUENCES {
            let r = sequence(axes, u);
            let product = rot(axes[0], u[0]) * rot(axes[1], u[1]) * rot(axes[2], u[2]);
            assert!(close(&r, &product, 0.0));
            assert!(close(&inverse_sequence(axes, u), &r.transpose(), 1e-15));
            assert!(close(&(inverse_sequence(axes, u) * r), &Matrix3::identity(), 1e-14));
        }
    }
    // A quarter turn about z takes x to y.
    let e = rot_z(PI / 2.0) * Vector3::x();
    assert!((e - Vector3::y()).norm() <= 1e-16);
}

#[test]
fn rodrigues_axis_angle_and_quaternion_agree() {
    for u in angles(50) {
        let n = Vector3::new(u[0], u[1], u[2]).normalize();
        let theta = u[0];
        let r = axis_angle(&n, theta);
        let (s, c) = (theta / 2.0).sin_cos();
        let q = [c, n.x * s, n.y * s, n.z * s];
        assert!(close(&r, &quaternion_to_matrix(q), 1e-14));
        // The vector form (eq. 4.16) on a vector.
        let v = Vector3::new(0.3, -1.2, 2.0);
        let rodrigues =
            v * theta.cos() + n * (n.dot(&v) * (1.0 - theta.cos())) + n.cross(&v) * theta.sin();
        assert!((r * v - rodrigues).norm() <= 1e-14);
        // −q is the same rotation; the axis does not move.
        assert!(close(&quaternion_to_matrix(q.map(|x| -x)), &r, 1e-15));
        assert!((r * n - n).norm() <= 1e-14);
    }
    for (axis, e) in [(Axis::X, Vector3::x()), (Axis::Y, Vector3::y()), (Axis::Z, Vector3::z())] {
        assert!(close(&axis_angle(&e, 0.7), &rot(axis, 0.7), 1e-15));
    }
}

#[test]
fn axis_angle_and_quaternion_round_trip_including_half_turns() {
    let mut cases: Vec<(Vector3<f64>, f64)> = angles(50)
        .into_iter()
        .map(|u| (Vector3::new(u[0], u[1], u[2]).normalize(), u[2].abs().max(1e-3)))
        .collect();
    cases.push((Vector3::new(1.0, 2.0, 3.0).normalize(), PI));
    cases.push((Vector3::new(0.0, 0.0, 1.0), PI - 1e-9));
    cases.push((Vector3::new(1.0, -1.0, 0.0).normalize(), 1e-7));
    for (n, theta) in cases {
        let r = axis_angle(&n, theta);
        let (axis, angle) = axis_angle_of(&r).expect("a rotation with an axis");
        // (n, θ) or (−n, −θ) read back as θ ∈ [0, π].
        assert!((angle - theta).abs() <= 1e-12, "θ = {theta}: {angle}");
        assert!(
            (axis - n).norm() <= 1e-8 || (axis + n).norm() <= 1e-8 && (theta - PI).abs() < 1e-6,
            "θ = {theta}: {axis} vs {n}"
        );
        let q = matrix_to_quaternion(&r);
        assert!(q[0] >= 0.0);
        assert!(close(&quaternion_to_matrix(q), &r, 1e-14));
    }
    assert!(axis_angle_of(&Matrix3::identity()).is_none());
}

#[test]
fn angles_round_trip_for_all_twelve_sequences() {
    for axes in ALL_SEQUENCES {
        for mut u in angles(40) {
            // The principal range of the middle angle: (0, π) for proper
            // Euler sequences, (−π/2, π/2) for Tait–Bryan ones.
            u[1] = if proper(axes) { u[1].abs() } else { u[1] / 2.0 };
            let r = sequence(axes, u);
            let [first, second] = angles_of(&r, axes).expect("away from the singularity");
            for (got, want) in first.iter().zip(&u) {
                assert!((got - want).abs() <= 1e-12, "{axes:?}: {first:?} vs {u:?}");
            }
            assert!(
                close(&sequence(axes, second), &r, 1e-13),
                "{axes:?}: second solution {second:?}"
            );
            assert!(second.iter().zip(&first).any(|(a, b)| (a - b).abs() > 1e-6));
        }
    }
}

#[test]
fn gimbal_lock_is_reported_with_the_angle_that_remains() {
    // Euler 3-1-3 at θ = 0 and π (notes §4.1.2): only φ ± ψ is determined.
    for theta in [0.0, PI] {
        let r = euler_313(0.4, theta, 0.9);
        let lock = angles_of(&r, [Axis::Z, Axis::X, Axis::Z]).unwrap_err();
        assert!((lock.middle - theta).abs() <= 1e-12);
        // The matrix is rebuilt from the middle and combined angles alone.
        let rebuilt = sequence([Axis::Z, Axis::X, Axis::Z], [lock.combined, lock.middle, 0.0]);
        assert!(close(&rebuilt, &r, 1e-12), "θ = {theta}");
    }
    // Bryan 1-2-3 written as R_x R_y R_z at the middle angle ±π/2.
    for b in [PI / 2.0, -PI / 2.0] {
        let axes = [Axis::X, Axis::Y, Axis::Z];
        let r = sequence(axes, [0.3, b, -1.1]);
        let lock = angles_of(&r, axes).unwrap_err();
        assert!((lock.middle - b).abs() <= 1e-12);
        let rebuilt = sequence(axes, [lock.combined, lock.middle, 0.0]);
        assert!(close(&rebuilt, &r, 1e-12), "b = {b}");
        assert!(lock.to_string().contains("gimbal lock"));
    }
}

/// `Rᵀ Ṙ` by central differences of `R(t)`, as a vector.
fn omega_by_differences(r: &dyn Fn(f64) -> Matrix3<f64>, t: f64) -> Vector3<f64> {
    let h = 1e-5;
    let r_dot = (r(t + h) - r(t - h)) / (2.0 * h);
    let w = r(t).transpose() * r_dot;
    Vector3::new(w[(2, 1)], w[(0, 2)], w[(1, 0)])
}

#[test]
fn angular_velocity_from_rates_matches_r_transpose_r_dot() {
    for axes in ALL_SEQUENCES {
        for (u, rates) in angles(10).into_iter().zip(angles(10).into_iter().rev()) {
            let path = |t: f64| {
                sequence(axes, [u[0] + rates[0] * t, u[1] + rates[1] * t, u[2] + rates[2] * t])
            };
            let fd = omega_by_differences(&path, 0.0);
            let w = angular_velocity(axes, u, rates);
            assert!((w - fd).norm() <= 1e-8 * (1.0 + w.norm()), "{axes:?}: {w} vs {fd}");
        }
    }
    // Quaternions: q(t) = normalised (q + t q̇ ⊥), rates tangent to |q| = 1.
    for u in angles(10) {
        let q = {
            let v = [u[0], u[1], u[2], 0.5];
            let n = v.iter().map(|x| x * x).sum::<f64>().sqrt();
            v.map(|x| x / n)
        };
        let d = [u[2], -u[0], 0.7, u[1]];
        let along: f64 = q.iter().zip(&d).map(|(a, b)| a * b).sum();
        let q_dot: [f64; 4] = std::array::from_fn(|i| d[i] - along * q[i]);
        let path = |t: f64| quaternion_to_matrix(std::array::from_fn(|i| q[i] + t * q_dot[i]));
        let fd = omega_by_differences(&path, 0.0);
        let w = quaternion_angular_velocity(q, q_dot);
        assert!((w - fd).norm() <= 1e-8 * (1.0 + w.norm()), "{w} vs {fd}");
    }
}

#[test]
fn point_velocity_and_acceleration_match_differences() {
    // P(t) = P0(t) + R(t) p(t): a point moving in a spinning, moving body.
    let axes = [Axis::Z, Axis::Y, Axis::X];
    let u = |t: f64| [0.3 + 1.1 * t + 0.2 * t * t, -0.4 + 0.7 * t, 0.2 - 0.5 * t * t];
    let du = |t: f64| [1.1 + 0.4 * t, 0.7, -t];
    let p0 = |t: f64| Vector3::new(t * t, (2.0 * t).sin(), 1.0 - t);
    let p = |t: f64| Vector3::new(0.5 + 0.1 * t, -0.2 * t * t, 0.3);
    let world = |t: f64| p0(t) + sequence(axes, u(t)) * p(t);
    let t = 0.6;
    let h = 1e-4;
    let v_fd = (world(t + h) - world(t - h)) / (2.0 * h);
    let a_fd = (world(t + h) - world(t) * 2.0 + world(t - h)) / (h * h);
    let omega = |t: f64| angular_velocity(axes, u(t), du(t));
    // ω̇ by differences of ω (it depends on the angles and their rates).
    let omega_dot = (omega(t + h) - omega(t - h)) / (2.0 * h);
    let r = sequence(axes, u(t));
    let (p_dot, p_ddot) = (Vector3::new(0.1, -0.4 * t, 0.0), Vector3::new(0.0, -0.4, 0.0));
    let p0_dot = Vector3::new(2.0 * t, 2.0 * (2.0 * t).cos(), -1.0);
    let p0_ddot = Vector3::new(2.0, -4.0 * (2.0 * t).sin(), 0.0);
    let v = point_velocity(&p0_dot, &r, &omega(t), &p(t), &p_dot);
    let a = point_acceleration(&p0_ddot, &r, &omega(t), &omega_dot, &p(t), &p_dot, &p_ddot);
    assert!((v - v_fd).norm() <= 1e-7, "{v} vs {v_fd}");
    assert!((a - a_fd).norm() <= 1e-5, "{a} vs {a_fd}");
}

#[test]
fn transforms_compose_and_invert() {
    use nalgebra::{Matrix4, Vector4};
    // Pure rotations compose to the sum of the angles (notes §4.1.1).
    let (alpha, beta) = (0.4, 1.1);
    let t =
        transform(&rot_z(alpha), &Vector3::zeros()) * transform(&rot_z(beta), &Vector3::zeros());
    assert!((t - transform(&rot_z(alpha + beta), &Vector3::zeros())).abs().max() <= 1e-15);
    for u in angles(10) {
        let r = sequence([Axis::Z, Axis::X, Axis::Y], u);
        let p = Vector3::new(u[2], u[0], -u[1]);
        let (t, ti) = (transform(&r, &p), inverse_transform(&r, &p));
        assert!((t * ti - Matrix4::identity()).abs().max() <= 1e-14);
        // A body point goes to p + R x_b (eq. 4.1).
        let xb = Vector3::new(0.3, -0.7, 1.1);
        let xw = t * Vector4::new(xb.x, xb.y, xb.z, 1.0);
        assert!((xw.xyz() - (p + r * xb)).norm() <= 1e-14 && xw.w == 1.0);
    }
    // Natural coordinates: two points at angle α give R_z(α).
    let p1 = Vector3::new(0.5, -0.2, 0.0);
    let p2 = p1 + Vector3::new(2.0 * alpha.cos(), 2.0 * alpha.sin(), 0.0);
    assert!((planar_frame(&p1, &p2) - rot_z(alpha)).abs().max() <= 1e-15);
}
