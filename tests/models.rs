//! End to end: models written in the model language, expanded by
//! `#[dae_model]`, integrated, and checked against exact solutions, an
//! independent reference, or a conserved quantity.

use daegen::prelude::*;

mod support;
use support::harness::methods_for;

include!("models/items.rs");
include!("models/n_body.rs");

example_1_1!(dae_model_with! { () });

/// Reference at t = 2: SciPy `solve_ivp`, DOP853 with rtol 1e-13, atol 1e-14
/// (Radau at the same tolerances agrees to 2e-14), on the notes' reduced system.
const EXAMPLE_1_1_AT_2: [(&str, f64); 5] = [
    ("x", 1.5034333031930631),
    ("der(x)", 0.4641985668711289),
    ("der(der(x))", -1.069542812039737),
    ("y", 6.520580363618382),
    ("der(y)", 5.282811888567393),
];

#[test]
fn example_1_1_is_reduced_like_the_notes_and_matches_the_reference() {
    assert_eq!(<Example11 as Model>::INFO.states, ["x", "der(x)", "der(der(x))", "y", "der(y)"]);
    assert_eq!(<Example11 as Model>::INDEX, 0);
    let sol = Example11::default()
        .simulate(0.0, 2.0, &Options::new().method(Method::Rk4).step(1e-3))
        .unwrap();
    for (name, reference) in EXAMPLE_1_1_AT_2 {
        let got = sol.last(name).unwrap();
        assert!((got - reference).abs() < 1e-10, "{name}(2) = {got}, reference {reference}");
    }
    assert_eq!(sol.stats().steps, 2000);
    assert_eq!(sol.stats().rhs_evals, 8000);
}

/// x'' = -ω² x with x(0) = 1, x'(0) = 0: x = cos ωt.
#[dae_model]
fn oscillator() {
    let omega = param(2.0);
    let x = state(1.0);
    der(der(x)) == -omega.powi(2) * x;
    let energy = output(0.5 * (der(x) * der(x) + omega * omega * x * x));
    let acceleration = output(der(der(x)));
}

#[test]
fn oscillator_follows_its_exact_solution() {
    let model = Oscillator { omega: 3.0 };
    let sol = model.simulate(0.0, 5.0, &Options::new().method(Method::Rk4).step(1e-3)).unwrap();
    let t: f64 = 5.0;
    assert!((sol.last("x").unwrap() - (3.0 * t).cos()).abs() < 1e-10);
    assert!((sol.last("der(x)").unwrap() + 3.0 * (3.0 * t).sin()).abs() < 1e-9);
    // The output reads der(der(x)), replaced by its equation: -ω² x.
    assert!((sol.last("acceleration").unwrap() + 9.0 * (3.0 * t).cos()).abs() < 1e-9);
    assert!((sol.last("energy").unwrap() - 4.5).abs() < 1e-9);
    // Linear interpolation between steps: error below h²/8 · max|x''| = 1.2e-6.
    let mid = sol.at(2.0005, "x").unwrap();
    assert!((mid - (3.0 * 2.0005f64).cos()).abs() < 1.2e-6);
}

gravitating_bodies! {
    /// Three equal masses at the vertices of an equilateral triangle
    /// inscribed in the unit circle, on circular orbits: the Lagrange
    /// solution rotates rigidly with ω² = G m / (√3 R³).
    #[dae_model]
    fn three_body(planar) {
        const N: usize = 3;
        /// Gravitational constant.
        let g = param(1.0);
        let m = [1.0; N];
        let w = 3f64.powf(-0.25);
        let x = state_array([1.0, -0.5, -0.5]);
        let y = state_array([0.0, 0.8660254037844386, -0.8660254037844386]);
        let u = state_array([0.0, -0.8660254037844386 * w, 0.8660254037844386 * w]);
        let v = state_array([w, -0.5 * w, -0.5 * w]);
    } then {
        let angular_momentum = output(
            x[0] * v[0] - y[0] * u[0] + x[1] * v[1] - y[1] * u[1] + x[2] * v[2] - y[2] * u[2],
        );
        let unused = output(w);
    }
}

