// Models that a test runs and tests/expansion.rs snapshots, written once
// as macros that hand the model, a plain item, to another macro:
// `model!(dae_model_with! { (attributes) })` defines it,
// `model!(expansion_test! { name, (attributes), [items], })` snapshots its
// expansion. Those that take `{ statements }` add them to the model.

/// `contract_pendulum!(then! { arguments })`: `then!` called with its
/// arguments followed by the contract's pendulum as a plain item, so that
/// `contract_pendulum!(dae_model_with! { (taylor = 1) })` defines it and
/// tests/expansion.rs snapshots its expansion. Public, as the FMU tests and
/// examples define it in a module of their own.
#[allow(unused_macros)]
macro_rules! contract_pendulum {
    ($then:ident ! { $($arguments:tt)* }) => {
        $then! {
            $($arguments)*
            /// Planar pendulum as an index-3 DAE in Cartesian coordinates: the
            /// model of the contract, the notes' eq. 2.1. A point mass on a
            /// massless rod, the rod's force λ its algebraic variable.
            pub fn pendulum() {
                /// Mass (kg).
                let m = param(1.0);
                /// Rod length (m).
                let l = param(1.0);
                /// Gravity (m/s²).
                let g = param(9.81);
                /// Horizontal position (m).
                let x = state(1.0);
                /// Vertical position (m).
                let y = state(0.0);
                /// Horizontal velocity (m/s).
                let u = state(0.0);
                /// Vertical velocity (m/s).
                let v = state(0.0);
                /// Rod force over length (N/m).
                let lambda = algebraic(0.0);
                der(x) == u;
                der(y) == v;
                m * der(u) == -lambda * x;
                m * der(v) == -lambda * y - m * g;
                constraint(x * x + y * y - l * l);
                /// Total energy (J), kept by the exact solution.
                let energy = output(0.5 * m * (u * u + v * v) + m * g * y);
            }
        }
    };
}

/// `contract_pendulum_angle!(attributes)`: the contract's pendulum in its
/// angle θ from the downward vertical (x = l·sin θ, y = −l·cos θ),
/// released at rest from θ = π/2: the minimal-coordinate ODE of the notes,
/// as `PendulumAngle`.
#[allow(unused_macros)]
macro_rules! contract_pendulum_angle {
    ($($attr:tt)*) => {
        /// The contract's pendulum in its angle from the downward vertical.
        #[dae_model($($attr)*)]
        fn pendulum_angle() {
            let l = param(1.0);
            let g = param(9.81);
            let theta = state(1.5707963267948966);
            init(der(theta), 0.0);
            l * der(der(theta)) == -g * sin(theta);
        }
    };
}

/// `dae_model_with! { (attributes) item }`: `item` under
/// `#[dae_model(attributes)]`.
#[allow(unused_macros)]
macro_rules! dae_model_with {
    (($($attribute:tt)*) $item:item) => {
        #[dae_model($($attribute)*)]
        $item
    };
}

/// `example_1_1!(then! { arguments })`: course notes, Example 1.1, a
/// third-order system.
#[allow(unused_macros)]
macro_rules! example_1_1 {
    ($then:ident ! { $($arguments:tt)* }) => {
        $then! {
            $($arguments)*
            /// Course notes, Example 1.1: a third-order system, reduced to
            /// first order by the macro exactly as the notes do by hand
            /// (z = x', w = x'', p = y').
            fn example_1_1() {
                let t = time();
                let x = state(0.0);
                let y = state(0.0);
                init(der(x), 0.0);
                init(der(der(x)), 2.0);
                init(der(y), 2.0);
                der(der(der(x))) + der(y) == x * x + t;
                der(der(y)) + x == t * t + 1.0;
            }
        }
    };
}

