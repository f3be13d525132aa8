//! The driver shared by embedded explicit Runge–Kutta pairs (DOPRI5,
//! DOP853): stages from the tableau, error norm, PI step control, step
//! rejection, first-same-as-last reuse, dense output and the failure modes
//! of a real run (Hairer, Nørsett, Wanner, *Solving ODEs I*, §II.4–§II.6).

use crate::error::Error;
use crate::info::EvalError;
use crate::model::{Model, StateVector};
use crate::solution::Solution;
use crate::step::control::{error_weights, initial_step, Controller, PiState};
use crate::step::driver::{Counts, DenseOutput, Driver};
use crate::step::stiffness::{stage_quotient, Finish, StiffnessTest};
use crate::step::Problem;

/// What the driver needs from one embedded pair.
pub trait EmbeddedPair {
    /// Order of the propagated solution (for the initial step).
    const ORDER: usize;
    /// Stages of a step including the last, which is f at the new point and
    /// becomes the first stage of the next step.
    const STAGES: usize;
    /// Vectors of dense-output coefficients per step.
    const DENSE_WIDTH: usize;
    /// Extra stages evaluated after an accepted step for the dense output.
    const DENSE_STAGES: usize = 0;
    /// Bound on h·ρ (ρ the spectral radius estimated from the last two
    /// stages, both at t + h) beyond which a step counts as stiff: the edge
    /// of the stability region on the negative axis (3.25 for DOPRI5, 6.1
    /// for DOP853, as in Hairer's codes).
    const STIFFNESS_BOUND: f64;
    /// Nodes c (of all stages, dense ones last).
    fn nodes() -> &'static [f64];
    /// Rows of A; row `STAGES - 1` holds the weights b of the new solution.
    fn coefficients() -> &'static [&'static [f64]];
    /// Controller constants.
    fn controller() -> Controller;
    /// Scaled error of the step (≤ 1 accepts it); `k` holds the stages,
    /// `weights` each component's 1 / (atol + rtol·|y|).
    /// A batch of `lanes` members (component `i` of lane `l` at
    /// `i·lanes + l`) is measured lane by lane and its worst lane counts,
    /// so each member meets the tolerance as it would alone.
    fn error<S: StateVector>(h: f64, k: &[S], weights: &S, lanes: usize) -> f64;
    /// Dense-output coefficients of an accepted step, `DENSE_WIDTH` vectors
    /// of length n one after the other in `out`.
    fn dense_coefficients<S: StateVector>(h: f64, y: &S, y_new: &S, k: &[S], out: &mut [f64]);
    /// Component `i` of the dense output at `s = (t - t_old) / h`.
    fn interpolate(coefficients: &[f64], n: usize, i: usize, s: f64) -> f64;
}

/// Counts right-hand-side evaluations.
struct Rhs<'m, M> {
    model: &'m M,
    counts: Counts,
}

impl<M: Model> Rhs<'_, M> {
    fn call(&mut self, t: f64, y: &[f64], out: &mut [f64]) -> Result<(), EvalError> {
        self.counts.evals += 1;
        self.model.rhs(t, y, out)
    }
}

/// `out = y + h Σ_{j<S} a_j k_j` component by component, the newest
/// stage's term added last: `(y + h Σ_{j<S-1} a_j k_j) + (h a_{S-1}) k_{S-1}`.
/// The sum over the older stages runs while the right-hand side computes
/// the newest, so between that evaluation and the next only a product and
/// a sum wait (Hairer's codes sum all terms, then multiply by h and add y:
/// four operations in the way of every stage; the difference is one
/// rounding of the increment). With `S` and the row constant, the sums
/// unroll and the tableau's zeros drop out.
#[inline(always)]
fn combine_row<V: StateVector, const S: usize>(y: &V, h: f64, a: &[f64], k: &[V], out: &mut V) {
    let Some(k) = k.first_chunk::<S>() else { return };
    let Some(a) = a.first_chunk::<S>() else { return };
    let Some((newest, older)) = k.split_last() else { return };
    let h_newest = h * a[S - 1];
    let out = out.as_mut();
    let y = &y.as_ref()[..out.len()];
    for (i, (o, yv)) in out.iter_mut().zip(y).enumerate() {
        let sum = older_terms(a, older, i);
        // Fused where the target has FMA: one operation after the newest
        // stage instead of two.
        *o = if a[S - 1] == 0.0 {
            yv + h * sum
        } else {
            crate::taylor_tape::mul_add(h_newest, newest.as_ref()[i], yv + h * sum)
        };
    }
}

