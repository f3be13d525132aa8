//! `LinearSolver::Krylov`: RODAS5P's linear systems solved by GMRES with an
//! incomplete LU, on a grid with an exact solution, and the requests it
//! refuses with what to use instead.

use daegen::prelude::*;
use daegen::{EvalError, ModelInfo};

mod support;
use support::harness::{is_implicit, is_stiff_method, methods_for};

/// Advection and diffusion on a 32 × 32 periodic grid (unit spacing):
/// u′ = c·Δu − v·D_x u with central differences, from the mode
/// u = cos(θi)·cos(θj), θ = 2π/N. The Jacobian is not symmetric (the
/// advection), its spectral radius 8c = 800 against the mode's decay rate
/// of about 7.7: stiff. 1024 states: large enough for `LinearSolver::Auto`
/// to pick GMRES.
#[dae_model]
fn advected_heat() {
    const N: usize = 32;
    const PI: f64 = 3.141592653589793;
    let c = param(100.0);
    let v = param(30.0);
    let u = state_array((0..N * N).map(|k| {
        cos(2.0 * PI * (((k - k % N) / N) as f64) / (N as f64))
            * cos(2.0 * PI * ((k % N) as f64) / (N as f64))
    }));
    for i in 0..N {
        for j in 0..N {
            let east = ((i + 1) % N) * N + j;
            let west = ((i + N - 1) % N) * N + j;
            let north = i * N + (j + 1) % N;
            let south = i * N + (j + N - 1) % N;
            let k = i * N + j;
            der(u[k])
                == c * (u[east] + u[west] + u[north] + u[south] - 4.0 * u[k])
                    - v * (u[east] - u[west]) / 2.0;
        }
    }
}

/// The semi-discrete system's exact solution: the central difference
/// turns cos(θi + φ) into −sin θ·sin(θi + φ), so the mode travels with
/// phase speed v·sin θ and decays at the discrete Laplacian's rate
/// 2c(2 − 2cos θ): u = e^(−2c(2 − 2cos θ)t)·cos(θi − v sin θ·t)·cos(θj).
fn advected_heat_exact(i: usize, j: usize, t: f64) -> f64 {
    let (c, v, n) = (100.0, 30.0, 32.0);
    let theta = 2.0 * std::f64::consts::PI / n;
    let rate = 2.0 * c * (2.0 - 2.0 * theta.cos());
    (-rate * t).exp() * (theta * i as f64 - v * theta.sin() * t).cos() * (theta * j as f64).cos()
}

#[test]
fn gmres_follows_the_exact_solution_of_an_advected_heat_grid() {
    // To t = 0.3 the mode has decayed to e^(−2.3) ≈ 0.1 and travelled
    // 1.8 cells; the error stays within 10·tol at each tolerance.
    let t1 = 0.3;
    for tol in [1e-4, 1e-6, 1e-8] {
        let opts = Options::new()
            .method(Method::Rodas5P)
            .linear_solver(LinearSolver::Krylov)
            .tolerance(tol);
        let sol = AdvectedHeat::default().simulate(0.0, t1, &opts).unwrap();
        let y = sol.final_state();
        let worst = (0..32 * 32)
            .map(|k| (y[k] - advected_heat_exact(k / 32, k % 32, t1)).abs())
            .fold(0.0, f64::max);
        assert!(worst <= 10.0 * tol, "tol {tol:e}: error {worst:e}");
        let stats = sol.stats();
        assert_eq!(stats.linear_solver, "GMRES");
        // Iterations happened, and fewer than a handful per solve (eight
        // solves a step): the incomplete LU preconditions the grid.
        let solves = 8 * (stats.steps + stats.rejected);
        assert!(
            stats.linear_iterations > 0 && stats.linear_iterations <= 5 * solves,
            "tol {tol:e}: {} iterations for {solves} solves",
            stats.linear_iterations
        );
    }
}

#[test]
fn asked_for_the_direct_solver_both_methods_factor_the_grid_sparse() {
    let opts = Options::new().linear_solver(LinearSolver::Direct).tolerance(1e-6);
    // Every adaptive stiff method that runs the grid: each factors its
    // matrix and says how. Not Auto: it starts with an explicit pair,
    // which on this interval never hands over, so it factors nothing. (Nor
    // backward Euler, whose statistics name no linear solver.)
    let stiff = |m: Method| is_stiff_method(m) && m != Method::Auto;
    for method in methods_for::<AdvectedHeat>(stiff) {
        let sol = AdvectedHeat::default().simulate(0.0, 0.1, &opts.method(method)).unwrap();
        // A periodic grid: no renumbering bands it.
        assert_eq!(sol.stats().linear_solver, "sparse LU");
        assert_eq!(sol.stats().linear_iterations, 0);
    }
}

