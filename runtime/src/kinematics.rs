//! Rigid-body kinematics on nalgebra types (course notes §4.1): primitive
//! rotations and sequences of them, inverse sequences, axis–angle
//! (Rodrigues), quaternions, the angles of a sequence recovered from a
//! rotation matrix with the gimbal lock detected, angular velocity from the
//! parameter rates, and the velocity and acceleration of a body point.
//!
//! Conventions: rotations are active, `R_x(θ)` of eq. 4.9, and a sequence
//! `[a, b, c]` about axes `[i, j, k]` is the product `R_i(a) R_j(b) R_k(c)`
//! (the notes' `R_x(θ) R_y(φ) R_z(ψ)` reads "first ψ about z, then φ about
//! the new y, then θ about the new x"). Quaternions are `[q0, q1, q2, q3]`
//! with `q0 = cos(θ/2)` (eq. 4.19). Angular velocities are in body axes,
//! `Rᵀ Ṙ = skew(ω)` (eq. 4.20).

use nalgebra::{Matrix3, Matrix4, Vector3};

/// A coordinate axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Axis {
    /// x (1).
    X,
    /// y (2).
    Y,
    /// z (3).
    Z,
}

impl Axis {
    fn index(self) -> usize {
        match self {
            Axis::X => 0,
            Axis::Y => 1,
            Axis::Z => 2,
        }
    }

    fn unit(self) -> Vector3<f64> {
        let mut e = Vector3::zeros();
        e[self.index()] = 1.0;
        e
    }
}

/// `R_x(θ)` (eq. 4.9).
pub fn rot_x(theta: f64) -> Matrix3<f64> {
    let (s, c) = theta.sin_cos();
    Matrix3::new(1.0, 0.0, 0.0, 0.0, c, -s, 0.0, s, c)
}

/// `R_y(θ)` (eq. 4.9).
pub fn rot_y(theta: f64) -> Matrix3<f64> {
    let (s, c) = theta.sin_cos();
    Matrix3::new(c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c)
}

/// `R_z(θ)` (eq. 4.9).
pub fn rot_z(theta: f64) -> Matrix3<f64> {
    let (s, c) = theta.sin_cos();
    Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0)
}

/// The primitive rotation about `axis`.
pub fn rot(axis: Axis, theta: f64) -> Matrix3<f64> {
    match axis {
        Axis::X => rot_x(theta),
        Axis::Y => rot_y(theta),
        Axis::Z => rot_z(theta),
    }
}

/// `R_i(a) R_j(b) R_k(c)` for `axes = [i, j, k]`, `angles = [a, b, c]`.
pub fn sequence(axes: [Axis; 3], angles: [f64; 3]) -> Matrix3<f64> {
    rot(axes[0], angles[0]) * rot(axes[1], angles[1]) * rot(axes[2], angles[2])
}

/// The inverse of a sequence (eq. 4.12): the axes reversed and the angles
/// negated, `R_k(−c) R_j(−b) R_i(−a) = (R_i(a) R_j(b) R_k(c))ᵀ`.
pub fn inverse_sequence(axes: [Axis; 3], angles: [f64; 3]) -> Matrix3<f64> {
    sequence([axes[2], axes[1], axes[0]], [-angles[2], -angles[1], -angles[0]])
}

/// Euler angles, sequence 3-1-3 (eq. 4.10): ψ about z, then θ about x, then
/// φ about z, `R_z(φ) R_x(θ) R_z(ψ)`.
pub fn euler_313(psi: f64, theta: f64, phi: f64) -> Matrix3<f64> {
    rot_z(phi) * rot_x(theta) * rot_z(psi)
}

/// Bryan (Cardan) angles, sequence 1-2-3 (eq. 4.11): φ1 about x, then φ2
/// about y, then φ3 about z, `R_z(φ3) R_y(φ2) R_x(φ1)`.
pub fn bryan_123(phi1: f64, phi2: f64, phi3: f64) -> Matrix3<f64> {
    rot_z(phi3) * rot_y(phi2) * rot_x(phi1)
}

/// The cross-product matrix: `skew(w) v = w × v` (eq. 4.17).
pub fn skew(w: &Vector3<f64>) -> Matrix3<f64> {
    Matrix3::new(0.0, -w.z, w.y, w.z, 0.0, -w.x, -w.y, w.x, 0.0)
}

