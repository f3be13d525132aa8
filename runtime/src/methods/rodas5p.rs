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
use crate::methods::stiffness::{Finish, NonStiffWatch};
use crate::methods::Problem;
use crate::model::{has_mass_matrix, Model};
use crate::options::LinearSolver;
use crate::solution::Solution;
use crate::step::events::{after_accepted_step, EventWatch};
use crate::step::jacobian::DenseJacobian;
use crate::step::projection::{project_onto_constraints, Projector};

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

/// What the run has counted, for the statistics of its solution.
#[derive(Default)]
struct Counts {
    accepted: usize,
    rejected: usize,
    evals: usize,
    jacobian_evals: usize,
    /// How the linear systems were solved, and GMRES's iterations.
    linear_solver: &'static str,
    linear_iterations: usize,
}

impl Counts {
    fn record(&self, solution: &mut Solution) {
        let stats = solution.stats_mut();
        stats.steps += self.accepted;
        stats.rejected += self.rejected;
        stats.rhs_evals += self.evals;
        stats.jacobian_evals += self.jacobian_evals;
        stats.linear_solver = self.linear_solver;
        stats.linear_iterations += self.linear_iterations;
    }
}

/// The model's ∂f/∂y, ∂f/∂t and right-hand side, counted.
struct Derivatives<'m, M> {
    model: &'m M,
    jacobian: DenseJacobian,
    /// ∂f/∂t at the step's start.
    dfdt: Vec<f64>,
    /// f at a later time (differencing ∂f/∂t where the model has none).
    shifted: Vec<f64>,
}

impl<M: Model> Derivatives<'_, M> {
    fn rhs(
        &self,
        counts: &mut Counts,
        t: f64,
        y: &[f64],
        out: &mut [f64],
    ) -> Result<(), EvalError> {
        counts.evals += 1;
        self.model.rhs(t, y, out)
    }

    /// J and ∂f/∂t at `(t, y)`, `f0 = f(t, y)`; ∂f/∂t by a forward
    /// difference (`rodas.f`'s increment) where the model has none, or
    /// where its value is not finite (a rate such as exp(−a/sin ωt), flat
    /// where sin ωt = 0 but 0·∞ there when written out).
    fn evaluate(
        &mut self,
        counts: &mut Counts,
        t: f64,
        y: &mut [f64],
        f0: &[f64],
    ) -> Result<(), EvalError> {
        counts.jacobian_evals += 1;
        self.jacobian.evaluate(self.model, t, y, f0, &mut counts.evals)?;
        if M::JACOBIAN.has_time_derivative() {
            self.model.time_derivative(t, y, &mut self.dfdt)?;
            if self.dfdt.iter().all(|v| v.is_finite()) {
                return Ok(());
            }
        }
        let delta = (f64::EPSILON * t.abs().max(1e-5)).sqrt();
        counts.evals += 1;
        self.model.rhs(t + delta, y, &mut self.shifted)?;
        for ((d, s), f) in self.dfdt.iter_mut().zip(&self.shifted).zip(f0) {
            *d = (s - f) / delta;
        }
        Ok(())
    }
}

