//! RODAS5P: a stiffly accurate Rosenbrock method of order 5 with an
//! embedded method of order 4 and a continuous output of order 4
//! (Steinebach, "Construction of Rosenbrock–Wanner method Rodas5P and
//! numerical benchmarks within the Julia Differential Equations package",
//! BIT Numer. Math. 63, 2023). A step evaluates the Jacobian and ∂f/∂t
//! once and factors one real matrix `M/(hγ) − J`, where RADAU5 iterates
//! Newton on a real and a complex one: fewer operations per step where
//! few digits are asked. The step loop follows Hairer & Wanner's `rodas.f`
//! (*Solving ODEs II*, §VI.4): stages in the transformed variables
//! `u_i = Σ γ_ij k_j`, the last increment as the error estimate, and
//! Gustafsson's predictive step control.

// Published coefficients are kept digit for digit as printed.
#![allow(clippy::excessive_precision)]

use crate::error::Error;
use crate::info::EvalError;
use crate::linalg::apply_mass;
use crate::linalg::newton::{Factored, Newton, Shifts, Structure};
use crate::methods::mass::Mass;
use crate::model::{has_mass_matrix, Model};
use crate::options::LinearSolver;
use crate::solution::Solution;
use crate::step::control::Predictive;
use crate::step::driver::{Counts, DenseOutput, Driver};
use crate::step::jacobian::DenseJacobian;
use crate::step::stiffness::{Finish, NonStiffWatch};
use crate::step::Problem;

/// The diagonal γ of the method's Γ.
const GAMMA: f64 = 0.21193756319429014;
const STAGES: usize = 8;

/// `a_ij` of the transformed stages 2 to 6 (row i − 2). Stages 7 and 8
/// start from the previous stage's argument plus its increment, and the
/// solution is stage 8's argument plus its increment: the method is
/// stiffly accurate twice over, which makes its last increment an error
/// estimate.
const A: [[f64; 5]; 5] = [
    [3.0, 0.0, 0.0, 0.0, 0.0],
    [2.849394379747939, 0.45842242204463923, 0.0, 0.0, 0.0],
    [-6.954028509809101, 2.489845061869568, -10.358996098473584, 0.0, 0.0],
    [2.8029986275628964, 0.5072464736228206, -0.3988312541770524, -0.04721187230404641, 0.0],
    [
        -7.502846399306121,
        2.561846144803919,
        -11.627539656261098,
        -0.18268767659942256,
        0.030198172008377946,
    ],
];