#[test]
fn by_default_a_large_grid_runs_rodas5p_with_gmres_at_any_tolerance() {
    // Method::Auto and LinearSolver::Auto: at 1e-8 the stiff method of a
    // small system would be RADAU5; a grid of 1024 states whose LU fills
    // in gets RODAS5P with GMRES, and says so.
    let tol = 1e-8;
    let sol = AdvectedHeat::default().simulate(0.0, 0.3, &Options::new().tolerance(tol)).unwrap();
    let stats = sol.stats();
    assert!(stats.method.ends_with("Rodas5P"), "{}", stats.method);
    assert_eq!(stats.linear_solver, "GMRES");
    let y = sol.final_state();
    let worst = (0..32 * 32)
        .map(|k| (y[k] - advected_heat_exact(k / 32, k % 32, 0.3)).abs())
        .fold(0.0, f64::max);
    assert!(worst <= 10.0 * tol, "error {worst:e}");
}

/// The names of a model written by hand: its states and their docs.
const fn hand_written_info(
    name: &'static str,
    states: &'static [&'static str],
    state_docs: &'static [&'static str],
    equations: usize,
) -> ModelInfo {
    ModelInfo { state_docs, ..ModelInfo::bare(name, states, equations) }
}

/// y′ = −y with a hand-written right-hand side: no Jacobian to build the
/// matrix from.
#[derive(Clone)]
struct HandWritten;

impl Model for HandWritten {
    const STATES: usize = 1;
    type State = [f64; 1];
    const INDEX: usize = 0;
    const INFO: ModelInfo = hand_written_info("HandWritten", &["y"], &[""], 1);
    fn initial_state(&self, y: &mut [f64]) {
        y[0] = 1.0;
    }
    fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), EvalError> {
        dy[0] = -y[0];
        Ok(())
    }
}

/// An RC circuit's node in mass-matrix form: C·v′ = (u − v)/R, 0 = i − (u − v)/R.
#[dae_model]
fn rc_node() {
    let c = param(1e-6);
    let r = param(1e3);
    let v = state(0.0);
    let i = algebraic(1e-3);
    let u = 1.0;
    c * der(v) == i;
    0.0 == i - (u - v) / r;
}

#[test]
fn requests_gmres_cannot_serve_are_refused_with_what_to_use() {
    let krylov = Options::new().linear_solver(LinearSolver::Krylov);
    let message = |result: Result<Solution, Error>| match result {
        Err(e @ Error::InvalidOptions { .. }) => e.to_string(),
        other => panic!("expected InvalidOptions, got {other:?}"),
    };
    // A method that factors its own matrices: every implicit method but
    // RODAS5P, whose stages GMRES solves, and Auto, which switches to it.
    let own = |m: Method| is_implicit(m) && !matches!(m, Method::Rodas5P | Method::Auto);
    for method in methods_for::<AdvectedHeat>(own) {
        let opts = krylov.method(method).step(0.01);
        let m = message(AdvectedHeat::default().simulate(0.0, 0.1, &opts));
        assert!(m.contains("Method::Rodas5P") && m.contains("LinearSolver::Direct"), "{m}");
    }
    // A model without a generated Jacobian.
    let m = message(HandWritten.simulate(0.0, 1.0, &krylov.method(Method::Rodas5P)));
    assert!(m.contains("HandWritten") && m.contains("LinearSolver::Direct"), "{m}");
    // A mass matrix.
    let opts = krylov.method(Method::Rodas5P).formulation(Formulation::MassMatrix);
    let m = message(RcNode::default().simulate(0.0, 1e-3, &opts));
    assert!(m.contains("mass matrix") && m.contains("LinearSolver::Direct"), "{m}");
}

/// States of [`SkewOscillators`].
const SKEW_N: usize = 60;
/// Each state's couplings reach this far ahead (mod N), and back.
const SKEW_OFFSETS: [usize; 3] = [1, 17, 45];

/// Coupling k of state i's weight, in [0.5, 1.4].
fn skew_weight(i: usize, k: usize) -> f64 {
    0.5 + ((i * 37 + k * 11) % 10) as f64 / 10.0
}