#[test]
fn lagrange_triangle_rotates_rigidly() {
    let omega = 3f64.powf(-0.25);
    assert_eq!(omega, 0.7598356856515925);
    let sol = ThreeBody::default()
        .simulate(0.0, 10.0, &Options::new().method(Method::Rk4).step(1e-3))
        .unwrap();
    let t = 10.0;
    for (i, phase) in [0.0, 2.0, 4.0].iter().enumerate() {
        let angle = omega * t + phase * std::f64::consts::PI / 3.0;
        let (x, y) = (sol.last(&format!("x[{i}]")).unwrap(), sol.last(&format!("y[{i}]")).unwrap());
        assert!(
            (x - angle.cos()).abs() < 1e-9 && (y - angle.sin()).abs() < 1e-9,
            "body {i}: ({x}, {y})"
        );
    }
    assert!((sol.last("angular_momentum").unwrap() - 3.0 * omega).abs() < 1e-12);
}

/// Constant coefficients in front of the derivatives: solved exactly at
/// compile time. With E = [[1, 1], [1, -1]]: x' = (y - x)/2, y' = (y + x)/2.
#[dae_model]
fn constant_mass_matrix() {
    let x = state(1.0);
    let y = state(0.5);
    der(x) + der(y) == y;
    der(x) - der(y) == -x;
}

#[test]
fn constant_coefficients_are_solved_symbolically() {
    let model = ConstantMassMatrix::default();
    let (x, y) = (0.3, -1.7);
    let mut dy = [0.0; 2];
    model.rhs(0.0, &[x, y], &mut dy).unwrap();
    assert_eq!(dy, [(y - x) / 2.0, (y + x) / 2.0]);
    let mut jac = [0.0; 4];
    model.jacobian(0.0, &[x, y], &mut jac).unwrap();
    assert_eq!(<ConstantMassMatrix as Model>::JACOBIAN.pattern(), [(0, 0), (0, 1), (1, 0), (1, 1)]);
    assert_eq!(jac, [-0.5, 0.5, 0.5, 0.5]);
}

double_pendulum_angles!(dae_model_with! { () } {
    let energy = output(
        der(a) * der(a) + 0.5 * der(b) * der(b) + der(a) * der(b) * c
            - 2.0 * g * cos(a)
            - g * cos(b),
    );
});

#[test]
fn double_pendulum_conserves_energy_through_its_solved_mass_matrix() {
    let model = DoublePendulum::default();
    let sol = model.simulate(0.0, 5.0, &Options::new().method(Method::Rk4).step(1e-3)).unwrap();
    let e0 = -2.0 * 9.81 * 1f64.cos() - 9.81 * (-0.5f64).cos();
    let drift = (sol.last("energy").unwrap() - e0).abs();
    assert!(drift < 1e-8, "energy drift {drift:e}");
    // The analytic Jacobian against central differences of the right-hand side.
    let y = [1.0, 0.3, -0.5, -0.2];
    let pattern = <DoublePendulum as Model>::JACOBIAN.pattern();
    let mut values = vec![0.0; pattern.len()];
    model.jacobian(0.0, &y, &mut values).unwrap();
    for (k, &(i, j)) in pattern.iter().enumerate() {
        let h = 1e-6;
        let (mut yp, mut ym) = (y, y);
        yp[j] += h;
        ym[j] -= h;
        let (mut fp, mut fm) = ([0.0; 4], [0.0; 4]);
        model.rhs(0.0, &yp, &mut fp).unwrap();
        model.rhs(0.0, &ym, &mut fm).unwrap();
        let fd = (fp[i] - fm[i]) / (2.0 * h);
        assert!(
            (values[k] - fd).abs() <= 1e-7 * fd.abs().max(1.0),
            "∂f{i}/∂y{j}: {} vs {fd}",
            values[k]
        );
    }
}

/// x' = -sqrt(x), x(0) = 1: x = (1 - t/2)², which reaches 0 at t = 2; past
/// it a Runge–Kutta stage takes the square root of a negative number.
#[dae_model]
fn leaves_its_domain() {
    let x = state(1.0);
    der(x) == -sqrt(x);
}