/// `C_ij`: stage i's right-hand side adds `M·Σ_j (C_ij/h)·u_j` (row i − 2,
/// stages 2 to 8).
const C: [[f64; 7]; 7] = [
    [-14.155112264123755, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [-17.97296035885952, -2.859693295451294, 0.0, 0.0, 0.0, 0.0, 0.0],
    [147.12150275711716, -1.41221402718213, 71.68940251302358, 0.0, 0.0, 0.0, 0.0],
    [165.43517024871676, -0.4592823456491126, 42.90938336958603, -5.961986721573306, 0.0, 0.0, 0.0],
    [
        24.854864614690072,
        -3.0009227002832186,
        47.4931110020768,
        5.5814197821558125,
        -0.6610691825249471,
        0.0,
        0.0,
    ],
    [
        30.91273214028599,
        -3.1208243349937974,
        77.79954646070892,
        34.28646028294783,
        -19.097331116725623,
        -28.087943162872662,
        0.0,
    ],
    [
        37.80277123390563,
        -3.2571969029072276,
        112.26918849496327,
        66.9347231244047,
        -40.06618937091002,
        -54.66780262877968,
        -9.48861652309627,
    ],
];

/// The stages' times, `t + c_i·h`.
const STAGE_TIME: [f64; STAGES] = [
    0.0,
    0.6358126895828704,
    0.4095798393397535,
    0.9769306725060716,
    0.4288403609558664,
    1.0,
    1.0,
    1.0,
];

/// `γ_i = Σ_j γ_ij`: stage i's right-hand side adds `h·γ_i·∂f/∂t`.
const TIME_WEIGHT: [f64; STAGES] = [
    0.21193756319429014,
    -0.42387512638858027,
    -0.3384627126235924,
    1.8046452872882734,
    2.325825639765069,
    0.0,
    0.0,
    0.0,
];

/// The continuous output's three coefficient vectors, each a combination
/// of the eight increments (row r: weights of u_1 … u_8).
const DENSE: [[f64; STAGES]; 3] = [
    [
        25.948786856663858,
        -2.5579724845846235,
        10.433815404888879,
        -2.3679251022685204,
        0.524948541321073,
        1.1241088310450404,
        0.4272876194431874,
        -0.17202221070155493,
    ],
    [
        -9.91568850695171,
        -0.9689944594115154,
        3.0438037242978453,
        -24.495224566215796,
        20.176138334709044,
        15.98066361424651,
        -6.789040303419874,
        -6.710236069923372,
    ],
    [
        11.419903575922262,
        2.8879645146136994,
        72.92137995996029,
        80.12511834622643,
        -52.072871366152654,
        -59.78993625266729,
        -0.15582684282751913,
        4.883087185713722,
    ],
];

/// Step-size controller (`rodas.f`'s defaults): the safety factor, and
/// h_new/h within [1/`MAX_SHRINK`, `MAX_GROWTH`].
const SAFE: f64 = 0.9;
/// h_new ≥ h / MAX_SHRINK.
const MAX_SHRINK: f64 = 5.0;
/// h_new ≤ h · MAX_GROWTH.
const MAX_GROWTH: f64 = 6.0;
/// The error estimate is O(h⁵).
const ERROR_EXPONENT: f64 = 0.2;

/// Component `i` of the continuous output at `s = (t − t_old)/h`:
/// `y_old·(1 − s) + s·(y_new + (1 − s)·(d₁ + s·(d₂ + s·d₃)))`, from the
/// coefficients `[y_old, y_new, d₁, d₂, d₃]`.
pub(crate) fn interpolate(c: &[f64], n: usize, i: usize, s: f64) -> f64 {
    let s1 = 1.0 - s;
    c[i] * s1 + s * (c[n + i] + s1 * (c[2 * n + i] + s * (c[3 * n + i] + s * c[4 * n + i])))
}

/// GMRES steps that fail in a row, each retried with half the step,
/// before the run factors its matrix instead.
const KRYLOV_RETRIES: usize = 3;

/// Below this many states `LinearSolver::Auto` keeps the factorisation:
/// the smallest grids measured (1800 and 2048 states, `bench --large`)
/// ran 2.5–4× faster with GMRES than with the sparse LU, and smaller ones
/// fill in less.
const KRYLOV_FROM: usize = 1000;

/// Whether RODAS5P solves `M`'s systems by GMRES: where asked (the checks
/// made sure the model has a generated Jacobian and no mass matrix), and
/// under `Auto` where a large pattern calls for a sparse LU (a grid no
/// renumbering bands, whose LU fills in).
pub(crate) fn krylov_for<M: Model>(choice: LinearSolver) -> bool {
    krylov_in::<M>(choice, &Structure::of(M::STATES, M::JACOBIAN.pattern()).0)
}

/// [`krylov_for`], the pattern's storage known.
fn krylov_in<M: Model>(choice: LinearSolver, structure: &Structure) -> bool {
    match choice {
        LinearSolver::Krylov => true,
        LinearSolver::Direct => false,
        LinearSolver::Auto => {
            M::SENSITIVITY_COLUMNS == 0
                && M::STATES >= KRYLOV_FROM
                && !has_mass_matrix::<M>()
                && matches!(structure, Structure::Sparse(_))
        }
    }
}

/// RODAS5P's matrices for `M` with Jacobian `pattern` (empty for a mass
/// matrix): the base block's for a model with sensitivities, GMRES where
/// [`krylov_for`] says, else the factorisation the pattern calls for.
fn linear_systems<M: Model>(pattern: &'static [(usize, usize)], choice: LinearSolver) -> Newton {
    let n = M::STATES;
    if M::SENSITIVITY_COLUMNS > 0 && !pattern.is_empty() {
        let columns = M::SENSITIVITY_COLUMNS;
        return Newton::for_sensitivities(n / (1 + columns), columns, pattern, Shifts::Real).0;
    }
    let (structure, _) = Structure::of(n, pattern);
    if krylov_in::<M>(choice, &structure) {
        Newton::krylov(n, pattern)
    } else {
        Newton::in_structure(n, structure, Shifts::Real)
    }
}

/// Integrates `model` from `t0` to `t1` with RODAS5P.
pub(crate) fn integrate<M: Model>(
    problem: Problem<'_, M>,
    solution: Solution,
) -> Result<Solution, Error> {
    integrate_watching(problem, None, solution).map(|(s, _)| s)
}

/// The model's ∂f/∂y, ∂f/∂t and right-hand side, counted.
struct Derivatives<'m, M> {
    model: &'m M,
    jacobian: DenseJacobian,
    /// ∂f/∂t at the step's start.
    dfdt: Vec<f64>,
    /// f at a later time (differencing ∂f/∂t where the model has none).
    shifted: Vec<f64>,
    counts: Counts,
}