/// Component `i` of `Σ_{j<S-1} a_j k_j`, the terms of every stage but the
/// newest, in stage order; a zero coefficient adds nothing.
#[inline(always)]
fn older_terms<V: StateVector, const S: usize>(a: &[f64; S], older: &[V], i: usize) -> f64 {
    let mut sum = 0.0;
    for (aj, kj) in a.iter().zip(older) {
        if *aj != 0.0 {
            sum += aj * kj.as_ref()[i];
        }
    }
    sum
}

/// The rounding error of the solution's sums, carried from one step into
/// the next (compensated summation: Kahan; Hairer, Lubich & Wanner, GNI
/// §VIII.5), as the Taylor method carries its own: with it the error at
/// the tightest tolerances stops at the stages' rounding, not at the
/// rounding of y + h·Σ b_j k_j added up over thousands of steps.
struct Carry<V> {
    /// The error left by the last accepted step.
    carried: V,
    /// The error the step being tried leaves, kept if it is accepted.
    next: V,
}

impl<V: StateVector> Carry<V> {
    fn new() -> Carry<V> {
        Carry { carried: V::zeros(), next: V::zeros() }
    }
}

/// The new solution `y + h Σ_j b_j k_j` ([`combine_row`]'s sum), the
/// increment added to `y` with the error carried in, and the sum's own
/// rounding error kept in `carry.next`.
#[inline(always)]
fn solution_row<V: StateVector, const S: usize>(
    y: &V,
    h: f64,
    b: &[f64],
    k: &[V],
    carry: &mut Carry<V>,
    y_new: &mut V,
) {
    let Some(k) = k.first_chunk::<S>() else { return };
    let Some(b) = b.first_chunk::<S>() else { return };
    let Some((newest, older)) = k.split_last() else { return };
    let h_newest = h * b[S - 1];
    let out = y_new.as_mut();
    let n = out.len();
    let (y, carried, next) =
        (&y.as_ref()[..n], &carry.carried.as_ref()[..n], &mut carry.next.as_mut()[..n]);
    for (i, ((o, yv), (c, e))) in
        out.iter_mut().zip(y).zip(carried.iter().zip(next.iter_mut())).enumerate()
    {
        let sum = older_terms(b, older, i);
        let increment =
            if b[S - 1] == 0.0 { h * sum } else { h * sum + h_newest * newest.as_ref()[i] };
        let t = increment + c;
        let s = yv + t;
        // Exact when |y| ≥ |t| (Dekker's Fast2Sum): the part of t the sum lost.
        *e = t - (s - yv);
        *o = s;
    }
}

/// Stage `S` of one step: `k[S] = f(t + c_S h, y + h Σ_{j<S} a_Sj k_j)`,
/// the last stage at `y_new`.
#[inline(always)]
fn stage<M: Model, P: EmbeddedPair, const S: usize>(
    rhs: &mut Rhs<'_, M>,
    t: f64,
    h: f64,
    y: &M::State,
    k: &mut [M::State],
    stage: &mut M::State,
    (y_new, carry): (&mut M::State, &mut Carry<M::State>),
) -> Result<(), (f64, EvalError)> {
    if S >= P::STAGES {
        return Ok(());
    }
    if S + 1 < P::STAGES {
        return interior_stage::<M, P, S>(rhs, t, h, y, k, stage);
    }
    let (done, rest) = k.split_at_mut(S);
    solution_row::<M::State, S>(y, h, P::coefficients()[S], done, carry, y_new);
    rhs.call(t + h, y_new.as_ref(), rest[0].as_mut()).map_err(|cause| (t + h, cause))
}

