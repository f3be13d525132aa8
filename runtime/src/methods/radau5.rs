//! RADAU5: the 3-stage Radau IIA collocation method of order 5 for stiff
//! problems, as in Hairer & Wanner's code `radau5.f` (Hairer, Wanner,
//! *Solving ODEs II*, §IV.8): simplified Newton on the system transformed by
//! the eigenvectors of A⁻¹ (one real and one complex linear system of size
//! n), Jacobian and factorisation reuse across steps, the embedded error
//! estimate filtered through (γ/h − J)⁻¹, Gustafsson's predictive step
//! control, and continuous output from the collocation polynomial. A model
//! with sensitivity columns is iterated staggered: its own states to
//! convergence, then the columns, linear once the states are fixed, with
//! the same LU.

// Published coefficients are kept digit for digit as printed.
#![allow(clippy::excessive_precision)]

use crate::error::Error;
use crate::info::EvalError;
use crate::linalg::apply_mass;
use crate::linalg::newton::{Factored, Newton, Shifts, Structure};
use crate::methods::stiffness::{Finish, NonStiffWatch};
use crate::methods::Problem;
use crate::model::{has_mass_matrix, Model};
use crate::solution::Solution;
use crate::step::events::{after_accepted_step, EventWatch};
use crate::step::jacobian::DenseJacobian;
use crate::step::projection::{project_onto_constraints, Projector};

const SQ6: f64 = 2.449_489_742_783_178;
const C1: f64 = (4.0 - SQ6) / 10.0;
const C2: f64 = (4.0 + SQ6) / 10.0;
const C1M1: f64 = C1 - 1.0;
const C2M1: f64 = C2 - 1.0;
const C1MC2: f64 = C1 - C2;
const DD1: f64 = -(13.0 + 7.0 * SQ6) / 3.0;
const DD2: f64 = (-13.0 + 7.0 * SQ6) / 3.0;
const DD3: f64 = -1.0 / 3.0;
/// T and T⁻¹: A⁻¹ = T diag(γ, [α −β; β α]) T⁻¹ (values of `radau5.f`).
const T: [[f64; 3]; 3] = [
    [9.1232394870892942792e-02, -0.14125529502095420843, -3.0029194105147424492e-02],
    [0.24171793270710701896, 0.20412935229379993199, 0.38294211275726193779],
    [0.96604818261509293619, 1.0, 0.0],
];
const TI: [[f64; 3]; 3] = [
    [4.3255798900631553510, 0.33919925181580986954, 0.54177053993587487119],
    [-4.1787185915519047273, -0.32768282076106238708, 0.47662355450055045196],
    [-0.50287263494578687595, 2.5719269498556054292, -0.59603920482822492497],
];

/// Eigenvalues of A⁻¹: the real γ and the complex pair α ± iβ.
fn eigenvalues() -> (f64, f64, f64) {
    let (c81, c9) = (81f64.cbrt(), 9f64.cbrt());
    let u1 = (6.0 + c81 - c9) / 30.0;
    let alpha = (12.0 - c81 + c9) / 60.0;
    let beta = (c81 + c9) * 3f64.sqrt() / 60.0;
    let cno = alpha * alpha + beta * beta;
    (1.0 / u1, alpha / cno, beta / cno)
}

/// Controller constants of `radau5.f` (its defaults).
const NIT: usize = 7;
const SAFE: f64 = 0.9;
const FACL: f64 = 5.0;
const FACR: f64 = 1.0 / 8.0;

/// When RADAU5 keeps its Jacobian and its LU (`radau5.f`'s WORK(3),
/// WORK(5) and WORK(6)): the Jacobian while Newton's contraction θ stays
/// below `thet`, the LU too while h_new/h stays in `quot1..=quot2`.
#[derive(Clone, Copy)]
struct Reuse {
    thet: f64,
    quot1: f64,
    quot2: f64,
}

impl Reuse {
    /// Hairer's defaults for small systems (0.001, 1, 1.2) and, where one
    /// real factorisation takes over [`COSTLY_FACTORISATION`] operations,
    /// the values his documentation recommends for large ones (0.1 "when
    /// Jacobian evaluations are costly", as each one brings a
    /// factorisation; 0.99 and 2 "for large systems").
    fn for_factorisation(operations: f64) -> Reuse {
        if operations > COSTLY_FACTORISATION {
            Reuse { thet: 0.1, quot1: 0.99, quot2: 2.0 }
        } else {
            Reuse { thet: 0.001, quot1: 1.0, quot2: 1.2 }
        }
    }
}

/// Operations of one real factorisation above which it outweighs the
/// extra Newton iterations of a kept LU (a dense system of some 110
/// states, a sparse 2-D grid of a thousand).
const COSTLY_FACTORISATION: f64 = 1e6;