/// The rotation by `theta` about the unit axis `n` (Rodrigues, eq. 4.18):
/// `I + sin θ N + (1 − cos θ) N²`, `N = skew(n)`. `n` is normalised; a zero
/// axis gives the identity.
pub fn axis_angle(n: &Vector3<f64>, theta: f64) -> Matrix3<f64> {
    let norm = n.norm();
    if norm == 0.0 {
        return Matrix3::identity();
    }
    let big_n = skew(&(n / norm));
    Matrix3::identity() + big_n * theta.sin() + big_n * big_n * (1.0 - theta.cos())
}

/// `R(q)` of a unit quaternion `[q0, q1, q2, q3]` (eq. 4.19); `q` is
/// normalised first.
pub fn quaternion_to_matrix(q: [f64; 4]) -> Matrix3<f64> {
    let norm = q.iter().map(|v| v * v).sum::<f64>().sqrt();
    let [q0, q1, q2, q3] = q.map(|v| v / norm);
    Matrix3::new(
        2.0 * (q0 * q0 + q1 * q1) - 1.0,
        2.0 * (q1 * q2 - q0 * q3),
        2.0 * (q0 * q2 + q1 * q3),
        2.0 * (q0 * q3 + q1 * q2),
        2.0 * (q0 * q0 + q2 * q2) - 1.0,
        2.0 * (q2 * q3 - q0 * q1),
        2.0 * (q1 * q3 - q0 * q2),
        2.0 * (q0 * q1 + q2 * q3),
        1.0 - 2.0 * (q1 * q1 + q2 * q2),
    )
}

/// The unit quaternion of a rotation matrix, with `q0 ≥ 0` (Shepperd's
/// method: from the largest of the four squared components, so no
/// division by a small number).
pub fn matrix_to_quaternion(r: &Matrix3<f64>) -> [f64; 4] {
    let trace = r.trace();
    let candidates = [trace, r[(0, 0)], r[(1, 1)], r[(2, 2)]];
    let k = (0..4).max_by(|&a, &b| candidates[a].total_cmp(&candidates[b])).unwrap_or(0);
    let q = match k {
        0 => {
            let s = 2.0 * (1.0 + trace).sqrt();
            [
                s / 4.0,
                (r[(2, 1)] - r[(1, 2)]) / s,
                (r[(0, 2)] - r[(2, 0)]) / s,
                (r[(1, 0)] - r[(0, 1)]) / s,
            ]
        }
        1 => {
            let s = 2.0 * (1.0 + r[(0, 0)] - r[(1, 1)] - r[(2, 2)]).sqrt();
            [
                (r[(2, 1)] - r[(1, 2)]) / s,
                s / 4.0,
                (r[(0, 1)] + r[(1, 0)]) / s,
                (r[(0, 2)] + r[(2, 0)]) / s,
            ]
        }
        2 => {
            let s = 2.0 * (1.0 - r[(0, 0)] + r[(1, 1)] - r[(2, 2)]).sqrt();
            [
                (r[(0, 2)] - r[(2, 0)]) / s,
                (r[(0, 1)] + r[(1, 0)]) / s,
                s / 4.0,
                (r[(1, 2)] + r[(2, 1)]) / s,
            ]
        }
        _ => {
            let s = 2.0 * (1.0 - r[(0, 0)] - r[(1, 1)] + r[(2, 2)]).sqrt();
            [
                (r[(1, 0)] - r[(0, 1)]) / s,
                (r[(0, 2)] + r[(2, 0)]) / s,
                (r[(1, 2)] + r[(2, 1)]) / s,
                s / 4.0,
            ]
        }
    };
    if q[0] < 0.0 {
        q.map(|v| -v)
    } else {
        q
    }
}

/// The rotation axis and angle of `R` (Euler's theorem, eq. 4.14), the
/// angle in [0, π]; `None` for the identity, whose axis is undetermined.
pub fn axis_angle_of(r: &Matrix3<f64>) -> Option<(Vector3<f64>, f64)> {
    // Through the quaternion: accurate near 0 and near π alike.
    let [q0, q1, q2, q3] = matrix_to_quaternion(r);
    let v = Vector3::new(q1, q2, q3);
    let s = v.norm();
    if s <= f64::EPSILON {
        return None;
    }
    Some((v / s, 2.0 * s.atan2(q0)))
}