impl<M: Model> Derivatives<'_, M> {
    fn rhs(&mut self, t: f64, y: &[f64], out: &mut [f64]) -> Result<(), EvalError> {
        self.counts.evals += 1;
        self.model.rhs(t, y, out)
    }

    /// J and ∂f/∂t at `(t, y)`, `f0 = f(t, y)`; ∂f/∂t by a forward
    /// difference (`rodas.f`'s increment) where the model has none, or
    /// where its value is not finite (a rate such as exp(−a/sin ωt), flat
    /// where sin ωt = 0 but 0·∞ there when written out).
    fn evaluate(&mut self, t: f64, y: &mut [f64], f0: &[f64]) -> Result<(), EvalError> {
        self.counts.jacobian_evals += 1;
        self.jacobian.evaluate(self.model, t, y, f0, &mut self.counts.evals)?;
        if M::JACOBIAN.has_time_derivative() {
            self.model.time_derivative(t, y, &mut self.dfdt)?;
            if self.dfdt.iter().all(|v| v.is_finite()) {
                return Ok(());
            }
        }
        let delta = (f64::EPSILON * t.abs().max(1e-5)).sqrt();
        self.counts.evals += 1;
        self.model.rhs(t + delta, y, &mut self.shifted)?;
        for ((d, s), f) in self.dfdt.iter_mut().zip(&self.shifted).zip(f0) {
            *d = (s - f) / delta;
        }
        Ok(())
    }
}

/// RODAS5P's work on one run: the derivatives, the linear systems, the
/// increments of a step and its dense output.
struct Rodas<'m, M> {
    d: Derivatives<'m, M>,
    mass: Mass,
    /// The Jacobian's pattern (empty for a mass-matrix model).
    pattern: &'static [(usize, usize)],
    newton: Newton,
    /// The transformed stages u_1 … u_8.
    u: Vec<Vec<f64>>,
    /// f at the step's start.
    f0: Vec<f64>,
    /// A stage's argument (the last stage's, after a step).
    arg: Vec<f64>,
    coupling: Vec<f64>,
    applied: Vec<f64>,
    /// The dense output's coefficients `[y_old, y_new, d₁, d₂, d₃]`.
    cont: Vec<f64>,
    /// GMRES solves that fell short in a row.
    unsolved_in_a_row: usize,
}

