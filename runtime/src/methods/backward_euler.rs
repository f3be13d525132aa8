//! Backward (implicit) Euler with a fixed step, y₁ = y₀ + h f(t₁, y₁):
//! order 1, L-stable (course notes §1.3; Hairer & Wanner, *Solving ODEs
//! II*, §IV.3). Each step solves its implicit equation by Newton's method
//! with the model's Jacobian, made robust as in Hairer & Wanner II §IV.8
//! and Deuflhard, *Newton Methods for Nonlinear Problems* (2004), §3.1:
//!
//! - the Newton matrix I/h − J is kept across steps while the iteration
//!   contracts fast, and re-formed at the current iterate when it slows
//!   (contraction factor θ above [`SLOW`]) or stops descending;
//! - convergence is judged on the increment scaled by the tolerances,
//!   `θ/(1 − θ)·‖Δ‖ ≤ target` (the distance to the root it predicts);
//! - each update is damped until Deuflhard's natural monotonicity test
//!   holds, ‖Δ̄(Y + λΔ)‖ ≤ (1 − λ/4)‖Δ‖ with Δ̄ the next simplified Newton
//!   correction: a test invariant under scaling of the equations, which
//!   carries the iteration along a stiff problem's slow manifold where the
//!   residual's norm, dominated by its stiff rows, would stall a line search
//!   (a decrease of that norm is accepted too);
//! - convergence measured with a matrix formed elsewhere is trusted only
//!   where that matrix still fits the iterate ([`Newton::matrix_fits`]);
//! - with half its matrices spent, the iteration turns to plain Newton
//!   (full steps, a matrix at every iterate), which reaches roots beyond a
//!   minimum of the merit function;
//! - a step that still cannot be taken, or whose local error is far too
//!   large, is taken in halves ([`integrate`]).

use crate::error::Error;
use crate::info::EvalError;
use crate::linalg::dense_lu::RealLu;
use crate::model::Model;
use crate::solution::Solution;
use crate::step::driver::{Counts, Driver};
use crate::step::jacobian::DenseJacobian;
use crate::step::Problem;

/// Iterations with one Newton matrix before it is refreshed.
const ITERATIONS_PER_MATRIX: usize = 10;
/// Newton matrices (Jacobian evaluations and factorisations) one step may use.
const MATRICES_PER_STEP: usize = 20;
/// Contraction factor above which a kept matrix is refreshed.
const SLOW: f64 = 0.5;
/// Newton stops when the predicted distance to the root is below κ times
/// the tolerances' scale (radau5.f's FNEWT plays this role; 0.1 as in
/// CVODE's nonlinear-solver test) ...
const KAPPA: f64 = 0.1;
/// ... and below this fraction of the step's local error, estimated as
/// (h/2)·(f(t₁, Y) − f(t₀, y)) ≈ (h²/2) y''. An adaptive method keeps its
/// local error near the tolerance, so κ alone suffices there; with a fixed
/// step the local error may be far below the tolerance, and an iteration
/// error above it, repeated over every step, would swamp the method's own
/// O(h) error (Hairer & Wanner II §IV.8: the iteration error must stay
/// below the discretisation error).
const LOCAL: f64 = 1e-2;
/// Smallest damping factor λ of an update.
const MIN_DAMPING: f64 = 1.0 / 1024.0;

/// What one step's Newton iteration did, for the error message.
#[derive(Default)]
struct Effort {
    iterations: usize,
    matrices: usize,
    smallest_damping: f64,
    /// Full steps taken where no damped one passed.
    undamped: usize,
}

/// Why one step's Newton iteration stopped without a solution.
enum Trouble {
    /// The model failed at time `t`.
    Evaluation(f64, EvalError),
    /// I − hJ was singular at the start of the step.
    Singular,
    /// No convergence within the iterations and refreshes allowed.
    NoConvergence,
    /// Converged, but the step does not resolve the solution.
    Unresolved,
}

/// Newton's method for one backward Euler step and the state it keeps
/// across steps.
struct Newton {
    n: usize,
    h: f64,
    jacobian: DenseJacobian,
    lu: RealLu,
    /// Whether `lu` holds a factorisation usable as a Newton matrix.
    factored: bool,
    /// Whether it was formed during the current step, at an iterate.
    formed_in_step: bool,
    weights: Vec<f64>,
    residual: Vec<f64>,
    trial_residual: Vec<f64>,
    f: Vec<f64>,
    /// f(t₀, y) at the start of the step.
    f_start: Vec<f64>,
    delta: Vec<f64>,
    /// The correction at the trial point.
    next_delta: Vec<f64>,
    trial: Vec<f64>,
    evals: usize,
    jacobian_evals: usize,
}