/// Component `i` of the collocation polynomial at `s = (t - t_old)/h`.
pub(crate) fn interpolate(c: &[f64], n: usize, i: usize, s: f64) -> f64 {
    // radau5's CONTR5 measures s from the new point: s - 1 ∈ [-1, 0].
    let s = s - 1.0;
    c[i] + s * (c[n + i] + (s - C2M1) * (c[2 * n + i] + (s - C1M1) * c[3 * n + i]))
}

/// What needs redoing before the next step: everything, the factorisation
/// only, or nothing (same h, same LU).
#[derive(Clone, Copy, PartialEq)]
enum Refresh {
    Jacobian,
    Factorisation,
    Nothing,
}

/// The floating-point operations of one factorisation of RADAU5's two
/// Newton matrices (the real one and the complex one, which costs four
/// real ones) and of one solve with both, for `M`'s structure: banded
/// where [`Newton::for_pattern`] bands it, dense otherwise.
pub(crate) fn newton_operations<M: Model>() -> (f64, f64) {
    let n = M::STATES as f64;
    let pattern = if M::MASS.diagonal().is_empty() { M::JACOBIAN.pattern() } else { &[] };
    match Structure::of(M::STATES, pattern) {
        (Structure::Band(ordering), _) => {
            let (kl, ku) = (ordering.lower as f64, ordering.upper as f64);
            (5.0 * 2.0 * n * kl * (kl + ku + 1.0), 5.0 * 2.0 * n * (2.0 * kl + ku + 1.0))
        }
        (Structure::Sparse(sparse), operations) => {
            (5.0 * operations, 5.0 * 2.0 * sparse.entries() as f64)
        }
        (Structure::Dense, _) => (5.0 * 2.0 / 3.0 * n * n * n, 5.0 * 2.0 * n * n),
    }
}

struct Work<'m, M> {
    model: &'m M,
    evals: usize,
    jacobian_evals: usize,
    jacobian: DenseJacobian,
    /// How the Newton matrices are solved (`Newton::label`).
    linear_solver: &'static str,
}

impl<M: Model> Work<'_, M> {
    fn rhs(&mut self, t: f64, y: &[f64], out: &mut [f64]) -> Result<(), EvalError> {
        self.evals += 1;
        self.model.rhs(t, y, out)
    }

    /// The model's own derivatives alone (`Model::own_rhs`).
    fn own_rhs(&mut self, t: f64, y: &[f64], out: &mut [f64]) -> Result<(), EvalError> {
        self.evals += 1;
        self.model.own_rhs(t, y, out).unwrap_or(Err(EvalError::JacobianUnavailable))
    }

    /// The dense Jacobian at `(t, y)`, `f0 = f(t, y)`.
    fn evaluate_jacobian(&mut self, t: f64, y: &mut [f64], f0: &[f64]) -> Result<(), EvalError> {
        self.jacobian_evals += 1;
        self.jacobian.evaluate(self.model, t, y, f0, &mut self.evals)
    }
}

fn rms(values: [&[f64]; 3], scale: &[f64]) -> f64 {
    let n = scale.len();
    let sum: f64 =
        values.iter().map(|v| v.iter().zip(scale).map(|(x, s)| (x / s).powi(2)).sum::<f64>()).sum();
    (sum / (3 * n) as f64).sqrt()
}

/// Integrates `model` from `t0` to `t1` with RADAU5.
pub(crate) fn integrate<M: Model>(
    problem: Problem<'_, M>,
    solution: Solution,
) -> Result<Solution, Error> {
    integrate_watching(problem, None, solution).map(|(s, _)| s)
}

/// Integrates `model` from `t0` to `t1` with RADAU5, stopping early with
/// [`Finish::NonStiffAt`] where `watch` finds the problem no longer stiff
/// (h·ρ(J), ρ by the power iteration on each new Jacobian).
pub(crate) fn integrate_watching<M: Model>(
    problem: Problem<'_, M>,
    watch: Option<NonStiffWatch>,
    solution: Solution,
) -> Result<(Solution, Finish), Error> {
    let Problem { model, t0, t1, y0, options } = problem;
    step_loop(model, t0, t1, y0, options, watch, solution)
}

