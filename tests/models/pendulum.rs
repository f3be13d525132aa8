// Cash's index-3 pendulum (`pendul3.f`; ../shared/notes/reference-problems.md
// §4) and its minimal-coordinate ODE, shared by the DAE tests and the
// benchmark.

/// `cash_pendulum_model!(attributes)`: the pendulum with g = 1 released
/// from (1, 0) moving up at unit speed, an index-3 DAE in x, y, u, v, λ.
#[allow(unused_macros)]
macro_rules! cash_pendulum_model {
    ($($attr:tt)*) => {
        /// Cash's index-3 pendulum: x' = u, y' = v, u' = −λx, v' = −λy − 1,
        /// x² + y² = 1.
        #[dae_model($($attr)*)]
        fn cash_pendulum() {
            let g = param(1.0);
            let x = state(1.0);
            let y = state(0.0);
            let u = state(0.0);
            let v = state(1.0);
            let lambda = algebraic(1.0);
            der(x) == u;
            der(y) == v;
            der(u) == -lambda * x;
            der(v) == -lambda * y - g;
            constraint(x * x + y * y - 1.0);
        }

        /// The same pendulum in its angle (x = cos θ, y = sin θ): θ'' = −g cos θ.
        #[dae_model($($attr)*)]
        fn cash_pendulum_angle() {
            let g = param(1.0);
            let theta = state(0.0);
            init(der(theta), 1.0);
            der(der(theta)) == -g * cos(theta);
        }
    };
}

/// (x, y, u, v, λ) at t = 10, recomputed to 25 digits (the printed values
/// of `pendul3.f` hold only 9–12).
#[allow(dead_code)]
const CASH_PENDULUM_AT_10: [f64; 5] = [
    0.884392383092720254000816,
    0.466744161964109775211094,
    0.1203726552417017963052549,
    -0.2280835372003925465259898,
    -0.400232485892329325633282,
];