#[test]
fn a_run_that_breaks_down_says_where_and_keeps_the_partial_solution() {
    let err = LeavesItsDomain::default()
        .simulate(0.0, 3.0, &Options::new().method(Method::Rk4).step(1e-3))
        .unwrap_err();
    match &err {
        Error::NonFinite { t, variable, partial } => {
            assert_eq!(*variable, "x");
            assert!(*t > 1.9 && *t < 2.1, "t = {t}");
            assert!(partial.times().len() > 1900);
            let (t_last, x_last) =
                (partial.times()[partial.times().len() - 1], partial.last("x").unwrap());
            assert!(
                (x_last - (1.0 - t_last / 2.0).powi(2)).abs() < 1e-6,
                "the partial solution is the exact one up to the failure"
            );
        }
        other => panic!("expected NonFinite, got {other}"),
    }
    assert!(err.partial_solution().is_some());
    assert!(err.to_string().contains("`x` became non-finite"));
}

#[test]
fn bad_requests_are_errors_not_panics() {
    let sol = Oscillator::default().simulate(0.0, 1.0, &Options::new()).unwrap();
    assert!(matches!(sol.last("z"), Err(Error::UnknownName { .. })));
    assert!(matches!(sol.at(2.0, "x"), Err(Error::OutOfRange { .. })));
    // The fixed-step Taylor scheme needs the derivatives of
    // #[dae_model(taylor = p)]: said, not panicked.
    let taylor = Oscillator::default().simulate(
        0.0,
        1.0,
        &Options::new().method(Method::TaylorFixed { order: 4, step: 0.1 }),
    );
    assert!(
        matches!(&taylor, Err(Error::InvalidOptions { message }) if message.contains("taylor = 4"))
    );
    // Every unusable option is refused before the first step, by name, for
    // every method (a step given to an adaptive method is checked too).
    let refused = |options: Options, name: &str| {
        // Every method that runs the model: the options are checked
        // before any method's first step.
        for method in methods_for::<Oscillator>(|_| true) {
            match Oscillator::default().simulate(0.0, 1.0, &options.method(method)) {
                Err(Error::InvalidOptions { message }) => {
                    assert!(message.contains(name), "{method:?}: {message}")
                }
                other => panic!("{method:?}, {name}: expected InvalidOptions, got {other:?}"),
            }
        }
    };
    refused(Options::new().step(-1.0), "step(-1)");
    refused(Options::new().step(0.0), "step(0)");
    refused(Options::new().initial_step(f64::NAN), "initial_step(NaN)");
    refused(Options::new().max_step(0.0), "max_step(0)");
    refused(Options::new().min_step(-1e-3), "min_step(-0.001)");
    refused(
        Options::new().max_step(1e-3).min_step(1e-2),
        "max_step(0.001) is below min_step(0.01)",
    );
    refused(Options::new().max_steps(0), "max_steps(0)");
    refused(Options::new().tolerance(0.0), "rtol(0) with atol(0)");
    refused(Options::new().rtol(-1e-6), "rtol(-0.000001)");
    refused(Options::new().atol(f64::NAN), "atol(NaN)");
    refused(Options::new().rtol(f64::INFINITY), "rtol(inf)");
    // A NaN or infinite parameter or initial value, by name.
    for value in [f64::NAN, f64::INFINITY] {
        let err = Oscillator { omega: value }.simulate(0.0, 1.0, &Options::new()).unwrap_err();
        assert!(matches!(err, Error::NonFiniteParameter { parameter: "omega", .. }), "{err:?}");
        assert!(err.to_string().contains("parameter `omega`"), "{err}");
        let err = Oscillator::default()
            .simulate_from(0.0, &[1.0, value], 1.0, &Options::new())
            .unwrap_err();
        assert!(matches!(err, Error::NonFiniteInitialValue { variable: "der(x)", .. }), "{err:?}");
        assert!(err.to_string().contains("initial value of `der(x)`"), "{err}");
    }
}

/// The README's model, verbatim, so the README cannot rot.
mod readme {
    use daegen::prelude::*;

    /// Planar pendulum in its angle.
    #[dae_model]
    fn pendulum() {
        /// Length (m).
        let l = param(1.0);
        let g = param(9.81);
        let theta = state(1.0); // initial angle; der(theta) starts at 0
        der(der(theta)) == -g / l * sin(theta); // reduced to first order by the macro
        let energy = output(0.5 * l * l * der(theta) * der(theta) - g * l * cos(theta));
    }

    #[test]
    fn readme_model_runs_and_conserves_energy() -> Result<(), daegen::Error> {
        let model = Pendulum { l: 2.0, ..Pendulum::default() };
        let sol = model.simulate(0.0, 10.0, &Options::new().method(Method::Rk4).step(1e-3))?;
        let e0 = -9.81 * 2.0 * 1f64.cos();
        assert!((sol.last("energy")? - e0).abs() < 1e-9);
        assert!(sol.last("theta")?.abs() <= 1.0 + 1e-9);
        Ok(())
    }
}