impl Newton {
    fn new<M: Model>(h: f64) -> Newton {
        let n = M::STATES;
        Newton {
            n,
            h,
            jacobian: DenseJacobian::new::<M>(),
            lu: RealLu::new(n),
            factored: false,
            formed_in_step: false,
            weights: vec![0.0; n],
            residual: vec![0.0; n],
            trial_residual: vec![0.0; n],
            f: vec![0.0; n],
            f_start: vec![0.0; n],
            delta: vec![0.0; n],
            next_delta: vec![0.0; n],
            trial: vec![0.0; n],
            evals: 0,
            jacobian_evals: 0,
        }
    }

    /// The evaluations so far, for the run's statistics.
    fn counts(&self) -> Counts {
        Counts { evals: self.evals, jacobian_evals: self.jacobian_evals, ..Counts::default() }
    }

    /// Evaluates the residual `(Y − y)/h − f(t₁, Y)` at `Y = self.trial`
    /// into `self.trial_residual` (the residual over h, so that the Newton
    /// matrix is `I/h − J`).
    fn trial_residual<M: Model>(&mut self, model: &M, t1: f64, y: &[f64]) -> Result<(), EvalError> {
        self.evals += 1;
        model.rhs(t1, &self.trial, &mut self.f)?;
        for i in 0..self.n {
            self.trial_residual[i] = (self.trial[i] - y[i]) / self.h - self.f[i];
        }
        Ok(())
    }

    /// The relative size of the step's local error, filtered as RADAU5
    /// filters its estimate (Hairer & Wanner II §IV.8, eq. 8.19):
    /// `(I/h − J)⁻¹ (f(t₁, Y) − f(t₀, y))/2` ≈ (I − hJ)⁻¹ (h²/2) y'',
    /// largest over the components relative to `scale`. The filter keeps a
    /// stiff component that decays within the step from counting; what is
    /// left large is a step that does not resolve the solution.
    fn local_error<M: Model>(
        &mut self,
        model: &M,
        t0: f64,
        y: &[f64],
        scale: &[f64],
    ) -> Result<f64, Trouble> {
        if self.formed_in_step {
            // Formed at an iterate, which across a jump may lie anywhere
            // (where J is huge, the filter would hide any error): the
            // filter is the matrix at the start of the step, as in RADAU5.
            self.evals += 1;
            self.next_delta.copy_from_slice(y);
            model.rhs(t0, y, &mut self.trial_residual).map_err(|e| Trouble::Evaluation(t0, e))?;
            self.jacobian_evals += 1;
            self.jacobian
                .evaluate(model, t0, &mut self.next_delta, &self.trial_residual, &mut self.evals)
                .map_err(|e| Trouble::Evaluation(t0, e))?;
            self.factored = self.lu.factor_shifted(1.0 / self.h, &self.jacobian.matrix);
            if !self.factored {
                return Ok(f64::INFINITY);
            }
        }
        for i in 0..self.n {
            self.next_delta[i] = 0.5 * (self.f[i] - self.f_start[i]);
        }
        self.lu.solve(&mut self.next_delta);
        Ok(self.next_delta.iter().zip(scale).map(|(e, s)| (e / s).abs()).fold(0.0, f64::max))
    }

    /// The step was accepted: f(t₁, Y) is f at the start of the next.
    fn accept(&mut self) {
        self.f_start.copy_from_slice(&self.f);
    }

    /// Steps by `h` from now on (the matrix I/h − J is formed anew).
    fn set_step(&mut self, h: f64) {
        if h != self.h {
            self.h = h;
            self.factored = false;
        }
    }

    /// The Jacobian at `(t₁, Y)`, `f` holding f(t₁, Y), and `I/h − J`
    /// factored; `false` if singular.
    fn refresh<M: Model>(
        &mut self,
        model: &M,
        t1: f64,
        big_y: &mut [f64],
    ) -> Result<bool, Trouble> {
        self.jacobian_evals += 1;
        self.jacobian
            .evaluate(model, t1, big_y, &self.f, &mut self.evals)
            .map_err(|e| Trouble::Evaluation(t1, e))?;
        self.factored = self.lu.factor_shifted(1.0 / self.h, &self.jacobian.matrix);
        Ok(self.factored)
    }