/// The step loop of [`integrate_watching`], its inputs as separate
/// arguments, as the explicit pairs' (`adaptive::integrate_from` says why).
#[allow(clippy::too_many_arguments)]
fn step_loop<M: Model>(
    model: &M,
    t0: f64,
    t1: f64,
    start: &[f64],
    options: &crate::options::Options,
    watch: Option<NonStiffWatch>,
    mut solution: Solution,
) -> Result<(Solution, Finish), Error> {
    // One function, as radau5.f's step loop is: the Newton iteration, the error estimate and
    // the step-size control share its state (the LU, the last step's stages, θ), and splitting
    // them would pass a dozen values each way.
    let n = M::STATES;
    // radau5.f tightens the user's tolerances: rtol' = 0.1 rtol^(2/3).
    let rtol = 0.1 * options.rtol.max(1e-15).powf(2.0 / 3.0);
    let atol = rtol * options.atol / options.rtol.max(1e-15);
    let fnewt = (10.0 * f64::EPSILON / rtol).max(0.03f64.min(rtol.sqrt()));
    let (gamma, alpha, beta) = eigenvalues();
    let direction = if t1 >= t0 { 1.0 } else { -1.0 };
    let hmax = options.max_step.unwrap_or((t1 - t0).abs()).min((t1 - t0).abs());

    // A singular mass matrix (Hairer's IMAS = 1): diagonal, or general and
    // dense (`mass_matrix`, applied by `apply_mass`); dense Newton either way.
    let mass: Vec<f64> =
        if M::MASS.diagonal().len() == n { M::MASS.diagonal().to_vec() } else { vec![1.0; n] };
    let mass_matrix = if M::MASS.pattern().is_empty() {
        Vec::new()
    } else {
        crate::model::dense_mass_matrix(model)
    };
    let pattern = if has_mass_matrix::<M>() { &[] } else { M::JACOBIAN.pattern() };
    let (mut newton, factor_operations) = if M::SENSITIVITY_COLUMNS > 0 && !pattern.is_empty() {
        let columns = M::SENSITIVITY_COLUMNS;
        Newton::for_sensitivities(n / (1 + columns), columns, pattern, Shifts::RealAndComplex)
    } else {
        Newton::for_pattern(n, pattern, Shifts::RealAndComplex)
    };
    let jacobian = DenseJacobian::with_matrix::<M>(newton.dense_jacobian());
    let linear_solver = newton.label();
    let mut w = Work { model, evals: 0, jacobian_evals: 0, jacobian, linear_solver };
    let mut mass_applied = [vec![0.0; n], vec![0.0; n], vec![0.0; n]];
    let mut y = vec![0.0; n];
    let mut y0 = vec![0.0; n];
    let (mut z1, mut z2, mut z3) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let (mut f1, mut f2, mut f3) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let mut cont = vec![0.0; 4 * n];
    let mut stage = vec![0.0; n];
    let mut scal = vec![0.0; n];
    // The error test's states (the model's own, where sensitivities are
    // left out of it); Newton converges on all.
    let n_error = crate::methods::error_states::<M>(options);
    let mut scratch = vec![0.0; n];
    let mut events = EventWatch::new(model, t0, start, 1);
    let mut projector = Projector::new(model);
    let keep_dense = options.dense_output || events.is_some();
    if keep_dense {
        solution.set_interpolant(4, interpolate);
    }

    y.copy_from_slice(start);
    if t0 == t1 {
        return Ok((solution, Finish::Done));
    }
    // ρ(J) at the last Jacobian, and the steps in a row RADAU5 took with
    // h·ρ below the watch's bound.
    let (mut rho, mut calm) = (f64::INFINITY, 0usize);
    let fail = |solution: Solution,
                w: &Work<'_, M>,
                steps: usize,
                rejected: usize,
                t: f64,
                cause: EvalError|
     -> Result<(Solution, Finish), Error> {
        let mut solution = solution;
        finish(&mut solution, steps, rejected, w);
        Err(Error::Evaluation { t, cause, partial: Box::new(solution) })
    };
    if let Err(cause) = w.rhs(t0, &y, &mut y0) {
        return fail(solution, &w, 0, 0, t0, cause);
    }
    // Index-2 variables of a mass-matrix model: their error is measured
    // relative to the step that computed the scale (radau5.f's HHFAC).
    let set_scale = |scal: &mut [f64], y: &[f64], h: f64| {
        for (s, v) in scal.iter_mut().zip(y) {
            *s = atol + rtol * v.abs();
        }
        for &i in M::INDEX2_COMPONENTS {
            scal[i] /= h.abs();
        }
    };

    let mut h = options.initial_step.unwrap_or(1e-6).abs().min(hmax) * direction;
    set_scale(&mut scal, &y, h);
    let mut t = t0;
    let mut last = false;
    if (t + h * 1.0001 - t1) * direction >= 0.0 {
        h = t1 - t;
        last = true;
    }
    let (mut h_old, mut h_acc, mut err_acc) = (h, h, 1e-2);
    let (mut first, mut reject) = (true, false);
    let reuse = Reuse::for_factorisation(factor_operations);
    // Newton's contraction and its convergence factor, carried from step to
    // step: the model's states', and the sensitivity columns' when they are
    // iterated apart.
    let mut state_control = Contraction { theta: reuse.thet, faccon: 1.0 };
    let mut column_control = state_control;
    let own = n / (1 + M::SENSITIVITY_COLUMNS);
    let staggered =
        newton.sensitivity().is_some() && model.own_rhs(t0, &y, &mut scratch[..own]).is_some();
    let parts: &[Part] =
        if staggered { &[Part::Own(own), Part::Columns(own)] } else { &[Part::All] };
    let cfac = SAFE * (1 + 2 * NIT) as f64;
    let (mut accepted, mut rejected, mut singular) = (0usize, 0usize, 0usize);
    let mut newton_failures = 0usize;
    let mut refresh = Refresh::Jacobian;
    let mut caljac;

    'steps: loop {
        if refresh == Refresh::Jacobian {
            if let Err(cause) = w.evaluate_jacobian(t, &mut y, &y0) {
                return fail(solution, &w, accepted, rejected, t, cause);
            }
            if watch.is_some() {
                rho = w.jacobian.spectral_radius::<M>();
            }
            caljac = true;
        } else {
            caljac = false;
        }
        if refresh != Refresh::Nothing {
            let factor_mass =
                if mass_matrix.is_empty() { M::MASS.diagonal() } else { &mass_matrix[..] };
            let pattern = M::JACOBIAN.pattern();
            let shifts = (gamma / h, (alpha / h, beta / h));
            let mut factored = newton.factor(
                shifts.0,
                shifts.1,
                factor_mass,
                &w.jacobian.matrix,
                w.jacobian.values(),
                pattern,
            );
            if factored == Factored::NeedsDenseJacobian {
                w.jacobian = DenseJacobian::new::<M>();
                if let Err(cause) = w.evaluate_jacobian(t, &mut y, &y0) {
                    return fail(solution, &w, accepted, rejected, t, cause);
                }
                factored = newton.factor(
                    shifts.0,
                    shifts.1,
                    factor_mass,
                    &w.jacobian.matrix,
                    w.jacobian.values(),
                    pattern,
                );
                w.linear_solver = newton.label();
            }
            if factored != Factored::Yes {
                singular += 1;
                if singular >= 5 {
                    finish(&mut solution, accepted, rejected, &w);
                    return Err(Error::SingularMatrix { t, h, partial: Box::new(solution) });
                }
                refresh = retry(&mut h, 0.5, &mut reject, &mut last, caljac);
                continue 'steps;
            }
        }
        if accepted + rejected >= options.max_steps {
            finish(&mut solution, accepted, rejected, &w);
            return Err(Error::MaxSteps {
                t,
                max_steps: options.max_steps,
                partial: Box::new(solution),
            });
        }
        if 0.1 * h.abs() <= t.abs().max(1e-300) * f64::EPSILON || h.abs() < options.min_step {
            finish(&mut solution, accepted, rejected, &w);
            let partial = Box::new(solution);
            return Err(if newton_failures > 0 {
                Error::NewtonFailure {
                    t,
                    h,
                    tried: format!(
                        "{newton_failures} Newton iterations in a row failed to converge while the step shrank to {h:e}, each retried with a fresh Jacobian or factorisation"
                    ),
                    partial,
                }
            } else {
                Error::StepSizeUnderflow { t, h, partial }
            });
        }
        // Starting values: zero, or the last collocation polynomial extrapolated.
        if first {
            for v in [&mut z1, &mut z2, &mut z3, &mut f1, &mut f2, &mut f3] {
                v.iter_mut().for_each(|x| *x = 0.0);
            }
        } else {
            let c3q = h / h_old;
            let (c1q, c2q) = (C1 * c3q, C2 * c3q);
            for i in 0..n {
                let (ak1, ak2, ak3) = (cont[n + i], cont[2 * n + i], cont[3 * n + i]);
                let z1i = c1q * (ak1 + (c1q - C2M1) * (ak2 + (c1q - C1M1) * ak3));
                let z2i = c2q * (ak1 + (c2q - C2M1) * (ak2 + (c2q - C1M1) * ak3));
                let z3i = c3q * (ak1 + (c3q - C2M1) * (ak2 + (c3q - C1M1) * ak3));
                z1[i] = z1i;
                z2[i] = z2i;
                z3[i] = z3i;
                f1[i] = TI[0][0] * z1i + TI[0][1] * z2i + TI[0][2] * z3i;
                f2[i] = TI[1][0] * z1i + TI[1][1] * z2i + TI[1][2] * z3i;
                f3[i] = TI[2][0] * z1i + TI[2][1] * z2i + TI[2][2] * z3i;
            }
        }
        // Simplified Newton iteration on the transformed system: on every
        // state at once, or staggered (the model's own states first, then
        // the sensitivity columns with those fixed).
        let iteration = Iteration { t, h, y: &y, scal: &scal, mass: &mass, fnewt };
        let mut newt = 0usize;
        for &part in parts {
            let control = match part {
                Part::Columns(_) => &mut column_control,
                _ => &mut state_control,
            };
            let stages = ([&mut z1, &mut z2, &mut z3], [&mut f1, &mut f2, &mut f3]);
            let buffers = (&mut stage[..], &mut scratch[..], &mut mass_applied);
            let outcome = simplified_newton(
                &mut w,
                &mut newton,
                (&iteration, part, &mass_matrix),
                stages,
                buffers,
                control,
            );
            match outcome {
                Iterated::Converged(iterations) => newt = newt.max(iterations),
                Iterated::Retry { factor, failed } => {
                    newton_failures += usize::from(failed);
                    refresh = retry(&mut h, factor, &mut reject, &mut last, caljac);
                    continue 'steps;
                }
                Iterated::Failed { at, cause } => {
                    return fail(solution, &w, accepted, rejected, at, cause);
                }
            }
        }
        let theta = state_control.theta;
        newton_failures = 0;
        // Error estimate (ESTRAD): (γ/h − J)⁻¹ (f(y) + (DD·Z)/h), refined once
        // through f after a rejection or on the first step.
        let (hee1, hee2, hee3) = (DD1 / h, DD2 / h, DD3 / h);
        if mass_matrix.is_empty() {
            for i in 0..n {
                f2[i] = mass[i] * (hee1 * z1[i] + hee2 * z2[i] + hee3 * z3[i]);
            }
        } else {
            let combined = &mut mass_applied[0];
            for i in 0..n {
                combined[i] = hee1 * z1[i] + hee2 * z2[i] + hee3 * z3[i];
            }
            apply_mass(&mass_matrix, combined, &mut f2);
        }
        for i in 0..n {
            scratch[i] = f2[i] + y0[i];
        }
        newton.solve_real(&mut scratch);
        let estimate = |scratch: &[f64]| {
            (scratch[..n_error].iter().zip(&scal).map(|(e, s)| (e / s).powi(2)).sum::<f64>()
                / n_error as f64)
                .sqrt()
                .max(1e-10)
        };
        let mut err = estimate(&scratch);
        if err >= 1.0 && (first || reject) {
            for i in 0..n {
                stage[i] = y[i] + scratch[i];
            }
            if let Err(cause) = w.rhs(t, &stage, &mut f1) {
                return fail(solution, &w, accepted, rejected, t, cause);
            }
            for i in 0..n {
                scratch[i] = f1[i] + f2[i];
            }
            newton.solve_real(&mut scratch);
            err = estimate(&scratch);
        }
        if !err.is_finite() {
            refresh = retry(&mut h, 0.5, &mut reject, &mut last, caljac);
            continue 'steps;
        }
        let fac = SAFE.min(cfac / (newt + 2 * NIT) as f64);
        let mut quot = FACR.max(FACL.min(err.powf(0.25) / fac));
        let mut h_new = h / quot;
        if err < 1.0 {
            // Accepted.
            first = false;
            accepted += 1;
            if accepted > 1 {
                // Gustafsson's predictive controller.
                let facgus =
                    ((h_acc / h) * (err * err / err_acc).powf(0.25) / SAFE).clamp(FACR, FACL);
                quot = quot.max(facgus);
                h_new = h / quot;
            }
            h_acc = h;
            err_acc = err.max(1e-2);
            h_old = h;
            t = if last { t1 } else { t + h };
            for i in 0..n {
                y[i] += z3[i];
                let (z1i, z2i) = (z1[i], z2[i]);
                cont[n + i] = (z2i - z3[i]) / C2M1;
                let ak = (z1i - z2i) / C1MC2;
                let acont3 = (ak - z1i / C1) / C2;
                cont[2 * n + i] = (ak - cont[n + i]) / C1M1;
                cont[3 * n + i] = cont[2 * n + i] - acont3;
                cont[i] = y[i];
            }
            if let Some(i) = y.iter().position(|v| !v.is_finite()) {
                finish(&mut solution, accepted, rejected, &w);
                return Err(Error::NonFinite {
                    t,
                    variable: M::INFO.states[i],
                    partial: Box::new(solution),
                });
            }
            project_onto_constraints!(projector, t, &mut y, solution);
            set_scale(&mut scal, &y, h);
            if keep_dense {
                solution.push_dense(t, &y, &cont);
            } else {
                solution.push(t, &y);
            }
            after_accepted_step!(events, solution);
            if last {
                break;
            }
            if let Err(cause) = w.rhs(t, &y, &mut y0) {
                return fail(solution, &w, accepted, rejected, t, cause);
            }
            h_new = direction * h_new.abs().min(hmax);
            if reject {
                h_new = direction * h_new.abs().min(h.abs());
            }
            reject = false;
            if let Some(watch) = watch {
                calm = if h.abs() * rho < watch.below { calm + 1 } else { 0 };
                if calm >= watch.confirmations {
                    finish(&mut solution, accepted, rejected, &w);
                    return Ok((solution, Finish::NonStiffAt { t, h: h_new }));
                }
            }
            if (t + h_new / reuse.quot1 - t1) * direction >= 0.0 {
                h = t1 - t;
                last = true;
            } else {
                let qt = h_new / h;
                if theta <= reuse.thet && (reuse.quot1..=reuse.quot2).contains(&qt) {
                    refresh = Refresh::Nothing;
                    continue 'steps;
                }
                h = h_new;
            }
            refresh = if theta <= reuse.thet { Refresh::Factorisation } else { Refresh::Jacobian };
        } else {
            reject = true;
            last = false;
            if first {
                h *= 0.1;
            } else {
                h = h_new;
            }
            if accepted >= 1 {
                rejected += 1;
            }
            refresh = if caljac { Refresh::Factorisation } else { Refresh::Jacobian };
        }
    }
    finish(&mut solution, accepted, rejected, &w);
    Ok((solution, Finish::Done))
}