impl<'m, M: Model> Rodas<'m, M> {
    fn new(model: &'m M, choice: LinearSolver) -> Rodas<'m, M> {
        let n = M::STATES;
        let pattern = if has_mass_matrix::<M>() { &[] } else { M::JACOBIAN.pattern() };
        let newton = linear_systems::<M>(pattern, choice);
        let d = Derivatives {
            model,
            jacobian: DenseJacobian::with_matrix::<M>(newton.dense_jacobian()),
            dfdt: vec![0.0; n],
            shifted: vec![0.0; n],
            counts: Counts { linear_solver: newton.label(), ..Counts::default() },
        };
        Rodas {
            d,
            mass: Mass::of(model),
            pattern,
            newton,
            u: vec![vec![0.0; n]; STAGES],
            f0: vec![0.0; n],
            arg: vec![0.0; n],
            coupling: vec![0.0; n],
            applied: vec![0.0; n],
            cont: vec![0.0; 5 * n],
            unsolved_in_a_row: 0,
        }
    }

    /// Factors `M/(hγ) − J`, evaluating the dense Jacobian where the
    /// structure asks for it: `false` where the matrix is singular.
    fn factor(&mut self, t: f64, y: &mut [f64], h: f64) -> Result<bool, EvalError> {
        let shift = 1.0 / (h * GAMMA);
        let mass = self.mass.for_factorisation::<M>();
        let jacobian = &self.d.jacobian;
        let (matrix, values) = (&jacobian.matrix, jacobian.values());
        let mut factored =
            self.newton.factor(shift, (0.0, 0.0), mass, matrix, values, self.pattern);
        if factored == Factored::NeedsDenseJacobian {
            self.d.jacobian = DenseJacobian::new::<M>();
            self.d.evaluate(t, y, &self.f0)?;
            let jacobian = &self.d.jacobian;
            let (matrix, values) = (&jacobian.matrix, jacobian.values());
            factored = self.newton.factor(shift, (0.0, 0.0), mass, matrix, values, self.pattern);
            let counts = &mut self.d.counts;
            let after_gmres = counts.linear_solver.starts_with("GMRES");
            counts.linear_solver =
                if after_gmres { self.newton.after_gmres() } else { self.newton.label() };
        }
        Ok(factored == Factored::Yes)
    }

    /// The stages of a step of `h` from `(t, y)`: u_i = (M/(hγ) − J)⁻¹
    /// (f(t + c_i h, arg_i) + h γ_i ∂f/∂t + M Σ_j (C_ij/h) u_j). `false`
    /// where GMRES fell short of a solve.
    fn stages(&mut self, t: f64, h: f64, y: &[f64]) -> Result<bool, (f64, EvalError)> {
        // Slices of the model's constant length: with the vectors' lengths
        // unknown here, every copy and sum became a call or a loop, and
        // RODAS5P took 17 % more instructions a step on Lorenz (3 states).
        let n = M::STATES;
        let Rodas { d, mass, newton, u, f0, arg, coupling, applied, .. } = self;
        let (arg, coupling, applied) = (&mut arg[..n], &mut coupling[..n], &mut applied[..n]);
        let (y, f0, diagonal, dense) = (&y[..n], &f0[..n], &mass.diagonal[..n], &mass.dense[..]);
        for i in 0..STAGES {
            let (done, rest) = u.split_at_mut(i);
            let ui = &mut rest[0][..n];
            if i == 0 {
                arg.copy_from_slice(y);
                ui.copy_from_slice(f0);
            } else {
                if i <= 5 {
                    arg.copy_from_slice(y);
                    for (uj, &a) in done.iter().zip(&A[i - 1]) {
                        arg.iter_mut().zip(&uj[..n]).for_each(|(x, v)| *x += a * v);
                    }
                } else {
                    arg.iter_mut().zip(&done[i - 1][..n]).for_each(|(x, v)| *x += v);
                }
                let ti = t + STAGE_TIME[i] * h;
                d.rhs(ti, arg, ui).map_err(|cause| (ti, cause))?;
                coupling.fill(0.0);
                for (uj, &c) in done.iter().zip(&C[i - 1]) {
                    let c_over_h = c / h;
                    coupling.iter_mut().zip(&uj[..n]).for_each(|(x, v)| *x += c_over_h * v);
                }
                if dense.is_empty() {
                    for ((f, c), m) in ui.iter_mut().zip(&*coupling).zip(diagonal) {
                        *f += m * c;
                    }
                } else {
                    apply_mass(dense, coupling, applied);
                    ui.iter_mut().zip(&*applied).for_each(|(f, c)| *f += c);
                }
            }
            if TIME_WEIGHT[i] != 0.0 {
                let w = h * TIME_WEIGHT[i];
                ui.iter_mut().zip(&d.dfdt[..n]).for_each(|(f, g)| *f += w * g);
            }
            if !newton.solve_real(ui) {
                return Ok(false);
            }
        }
        Ok(true)
    }

    /// After GMRES fell short: `true` where it has done so often enough in
    /// a row that the rest of the run factors the matrix instead (a
    /// shorter step brings the matrix nearer its diagonal, where the
    /// preconditioner is better; the caller halves it otherwise).
    fn after_unsolved(&mut self, t: f64, y: &mut [f64]) -> Result<bool, EvalError> {
        self.unsolved_in_a_row += 1;
        if self.unsolved_in_a_row < KRYLOV_RETRIES {
            return Ok(false);
        }
        self.newton = Newton::for_pattern(M::STATES, self.pattern, Shifts::Real).0;
        self.d.counts.linear_solver = self.newton.after_gmres();
        self.unsolved_in_a_row = 0;
        if self.newton.dense_jacobian() {
            // GMRES kept the Jacobian's values alone.
            self.d.jacobian = DenseJacobian::new::<M>();
            self.d.evaluate(t, y, &self.f0)?;
        }
        Ok(true)
    }

    /// The scaled error of the step from `y` (stage 8's increment, over
    /// the first `n_error` states), or `None` where the new solution
    /// overflows (an exponential taken too far by the linearisation).
    fn error(&self, y: &[f64], (rtol, atol): (f64, f64), n_error: usize) -> Option<f64> {
        let n = M::STATES;
        let estimate = &self.u[STAGES - 1][..n];
        let mut overflow = false;
        let err = (estimate
            .iter()
            .zip(&self.arg[..n])
            .zip(&y[..n])
            .enumerate()
            .map(|(i, ((e, new), old))| {
                overflow |= !(new + e).is_finite();
                let scale = atol + rtol * old.abs().max((new + e).abs());
                if i < n_error {
                    (e / scale).powi(2)
                } else {
                    0.0
                }
            })
            .sum::<f64>()
            / n_error as f64)
            .sqrt()
            .max(1e-10);
        (!overflow && err.is_finite()).then_some(err)
    }

    /// Takes the step: `y` becomes stage 8's argument plus its increment,
    /// and, where the run keeps it, the dense output its coefficients.
    fn advance(&mut self, y: &mut [f64], keep_dense: bool) {
        // Slices of the model's constant length, as in `stages`.
        let n = M::STATES;
        let (y, u, arg, cont) = (&mut y[..n], &self.u[..], &self.arg[..n], &mut self.cont[..5 * n]);
        if keep_dense {
            cont[..n].copy_from_slice(y);
        }
        for ((yi, a), e) in y.iter_mut().zip(arg).zip(&u[STAGES - 1][..n]) {
            *yi = a + e;
        }
        if keep_dense {
            cont[n..2 * n].copy_from_slice(y);
            for (r, weights) in DENSE.iter().enumerate() {
                let out = &mut cont[(2 + r) * n..(3 + r) * n];
                out.fill(0.0);
                for (uj, &wj) in u.iter().zip(weights) {
                    out.iter_mut().zip(&uj[..n]).for_each(|(o, v)| *o += wj * v);
                }
            }
        }
    }
}

/// Integrates `model` from `t0` to `t1` with RODAS5P, stopping early with
/// [`Finish::NonStiffAt`] where `watch` finds the problem no longer stiff
/// (h·ρ(J), ρ by the power iteration on each new Jacobian).
pub(crate) fn integrate_watching<M: Model>(
    problem: Problem<'_, M>,
    watch: Option<NonStiffWatch>,
    solution: Solution,
) -> Result<(Solution, Finish), Error> {
    let dense = DenseOutput { width: 5, interpolate };
    let mut run = Driver::new(&problem, solution, Some(dense), 1).watching(watch);
    let Problem { model, t0, y0: start, options, .. } = problem;
    let tolerances = (options.rtol, options.atol);
    // The error test's states (the model's own, where sensitivities are
    // left out of it).
    let n_error = crate::methods::error_states::<M>(options);
    let mut r = Rodas::new(model, options.linear_solver);
    let mut y = start.to_vec();
    if t0 == run.t1 {
        return Ok((run.finish(&r.d.counts), Finish::Done));
    }
    if let Err(cause) = r.d.rhs(t0, &y, &mut r.f0) {
        return Err(run.evaluation_failed(t0, cause, &r.d.counts));
    }

    let mut t = t0;
    let mut h = options.initial_step.unwrap_or(1e-6).abs().min(run.hmax) * run.direction;
    let mut last = false;
    if run.reaches_end(t, h * 1.0001) {
        h = run.t1 - t;
        last = true;
    }
    let bounds = (1.0 / MAX_GROWTH, MAX_SHRINK);
    let mut control = Predictive::new(ERROR_EXPONENT, SAFE, bounds, h);
    let (mut reject, mut fresh_jacobian, mut singular) = (false, true, 0usize);
    // ρ(J) at the last Jacobian.
    let mut rho = f64::INFINITY;
    loop {
        if fresh_jacobian {
            if let Err(cause) = r.d.evaluate(t, &mut y, &r.f0) {
                return Err(run.evaluation_failed(t, cause, &r.d.counts));
            }
            if watch.is_some() {
                rho = r.d.jacobian.spectral_radius::<M>();
            }
            fresh_jacobian = false;
        }
        run.check_steps(t, &r.d.counts)?;
        if run.step_too_small(t, h) {
            return Err(run.fail(&r.d.counts, |partial| Error::StepSizeUnderflow {
                t,
                h,
                partial,
            }));
        }
        match r.factor(t, &mut y, h) {
            Err(cause) => return Err(run.evaluation_failed(t, cause, &r.d.counts)),
            Ok(true) => {}
            Ok(false) => {
                singular += 1;
                if singular >= 5 {
                    let counts = &r.d.counts;
                    return Err(run.fail(counts, |partial| Error::SingularMatrix {
                        t,
                        h,
                        partial,
                    }));
                }
                (h, reject, last) = (h * 0.5, true, false);
                continue;
            }
        }
        r.newton.set_error_weights(&y, tolerances.0, tolerances.1);
        let solved = r.stages(t, h, &y);
        r.d.counts.linear_iterations =
            r.d.counts.linear_iterations.max(r.newton.linear_iterations());
        match solved {
            Err((ti, cause)) => return Err(run.evaluation_failed(ti, cause, &r.d.counts)),
            Ok(true) => r.unsolved_in_a_row = 0,
            Ok(false) => {
                match r.after_unsolved(t, &mut y) {
                    Err(cause) => return Err(run.evaluation_failed(t, cause, &r.d.counts)),
                    Ok(true) => {}
                    Ok(false) => h *= 0.5,
                }
                (reject, last) = (true, false);
                run.rejected += usize::from(run.accepted > 0);
                continue;
            }
        }
        // A step that overflows is retried shorter, as one that fails the test.
        let Some(err) = r.error(&y, tolerances, n_error) else {
            (h, reject, last) = (h * 0.5, true, false);
            run.rejected += usize::from(run.accepted > 0);
            continue;
        };
        let quot = (err.powf(ERROR_EXPONENT) / SAFE).clamp(1.0 / MAX_GROWTH, MAX_SHRINK);
        if err > 1.0 {
            // Rejected: the same Jacobian, a smaller step.
            run.rejected += usize::from(run.accepted > 0);
            (h, reject, last) = (h / quot, true, false);
            continue;
        }
        singular = 0;
        let quot = control.accepted(h, err, quot, run.accepted > 0);
        r.advance(&mut y, run.keep_dense());
        t = if last { run.t1 } else { t + h };
        run.check_finite(t, &y, &r.d.counts)?;
        run.project(t, &mut y, &r.d.counts)?;
        if run.record(t, &y, &r.cont, &r.d.counts)? || last {
            break;
        }
        if let Err(cause) = r.d.rhs(t, &y, &mut r.f0) {
            return Err(run.evaluation_failed(t, cause, &r.d.counts));
        }
        let h_new = run.next_step(h / quot, h, reject);
        reject = false;
        if run.calm(h.abs() * rho) {
            return Ok((run.finish(&r.d.counts), Finish::NonStiffAt { t, h: h_new }));
        }
        h = h_new;
        // A remainder within rounding of t1 joins this step.
        if run.reaches_end(t, h * 1.0001) {
            h = run.t1 - t;
            last = true;
        }
        fresh_jacobian = true;
    }
    Ok((run.finish(&r.d.counts), Finish::Done))
}

#[cfg(test)]
mod tests {
    use crate::info::{EvalError, ModelInfo};
    use crate::model::Model;
    use crate::options::{Method, Options};