    /// Whether θ, measured with the Newton matrix M = I/h − J_M, can be
    /// trusted at `Y`: the true matrix there is M − (J(Y) − J_M), and the
    /// estimate holds while ‖M⁻¹(J(Y) − J_M)Δ‖ ≤ ‖Δ‖/2 along the last
    /// correction Δ. Across a relaxation jump a matrix formed before it maps
    /// every residual to a tiny correction, and the iteration would seem to
    /// converge to a point that solves nothing.
    fn matrix_fits<M: Model>(
        &mut self,
        model: &M,
        t1: f64,
        big_y: &[f64],
    ) -> Result<bool, Trouble> {
        self.jacobian_evals += 1;
        let checked = self
            .jacobian
            .change_along(model, t1, big_y, &self.delta, &mut self.next_delta)
            .map_err(|e| Trouble::Evaluation(t1, e))?;
        if !checked {
            return Ok(true);
        }
        self.lu.solve(&mut self.next_delta);
        Ok(norm(&self.next_delta, &self.weights) <= 0.5 * norm(&self.delta, &self.weights))
    }

    /// The scaled increment below which Newton has converged at `Y`, with
    /// `f` = f(t₁, Y): κ, or less where the step's local error is smaller
    /// (see [`LOCAL`]), but never below rounding in Y and h·f.
    fn target(&self, big_y: &[f64]) -> f64 {
        let (mut local, mut rounding) = (0.0f64, 0.0f64);
        for i in 0..self.n {
            let w = self.weights[i];
            local += (0.5 * self.h * (self.f[i] - self.f_start[i]) / w).powi(2);
            rounding +=
                (100.0 * f64::EPSILON * (big_y[i].abs() + (self.h * self.f[i]).abs()) / w).powi(2);
        }
        let scale = 1.0 / self.n.max(1) as f64;
        let (local, rounding) = ((local * scale).sqrt(), (rounding * scale).sqrt());
        KAPPA.min(LOCAL * local).max(rounding)
    }

