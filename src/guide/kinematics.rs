//! # Kinematics helpers
//!
//! Rotations and frames (course notes §4.1) exist twice: symbolically in
//! the model language, where the macro differentiates through them, and
//! numerically in [`crate::runtime::kinematics`] on nalgebra types, for
//! set-up and post-processing.
//!
//! | in the model language | numerically |
//! |---|---|
//! | `rot_x(a)`, `rot_y(a)`, `rot_z(a)` (eq. 4.9) | `rot_x`, `rot_y`, `rot_z`, `rot(axis, a)` |
//! | `euler_313(ψ, θ, φ)`, `bryan_123(..)`, `rot_seq("zyx", a, b, c)`, `inverse_rot_seq(..)` (eq. 4.10–4.12) | `euler_313`, `bryan_123`, `sequence`, `inverse_sequence` |
//! | R → angles | `angles_of(&r, axes)`: both solutions, or `Err(GimbalLock)` at the singularity |
//! | `axis_angle(n, θ)` (Rodrigues, eq. 4.16–4.18), `skew(w)` | `axis_angle`, `axis_angle_of`, `skew` |
//! | `quat_to_rot(q0, q1, q2, q3)` (eq. 4.19), `quaternion_state([..])` (|q| = 1 kept) | `quaternion_to_matrix`, `matrix_to_quaternion` |
//! | `omega_seq("zxz", a, b, c)`, `omega_quat(..)`: ω from the rates (§4.1.4) | `angular_velocity`, `quaternion_angular_velocity` |
//! | `transform(r, p)`, `inverse_transform(r, p)`, `homogeneous(p)` (eq. 4.7–4.8) | `transform`, `inverse_transform` |
//! | `planar_frame(p1, p2)`, `natural_frame(p1, p2, p3)` (natural coordinates, §4.1.5) | `planar_frame` |
//! | `vec3`, `mat3`, `cross`, `dot`, `norm`, `transpose`, `*`, `+` | nalgebra |
//!
//! ```
//! use daegen::prelude::*;
//! use daegen::runtime::kinematics::{angles_of, euler_313, is_rotation, Axis};
//!
//! /// A body turning about its z axis at a constant rate, tilted by 0.3
//! /// about x: its angular velocity from the 3-1-3 angles and their rates.
//! #[dae_model]
//! fn turning() {
//!     let psi = state(0.0);
//!     let theta = state(0.3);
//!     let phi = state(0.0);
//!     der(psi) == 2.0;
//!     der(theta) == 0.0;
//!     der(phi) == 0.0;
//!     // The angles must be states: their rates are their `der`.
//!     let w = omega_seq("zxz", psi, theta, phi);
//!     let wz = output(w[2]);
//!     let r = euler_313(psi, theta, phi);
//!     let rise = output((r * vec3(1.0, 0.0, 0.0))[2]);
//! }
//!
//! let sol = Turning::default().simulate(0.0, 1.0, &Options::new().method(Method::Rk4).step(1e-2))?;
//! // ω in body axes: ψ' cos θ about the body z axis.
//! assert!((sol.last("wz")? - 2.0 * 0.3f64.cos()).abs() < 1e-12);
//! // eq. 4.10 is R = R_z(φ) R_x(θ) R_z(ψ): the third component of R e1 is
//! // sin ψ sin θ.
//! assert!((sol.last("rise")? - 2f64.sin() * 0.3f64.sin()).abs() < 1e-9);
//!
//! // Numerically: the angles [a, b, c] of R = R_z(a) R_x(b) R_z(c) back
//! // from the matrix, both solutions (here a = φ, c = ψ)…
//! let r = euler_313(0.4, 0.3, -1.2);
//! assert!(is_rotation(&r, 1e-12));
//! let [first, second] = angles_of(&r, [Axis::Z, Axis::X, Axis::Z]).unwrap();
//! let exact = |s: [f64; 3]| (s[0] + 1.2).abs() < 1e-12 && (s[1] - 0.3).abs() < 1e-12 && (s[2] - 0.4).abs() < 1e-12;
//! assert!(exact(first) || exact(second));
//! // …and at θ = 0 only ψ + φ is determined: gimbal lock, reported.
//! let lock = angles_of(&euler_313(0.4, 0.0, 0.5), [Axis::Z, Axis::X, Axis::Z]).unwrap_err();
//! assert!((lock.combined - 0.9).abs() < 1e-12);
//! # Ok::<(), daegen::Error>(())
//! ```
