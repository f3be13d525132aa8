//! What a step loop does that is not its method: the limits a run keeps
//! (its steps, the smallest step, the largest), what becomes of an
//! accepted step (the check for non-finite states, the projection onto the
//! constraints, storing it with its dense output, the events and the step
//! callback), the watch for the end of stiffness, and the statistics and
//! partial solution that every way out of the loop carries. A method keeps
//! its step, its error estimate and its step-size control, and calls the
//! driver around them.

use crate::error::Error;
use crate::info::EvalError;
use crate::model::Model;
use crate::solution::{Interpolant, Solution};
use crate::step::events::EventWatch;
use crate::step::projection::{Projector, STEP_ITERATIONS};
use crate::step::stiffness::NonStiffWatch;
use crate::step::Problem;

/// What a method counts as it runs, added to the solution's statistics
/// however the run ends (the driver counts the steps).
#[derive(Clone, Copy, Default)]
pub(crate) struct Counts {
    /// Evaluations of the right-hand side (or of a Taylor jet).
    pub(crate) evals: usize,
    /// Evaluations of the Jacobian.
    pub(crate) jacobian_evals: usize,
    /// How the linear systems were solved (`Newton::label`); empty for a
    /// method that solves none, which leaves the statistics' own.
    pub(crate) linear_solver: &'static str,
    /// GMRES's iterations.
    pub(crate) linear_iterations: usize,
}

/// The dense output a method offers: coefficients per state and the
/// function that interpolates them.
#[derive(Clone, Copy)]
pub(crate) struct DenseOutput {
    /// Coefficients of one state's polynomial.
    pub(crate) width: usize,
    /// Component `i` at `s = (t − t_old)/h` from the step's coefficients.
    pub(crate) interpolate: Interpolant,
}

/// One run's step loop around its method: see the module's documentation.
pub(crate) struct Driver<'m, M: Model> {
    /// The end of the interval.
    pub(crate) t1: f64,
    /// +1 forwards in time, −1 backwards.
    pub(crate) direction: f64,
    /// The largest step: [`crate::Options::max_step`], at most the interval.
    pub(crate) hmax: f64,
    /// Steps accepted and rejected so far.
    pub(crate) accepted: usize,
    pub(crate) rejected: usize,
    max_steps: usize,
    min_step: f64,
    events: Option<EventWatch<'m, M>>,
    projector: Option<Projector<'m, M>>,
    keep_dense: bool,
    /// The watch for the end of stiffness, and the steps in a row it saw
    /// below its bound.
    non_stiff: Option<(NonStiffWatch, usize)>,
    solution: Solution,
}