/// Integrates `model` from `t0` to `t1` with RODAS5P, stopping early with
/// [`Finish::NonStiffAt`] where `watch` finds the problem no longer stiff
/// (h·ρ(J), ρ by the power iteration on each new Jacobian).
pub(crate) fn integrate_watching<M: Model>(
    problem: Problem<'_, M>,
    watch: Option<NonStiffWatch>,
    mut solution: Solution,
) -> Result<(Solution, Finish), Error> {
    // One function, as rodas.f's step loop is: the stages, the error test
    // and the step control share the factored matrix, the increments and h.
    let Problem { model, t0, t1, y0: start, options } = problem;
    let n = M::STATES;
    let (rtol, atol) = (options.rtol, options.atol);
    // The error test's states (the model's own, where sensitivities are
    // left out of it).
    let n_error = crate::methods::error_states::<M>(options);
    let direction = if t1 >= t0 { 1.0 } else { -1.0 };
    let hmax = options.max_step.unwrap_or((t1 - t0).abs()).min((t1 - t0).abs());

    // A mass matrix: its diagonal, or the dense matrix (`mass_matrix`).
    let mass: Vec<f64> =
        if M::MASS.diagonal().len() == n { M::MASS.diagonal().to_vec() } else { vec![1.0; n] };
    let mass_matrix = if M::MASS.pattern().is_empty() {
        Vec::new()
    } else {
        crate::model::dense_mass_matrix(model)
    };
    let pattern = if has_mass_matrix::<M>() { &[] } else { M::JACOBIAN.pattern() };
    let mut newton = linear_systems::<M>(pattern, options.linear_solver);
    let mut d = Derivatives {
        model,
        jacobian: DenseJacobian::with_matrix::<M>(newton.dense_jacobian()),
        dfdt: vec![0.0; n],
        shifted: vec![0.0; n],
    };
    let mut counts = Counts { linear_solver: newton.label(), ..Counts::default() };
    let mut unsolved_in_a_row = 0;
    let mut u: Vec<Vec<f64>> = vec![vec![0.0; n]; STAGES];
    let (mut y, mut f0) = (start.to_vec(), vec![0.0; n]);
    let (mut arg, mut coupling, mut applied) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let mut cont = vec![0.0; 5 * n];
    let mut events = EventWatch::new(model, t0, start, 1);
    let mut projector = Projector::new(model);
    let keep_dense = options.dense_output || events.is_some();
    if keep_dense {
        solution.set_interpolant(5, interpolate);
    }
    if t0 == t1 {
        return Ok((solution, Finish::Done));
    }
    let fail = |mut solution: Solution, counts: &Counts, t: f64, cause: EvalError| {
        counts.record(&mut solution);
        Err(Error::Evaluation { t, cause, partial: Box::new(solution) })
    };
    if let Err(cause) = d.rhs(&mut counts, t0, &y, &mut f0) {
        return fail(solution, &counts, t0, cause);
    }

    let mut t = t0;
    let mut h = options.initial_step.unwrap_or(1e-6).abs().min(hmax) * direction;
    let mut last = false;
    if (t + h * 1.0001 - t1) * direction >= 0.0 {
        h = t1 - t;
        last = true;
    }
    let (mut h_acc, mut err_acc) = (h, 1e-2);
    let (mut reject, mut fresh_jacobian, mut singular) = (false, true, 0usize);
    // ρ(J) at the last Jacobian, and the steps in a row with h·ρ below the watch's bound.
    let (mut rho, mut calm) = (f64::INFINITY, 0usize);

    loop {
        if fresh_jacobian {
            if let Err(cause) = d.evaluate(&mut counts, t, &mut y, &f0) {
                return fail(solution, &counts, t, cause);
            }
            if watch.is_some() {
                rho = d.jacobian.spectral_radius::<M>();
            }
            fresh_jacobian = false;
        }
        if counts.accepted + counts.rejected >= options.max_steps {
            counts.record(&mut solution);
            let max_steps = options.max_steps;
            return Err(Error::MaxSteps { t, max_steps, partial: Box::new(solution) });
        }
        if 0.1 * h.abs() <= t.abs().max(1e-300) * f64::EPSILON || h.abs() < options.min_step {
            counts.record(&mut solution);
            return Err(Error::StepSizeUnderflow { t, h, partial: Box::new(solution) });
        }
        let shift = 1.0 / (h * GAMMA);
        let factor_mass =
            if mass_matrix.is_empty() { M::MASS.diagonal() } else { &mass_matrix[..] };
        let mut factored = newton.factor(
            shift,
            (0.0, 0.0),
            factor_mass,
            &d.jacobian.matrix,
            d.jacobian.values(),
            pattern,
        );
        if factored == Factored::NeedsDenseJacobian {
            d.jacobian = DenseJacobian::new::<M>();
            if let Err(cause) = d.evaluate(&mut counts, t, &mut y, &f0) {
                return fail(solution, &counts, t, cause);
            }
            factored = newton.factor(
                shift,
                (0.0, 0.0),
                factor_mass,
                &d.jacobian.matrix,
                d.jacobian.values(),
                pattern,
            );
            let after_gmres = counts.linear_solver.starts_with("GMRES");
            counts.linear_solver = if after_gmres { newton.after_gmres() } else { newton.label() };
        }
        if factored != Factored::Yes {
            singular += 1;
            if singular >= 5 {
                counts.record(&mut solution);
                return Err(Error::SingularMatrix { t, h, partial: Box::new(solution) });
            }
            (h, reject, last) = (h * 0.5, true, false);
            continue;
        }

        newton.set_error_weights(&y, rtol, atol);
        let mut unsolved = false;
        // The stages: u_i = (M/(hγ) − J)⁻¹ (f(t + c_i h, arg_i) + h γ_i ∂f/∂t
        // + M Σ_j (C_ij/h) u_j).
        for i in 0..STAGES {
            let (done, rest) = u.split_at_mut(i);
            let ui = &mut rest[0];
            if i == 0 {
                arg.copy_from_slice(&y);
                ui.copy_from_slice(&f0);
            } else {
                if i <= 5 {
                    arg.copy_from_slice(&y);
                    for (uj, &a) in done.iter().zip(&A[i - 1]) {
                        arg.iter_mut().zip(uj).for_each(|(x, v)| *x += a * v);
                    }
                } else {
                    arg.iter_mut().zip(&done[i - 1]).for_each(|(x, v)| *x += v);
                }
                let ti = t + STAGE_TIME[i] * h;
                if let Err(cause) = d.rhs(&mut counts, ti, &arg, ui) {
                    return fail(solution, &counts, ti, cause);
                }
                coupling.fill(0.0);
                for (uj, &c) in done.iter().zip(&C[i - 1]) {
                    let c_over_h = c / h;
                    coupling.iter_mut().zip(uj).for_each(|(x, v)| *x += c_over_h * v);
                }
                if mass_matrix.is_empty() {
                    for ((f, c), m) in ui.iter_mut().zip(&coupling).zip(&mass) {
                        *f += m * c;
                    }
                } else {
                    apply_mass(&mass_matrix, &coupling, &mut applied);
                    ui.iter_mut().zip(&applied).for_each(|(f, c)| *f += c);
                }
            }
            if TIME_WEIGHT[i] != 0.0 {
                let w = h * TIME_WEIGHT[i];
                ui.iter_mut().zip(&d.dfdt).for_each(|(f, g)| *f += w * g);
            }
            if !newton.solve_real(ui) {
                unsolved = true;
                break;
            }
        }
        counts.linear_iterations = counts.linear_iterations.max(newton.linear_iterations());
        if unsolved {
            // GMRES fell short: a shorter step brings the matrix nearer
            // its diagonal, where the preconditioner is better; where that
            // does not help, the rest of the run factors the matrix.
            unsolved_in_a_row += 1;
            if unsolved_in_a_row >= KRYLOV_RETRIES {
                newton = Newton::for_pattern(n, pattern, Shifts::Real).0;
                counts.linear_solver = newton.after_gmres();
                unsolved_in_a_row = 0;
                if newton.dense_jacobian() {
                    // GMRES kept the Jacobian's values alone.
                    d.jacobian = DenseJacobian::new::<M>();
                    if let Err(cause) = d.evaluate(&mut counts, t, &mut y, &f0) {
                        return fail(solution, &counts, t, cause);
                    }
                }
            } else {
                h *= 0.5;
            }
            (reject, last) = (true, false);
            counts.rejected += usize::from(counts.accepted > 0);
            continue;
        }
        unsolved_in_a_row = 0;
        // arg is stage 8's; the solution adds its increment, the error
        // estimate. A step that overflows (an exponential taken too far by
        // the linearisation) is retried shorter, as one that fails the test.
        let estimate = &u[STAGES - 1];
        let mut overflow = false;
        let err = (estimate
            .iter()
            .zip(&arg)
            .zip(&y)
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
        if overflow || !err.is_finite() {
            (h, reject, last) = (h * 0.5, true, false);
            counts.rejected += usize::from(counts.accepted > 0);
            continue;
        }
        let mut quot = (err.powf(ERROR_EXPONENT) / SAFE).clamp(1.0 / MAX_GROWTH, MAX_SHRINK);
        if err <= 1.0 {
            counts.accepted += 1;
            singular = 0;
            if counts.accepted > 1 {
                // Gustafsson's predictive controller.
                let predicted = ((h_acc / h) * (err * err / err_acc).powf(ERROR_EXPONENT) / SAFE)
                    .clamp(1.0 / MAX_GROWTH, MAX_SHRINK);
                quot = quot.max(predicted);
            }
            (h_acc, err_acc) = (h, err.max(1e-2));
            if keep_dense {
                cont[..n].copy_from_slice(&y);
            }
            for ((yi, a), e) in y.iter_mut().zip(&arg).zip(&u[STAGES - 1]) {
                *yi = a + e;
            }
            if keep_dense {
                cont[n..2 * n].copy_from_slice(&y);
                for (r, weights) in DENSE.iter().enumerate() {
                    let out = &mut cont[(2 + r) * n..(3 + r) * n];
                    out.fill(0.0);
                    for (uj, &wj) in u.iter().zip(weights) {
                        out.iter_mut().zip(uj).for_each(|(o, v)| *o += wj * v);
                    }
                }
            }
            t = if last { t1 } else { t + h };
            if let Some(i) = y.iter().position(|v| !v.is_finite()) {
                counts.record(&mut solution);
                let variable = M::INFO.states[i];
                return Err(Error::NonFinite { t, variable, partial: Box::new(solution) });
            }
            project_onto_constraints!(projector, t, &mut y, solution);
            if keep_dense {
                solution.push_dense(t, &y, &cont);
            } else {
                solution.push(t, &y);
            }
            after_accepted_step!(events, solution);
            if last {
                break;
            }
            if let Err(cause) = d.rhs(&mut counts, t, &y, &mut f0) {
                return fail(solution, &counts, t, cause);
            }
            let mut h_new = direction * (h / quot).abs().min(hmax);
            if reject {
                h_new = direction * h_new.abs().min(h.abs());
            }
            reject = false;
            if let Some(watch) = watch {
                calm = if h.abs() * rho < watch.below { calm + 1 } else { 0 };
                if calm >= watch.confirmations {
                    counts.record(&mut solution);
                    return Ok((solution, Finish::NonStiffAt { t, h: h_new }));
                }
            }
            h = h_new;
            // A remainder within rounding of t1 joins this step.
            if (t + h * 1.0001 - t1) * direction >= 0.0 {
                h = t1 - t;
                last = true;
            }
            fresh_jacobian = true;
        } else {
            // Rejected: the same Jacobian, a smaller step.
            counts.rejected += usize::from(counts.accepted > 0);
            (h, reject, last) = (h / quot, true, false);
        }
    }
    counts.record(&mut solution);
    Ok((solution, Finish::Done))
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