/// `double_pendulum_cartesian!(then! { arguments } { statements })`: two
/// unit masses on unit massless rods in Cartesian coordinates, a 6 × 6 KKT
/// system whose four accelerations have constant pivots, leaving the 2 × 2
/// Schur complement in the multipliers, solved symbolically.
#[allow(unused_macros)]
macro_rules! double_pendulum_cartesian {
    ($then:ident ! { $($arguments:tt)* } { $($statements:tt)* }) => {
        $then! {
            $($arguments)*
            /// Two unit masses on unit massless rods in Cartesian
            /// coordinates.
            fn double_pendulum_cartesian() {
                let g = param(9.81);
                let x1 = state(1.0);
                let y1 = state(0.0);
                let x2 = state(2.0);
                let y2 = state(0.0);
                let l1 = algebraic(0.0);
                let l2 = algebraic(0.0);
                der(der(x1)) == -l1 * x1 + l2 * (x2 - x1);
                der(der(y1)) == -l1 * y1 + l2 * (y2 - y1) - g;
                der(der(x2)) == -l2 * (x2 - x1);
                der(der(y2)) == -l2 * (y2 - y1) - g;
                constraint(x1 * x1 + y1 * y1 - 1.0);
                constraint((x2 - x1) * (x2 - x1) + (y2 - y1) * (y2 - y1) - 1.0);
                $($statements)*
            }
        }
    };
}

/// `double_pendulum_angles!(then! { arguments } { statements })`: a double
/// pendulum in its angles (unit masses and lengths), the mass matrix
/// [[2, c], [c, 1]], c = cos(θ1 − θ2), full and configuration-dependent; a
/// 2 × 2 block solved symbolically (its pivot 1 − c²/2 never vanishes), so
/// the model has an analytic Jacobian.
#[allow(unused_macros)]
macro_rules! double_pendulum_angles {
    ($then:ident ! { $($arguments:tt)* } { $($statements:tt)* }) => {
        $then! {
            $($arguments)*
            /// A double pendulum in its angles, unit masses and lengths.
            fn double_pendulum() {
                let g = param(9.81);
                let a = state(1.0);
                let b = state(-0.5);
                let c = cos(a - b);
                let s = sin(a - b);
                2.0 * der(der(a)) + c * der(der(b)) == -s * der(b) * der(b) - 2.0 * g * sin(a);
                c * der(der(a)) + der(der(b)) == s * der(a) * der(a) - g * sin(b);
                $($statements)*
            }
        }
    };
}

/// `example_1_4!(then! { arguments })`: course notes, Example 1.4,
/// y' = x y + x, y(0) = 1, whose solution is y = 2 exp(x²/2) − 1.
#[allow(unused_macros)]
macro_rules! example_1_4 {
    ($then:ident ! { $($arguments:tt)* }) => {
        $then! {
            $($arguments)*
            /// Course notes, Example 1.4: y' = x y + x, y(0) = 1,
            /// y = 2 exp(x²/2) − 1.
            fn example_1_4() {
                let x = time();
                let y = state(1.0);
                der(y) == x * y + x;
            }
        }
    };
}

/// `double_pendulum_released_horizontal!(attributes)`: the Cartesian double
/// pendulum's angle form (angles from the downward vertical, unit masses
/// and lengths, both rods horizontal at rest), the mass matrix
/// [[2, c], [c, 1]], c = cos(a − b), as `DoublePendulumAngles`.
#[allow(unused_macros)]
macro_rules! double_pendulum_released_horizontal {
    ($($attr:tt)*) => {
        /// The double pendulum in its angles from the downward vertical,
        /// released with both rods horizontal.
        #[dae_model($($attr)*)]
        fn double_pendulum_angles() {
            let g = param(9.81);
            let a = state(1.5707963267948966);
            let b = state(1.5707963267948966);
            let c = cos(a - b);
            let s = sin(a - b);
            2.0 * der(der(a)) + c * der(der(b)) == -s * der(b) * der(b) - 2.0 * g * sin(a);
            c * der(der(a)) + der(der(b)) == s * der(a) * der(a) - g * sin(b);
        }
    };
}