/// Whether `R` is a rotation: `RᵀR = I` and `det R = 1` within `tol`.
pub fn is_rotation(r: &Matrix3<f64>, tol: f64) -> bool {
    let orthogonal = (r.transpose() * r - Matrix3::identity()).abs().max() <= tol;
    orthogonal && (r.determinant() - 1.0).abs() <= tol
}

/// The angles of a sequence at a singular configuration (gimbal lock):
/// only a combination of the first and last angle is determined.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GimbalLock {
    /// The middle angle (0 or π for a proper Euler sequence, ±π/2 for a
    /// Tait–Bryan one).
    pub middle: f64,
    /// The one angle φ the matrix still determines: `R = R_i(φ) R_j(middle)`
    /// (the first and last angles combined, as a sum or a difference).
    pub combined: f64,
}

impl std::fmt::Display for GimbalLock {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "gimbal lock: the middle angle is {} and only a combination of the first and last angles ({}) is determined",
            self.middle, self.combined
        )
    }
}

impl std::error::Error for GimbalLock {}

/// Both solutions `[a, b, c]` of `R_i(a) R_j(b) R_k(c) = R` (the system of
/// eq. 4.13 has two in (−π, π]), for a Tait–Bryan sequence (three distinct
/// axes) or a proper Euler sequence (first and last axis equal). At a
/// singular configuration the angles are not determined: `Err` says so.
/// A matrix that is not a rotation gives meaningless angles: check
/// [`is_rotation`] first. A sequence with two equal consecutive axes has a
/// degree of freedom too few and is answered with `Err` at every matrix.
pub fn angles_of(r: &Matrix3<f64>, axes: [Axis; 3]) -> Result<[[f64; 3]; 2], GimbalLock> {
    let (i, j) = (axes[0].index(), axes[1].index());
    let wrap = |x: f64| {
        let y = (x + std::f64::consts::PI).rem_euclid(2.0 * std::f64::consts::PI)
            - std::f64::consts::PI;
        if y == -std::f64::consts::PI {
            std::f64::consts::PI
        } else {
            y
        }
    };
    if i == j || axes[1] == axes[2] {
        return Err(GimbalLock { middle: f64::NAN, combined: f64::NAN });
    }
    // The third axis k and the parity s of (i, j, k).
    let k = 3 - i - j;
    let s = if (i + 1) % 3 == j { 1.0 } else { -1.0 };
    if axes[2] == axes[0] {
        // Proper Euler: R[i][i] = cos b.
        let sin_b = (r[(j, i)].powi(2) + r[(k, i)].powi(2)).sqrt();
        let b = sin_b.atan2(r[(i, i)]);
        if sin_b <= 1e-12 {
            return Err(locked(r, axes, b));
        }
        let a = r[(j, i)].atan2(-s * r[(k, i)]);
        let c = r[(i, j)].atan2(s * r[(i, k)]);
        Ok([
            [wrap(a), b, wrap(c)],
            [wrap(a + std::f64::consts::PI), -b, wrap(c + std::f64::consts::PI)],
        ])
    } else {
        let k = axes[2].index();
        // Tait–Bryan: R[i][k] = s sin b.
        let sin_b = (s * r[(i, k)]).clamp(-1.0, 1.0);
        let cos_b = (r[(i, i)].powi(2) + r[(i, j)].powi(2)).sqrt();
        let b = sin_b.atan2(cos_b);
        if cos_b <= 1e-12 {
            return Err(locked(r, axes, b));
        }
        let a = (-s * r[(j, k)]).atan2(r[(k, k)]);
        let c = (-s * r[(i, j)]).atan2(r[(i, i)]);
        Ok([
            [wrap(a), b, wrap(c)],
            [
                wrap(a + std::f64::consts::PI),
                wrap(std::f64::consts::PI - b),
                wrap(c + std::f64::consts::PI),
            ],
        ])
    }
}