/// Newton's contraction θ and the factor θ/(1 − θ) that turns the last
/// increment into an error bound (`radau5.f`'s THETA and FACCON).
#[derive(Clone, Copy)]
struct Contraction {
    theta: f64,
    faccon: f64,
}

/// Which states a simplified Newton iteration solves for.
#[derive(Clone, Copy)]
enum Part {
    /// Every state, with the whole Newton matrix.
    All,
    /// The model's own states (the first `own`), through `Model::own_rhs`
    /// and the base block: the first half of the staggered corrector
    /// (Feehery, Tolsma & Barton, "Efficient sensitivity analysis of
    /// large-scale differential-algebraic systems", Appl. Numer. Math. 25,
    /// 1997; CVODES's `CV_STAGGERED`).
    Own(usize),
    /// The sensitivity columns (the states from `own` on) with the model's
    /// own stages fixed: linear and uncoupled, each with the base block.
    Columns(usize),
}

/// How a simplified Newton iteration ended.
enum Iterated {
    /// Converged after this many iterations.
    Converged(usize),
    /// Retry the step with h times `factor`; `failed` when the iteration
    /// diverged (rather than converging too slowly).
    Retry { factor: f64, failed: bool },
    /// The right-hand side could not be evaluated at `at`.
    Failed { at: f64, cause: EvalError },
}