/// Stage `S` at an interior point, a step's own or the dense output's:
/// `k[S] = f(t + c_S h, y + h Σ_{j<S} a_Sj k_j)`, the point in `stage`.
#[inline(always)]
fn interior_stage<M: Model, P: EmbeddedPair, const S: usize>(
    rhs: &mut Rhs<'_, M>,
    t: f64,
    h: f64,
    y: &M::State,
    k: &mut [M::State],
    stage: &mut M::State,
) -> Result<(), (f64, EvalError)> {
    let (done, rest) = k.split_at_mut(S);
    combine_row::<M::State, S>(y, h, P::coefficients()[S], done, stage);
    let ts = t + P::nodes()[S] * h;
    rhs.call(ts, stage.as_ref(), rest[0].as_mut()).map_err(|cause| (ts, cause))
}

/// The most stages of a pair (DOP853's 12 and the new solution's).
const MAX_STAGES: usize = 13;

/// Stages 1.. of one step from `(t, y)` with `k[0] = f(t, y)` given: fills
/// `k`, the new solution `y_new` (with the rounding error carried in
/// `carry`) and f at it (the last stage). On failure, the time of the
/// evaluation that failed.
///
/// A function of its own, not inlined into the step loop: inlined there,
/// DOP853's twelve stages and the loop's bookkeeping made one body so
/// large that on Arenstorf (AVX2 build) a step took 1.24× `ode_solvers`'
/// time; on its own, 0.79–0.82× (Lorenz 0.66–0.70×, DOPRI5 0.60–0.74×).
#[allow(clippy::too_many_arguments)]
#[inline(never)]
fn stages<M: Model, P: EmbeddedPair>(
    rhs: &mut Rhs<'_, M>,
    t: f64,
    h: f64,
    y: &M::State,
    k: &mut [M::State],
    s: &mut M::State,
    y_new: &mut M::State,
    carry: &mut Carry<M::State>,
) -> Result<(), (f64, EvalError)> {
    const { assert!(P::STAGES <= MAX_STAGES) };
    macro_rules! stages {
        ($($s:literal),*) => {$(
            stage::<M, P, $s>(rhs, t, h, y, k, s, (&mut *y_new, &mut *carry))?;
        )*};
    }
    stages!(1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12);
    Ok(())
}

/// The dense output's extra stages after an accepted step (DOP853's
/// three; none for DOPRI5), each row a constant as the step's own.
fn dense_stages<M: Model, P: EmbeddedPair>(
    rhs: &mut Rhs<'_, M>,
    t: f64,
    h: f64,
    y: &M::State,
    k: &mut [M::State],
    stage: &mut M::State,
) -> Result<(), (f64, EvalError)> {
    // The indices below cover every pair's dense stages.
    const { assert!(P::DENSE_STAGES == 0 || (P::STAGES >= 7 && P::STAGES + P::DENSE_STAGES <= 16)) };
    // Each index past the step's own stages, with its row a constant.
    macro_rules! dense_stages {
        ($($s:literal),*) => {$(
            if (P::STAGES..P::STAGES + P::DENSE_STAGES).contains(&$s) {
                interior_stage::<M, P, $s>(rhs, t, h, y, k, stage)?;
            }
        )*};
    }
    dense_stages!(7, 8, 9, 10, 11, 12, 13, 14, 15);
    Ok(())
}

/// What a run does about stiffness.
pub(crate) enum Stiffness {
    /// Nothing (`Options::stiffness_detection(false)`).
    Ignore,
    /// Stops with [`Error::Stiff`] when Hairer's test finds the problem
    /// stiff: h·ρ beyond the stability boundary for 15 steps.
    Fail,
    /// Returns [`Finish::StiffAt`] when this test fires (`Method::Auto`).
    Switch(StiffnessTest),
}

/// An explicit pair on its own: it stops with `Error::Stiff` where the
/// problem turns stiff, unless told not to look.
pub(crate) fn integrate_alone<M: Model, P: EmbeddedPair>(
    problem: Problem<'_, M>,
    solution: Solution,
) -> Result<Solution, Error> {
    let watch = problem.options.stiffness_detection;
    let stiffness = if watch { Stiffness::Fail } else { Stiffness::Ignore };
    integrate::<M, P>(problem, stiffness, solution).map(|r| r.0)
}