    /// Solves `Y = y + h f(t₁, Y)` for `Y` (in `big_y`) from `Y = y`;
    /// `f_start` holds f(t₀, y).
    #[allow(clippy::too_many_arguments)]
    fn solve<M: Model>(
        &mut self,
        model: &M,
        t1: f64,
        y: &[f64],
        big_y: &mut [f64],
        rtol: f64,
        atol: f64,
        effort: &mut Effort,
    ) -> Result<(), Trouble> {
        // One Newton iteration with its damping, matrix reuse and convergence tests, which
        // share the iterates; splitting it would pass them each way.
        for (w, v) in self.weights.iter_mut().zip(y) {
            *w = atol + rtol * v.abs();
        }
        *effort = Effort { smallest_damping: 1.0, ..Effort::default() };
        self.formed_in_step = false;
        big_y.copy_from_slice(y);
        self.trial.copy_from_slice(y);
        self.trial_residual(model, t1, y).map_err(|e| Trouble::Evaluation(t1, e))?;
        std::mem::swap(&mut self.residual, &mut self.trial_residual);
        // The matrix of the last step is kept while it serves.
        let mut keep_matrix = self.factored;
        // The matrix was formed at the current iterate.
        let mut formed_here;
        // The last correction of plain Newton (the fallback, see below).
        let mut plain_previous: Option<f64> = None;
        let mut residual_norm = norm(&self.residual, &self.weights);
        'matrices: loop {
            formed_here = !keep_matrix;
            if !keep_matrix {
                if effort.matrices == MATRICES_PER_STEP {
                    return Err(Trouble::NoConvergence);
                }
                effort.matrices += 1;
                // f(t₁, Y), which a finite-difference Jacobian reads.
                self.evals += 1;
                model.rhs(t1, big_y, &mut self.f).map_err(|e| Trouble::Evaluation(t1, e))?;
                self.formed_in_step = true;
                if !self.refresh(model, t1, big_y)? {
                    if big_y == y {
                        return Err(Trouble::Singular);
                    }
                    // Singular at Y: once more from the start of the step.
                    big_y.copy_from_slice(y);
                    self.trial.copy_from_slice(y);
                    self.trial_residual(model, t1, y).map_err(|e| Trouble::Evaluation(t1, e))?;
                    std::mem::swap(&mut self.residual, &mut self.trial_residual);
                    residual_norm = norm(&self.residual, &self.weights);
                    continue 'matrices;
                }
            }
            keep_matrix = false;
            let mut size = correction(&self.lu, &self.weights, &self.residual, &mut self.delta);
            if effort.matrices > MATRICES_PER_STEP / 2 {
                // Half the budget spent: damping has led to a minimum of the
                // merit that is no root (near a fold, the one root may lie
                // far beyond). Plain Newton from here: full steps, a new
                // matrix at every iterate.
                if self.plain_step(model, (t1, y), big_y, size, &mut plain_previous, effort)? {
                    return Ok(());
                }
                continue 'matrices;
            }
            for _ in 0..ITERATIONS_PER_MATRIX {
                effort.iterations += 1;
                if !size.is_finite() {
                    continue 'matrices;
                }
                let search = (size, formed_here, &mut residual_norm);
                let (damping, next_size) =
                    match self.line_search(model, (t1, y), big_y, search, effort)? {
                        Search::Accepted { damping, next_size } => (damping, next_size),
                        Search::NewMatrix => continue 'matrices,
                    };
                effort.smallest_damping = effort.smallest_damping.min(damping);
                formed_here = false;
                big_y.copy_from_slice(&self.trial);
                std::mem::swap(&mut self.residual, &mut self.trial_residual);
                std::mem::swap(&mut self.delta, &mut self.next_delta);
                // θ: how much the correction shrank over a full step.
                let theta = next_size / size;
                if damping == 1.0 && theta < 1.0 {
                    let eta = theta / (1.0 - theta);
                    if eta * next_size <= self.target(big_y) {
                        if !self.matrix_fits(model, t1, big_y)? {
                            continue 'matrices;
                        }
                        // Converged; the last correction is computed, so take it.
                        for (v, d) in big_y.iter_mut().zip(&self.delta) {
                            *v += d;
                        }
                        return Ok(());
                    }
                    if theta > SLOW {
                        // Slow: the matrix no longer fits the iterate.
                        continue 'matrices;
                    }
                }
                size = next_size;
            }
        }
    }

    /// One step of plain Newton (full steps, a new matrix at every
    /// iterate), damped only where the residual cannot be evaluated:
    /// `true` when the last correction `size` shows convergence (and
    /// `big_y` has taken it); `previous` is the correction before.
    fn plain_step<M: Model>(
        &mut self,
        model: &M,
        (t1, y): (f64, &[f64]),
        big_y: &mut [f64],
        size: f64,
        previous: &mut Option<f64>,
        effort: &mut Effort,
    ) -> Result<bool, Trouble> {
        effort.iterations += 1;
        let target = self.target(big_y);
        if let Some(before) = *previous {
            let theta = size / before;
            if size <= target || (theta < 1.0 && theta / (1.0 - theta) * size <= target) {
                for (v, d) in big_y.iter_mut().zip(&self.delta) {
                    *v += d;
                }
                return Ok(true);
            }
        }
        *previous = Some(size);
        let mut damping = 1.0;
        loop {
            for i in 0..self.n {
                self.trial[i] = big_y[i] + damping * self.delta[i];
            }
            if self.trial_residual(model, t1, y).is_ok() {
                break;
            }
            damping *= 0.5;
            if damping < MIN_DAMPING {
                return Err(Trouble::NoConvergence);
            }
        }
        effort.undamped += 1;
        big_y.copy_from_slice(&self.trial);
        std::mem::swap(&mut self.residual, &mut self.trial_residual);
        Ok(false)
    }

    /// The largest λ ∈ {1, 1/2, …} along the correction that passes the
    /// natural monotonicity test, or decreases the scaled residual (whose
    /// norm `residual_norm` it updates), from a correction of `size`.
    /// Where none does, a new matrix: at once where the matrix was not
    /// `formed_here`, else after the full step.
    fn line_search<M: Model>(
        &mut self,
        model: &M,
        (t1, y): (f64, &[f64]),
        big_y: &mut [f64],
        (size, formed_here, residual_norm): (f64, bool, &mut f64),
        effort: &mut Effort,
    ) -> Result<Search, Trouble> {
        let mut damping = 1.0;
        loop {
            for i in 0..self.n {
                self.trial[i] = big_y[i] + damping * self.delta[i];
            }
            let evaluated = self.trial_residual(model, t1, y).is_ok();
            let next =
                correction(&self.lu, &self.weights, &self.trial_residual, &mut self.next_delta);
            let trial_norm = norm(&self.trial_residual, &self.weights);
            if evaluated
                && (next <= (1.0 - damping / 4.0) * size
                    || next <= self.target(&self.trial)
                    || trial_norm <= (1.0 - 1e-4 * damping) * *residual_norm)
            {
                *residual_norm = trial_norm;
                return Ok(Search::Accepted { damping, next_size: next });
            }
            damping *= 0.5;
            if damping >= MIN_DAMPING {
                continue;
            }
            if !formed_here {
                // No descent along this direction: a new matrix here.
                return Ok(Search::NewMatrix);
            }
            // Not even with a matrix formed here: across the fold of a slow
            // manifold the root lies beyond where either test can see. Take
            // the full Newton step (plain Newton, as near a root) and form
            // the matrix anew there.
            for i in 0..self.n {
                self.trial[i] = big_y[i] + self.delta[i];
            }
            if self.trial_residual(model, t1, y).is_err() {
                return Err(Trouble::NoConvergence);
            }
            effort.undamped += 1;
            big_y.copy_from_slice(&self.trial);
            std::mem::swap(&mut self.residual, &mut self.trial_residual);
            *residual_norm = norm(&self.residual, &self.weights);
            return Ok(Search::NewMatrix);
        }
    }
}

