//! The result of a run: what it stored of its steps, statistics, and
//! values by name (states, algebraic variables, outputs) on request.
//!
//! `record.rs` is how a run fills a solution step by step (which steps it
//! keeps, the last step it always keeps, the output times it interpolates);
//! `stream.rs` the callback and progress bar that watch it; `query.rs`
//! what a user asks of the result; this file the data and its plain
//! accessors.

mod query;
mod record;
mod stream;
pub mod table;

use crate::info::{EventInfo, ModelInfo};
use record::{LastStep, Storage};
use std::sync::Arc;
use stream::Stream;

/// Counters of a run.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Stats {
    /// Accepted steps.
    pub steps: usize,
    /// Rejected steps (adaptive methods).
    pub rejected: usize,
    /// Evaluations of the right-hand side.
    pub rhs_evals: usize,
    /// Evaluations of the Jacobian.
    pub jacobian_evals: usize,
    /// The methods that ran, in order: `"Dopri5"`, or for `Method::Auto`
    /// the chain it switched along, `"Dopri5→Radau5"` (`"Dopri5⇄Radau5"`
    /// beyond four stretches; [`Stats::switches`] counts them).
    pub method: &'static str,
    /// How often `Method::Auto` switched between its explicit pair and
    /// its stiff method (0 for every other method).
    pub switches: usize,
    /// How the model was integrated: an ODE, or which DAE formulation.
    pub formulation: &'static str,
    /// How the stiff methods solved their linear systems: `"dense LU"`,
    /// `"band LU"`, `"sparse LU"` or `"GMRES"` ("" where no stiff method
    /// ran; see [`crate::LinearSolver`]).
    pub linear_solver: &'static str,
    /// GMRES iterations, each one product with the matrix and one
    /// preconditioner solve (0 for the LU factorisations).
    pub linear_iterations: usize,
    /// `Method::Taylor`'s order (0 for the other methods).
    pub taylor_order: usize,
    /// Whether that order ran as the macro's straight-line recurrences
    /// (`#[dae_model(unroll = [..])]`) rather than the interpreted tape.
    pub taylor_unrolled: bool,
}

/// An initial value that consistent initialization moved: the constraints
/// of a DAE (or the algebraic equations of a mass-matrix model) did not
/// hold at the value given, and the run started from `used` instead.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct InitialCorrection {
    /// The state, as [`crate::ModelInfo::states`] names it.
    pub name: &'static str,
    /// The value given (by the model's `state(..)`, or to `simulate_from`).
    pub given: f64,
    /// The value the run started from.
    pub used: f64,
}

/// The largest constraint residuals at one point, by level.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Residuals {
    /// |Φ| of the constraints as written.
    pub(crate) position: f64,
    /// |Φ̇|: the constraints differentiated once.
    pub(crate) velocity: f64,
}

/// A crossing of an event function, located to machine precision.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct EventHit {
    /// The event's `let` name.
    pub name: &'static str,
    /// Its position in [`crate::ModelInfo::events`].
    pub index: usize,
    /// The time of the crossing: the first floating-point time past the zero.
    pub t: f64,
    /// The event function went from negative to positive (else the reverse).
    pub rising: bool,
    /// The state at `t`, from the step's continuous extension.
    pub state: Vec<f64>,
}

/// An instant where actions changed the state: the solution holds its
/// value on either side ([`Solution::at`] reads the value after,
/// [`Solution::at_left`] the value before).
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Jump {
    /// The time.
    pub t: f64,
    /// The state just before (the left limit).
    pub before: Vec<f64>,
    /// The state just after, where the run went on from.
    pub after: Vec<f64>,
    /// What acted, by name: events and clocks, in the order they fired.
    pub triggers: Vec<&'static str>,
}

/// What a solution needs of its model after the run (outputs by name, and
/// the derivative that fixed-step methods interpolate with), so that
/// `Solution` has no type parameter.
pub(crate) trait Observables: Send + Sync {
    fn output(&self, index: usize, t: f64, y: &[f64]) -> f64;
    /// y' at `(t, y)`; `false` where the model has none to give (a mass
    /// matrix, or a failed evaluation).
    fn derivative(&self, t: f64, y: &[f64], dy: &mut [f64]) -> bool;
}

/// The names of a model's values, fixed at compile time.
#[derive(Clone, Copy)]
pub(crate) struct Names {
    model: &'static str,
    states: &'static [&'static str],
    outputs: &'static [&'static str],
    algebraics: &'static [&'static str],
    events: &'static [EventInfo],
    discrete: &'static [&'static str],
}