/// Integrates `model` from `t0` to `t1` (either direction) with pair `P`.
pub(crate) fn integrate<M: Model, P: EmbeddedPair>(
    problem: Problem<'_, M>,
    stiffness: Stiffness,
    solution: Solution,
) -> Result<(Solution, Finish), Error> {
    let dense = DenseOutput { width: P::DENSE_WIDTH, interpolate: P::interpolate };
    let run = Driver::new(&problem, solution, Some(dense), 1);
    let Problem { model, t0, y0, options, .. } = problem;
    integrate_from::<M, P>(model, t0, y0, options, stiffness, run)
}

/// The step loop of [`integrate`], its inputs as separate arguments: taking
/// the one `Problem` value, it ran 6 % slower (DOP853 on Kepler at 1e-12 …
/// 1e-14, timed in alternation with `ode_solvers`' DOP853).
fn integrate_from<M: Model, P: EmbeddedPair>(
    model: &M,
    t0: f64,
    y0: &[f64],
    options: &crate::options::Options,
    stiffness: Stiffness,
    mut run: Driver<'_, M>,
) -> Result<(Solution, Finish), Error> {
    let n = M::STATES;
    let (rtol, atol) = (options.rtol, options.atol);
    let mut test = match stiffness {
        Stiffness::Ignore => None,
        Stiffness::Fail => Some(StiffnessTest::new(P::STIFFNESS_BOUND, 15)),
        Stiffness::Switch(test) => Some(test),
    };
    let fail_when_stiff = matches!(stiffness, Stiffness::Fail);
    let controller = P::controller();
    let mut k = vec![M::State::zeros(); P::STAGES + P::DENSE_STAGES];
    let (mut y, mut y_new, mut stage) = (M::State::zeros(), M::State::zeros(), M::State::zeros());
    let mut carry = Carry::<M::State>::new();
    let mut weights = M::State::zeros();
    // The error test's states (the model's own, where sensitivities are
    // left out of it), and the factor from the norm over all to theirs
    // (none for a model without states, every variable a function of the
    // time: its error is zero).
    let n_error = crate::methods::error_states::<M>(options);
    let error_dilution = if n_error == 0 { 1.0 } else { (n as f64 / n_error as f64).sqrt() };
    let mut dense = vec![0.0; P::DENSE_WIDTH * n];
    let mut rhs = Rhs { model, counts: Counts::default() };

    y.as_mut().copy_from_slice(y0);
    if let Err(cause) = rhs.call(t0, y.as_ref(), k[0].as_mut()) {
        return Err(run.evaluation_failed(t0, cause, &rhs.counts));
    }
    if let Some(i) = k[0].as_ref().iter().position(|v| !v.is_finite()) {
        return Err(run.non_finite(t0, i, &Counts::default()));
    }
    if t0 == run.t1 {
        return Ok((run.finish(&Counts::default()), Finish::Done));
    }
    let mut h = match options.initial_step {
        Some(h0) => h0.abs().min(run.hmax),
        None => first_step::<M, P>(&mut rhs, t0, &y, &mut k, &mut stage, &run, options),
    } * run.direction;

    let (mut t, mut compensation) = (t0, 0.0);
    let mut pi = PiState::default();
    let mut last_rejected = false;
    let mut non_finite: Option<usize> = None;
    loop {
        run.check_steps(t, &rhs.counts)?;
        if run.step_too_small(t, h) {
            return Err(run.fail(&rhs.counts, |partial| match non_finite {
                Some(i) => Error::NonFinite { t, variable: M::INFO.states[i], partial },
                None => Error::StepSizeUnderflow { t, h, partial },
            }));
        }
        let last = run.reaches_end(t, 1.01 * h);
        if last {
            h = run.t1 - t;
        }
        if let Err((ts, cause)) =
            stages::<M, P>(&mut rhs, t, h, &y, &mut k, &mut stage, &mut y_new, &mut carry)
        {
            return Err(run.evaluation_failed(ts, cause, &rhs.counts));
        }
        error_weights(atol, rtol, y.as_ref(), y_new.as_ref(), weights.as_mut());
        // Sensitivities left out of the error test weigh nothing, and the
        // norm is the one over the states left in it.
        weights.as_mut()[n_error..].fill(0.0);
        let err = P::error(h, &k[..P::STAGES], &weights, M::LANES) * error_dilution;
        if !err.is_finite() {
            // A stage left the domain of f: retry with a much smaller step,
            // and name the variable if the step underflows.
            non_finite = (0..n).find(|&i| {
                !y_new.as_ref()[i].is_finite()
                    || k[..P::STAGES].iter().any(|ks| !ks.as_ref()[i].is_finite())
            });
            h *= 0.1;
            run.rejected += 1;
            last_rejected = true;
            continue;
        }
        if err > 1.0 {
            h *= controller.rejected_factor(err);
            run.rejected += 1;
            last_rejected = true;
            continue;
        }
        // h·ρ from the last two stages, both at t + h (before the dense
        // stages reuse `stage`), where a stiffness test reads it.
        let (turned_stiff, h_rho) = match test.as_mut() {
            Some(test) => {
                let h_rho = stage_quotient(
                    h,
                    k[P::STAGES - 1].as_ref(),
                    k[P::STAGES - 2].as_ref(),
                    y_new.as_ref(),
                    stage.as_ref(),
                );
                let change = || relative_change(y.as_ref(), y_new.as_ref(), weights.as_ref());
                (test.step_is_stiff(t + h, h_rho, change), h_rho)
            }
            None => (false, 0.0),
        };
        let (factor, state) = controller.factor(err, pi);
        pi = state;
        if run.keep_dense() {
            if let Err((ts, cause)) = dense_stages::<M, P>(&mut rhs, t, h, &y, &mut k, &mut stage) {
                return Err(run.evaluation_failed(ts, cause, &rhs.counts));
            }
            P::dense_coefficients(h, &y, &y_new, &k, &mut dense);
        }
        // Compensated summation: long runs keep t exact to rounding.
        let step = h - compensation;
        let t_next = t + step;
        compensation = (t_next - t) - step;
        t = if last { run.t1 } else { t_next };
        std::mem::swap(&mut y, &mut y_new);
        std::mem::swap(&mut carry.carried, &mut carry.next);
        if run.project(t, y.as_mut(), &rhs.counts)? {
            // The carried rounding errors belong to the state before it moved.
            carry.carried = M::State::zeros();
            // The last stage was evaluated before the projection.
            if let Err(cause) = rhs.call(t, y.as_ref(), k[0].as_mut()) {
                return Err(run.evaluation_failed(t, cause, &rhs.counts));
            }
        } else {
            k[0] = k[P::STAGES - 1];
        }
        non_finite = None;
        if run.record(t, y.as_ref(), &dense, &rhs.counts)? || last {
            break;
        }
        if turned_stiff {
            let solution = run.finish(&rhs.counts);
            if fail_when_stiff {
                let onset = test.map_or(t, |test| test.onset());
                return Err(Error::Stiff { t, onset, h, h_rho, partial: Box::new(solution) });
            }
            return Ok((solution, Finish::StiffAt { t, h, h_rho }));
        }
        h = run.next_step(h * factor, h, last_rejected);
        last_rejected = false;
    }
    Ok((run.finish(&rhs.counts), Finish::Done))
}