/// `(i, i)`, then for each coupling `(i, i + o)` and `(i + o, i)`.
const fn skew_pattern() -> [(usize, usize); 7 * SKEW_N] {
    let mut pattern = [(0, 0); 7 * SKEW_N];
    let mut i = 0;
    while i < SKEW_N {
        pattern[7 * i] = (i, i);
        let mut k = 0;
        while k < 3 {
            let j = (i + SKEW_OFFSETS[k]) % SKEW_N;
            pattern[7 * i + 1 + 2 * k] = (i, j);
            pattern[7 * i + 2 + 2 * k] = (j, i);
            k += 1;
        }
        i += 1;
    }
    pattern
}

const SKEW_PATTERN: [(usize, usize); 7 * SKEW_N] = skew_pattern();

/// y′ = −c(d·y + R·y), R sparse and skew-symmetric (written by hand with
/// its Jacobian): eigenvalues −cd ± iσ, a decay under oscillations up to
/// a thousand times faster. GMRES with ILU(0) does not converge on
/// `M/(hγ) − J` once the step is long beside 1/c (the matrix is then near
/// c·(d + R), indefinite in effect), as a first step over the whole
/// interval makes it.
#[derive(Clone)]
struct SkewOscillators;

impl SkewOscillators {
    const C: f64 = 1e4;
    const D: f64 = 0.01;

    fn jacobian_values(values: &mut [f64]) {
        for i in 0..SKEW_N {
            values[7 * i] = -Self::C * Self::D;
            for k in 0..3 {
                let w = skew_weight(i, k);
                values[7 * i + 1 + 2 * k] = -Self::C * w;
                values[7 * i + 2 + 2 * k] = Self::C * w;
            }
        }
    }
}

impl Model for SkewOscillators {
    const STATES: usize = SKEW_N;
    type State = [f64; SKEW_N];
    const INDEX: usize = 0;
    const INFO: ModelInfo =
        hand_written_info("SkewOscillators", &[""; SKEW_N], &[""; SKEW_N], SKEW_N);
    const JACOBIAN: daegen::Jacobian =
        daegen::Jacobian::Symbolic { pattern: &SKEW_PATTERN, time_derivative: true };
    fn initial_state(&self, y: &mut [f64]) {
        for (i, v) in y.iter_mut().enumerate() {
            *v = (i as f64).sin();
        }
    }
    fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), EvalError> {
        let mut values = [0.0; 7 * SKEW_N];
        Self::jacobian_values(&mut values);
        dy.fill(0.0);
        for (&(r, c), v) in SKEW_PATTERN.iter().zip(values) {
            dy[r] += v * y[c];
        }
        Ok(())
    }
    fn jacobian(&self, _t: f64, _y: &[f64], values: &mut [f64]) -> Result<(), EvalError> {
        Self::jacobian_values(values);
        Ok(())
    }
    fn time_derivative(&self, _t: f64, _y: &[f64], dfdt: &mut [f64]) -> Result<(), EvalError> {
        dfdt.fill(0.0);
        Ok(())
    }
}

#[test]
fn where_gmres_fails_the_run_factors_its_matrix_and_says_so() {
    use daegen::runtime::nalgebra::{DMatrix, DVector};
    // The exact solution e^(Jt)·y0 of the linear system.
    let t1 = 2e-2;
    let mut values = [0.0; 7 * SKEW_N];
    SkewOscillators::jacobian_values(&mut values);
    let mut jacobian = DMatrix::<f64>::zeros(SKEW_N, SKEW_N);
    for (&(r, c), v) in SKEW_PATTERN.iter().zip(values) {
        jacobian[(r, c)] += v * t1;
    }
    let mut y0 = vec![0.0; SKEW_N];
    SkewOscillators.initial_state(&mut y0);
    let exact = jacobian.exp() * DVector::from_vec(y0);
    let tol = 1e-6;
    for linear in [LinearSolver::Krylov, LinearSolver::Auto] {
        let opts = Options::new()
            .method(Method::Rodas5P)
            .linear_solver(linear)
            .initial_step(t1)
            .tolerance(tol);
        let sol = SkewOscillators.simulate(0.0, t1, &opts).unwrap();
        let stats = sol.stats();
        let worst = sol
            .final_state()
            .iter()
            .zip(exact.iter())
            .map(|(y, e)| (y - e).abs())
            .fold(0.0, f64::max);
        assert!(worst <= 100.0 * tol, "{linear:?}: error {worst:e}");
        match linear {
            // Tried, failed three times, factored: 60 states are dense.
            LinearSolver::Krylov => {
                assert_eq!(stats.linear_solver, "GMRES→dense LU");
                assert!(stats.linear_iterations > 3 * 100, "{}", stats.linear_iterations);
            }
            // Auto keeps the factorisation of a small model.
            _ => assert_eq!((stats.linear_solver, stats.linear_iterations), ("dense LU", 0)),
        }
    }
}