/// What an iteration reads: the step, the state, the error scale, the
/// diagonal mass and Newton's tolerance.
struct Iteration<'a> {
    t: f64,
    h: f64,
    y: &'a [f64],
    scal: &'a [f64],
    mass: &'a [f64],
    fnewt: f64,
}

/// `radau5.f`'s simplified Newton iteration on the transformed stages
/// (Hairer & Wanner II, §IV.8, (8.13)–(8.16)) for the states of `part`:
/// `z` the stage increments Z, `f` their transforms W = T⁻¹Z, updated in
/// place.
fn simplified_newton<M: Model>(
    w: &mut Work<'_, M>,
    newton: &mut Newton,
    (it, part, mass_matrix): (&Iteration<'_>, Part, &[f64]),
    (z, f): ([&mut Vec<f64>; 3], [&mut Vec<f64>; 3]),
    (stage, scratch, mass_applied): (&mut [f64], &mut [f64], &mut [Vec<f64>; 3]),
    control: &mut Contraction,
) -> Iterated {
    let n = it.y.len();
    let range = match part {
        Part::All => 0..n,
        Part::Own(own) => 0..own,
        Part::Columns(own) => own..n,
    };
    let (gamma, alpha, beta) = eigenvalues();
    let [z1, z2, z3] = z;
    let [f1, f2, f3] = f;
    let mut newt = 0usize;
    control.faccon = control.faccon.max(f64::EPSILON).powf(0.8);
    control.theta = control.theta.abs();
    let (mut dyno_old, mut thq_old) = (0.0f64, 0.0f64);
    loop {
        if newt >= NIT {
            return Iterated::Retry { factor: 0.5, failed: true };
        }
        for (zk, c) in [(&mut *z1, C1), (&mut *z2, C2), (&mut *z3, 1.0)] {
            let at = it.t + c * it.h;
            // The columns' right-hand side reads the states' stages too.
            let read = if let Part::Own(own) = part { 0..own } else { 0..n };
            for i in read {
                stage[i] = it.y[i] + zk[i];
            }
            let evaluated = match part {
                Part::All => w.rhs(at, stage, zk),
                Part::Own(own) => w.own_rhs(at, stage, &mut zk[..own]),
                Part::Columns(own) => w.rhs(at, stage, scratch).map(|()| {
                    zk[own..].copy_from_slice(&scratch[own..]);
                }),
            };
            if let Err(cause) = evaluated {
                return Iterated::Failed { at, cause };
            }
        }
        for i in range.clone() {
            let (a1, a2, a3) = (z1[i], z2[i], z3[i]);
            z1[i] = TI[0][0] * a1 + TI[0][1] * a2 + TI[0][2] * a3;
            z2[i] = TI[1][0] * a1 + TI[1][1] * a2 + TI[1][2] * a3;
            z3[i] = TI[2][0] * a1 + TI[2][1] * a2 + TI[2][2] * a3;
        }
        let (fac1, alphn, betan) = (gamma / it.h, alpha / it.h, beta / it.h);
        if mass_matrix.is_empty() {
            for i in range.clone() {
                let m = it.mass[i];
                let (s2, s3) = (-m * f2[i], -m * f3[i]);
                z1[i] -= m * f1[i] * fac1;
                z2[i] += s2 * alphn - s3 * betan;
                z3[i] += s3 * alphn + s2 * betan;
            }
        } else {
            for (out, f) in mass_applied.iter_mut().zip([&*f1, &*f2, &*f3]) {
                apply_mass(mass_matrix, f, out);
            }
            let [m1, m2, m3] = &*mass_applied;
            for i in range.clone() {
                let (s2, s3) = (-m2[i], -m3[i]);
                z1[i] -= m1[i] * fac1;
                z2[i] += s2 * alphn - s3 * betan;
                z3[i] += s3 * alphn + s2 * betan;
            }
        }
        match (part, newton.sensitivity()) {
            (Part::Own(own), Some(s)) => {
                s.solve_own_real(&mut z1[..own]);
                s.solve_own_complex(&mut z2[..own], &mut z3[..own]);
            }
            (Part::Columns(_), Some(s)) => {
                s.solve_columns_real(z1);
                s.solve_columns_complex(z2, z3);
            }
            _ => {
                newton.solve_real(z1);
                newton.solve_complex(z2, z3);
            }
        }
        newt += 1;
        let r = range.clone();
        let dyno = rms([&z1[r.clone()], &z2[r.clone()], &z3[r.clone()]], &it.scal[r]);
        if !dyno.is_finite() {
            return Iterated::Retry { factor: 0.5, failed: true };
        }
        if newt > 1 && newt < NIT {
            let thq = dyno / dyno_old;
            control.theta = if newt == 2 { thq } else { (thq * thq_old).sqrt() };
            thq_old = thq;
            let theta = control.theta;
            if theta < 0.99 {
                control.faccon = theta / (1.0 - theta);
                let dyth = control.faccon * dyno * theta.powi((NIT - 1 - newt) as i32) / it.fnewt;
                if dyth >= 1.0 {
                    // Convergence too slow for the remaining iterations: shrink h.
                    let qnewt = dyth.clamp(1e-4, 20.0);
                    let factor = 0.8 * qnewt.powf(-1.0 / (4.0 + (NIT - 1 - newt) as f64));
                    return Iterated::Retry { factor, failed: false };
                }
            } else {
                return Iterated::Retry { factor: 0.5, failed: true };
            }
        }
        dyno_old = dyno.max(f64::EPSILON);
        for i in range.clone() {
            let (a, b, c) = (f1[i] + z1[i], f2[i] + z2[i], f3[i] + z3[i]);
            f1[i] = a;
            f2[i] = b;
            f3[i] = c;
            z1[i] = T[0][0] * a + T[0][1] * b + T[0][2] * c;
            z2[i] = T[1][0] * a + T[1][1] * b + T[1][2] * c;
            z3[i] = T[2][0] * a + b;
        }
        if control.faccon * dyno <= it.fnewt {
            return Iterated::Converged(newt);
        }
    }
}

/// After a failed Newton iteration or step: shrink h by `factor`, mark the
/// step rejected, and refactor with the same Jacobian if it was just
/// computed, else get a new one (the JAC/DECOMP decision of radau5.f).
fn retry(h: &mut f64, factor: f64, reject: &mut bool, last: &mut bool, caljac: bool) -> Refresh {
    *h *= factor;
    *reject = true;
    *last = false;
    if caljac {
        Refresh::Factorisation
    } else {
        Refresh::Jacobian
    }
}

fn finish<M: Model>(solution: &mut Solution, steps: usize, rejected: usize, w: &Work<'_, M>) {
    let stats = solution.stats_mut();
    stats.steps += steps;
    stats.rejected += rejected;
    stats.rhs_evals += w.evals;
    stats.jacobian_evals += w.jacobian_evals;
    stats.linear_solver = w.linear_solver;
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::info::ModelInfo;
    use crate::model::MassMatrix;
    use crate::options::Options;

    /// Cash's pendulum (g = 1) in the Gear–Gupta–Leimkuhler index-2 form,
    /// written by hand: w = (x, y, u, v, λ, μ), M = diag(1, 1, 1, 1, 0, 0),
    /// x' = u − 2xμ, y' = v − 2yμ, u' = −λx, v' = −λy − 1,
    /// 0 = x² + y² − 1, 0 = 2(xu + yv).
    #[derive(Clone)]
    struct GglPendulum;

    impl Model for GglPendulum {
        const STATES: usize = 6;
        type State = [f64; 6];
        const INDEX: usize = 2;
        const INFO: ModelInfo =
            ModelInfo::bare("GglPendulum", &["x", "y", "u", "v", "lambda", "mu"], 6);
        const MASS: MassMatrix = MassMatrix::Diagonal(&[1.0, 1.0, 1.0, 1.0, 0.0, 0.0]);
        const INDEX2_COMPONENTS: &'static [usize] = &[4, 5];
        fn initial_state(&self, y: &mut [f64]) {
            y.copy_from_slice(&[1.0, 0.0, 0.0, 1.0, 1.0, 0.0]);
        }
        fn rhs(&self, _t: f64, w: &[f64], dw: &mut [f64]) -> Result<(), EvalError> {
            let [x, y, u, v, l, mu] = [w[0], w[1], w[2], w[3], w[4], w[5]];
            dw.copy_from_slice(&[
                u - 2.0 * x * mu,
                v - 2.0 * y * mu,
                -l * x,
                -l * y - 1.0,
                x * x + y * y - 1.0,
                2.0 * (x * u + y * v),
            ]);
            Ok(())
        }
    }

    /// (x, y, u, v, λ) at t = 1 and 10, recomputed to 25+ digits
    /// (../shared/notes/reference-problems.md §4).
    const AT_1: [f64; 5] = [
        0.867348640600439321734308116640,
        0.497701050479672929353712765065,
        -0.0337480180609545196091412779116,
        0.0588130114652500075408496027315,
        -0.493103151439018788061138295195,
    ];
    const AT_10: [f64; 5] = [
        0.884392383092720254000816,
        0.466744161964109775211094,
        0.1203726552417017963052549,
        -0.2280835372003925465259898,
        -0.400232485892329325633282,
    ];

    #[test]
    fn only_radau5_integrates_a_singular_mass_matrix() {
        let opts = Options::new().method(crate::Method::Dop853);
        let err = crate::run::simulate(&GglPendulum, 0.0, 1.0, &opts).unwrap_err();
        let message = err.to_string();
        assert!(message.contains("Method::Radau5") && message.contains("lambda, mu"), "{message}");
        let auto = crate::run::simulate(&GglPendulum, 0.0, 1.0, &Options::new()).unwrap();
        assert!(auto.stats().method.contains("Radau5"));
    }

    #[test]
    fn radau5_with_a_singular_mass_matrix_solves_the_ggl_pendulum() {
        let model = GglPendulum;
        for tol in [1e-6, 1e-8, 1e-10] {
            let opts = Options::new().method(crate::Method::Radau5).rtol(tol).atol(tol);
            let mut y0 = [0.0; 6];
            model.initial_state(&mut y0);
            let sol = crate::run::simulate(&model, 0.0, 10.0, &opts).unwrap();
            for (t, reference) in [(1.0, AT_1), (10.0, AT_10)] {
                let errs: Vec<f64> = ["x", "y", "u", "v", "lambda"]
                    .iter()
                    .zip(reference)
                    .map(|(n, r)| (sol.at(t, n).unwrap() - r).abs())
                    .collect();
                // Positions and velocities to the tolerance (measured ≤ 8 ×
                // at t = 1, ≤ 14 × at t = 10).
                let growth = if t == 1.0 { 1.0 } else { 50.0 };

                let e = errs[..4].iter().fold(0.0f64, |a, b| a.max(*b));
                assert!(e <= 20.0 * growth * tol, "tol {tol:e}, t = {t}: error {e:e}");
                // radau5.f controls an index-2 variable's error against
                // tol / h: the bound uses the mean step.
                let h_mean = 10.0 / sol.stats().steps as f64;
                assert!(
                    errs[4] <= 100.0 * tol / h_mean,
                    "tol {tol:e}, t = {t}: λ error {:e}",
                    errs[4]
                );
            }
            // μ vanishes on the exact solution; the constraints hold to the
            // Newton tolerance at every step, with no projection.
            let (mut phi, mut mu) = (0.0f64, 0.0f64);
            for k in 0..sol.times().len() {
                let s = sol.state(k).unwrap();
                phi = phi.max((s[0] * s[0] + s[1] * s[1] - 1.0).abs());
                mu = mu.max(s[5].abs());
            }
            assert!(phi <= tol, "max |Φ| = {phi:e}");
            // μ, zero on the exact solution, is an index-2 variable too.
            let h_mean = 10.0 / sol.stats().steps as f64;
            assert!(mu <= 1000.0 * tol / h_mean, "max |μ| = {mu:e}");
        }
    }
}