impl Names {
    /// The names in a model's [`ModelInfo`].
    pub(crate) fn of(info: &ModelInfo) -> Names {
        Names {
            model: info.name,
            states: info.states,
            outputs: info.outputs,
            algebraics: info.algebraics,
            events: info.events,
            discrete: info.discrete,
        }
    }
}

/// The stored steps of a run, and its end.
///
/// What is stored follows the options: every accepted step (the default,
/// with the method's dense output between them), every k-th
/// ([`crate::Options::keep_every`]), or only given times
/// ([`crate::Options::output_times`]). Values are read by name: a state
/// (`"x"`, `"der(x)"`), an algebraic variable or an output.
#[derive(Clone)]
pub struct Solution {
    n: usize,
    names: Names,
    observables: Arc<dyn Observables>,
    /// The stored times, and the states at them (time k's state at
    /// `states[k * n .. (k + 1) * n]`).
    times: Vec<f64>,
    states: Vec<f64>,
    /// Dense-output coefficients of the stored steps of each segment, read
    /// by the segment's interpolant (only when every step is stored).
    dense: Vec<f64>,
    /// One per method that ran (Method::Auto may switch), in step order.
    segments: Vec<Segment>,
    storage: Storage,
    /// The latest step, stored or not: events and output times read it.
    last: LastStep,
    /// Whether the latest step's states and coefficients are kept (only
    /// events and output times read them).
    track_last: bool,
    /// The end of the run: the latest step's end, or where a terminal
    /// event or the step callback ended it.
    end_t: f64,
    end_y: Vec<f64>,
    /// Steps accepted (the initial point not counted).
    steps: usize,
    /// The end the last step was computed for, when an event cut it
    /// short (its interpolant is scaled to that end).
    cut_from: Option<f64>,
    /// Stored steps an event cut short before the run went on, with the
    /// end each was computed for and the state there.
    cuts: Vec<(usize, f64, Vec<f64>)>,
    /// The instants where actions changed the state, with its value on
    /// either side.
    jumps: Vec<Jump>,
    /// The position in `events` of the terminal event that ended the run.
    stopped: Option<usize>,
    /// The events whose actions interrupted the run at its last instant.
    pending_actions: Vec<usize>,
    /// Where the step callback stopped the run.
    cancelled_at: Option<f64>,
    /// The step callback and progress bar, during the run.
    stream: Option<Stream>,
    /// Evaluations of y' made to interpolate (counted in the statistics).
    interpolation_evals: usize,
    /// Event crossings in time order.
    events: Vec<EventHit>,
    /// Largest |Φ| of the position-level constraints at the accepted steps.
    constraint_residual: f64,
    /// Largest |Φ̇| of their velocity level.
    velocity_residual: f64,
    /// n − rank Φ_q at the start, for a model with constraints.
    degrees_of_freedom: Option<usize>,
    /// The initial values consistent initialization moved.
    initial_corrections: Vec<InitialCorrection>,
    stats: Stats,
}

/// Steps from `first` on use `interpolant` on `width` vectors per step,
/// stored from `offset` in `dense`.
#[derive(Clone, Copy)]
struct Segment {
    first: usize,
    offset: usize,
    width: usize,
    interpolant: Interpolant,
}

/// Component `i` at `s = (t - t_old)/h` from one step's coefficients.
pub(crate) type Interpolant = fn(&[f64], usize, usize, f64) -> f64;

impl std::fmt::Debug for Solution {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Solution")
            .field("model", &self.names.model)
            .field("stored", &self.times.len())
            .field("interval", &(self.times.first(), self.end_t))
            .field("states", &self.names.states)
            .field("stats", &self.stats)
            .finish()
    }
}

impl Solution {
    /// The solution so far, for an error to carry, leaving an empty one in
    /// its place: a step loop checks its steps through `&mut` and gives
    /// the solution up only when it fails.
    pub(crate) fn take(&mut self) -> Box<Solution> {
        let empty = Solution::new(self.names, self.observables.clone(), self.n);
        Box::new(std::mem::replace(self, empty))
    }