/// At a singular configuration `R = R_i(φ) R_j(b)`: the one angle φ left.
fn locked(r: &Matrix3<f64>, axes: [Axis; 3], b: f64) -> GimbalLock {
    let m = r * rot(axes[1], b).transpose();
    let i = axes[0].index();
    let (n1, n2) = ((i + 1) % 3, (i + 2) % 3);
    GimbalLock { middle: b, combined: m[(n2, n1)].atan2(m[(n1, n1)]) }
}

/// Body angular velocity of a sequence from its angle rates, `ω = E(u) u̇`
/// (§4.1.4): `ω = R_kᵀ R_jᵀ e_i ȧ + R_kᵀ e_j ḃ + e_k ċ`.
pub fn angular_velocity(axes: [Axis; 3], angles: [f64; 3], rates: [f64; 3]) -> Vector3<f64> {
    let rk = rot(axes[2], angles[2]).transpose();
    let rj = rot(axes[1], angles[1]).transpose();
    rk * rj * axes[0].unit() * rates[0] + rk * axes[1].unit() * rates[1] + axes[2].unit() * rates[2]
}

/// Body angular velocity from quaternion rates (§4.1.4):
/// `ω = 2 (q0 q̇v − q̇0 qv − qv × q̇v)` for `R(q)` of eq. 4.19 and a unit `q`.
pub fn quaternion_angular_velocity(q: [f64; 4], q_dot: [f64; 4]) -> Vector3<f64> {
    let qv = Vector3::new(q[1], q[2], q[3]);
    let dv = Vector3::new(q_dot[1], q_dot[2], q_dot[3]);
    (dv * q[0] - qv * q_dot[0] - qv.cross(&dv)) * 2.0
}

/// Velocity of a body point (eq. 4.21): `ṗ0 + R (ω × p + ṗ)`, with `p`, `ṗ`
/// and `ω` in body axes and the origin's velocity `ṗ0` in world axes.
pub fn point_velocity(
    origin_velocity: &Vector3<f64>,
    r: &Matrix3<f64>,
    omega: &Vector3<f64>,
    p: &Vector3<f64>,
    p_dot: &Vector3<f64>,
) -> Vector3<f64> {
    origin_velocity + r * (omega.cross(p) + p_dot)
}

/// Acceleration of a body point (eq. 4.22): `p̈0 + R (ω × (ω × p)` (centripetal)
/// `+ ω̇ × p` (tangential) `+ 2 ω × ṗ + p̈)` (relative and Coriolis).
pub fn point_acceleration(
    origin_acceleration: &Vector3<f64>,
    r: &Matrix3<f64>,
    omega: &Vector3<f64>,
    omega_dot: &Vector3<f64>,
    p: &Vector3<f64>,
    p_dot: &Vector3<f64>,
    p_ddot: &Vector3<f64>,
) -> Vector3<f64> {
    origin_acceleration
        + r * (omega.cross(&omega.cross(p))
            + omega_dot.cross(p)
            + omega.cross(p_dot) * 2.0
            + p_ddot)
}

/// The 4 × 4 transform `[R p; 0 1]` of a frame at `p` with orientation `R`
/// (eq. 4.7): world coordinates of a point from its body coordinates.
pub fn transform(r: &Matrix3<f64>, p: &Vector3<f64>) -> Matrix4<f64> {
    let mut t = Matrix4::identity();
    t.fixed_view_mut::<3, 3>(0, 0).copy_from(r);
    t.fixed_view_mut::<3, 1>(0, 3).copy_from(p);
    t
}

/// The inverse transform `[Rᵀ −Rᵀp; 0 1]` (eq. 4.8).
pub fn inverse_transform(r: &Matrix3<f64>, p: &Vector3<f64>) -> Matrix4<f64> {
    let rt = r.transpose();
    transform(&rt, &(-(rt * p)))
}

/// The planar body frame of two points in natural coordinates (§4.1.5):
/// origin at `p1`, x axis along `p1 → p2`, z axis out of the plane.
pub fn planar_frame(p1: &Vector3<f64>, p2: &Vector3<f64>) -> Matrix3<f64> {
    let d = p2 - p1;
    let l = d.norm();
    let (c, s) = (d.x / l, d.y / l);
    Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0)
}