/// RADAU5 on a model whose mass matrix is solved at run time: there is no
/// analytic Jacobian, so it uses finite differences, and still conserves
/// the energy to the tolerance.
#[test]
fn radau5_works_without_an_analytic_jacobian() {
    let model = DoublePendulum::default();
    let options = Options::new().method(Method::Radau5).tolerance(1e-10);
    let sol = model.simulate(0.0, 5.0, &options).unwrap();
    let e0 = -2.0 * 9.81 * 1f64.cos() - 9.81 * (-0.5f64).cos();
    let drift = (sol.last("energy").unwrap() - e0).abs();
    assert!(drift < 1e-6, "energy drift {drift:e}");
    assert!(sol.stats().jacobian_evals > 0);
}

/// Diffusion on a ring of eight cells, u_i' = u_{i+1} − 2u_i + u_{i−1}
/// with the neighbours taken modulo N (`%` on loop indices), from the
/// mode u_i = cos(2π i/N) (initial values by index).
#[dae_model]
fn ring_diffusion() {
    const N: usize = 8;
    const PI: f64 = 3.141592653589793;
    let u = state_array((0..N).map(|i| cos(2.0 * PI * (i as f64) / (N as f64))));
    for i in 0..N {
        der(u[i]) == u[(i + 1) % N] - 2.0 * u[i] + u[(i + N - 1) % N];
    }
}

#[test]
fn periodic_neighbours_follow_the_rings_exact_mode() {
    // u_i = cos(2π i/N) is an eigenvector of the periodic Laplacian with
    // eigenvalue −(2 − 2 cos(2π/N)): it decays without changing shape.
    let n = 8;
    let mode: Vec<f64> =
        (0..n).map(|i| (2.0 * std::f64::consts::PI * i as f64 / n as f64).cos()).collect();
    let rate = 2.0 - 2.0 * (2.0 * std::f64::consts::PI / n as f64).cos();
    let opts = Options::new().method(Method::Dop853).tolerance(1e-12);
    let sol = RingDiffusion::default().simulate(0.0, 3.0, &opts).unwrap();
    for (i, m) in mode.iter().enumerate() {
        assert!((sol.state(0).unwrap()[i] - m).abs() <= 1e-15, "u[{i}] starts on the mode");
        let exact = m * (-rate * 3.0).exp();
        let got = sol.last(&format!("u[{i}]")).unwrap();
        assert!((got - exact).abs() <= 1e-11, "u[{i}]: {got} against {exact}");
    }
}

/// Numbers as the receivers of methods in the generated code: a rational
/// that binary does not hold exactly, raised to 3/2, and the sine of a
/// negative one.
#[dae_model]
fn constant_receivers() {
    let q = state_array((0..2).map(|i| (1.0 - ((i + 1) as f64) / 3.0).powf(1.5)));
    let s = state(sin(-1.0 / 3.0));
    der(q[0]) == -q[0];
    der(q[1]) == -q[1];
    der(s) == -s;
}

#[test]
fn constants_compile_as_method_receivers_and_keep_their_values() {
    let mut y = [0.0; 3];
    ConstantReceivers::default().initial_state(&mut y);
    let want = [(2.0f64 / 3.0).powf(1.5), (1.0f64 / 3.0).powf(1.5), (-1.0f64 / 3.0).sin()];
    for (got, want) in y.iter().zip(want) {
        assert!((got - want).abs() <= 2.0 * f64::EPSILON * want.abs(), "{got} against {want}");
    }
}

/// Diffusion on a 16 × 16 periodic grid, u′ = Δu (unit spacing), from the
/// mode u = cos(2πi/N)·cos(2πj/N): RADAU5's Newton matrices are sparse
/// (no renumbering bands a periodic grid).
#[dae_model]
fn periodic_heat() {
    const N: usize = 16;
    const PI: f64 = 3.141592653589793;
    let u = state_array((0..N * N).map(|k| {
        cos(2.0 * PI * (((k - k % N) / N) as f64) / (N as f64))
            * cos(2.0 * PI * ((k % N) as f64) / (N as f64))
    }));
    for i in 0..N {
        for j in 0..N {
            let k = i * N + j;
            der(u[k])
                == u[((i + 1) % N) * N + j]
                    + u[((i + N - 1) % N) * N + j]
                    + u[i * N + (j + 1) % N]
                    + u[i * N + (j + N - 1) % N]
                    - 4.0 * u[k];
        }
    }
}