/// The first step when none is given: Hairer's estimate from the initial
/// derivatives ([`initial_step`]), `k[0]` holding f(t0, y0).
fn first_step<M: Model, P: EmbeddedPair>(
    rhs: &mut Rhs<'_, M>,
    t0: f64,
    y: &M::State,
    k: &mut [M::State],
    stage: &mut M::State,
    run: &Driver<'_, M>,
    options: &crate::options::Options,
) -> f64 {
    let (f0, rest) = k.split_at_mut(1);
    let mut f = |t: f64, y: &[f64], out: &mut [f64]| rhs.call(t, y, out).is_ok();
    initial_step(
        &mut f,
        t0,
        y.as_ref(),
        f0[0].as_ref(),
        run.direction,
        P::ORDER,
        run.hmax,
        (options.atol, options.rtol),
        stage.as_mut(),
        rest[0].as_mut(),
        M::LANES,
    )
}

/// ‖y_new − y‖/‖y‖ in the norm the tolerances weigh by (`weights` holds
/// 1 / (atol + rtol·|y|)): how much the step changed the solution.
#[inline]
fn relative_change(y: &[f64], y_new: &[f64], weights: &[f64]) -> f64 {
    let (mut change, mut size) = (0.0, 0.0);
    for ((a, b), w) in y.iter().zip(y_new).zip(weights) {
        change += ((b - a) * w).powi(2);
        size += (a * w).powi(2);
    }
    if size > 0.0 {
        (change / size).sqrt()
    } else {
        f64::INFINITY
    }
}