/// What a line search found.
enum Search {
    /// The step damped by `damping`, whose next correction is `next_size`.
    Accepted { damping: f64, next_size: f64 },
    /// No descent: the iteration goes on with a new matrix.
    NewMatrix,
}

/// `out = −(I/h − J)⁻¹ residual` with the factorisation `lu`, and its
/// scaled norm.
fn correction(lu: &RealLu, weights: &[f64], residual: &[f64], out: &mut [f64]) -> f64 {
    for (o, r) in out.iter_mut().zip(residual) {
        *o = -r;
    }
    lu.solve(out);
    norm(out, weights)
}

/// The weighted root-mean-square norm.
fn norm(v: &[f64], weights: &[f64]) -> f64 {
    let sum: f64 = v.iter().zip(weights).map(|(x, w)| (x / w).powi(2)).sum();
    (sum / v.len().max(1) as f64).sqrt()
}

/// Halvings of one step before the run stops: a step can shrink to
/// 2⁻³⁰ ≈ 1e-9 of the step asked for.
const MAX_HALVINGS: i32 = 30;

/// Integrates `problem` in equal steps of [`crate::Options::step`] (see
/// [`crate::Method::BackwardEuler`]).
pub(crate) fn integrate<M: Model>(
    problem: Problem<'_, M>,
    solution: Solution,
) -> Result<Solution, Error> {
    let (steps, solution) = crate::step::option_steps(&problem, solution)?;
    integrate_in_steps(problem, steps, solution)
}