#[test]
fn radau5_and_rodas5p_with_sparse_matrices_follow_the_grids_exact_mode() {
    // The mode is an eigenvector of the periodic Laplacian with eigenvalue
    // −2(2 − 2 cos(2π/N)).
    let n = 16;
    let theta = 2.0 * std::f64::consts::PI / n as f64;
    let rate = 2.0 * (2.0 - 2.0 * theta.cos());
    for (method, tol) in [(Method::Radau5, 1e-10), (Method::Rodas5P, 1e-6)] {
        let opts = Options::new().method(method).tolerance(tol);
        let sol = PeriodicHeat::default().simulate(0.0, 2.0, &opts).unwrap();
        // 256 states: LinearSolver::Auto keeps the sparse LU.
        assert_eq!(sol.stats().linear_solver, "sparse LU");
        let y = sol.final_state();
        for i in 0..n {
            for j in 0..n {
                let exact =
                    (theta * i as f64).cos() * (theta * j as f64).cos() * (-rate * 2.0).exp();
                assert!(
                    (y[i * n + j] - exact).abs() <= 10.0 * tol,
                    "{method:?}: u[{i},{j}]: {} against {exact}",
                    y[i * n + j]
                );
            }
        }
    }
}

#[test]
fn a_grid_written_as_loops_of_index_tables_evaluates_every_cell() {
    // The 16 × 16 grid's right-hand side and Jacobian come out of the macro
    // as loops over tables of indices (alike cells); each entry against the
    // five-point formula at a state with no two values alike.
    let n = 16;
    let y: Vec<f64> = (0..n * n).map(|k| ((k * k) as f64 * 0.618).sin() + 0.1 * k as f64).collect();
    let mut dy = vec![0.0; n * n];
    PeriodicHeat::default().rhs(0.0, &y, &mut dy).unwrap();
    let at = |i: usize, j: usize| y[(i % n) * n + j % n];
    for i in 0..n {
        for j in 0..n {
            let want =
                at(i + 1, j) + at(i + n - 1, j) + at(i, j + 1) + at(i, j + n - 1) - 4.0 * at(i, j);
            // Rounding: a few units of the terms' magnitude (they cancel).
            let terms = at(i + 1, j).abs()
                + at(i + n - 1, j).abs()
                + at(i, j + 1).abs()
                + at(i, j + n - 1).abs()
                + 4.0 * at(i, j).abs();
            let got = dy[i * n + j];
            assert!((got - want).abs() <= 4.0 * f64::EPSILON * terms, "[{i},{j}]: {got} {want}");
        }
    }
    let pattern = PeriodicHeat::JACOBIAN.pattern();
    let mut values = vec![f64::NAN; pattern.len()];
    PeriodicHeat::default().jacobian(0.0, &y, &mut values).unwrap();
    for (&(r, c), v) in pattern.iter().zip(&values) {
        assert_eq!(*v, if r == c { -4.0 } else { 1.0 }, "∂f{r}/∂y{c}");
    }
}

/// Index arithmetic divides as Rust's integers do: `k / 2` of the index
/// truncates (species side by side, two per cell), and `i / N` of a loop
/// index picks a row.
#[dae_model]
fn cells_side_by_side() {
    const N: usize = 3;
    let c = state_array((0..2 * N).map(|k| ((k / 2) as f64) + 0.5 * ((k % 2) as f64)));
    for i in 0..2 * N {
        der(c[i]) == ((i / 2 + i / N) as f64) * c[i];
    }
}

#[test]
fn index_division_truncates_as_in_rust() {
    let mut y = [0.0; 6];
    CellsSideBySide::default().initial_state(&mut y);
    assert_eq!(y, [0.0, 0.5, 1.0, 1.5, 2.0, 2.5]);
    let mut dy = [0.0; 6];
    CellsSideBySide::default().rhs(0.0, &[1.0; 6], &mut dy).unwrap();
    // i / 2 + i / 3 for i = 0..6.
    assert_eq!(dy, [0.0, 0.0, 1.0, 2.0, 3.0, 3.0]);
}