/// The sums over components `0..n` of the squares of `terms(i)`, each in
/// four partial sums (components i ≡ 0, 1, 2, 3 mod 4) joined pairwise at
/// the end: one running sum is a chain of n dependent additions after the
/// last stage (on the outer solar system's 36 states, DOP853's error took
/// 11 % of a step), four are a quarter of it and vectorise.
#[inline(always)]
pub(crate) fn sums_of_squares<const K: usize>(
    n: usize,
    terms: impl Fn(usize) -> [f64; K],
) -> [f64; K] {
    let mut partial = [[0.0f64; 4]; K];
    let whole = n / 4 * 4;
    for base in (0..whole).step_by(4) {
        for lane in 0..4 {
            for (p, v) in partial.iter_mut().zip(terms(base + lane)) {
                p[lane] += v * v;
            }
        }
    }
    for i in whole..n {
        for (p, v) in partial.iter_mut().zip(terms(i)) {
            p[i - whole] += v * v;
        }
    }
    partial.map(|p| (p[0] + p[1]) + (p[2] + p[3]))
}

/// The worst over `lanes` lanes of `norm(sums)`, where `sums` holds each
/// lane's sums of the squared scaled error terms `terms(i)` of components
/// `i ≡ lane (mod lanes)`: the per-member error of a batch.
#[inline(never)]
pub(crate) fn worst_lane<const K: usize>(
    n: usize,
    lanes: usize,
    terms: impl Fn(usize) -> [f64; K],
    norm: impl Fn([f64; K], usize) -> f64,
) -> f64 {
    let per_lane = n / lanes.max(1);
    let mut worst = 0.0f64;
    for lane in 0..lanes {
        // Summed as a member alone sums its own: equal members take its steps.
        let sums = sums_of_squares(per_lane, |c| terms(c * lanes + lane));
        worst = worst.max(norm(sums, per_lane));
    }
    worst
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::info::ModelInfo;
    use crate::methods::dop853::Dop853;
    use crate::methods::dopri5::Dopri5;

    // Written out like the GGL pendulum of radau5's tests: unit tests
    // of the runtime cannot use the macro.
    /// Kepler problem with e = 0.5 written by hand (the runtime cannot use
    /// the macro): q'' = -q/|q|³.
    #[derive(Clone)]
    struct Kepler;

    impl Model for Kepler {
        const STATES: usize = 4;
        type State = [f64; 4];
        const INDEX: usize = 0;
        const INFO: ModelInfo = ModelInfo::bare("Kepler", &["q1", "q2", "p1", "p2"], 4);
        fn initial_state(&self, y: &mut [f64]) {
            y.copy_from_slice(&exact(0.0));
        }
        fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), EvalError> {
            let r3 = (y[0] * y[0] + y[1] * y[1]).powf(-1.5);
            dy.copy_from_slice(&[y[2], y[3], -y[0] * r3, -y[1] * r3]);
            Ok(())
        }
    }

    const E: f64 = 0.5;

    /// Exact state at t from Kepler's equation E − e sin E = t.
    fn exact(t: f64) -> [f64; 4] {
        let mut big_e = t + E * t.sin();
        for _ in 0..50 {
            big_e -= (big_e - E * big_e.sin() - t) / (1.0 - E * big_e.cos());
        }
        let (s, c) = big_e.sin_cos();
        let w = (1.0 - E * E).sqrt();
        [c - E, w * s, -s / (1.0 - E * c), w * c / (1.0 - E * c)]
    }

    /// Error of one step of size h from the exact state at t.
    fn local_error<P: EmbeddedPair>(t: f64, h: f64) -> f64 {
        let mut rhs = Rhs { model: &Kepler, counts: Counts::default() };
        let y = exact(t);
        let mut k = vec![[0.0; 4]; P::STAGES + P::DENSE_STAGES];
        let (mut stage, mut y_new) = ([0.0; 4], [0.0; 4]);
        rhs.call(t, &y, &mut k[0]).unwrap();
        let mut carry = Carry::new();
        stages::<Kepler, P>(&mut rhs, t, h, &y, &mut k, &mut stage, &mut y_new, &mut carry)
            .unwrap();
        let want = exact(t + h);
        y_new.iter().zip(want).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max)
    }

    /// Local error O(h^(p+1)): halving h divides it by 2^(p+1).
    fn observed_local_order<P: EmbeddedPair>(t: f64, h: f64) -> f64 {
        (local_error::<P>(t, h) / local_error::<P>(t, h / 2.0)).log2() - 1.0
    }

    #[test]
    fn dopri5_has_order_5() {
        // The asymptotic range starts late on Kepler near perihelion: at
        // h = 0.1 the observed order is 5.6, at 0.0125 it is 5.2, tending to 5.
        let p = observed_local_order::<Dopri5>(0.3, 0.0125);
        assert!((p - 5.0).abs() < 0.25, "observed order {p:.3}");
    }

    #[test]
    fn dop853_has_order_8() {
        // Near perihelion the asymptotic range starts where the error is
        // at rounding level (1 ulp at h = 0.025 from t = 0.3). At aphelion
        // (t = π) the solution varies slowest: from t = 3 the observed
        // order is 8.02–8.05 for h from 0.35 to 0.6, and the error at
        // h/2 = 0.25 is 1e-13, far above rounding.
        let p = observed_local_order::<Dop853>(3.0, 0.5);
        assert!((p - 8.0).abs() < 0.3, "observed order {p:.3}");
    }

    /// The dense output interpolates the step to its own order: halving h
    /// divides the error at the step's midpoint by about 2^(q+1).
    fn dense_error<P: EmbeddedPair>(h: f64) -> f64 {
        let t = 0.3;
        let mut rhs = Rhs { model: &Kepler, counts: Counts::default() };
        let y = exact(t);
        let n = 4;
        let mut k = vec![[0.0; 4]; P::STAGES + P::DENSE_STAGES];
        let (mut stage, mut y_new) = ([0.0; 4], [0.0; 4]);
        rhs.call(t, &y, &mut k[0]).unwrap();
        let mut carry = Carry::new();
        stages::<Kepler, P>(&mut rhs, t, h, &y, &mut k, &mut stage, &mut y_new, &mut carry)
            .unwrap();
        dense_stages::<Kepler, P>(&mut rhs, t, h, &y, &mut k, &mut stage).unwrap();
        let mut dense = vec![0.0; P::DENSE_WIDTH * n];
        P::dense_coefficients(h, &y, &y_new, &k, &mut dense);
        let want = exact(t + 0.37 * h);
        (0..n).map(|i| (P::interpolate(&dense, n, i, 0.37) - want[i]).abs()).fold(0.0, f64::max)
    }

    #[test]
    fn dense_output_has_the_promised_order() {
        let q5 = (dense_error::<Dopri5>(0.0125) / dense_error::<Dopri5>(0.00625)).log2() - 1.0;
        assert!((q5 - 4.0).abs() < 0.3, "DOPRI5 dense order {q5:.3}");
        let q8 = (dense_error::<Dop853>(0.1) / dense_error::<Dop853>(0.05)).log2() - 1.0;
        assert!((q8 - 7.0).abs() < 0.3, "DOP853 dense order {q8:.3}");
    }
}