    /// y' = −1000 (y − cos t) − sin t, y(0) = 1: y = cos t. Written by
    /// hand, so it has neither a Jacobian nor ∂f/∂t: both are differenced.
    /// (Its `impl Model` has the shape of every hand-written test model's,
    /// RADAU5's GGL pendulum among them: the shape is the trait's.)
    #[derive(Clone)]
    struct ForcedDecay;

    impl Model for ForcedDecay {
        const STATES: usize = 1;
        type State = [f64; 1];
        const INDEX: usize = 0;
        const INFO: ModelInfo = ModelInfo::bare("ForcedDecay", &["y"], 1);
        fn initial_state(&self, y: &mut [f64]) {
            y[0] = 1.0;
        }
        fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), EvalError> {
            dy[0] = -1000.0 * (y[0] - t.cos()) - t.sin();
            Ok(())
        }
    }

    #[test]
    fn a_model_without_derivatives_has_them_differenced() {
        for tol in [1e-5, 1e-8] {
            let opts = Options::new().method(Method::Rodas5P).tolerance(tol);
            let sol = crate::run::simulate(&ForcedDecay, 0.0, 2.0, &opts).unwrap();
            let e = (sol.last("y").unwrap() - 2f64.cos()).abs();
            assert!(e <= 10.0 * tol, "tol {tol:e}: error {e:e}");
        }
    }
}