// What runs every step is inlined always: left to the compiler, `record`
// stayed a call, which cost DOPRI5 25 instructions a step on Lorenz (3
// states); inlined, the loop takes 1 % fewer than with the code written out
// in each method. The ways out of the loop are cold.
impl<'m, M: Model> Driver<'m, M> {
    /// The driver of `problem`'s run, recording into `solution`. Where the
    /// run keeps dense output (asked for, or for the events to read), the
    /// method's `dense` is the interpolant of the steps it stores; `event_samples`
    /// sub-intervals of each step are searched for an event's sign change.
    pub(crate) fn new(
        problem: &Problem<'m, M>,
        mut solution: Solution,
        dense: Option<DenseOutput>,
        event_samples: usize,
    ) -> Driver<'m, M> {
        let Problem { model, t0, t1, y0, options } = *problem;
        let events = EventWatch::new(model, t0, y0, event_samples);
        let keep_dense = dense.is_some() && (options.dense_output || events.is_some());
        if let (true, Some(dense)) = (keep_dense, dense) {
            solution.set_interpolant(dense.width, dense.interpolate);
        }
        let span = (t1 - t0).abs();
        Driver {
            t1,
            direction: if t1 >= t0 { 1.0 } else { -1.0 },
            hmax: options.max_step.unwrap_or(span).min(span),
            accepted: 0,
            rejected: 0,
            max_steps: options.max_steps,
            min_step: options.min_step,
            events,
            projector: Projector::new(model),
            keep_dense,
            non_stiff: None,
            solution,
        }
    }

    /// The same, watching for the end of stiffness: [`Driver::calm`] says
    /// when `watch` would hand back to an explicit method.
    pub(crate) fn watching(mut self, watch: Option<NonStiffWatch>) -> Driver<'m, M> {
        self.non_stiff = watch.map(|w| (w, 0));
        self
    }

    /// Whether the run stores each step's dense output.
    #[inline(always)]
    pub(crate) fn keep_dense(&self) -> bool {
        self.keep_dense
    }

    /// Whether a step of `h` from `t` reaching `reach` further ends at or
    /// past the interval's end: the methods step onto the end when within
    /// a margin of it rather than leave a sliver.
    #[inline(always)]
    pub(crate) fn reaches_end(&self, t: f64, reach: f64) -> bool {
        (t + reach - self.t1) * self.direction >= 0.0
    }

    /// The next step from the controller's proposal `h_new`: at most the
    /// largest step, and after a rejection no longer than the step `h`
    /// that was accepted (Hairer's codes), signed in the run's direction.
    #[inline(always)]
    pub(crate) fn next_step(&self, h_new: f64, h: f64, after_rejection: bool) -> f64 {
        let bound = if after_rejection { h.abs().min(self.hmax) } else { self.hmax };
        self.direction * h_new.abs().min(bound)
    }

    /// `Error::MaxSteps` once the run has tried all the steps it may.
    #[inline(always)]
    pub(crate) fn check_steps(&mut self, t: f64, counts: &Counts) -> Result<(), Error> {
        if self.accepted + self.rejected < self.max_steps {
            return Ok(());
        }
        let max_steps = self.max_steps;
        Err(self.fail(counts, |partial| Error::MaxSteps { t, max_steps, partial }))
    }

    /// Whether a step of `h` from `t` is too small to go on with: below
    /// [`crate::Options::min_step`], or so small that `t + h` is `t` to
    /// within ten units of rounding (Hairer's codes' test).
    #[inline(always)]
    pub(crate) fn step_too_small(&self, t: f64, h: f64) -> bool {
        0.1 * h.abs() <= t.abs().max(1e-300) * f64::EPSILON || h.abs() < self.min_step
    }

    /// `Error::NonFinite` naming the first state of `y` that is NaN or
    /// infinite at `t`.
    #[inline(always)]
    pub(crate) fn check_finite(&mut self, t: f64, y: &[f64], counts: &Counts) -> Result<(), Error> {
        match y.iter().position(|v| !v.is_finite()) {
            None => Ok(()),
            Some(i) => Err(self.non_finite(t, i, counts)),
        }
    }

    /// `Error::NonFinite` for state `i` at `t`.
    #[cold]
    #[inline(never)]
    pub(crate) fn non_finite(&mut self, t: f64, i: usize, counts: &Counts) -> Error {
        let variable = M::INFO.states[i];
        self.fail(counts, |partial| Error::NonFinite { t, variable, partial })
    }

    /// Projects the accepted step's `y` at `t` onto the constraints (models
    /// without any skip this): `true` when the state moved.
    #[inline(always)]
    pub(crate) fn project(
        &mut self,
        t: f64,
        y: &mut [f64],
        counts: &Counts,
    ) -> Result<bool, Error> {
        let Some(projector) = self.projector.as_mut() else { return Ok(false) };
        match projector.project(t, y, STEP_ITERATIONS, None) {
            Ok(residuals) => {
                self.solution.note_constraint_residuals(residuals);
                Ok(!M::PROJECTION.is_empty())
            }
            Err(f) => {
                let c = &M::CONSTRAINTS[f.row];
                let (constraint, level, message) = (c.equation, c.level, f.message);
                Err(self.fail(counts, |partial| Error::Constraint {
                    t,
                    constraint,
                    level,
                    message,
                    partial,
                }))
            }
        }
    }

    /// Stores the accepted step to `(t, y)` with its dense coefficients
    /// `dense` (read where the run keeps them), counts it, and shows it to
    /// the events and the step callback: `true` when a terminal event or
    /// the callback ended the run there.
    #[inline(always)]
    pub(crate) fn record(
        &mut self,
        t: f64,
        y: &[f64],
        dense: &[f64],
        counts: &Counts,
    ) -> Result<bool, Error> {
        self.accepted += 1;
        if self.keep_dense {
            self.solution.push_dense(t, y, dense);
        } else {
            self.solution.push(t, y);
        }
        if let Some(events) = self.events.as_mut() {
            match events.after_step(&mut self.solution) {
                Ok(true) => return Ok(true),
                Ok(false) => {}
                Err(mut e) => {
                    if let Some(partial) = e.partial_solution_mut() {
                        self.add_counts(counts, partial);
                    }
                    return Err(e);
                }
            }
        }
        Ok(self.solution.after_accepted_step())
    }

    /// Whether the watch for the end of stiffness, seeing a step with
    /// h·ρ = `h_rho`, says to hand back: its bound held for its number
    /// of steps in a row. Never without a watch.
    #[inline(always)]
    pub(crate) fn calm(&mut self, h_rho: f64) -> bool {
        let Some((watch, calm)) = self.non_stiff.as_mut() else { return false };
        *calm = if h_rho < watch.below { *calm + 1 } else { 0 };
        *calm >= watch.confirmations
    }

    /// The error `error` builds from the solution so far, its statistics
    /// counted. The run ends with it.
    #[cold]
    #[inline(never)]
    pub(crate) fn fail(
        &mut self,
        counts: &Counts,
        error: impl FnOnce(Box<Solution>) -> Error,
    ) -> Error {
        let mut partial = self.solution.take();
        self.add_counts(counts, &mut partial);
        error(partial)
    }

    /// `Error::Evaluation`: the model could not be evaluated at `t`.
    #[cold]
    #[inline(never)]
    pub(crate) fn evaluation_failed(&mut self, t: f64, cause: EvalError, counts: &Counts) -> Error {
        self.fail(counts, |partial| Error::Evaluation { t, cause, partial })
    }

    /// The run's solution, its statistics counted.
    pub(crate) fn finish(self, counts: &Counts) -> Solution {
        let (accepted, rejected) = (self.accepted, self.rejected);
        let mut solution = self.solution;
        add_counts(&mut solution, (accepted, rejected), counts);
        solution
    }

    /// Adds the steps and `counts` to the statistics of `solution`, the
    /// run's (once: the run ends after).
    fn add_counts(&self, counts: &Counts, solution: &mut Solution) {
        add_counts(solution, (self.accepted, self.rejected), counts);
    }
}

/// Adds `(accepted, rejected)` steps and `counts` to the statistics of
/// `solution`.
fn add_counts(solution: &mut Solution, (accepted, rejected): (usize, usize), counts: &Counts) {
    let stats = solution.stats_mut();
    stats.steps += accepted;
    stats.rejected += rejected;
    stats.rhs_evals += counts.evals;
    stats.jacobian_evals += counts.jacobian_evals;
    if !counts.linear_solver.is_empty() {
        stats.linear_solver = counts.linear_solver;
    }
    stats.linear_iterations += counts.linear_iterations;
}