/// Integrates with `steps` equal steps from `t0` to `t1`.
///
/// A step that cannot be taken is taken as two halves instead,
/// recursively, and the steps grow back to the grid afterwards. A step
/// cannot be taken when its Newton iteration fails, or when its filtered
/// local error exceeds its share of the run, h/(t1 − t0) of its
/// component's largest magnitude so far (so that the local errors summed
/// over the run stay within that magnitude). Both happen across a
/// relaxation jump (Van der Pol with h ≫ ε): there the implicit equation's
/// only root lies far beyond a fold of the residual, where no Newton-type
/// iteration reaches it, or, where one does, it lands on the wrong side of
/// the jump and the solution bounces between the two branches; smaller
/// steps follow the jump instead. Each halving counts as a rejected step in
/// [`crate::Stats`], and the solution keeps every step taken; the grid
/// points are always among them.
fn integrate_in_steps<M: Model>(
    problem: Problem<'_, M>,
    steps: usize,
    solution: Solution,
) -> Result<Solution, Error> {
    let Problem { model, t0, t1, y0, options } = problem;
    let mut run = Driver::new(&problem, solution, None, 1);
    let n = M::STATES;
    let h = (t1 - t0) / steps as f64;
    let grid = |k: usize| {
        if k == steps {
            t1
        } else {
            t0 + (t1 - t0) * (k as f64 / steps as f64)
        }
    };
    let mut newton = Newton::new::<M>(h);
    let (mut y, mut next) = (y0.to_vec(), vec![0.0; n]);
    newton.evals += 1;
    if let Err(cause) = model.rhs(t0, &y, &mut newton.f_start) {
        return Err(run.evaluation_failed(t0, cause, &newton.counts()));
    }
    // The largest magnitude of each component so far: the scale of the
    // test of resolution.
    let mut magnitude: Vec<f64> = y0.iter().map(|v| v.abs() + options.atol).collect();
    let mut scale = magnitude.clone();
    // A step's share of the run: local errors within it, summed over the
    // steps, stay within each component's magnitude.
    let budget = 1.0 / steps as f64;
    // The next grid point, the time reached, and the step as h·2^-halvings.
    let (mut k, mut t, mut halvings) = (1usize, t0, 0i32);
    while k <= steps {
        let end = grid(k);
        let sub = h * 0.5f64.powi(halvings);
        let t_next = if halvings == 0 || sub.abs() >= (end - t).abs() * (1.0 - 1e-12) {
            end
        } else {
            t + sub
        };
        newton.set_step(t_next - t);
        let mut effort = Effort::default();
        let outcome =
            newton.solve(model, t_next, &y, &mut next, options.rtol, options.atol, &mut effort);
        let outcome = outcome.and_then(|()| {
            for ((s, m), v) in scale.iter_mut().zip(&magnitude).zip(&next) {
                *s = m.max(v.abs());
            }
            if newton.local_error(model, t, &y, &scale)? > budget {
                Err(Trouble::Unresolved)
            } else {
                Ok(())
            }
        });
        match outcome {
            Ok(()) => {
                newton.accept();
                magnitude.copy_from_slice(&scale);
            }
            Err(Trouble::Evaluation(t, cause)) => {
                return Err(run.evaluation_failed(t, cause, &newton.counts()));
            }
            Err(trouble) => {
                run.rejected += 1;
                halvings += 1;
                let smaller = h * 0.5f64.powi(halvings);
                if halvings <= MAX_HALVINGS && smaller.abs() > 64.0 * f64::EPSILON * t.abs() {
                    continue;
                }
                let failed = Failed { trouble, t, t_next, h, smaller, halvings, effort };
                return Err(run.fail(&newton.counts(), |partial| failed.error(partial)));
            }
        }
        run.check_finite(t_next, &next, &newton.counts())?;
        y.copy_from_slice(&next);
        t = t_next;
        if t == end {
            k += 1;
        }
        // Grow back towards the step asked for.
        halvings = (halvings - 1).max(0);
        run.project(t, &mut y, &newton.counts())?;
        if run.record(t, &y, &[], &newton.counts())? {
            break;
        }
    }
    Ok(run.finish(&newton.counts()))
}

/// A step that could not be taken however often it was halved.
struct Failed {
    trouble: Trouble,
    /// The step's start and end, the step asked for and the last tried.
    t: f64,
    t_next: f64,
    h: f64,
    smaller: f64,
    halvings: i32,
    /// The last Newton iteration's effort.
    effort: Effort,
}

impl Failed {
    /// The run's error, with the solution so far.
    fn error(self, partial: Box<Solution>) -> Error {
        let Failed { trouble, t, t_next, h, smaller, halvings, effort } = self;
        match trouble {
            Trouble::Evaluation(t, cause) => Error::Evaluation { t, cause, partial },
            Trouble::Singular => Error::SingularMatrix { t: t_next, h: t_next - t, partial },
            Trouble::Unresolved => Error::StepSizeUnderflow { t, h: smaller, partial },
            Trouble::NoConvergence => Error::NewtonFailure {
                t: t_next,
                h: t_next - t,
                tried: format!(
                    "the step halved {} times from {h:e}; at the last, {} Newton iterations with {} Jacobians evaluated at the iterates, updates damped down to {}, {} full steps past where damping stalled",
                    halvings - 1,
                    effort.iterations,
                    effort.matrices,
                    effort.smallest_damping,
                    effort.undamped
                ),
                partial,
            },
        }
    }
}