    /// An empty solution of a model with these names and observables, for
    /// `n` states.
    pub(crate) fn new(names: Names, observables: Arc<dyn Observables>, n: usize) -> Solution {
        Solution {
            n,
            names,
            observables,
            times: Vec::with_capacity(1024),
            states: Vec::with_capacity(1024 * n),
            dense: Vec::new(),
            segments: Vec::new(),
            storage: Storage::All,
            last: LastStep::new(n),
            track_last: true,
            end_t: f64::NAN,
            end_y: Vec::new(),
            steps: 0,
            cut_from: None,
            cuts: Vec::new(),
            jumps: Vec::new(),
            stopped: None,
            pending_actions: Vec::new(),
            cancelled_at: None,
            stream: None,
            interpolation_evals: 0,
            events: Vec::new(),
            constraint_residual: 0.0,
            velocity_residual: 0.0,
            degrees_of_freedom: None,
            initial_corrections: Vec::new(),
            stats: Stats::default(),
        }
    }

    pub(crate) fn stats_mut(&mut self) -> &mut Stats {
        &mut self.stats
    }

    /// The stored times, the initial time first: every accepted step by
    /// default, every k-th with [`crate::Options::keep_every`] (and the
    /// end), or the [`crate::Options::output_times`] the run reached.
    pub fn times(&self) -> &[f64] {
        &self.times
    }

    /// The state vector at stored time `k`.
    pub fn state(&self, k: usize) -> Option<&[f64]> {
        self.states.get(k * self.n..(k + 1) * self.n)
    }

    /// The state at the end of the run (at a terminal event, or where the
    /// step callback stopped it, if either did).
    pub fn final_state(&self) -> &[f64] {
        &self.end_y
    }

    /// The name of the model that ran.
    pub fn model_name(&self) -> &'static str {
        self.names.model
    }

    /// The time the run ended at.
    pub fn final_time(&self) -> f64 {
        self.end_t
    }

    /// Every event crossing, in time order.
    pub fn events(&self) -> &[EventHit] {
        &self.events
    }

    /// The terminal event the run stopped at, if it did.
    pub fn stopped_by(&self) -> Option<&EventHit> {
        self.stopped.and_then(|k| self.events.get(k))
    }

    /// The instants where an event's or a clock's actions changed the
    /// state, in time order, each with the state just before and just
    /// after: a solution is never interpolated across them.
    pub fn jumps(&self) -> &[Jump] {
        &self.jumps
    }

    /// Where [`crate::Options::on_step`]'s callback stopped the run, if it did.
    pub fn cancelled_at(&self) -> Option<f64> {
        self.cancelled_at
    }

    /// Counters of the run.
    pub fn stats(&self) -> Stats {
        self.stats
    }

    /// Largest |Φ| of the user's constraints (not their derivatives) over
    /// the accepted steps, measured at each (after projection, in the
    /// projected formulation); 0 for an ODE, which has none.
    pub fn max_constraint_residual(&self) -> f64 {
        self.constraint_residual
    }

    /// Largest |Φ̇| of the velocity level of the constraints (a position
    /// constraint differentiated once, or a velocity constraint as written)
    /// over the accepted steps; 0 for a model without.
    pub fn max_velocity_constraint_residual(&self) -> f64 {
        self.velocity_residual
    }

    /// Degrees of freedom of a constrained model at the start of the run:
    /// the coordinates its position-level constraints involve minus the
    /// rank of their Jacobian (n − rank Φ_q); `None` for an ODE.
    pub fn degrees_of_freedom(&self) -> Option<usize> {
        self.degrees_of_freedom
    }

    pub(crate) fn set_degrees_of_freedom(&mut self, dof: usize) {
        self.degrees_of_freedom = Some(dof);
    }

    /// Records the constraint residuals at an accepted step.
    pub(crate) fn note_constraint_residuals(&mut self, r: Residuals) {
        self.constraint_residual = self.constraint_residual.max(r.position);
        self.velocity_residual = self.velocity_residual.max(r.velocity);
    }

    /// The initial values that consistent initialization moved by more
    /// than `rtol·|given| + atol`, in state order; empty when nothing moved
    /// (always for an ODE). With [`crate::Options::strict_initial_values`]
    /// any such move is an error instead.
    pub fn initial_corrections(&self) -> &[InitialCorrection] {
        &self.initial_corrections
    }

    pub(crate) fn set_initial_corrections(&mut self, corrections: Vec<InitialCorrection>) {
        self.initial_corrections = corrections;
    }

    /// The degrees of freedom found at the start, if any.
    pub(crate) fn degrees_of_freedom_found(&self) -> Option<usize> {
        self.degrees_of_freedom
    }
}
