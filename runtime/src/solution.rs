//! The result of a run: accepted steps, statistics, and outputs on request.

use crate::error::Error;
use crate::model::Model;
use std::sync::Arc;

/// Counters of a run.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
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
    /// RADAU5 (0 for every other method).
    pub switches: usize,
    /// How the model was integrated: an ODE, or which DAE formulation.
    pub formulation: &'static str,
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
pub struct InitialCorrection {
    /// The state, as [`crate::ModelInfo::states`] names it.
    pub name: &'static str,
    /// The value given (by the model's `state(..)`, or to `simulate_from`).
    pub given: f64,
    /// The value the run started from.
    pub used: f64,
}

/// A crossing of an event function, located to machine precision.
#[derive(Clone, Debug, PartialEq)]
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

/// Evaluates a model's outputs after the run, so a `Solution` needs no type
/// parameter.
trait Observables: Send + Sync {
    fn output(&self, index: usize, t: f64, y: &[f64]) -> f64;
}

struct ModelObservables<M>(M);

impl<M: Model + Send + Sync> Observables for ModelObservables<M> {
    fn output(&self, index: usize, t: f64, y: &[f64]) -> f64 {
        self.0.output(index, t, y)
    }
}

/// The accepted steps of a run.
#[derive(Clone)]
pub struct Solution {
    times: Vec<f64>,
    /// States of step k at `states[k * n .. (k + 1) * n]`.
    states: Vec<f64>,
    n: usize,
    state_names: &'static [&'static str],
    output_names: &'static [&'static str],
    algebraic_names: &'static [&'static str],
    observables: Arc<dyn Observables>,
    /// Largest |Φ| of the position-level constraints at the accepted steps.
    constraint_residual: f64,
    /// Largest |Φ̇| of their velocity level.
    velocity_residual: f64,
    /// n − rank Φ_q at the start, for a model with constraints.
    degrees_of_freedom: Option<usize>,
    /// The initial values consistent initialization moved.
    initial_corrections: Vec<InitialCorrection>,
    stats: Stats,
    /// Dense-output coefficients of the steps of each segment, read by the
    /// segment's interpolant.
    dense: Vec<f64>,
    /// One per method that ran (Method::Auto may switch), in step order.
    segments: Vec<Segment>,
    /// Event crossings in time order.
    events: Vec<EventHit>,
    /// The end the last step was computed for, when a terminal event cut it
    /// short (its interpolant is scaled to that end).
    cut_from: Option<f64>,
    /// The last step's computed end state, when cut short.
    uncut_end: Vec<f64>,
    event_info: &'static [crate::model::EventInfo],
    /// Keep every `keep_every`-th accepted step (and always the latest).
    keep_every: usize,
    /// Steps pushed so far, kept or not.
    pushed: usize,
    /// The last stored entry is the latest step but not one to keep: the
    /// next step overwrites it.
    tail: bool,
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
            .field("steps", &self.times.len())
            .field("interval", &(self.times.first(), self.times.last()))
            .field("states", &self.state_names)
            .field("stats", &self.stats)
            .finish()
    }
}

impl Solution {
    pub(crate) fn new<M: Model + Clone + Send + Sync + 'static>(
        model: &M,
        capacity: usize,
    ) -> Solution {
        Solution {
            times: Vec::with_capacity(capacity),
            states: Vec::with_capacity(capacity * M::STATES),
            n: M::STATES,
            state_names: M::INFO.states,
            output_names: M::INFO.outputs,
            algebraic_names: M::INFO.algebraics,
            constraint_residual: 0.0,
            velocity_residual: 0.0,
            degrees_of_freedom: None,
            initial_corrections: Vec::new(),
            observables: Arc::new(ModelObservables(model.clone())),
            stats: Stats::default(),
            dense: Vec::new(),
            segments: Vec::new(),
            events: Vec::new(),
            cut_from: None,
            uncut_end: Vec::new(),
            event_info: M::INFO.events,
            keep_every: 1,
            pushed: 0,
            tail: false,
        }
    }

    /// Stores only every `k`-th accepted step from now on, and the latest
    /// (see [`crate::Options::keep_every`]).
    pub(crate) fn set_keep_every(&mut self, k: usize) {
        self.keep_every = k.max(1);
    }

    /// The steps pushed from now on carry `width` dense-output vectors, read by `f`.
    pub(crate) fn set_interpolant(&mut self, width: usize, f: Interpolant) {
        self.segments.push(Segment {
            first: self.times.len(),
            offset: self.dense.len(),
            width,
            interpolant: f,
        });
    }

    /// The last state, if any step was stored.
    pub(crate) fn last_state(&self) -> Option<&[f64]> {
        self.times.len().checked_sub(1).and_then(|k| self.state(k))
    }

    /// An accepted step with its dense-output coefficients.
    pub(crate) fn push_dense(&mut self, t: f64, y: &[f64], coefficients: &[f64]) {
        self.push(t, y);
        self.dense.extend_from_slice(coefficients);
    }

    /// State at `t` within the last step, from its continuous extension.
    pub(crate) fn interpolate_last_step(&self, t: f64, y: &mut [f64]) {
        let k = self.times.len().saturating_sub(1);
        for (i, yi) in y.iter_mut().enumerate() {
            *yi = self.interpolate(k, t, i);
        }
    }

    /// Ends the run at `t` inside the last step, with state `y` there.
    pub(crate) fn end_last_step_at(&mut self, t: f64, y: &[f64]) {
        let k = self.times.len().saturating_sub(1);
        if self.times.len() >= 2 {
            self.cut_from = Some(self.times[k]);
            self.uncut_end = self.states[k * self.n..(k + 1) * self.n].to_vec();
            self.times[k] = t;
            self.states[k * self.n..(k + 1) * self.n].copy_from_slice(y);
        }
    }

    pub(crate) fn push_event(&mut self, hit: EventHit) {
        self.events.push(hit);
    }

    pub(crate) fn push(&mut self, t: f64, y: &[f64]) {
        let k = self.pushed;
        self.pushed += 1;
        if self.tail && self.times.len() >= 2 {
            // Overwrite the provisional latest step: memory stays at one
            // entry per `keep_every` steps plus one.
            let last = self.times.len() - 1;
            self.times[last] = t;
            self.states[last * self.n..(last + 1) * self.n].copy_from_slice(y);
        } else {
            self.times.push(t);
            self.states.extend_from_slice(y);
        }
        self.tail = self.keep_every > 1 && k % self.keep_every != 0;
    }

    pub(crate) fn stats_mut(&mut self) -> &mut Stats {
        &mut self.stats
    }

    /// Times of the accepted steps (the initial time first).
    pub fn times(&self) -> &[f64] {
        &self.times
    }

    /// The state vector at step `k`.
    pub fn state(&self, k: usize) -> Option<&[f64]> {
        self.states.get(k * self.n..(k + 1) * self.n)
    }

    /// The state at the end of the run (at a terminal event, if one fired).
    pub fn final_state(&self) -> &[f64] {
        self.last_state().unwrap_or(&[])
    }

    /// Every event crossing, in time order.
    pub fn events(&self) -> &[EventHit] {
        &self.events
    }

    /// The times of the crossings of the event called `name`.
    pub fn event_times(&self, name: &str) -> Result<Vec<f64>, Error> {
        let Some(info) = self.event_info.iter().position(|e| e.name == name) else {
            return Err(Error::UnknownName {
                name: name.to_string(),
                known: self.event_info.iter().map(|e| e.name).collect(),
            });
        };
        Ok(self
            .events
            .iter()
            .filter(|e| e.index == info)
            .map(|e| e.t)
            .collect())
    }

    /// The terminal event the run stopped at, if it did.
    pub fn stopped_by(&self) -> Option<&EventHit> {
        self.cut_from.and(self.events.last())
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
    pub(crate) fn note_constraint_residuals(&mut self, r: crate::projection::Residuals) {
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

    /// The index of a name among the model's observables: outputs, then
    /// algebraic variables.
    fn observable(&self, name: &str) -> Option<usize> {
        self.output_names
            .iter()
            .chain(self.algebraic_names)
            .position(|n| *n == name)
    }

    /// Component `i` at `t` within step `k` (from `times[k - 1]` to `times[k]`).
    fn interpolate(&self, k: usize, t: f64, i: usize) -> f64 {
        if k == 0 || k >= self.times.len() {
            return self.states.get(i).copied().unwrap_or(f64::NAN);
        }
        let t0 = self.times[k - 1];
        let t1 = match self.cut_from {
            Some(end) if k == self.times.len() - 1 => end,
            _ => self.times[k],
        };
        let s = if t1 == t0 { 0.0 } else { (t - t0) / (t1 - t0) };
        match self.segments.iter().rev().find(|seg| seg.first <= k) {
            Some(seg) => {
                let width = seg.width * self.n;
                let start = seg.offset + (k - seg.first) * width;
                (seg.interpolant)(&self.dense[start..start + width], self.n, i, s)
            }
            None => {
                // Linear, on the step as computed (before any cut).
                let a = self.states[(k - 1) * self.n + i];
                let b = match self.cut_from {
                    Some(_) if k == self.times.len() - 1 => return a + s * (self.uncut_end[i] - a),
                    _ => self.states[k * self.n + i],
                };
                a + s * (b - a)
            }
        }
    }

    /// The error for a name that is neither a state nor an output.
    fn unknown_name(&self, name: &str) -> Error {
        Error::UnknownName {
            name: name.to_string(),
            known: self
                .state_names
                .iter()
                .chain(self.output_names)
                .chain(self.algebraic_names)
                .copied()
                .collect(),
        }
    }

    fn value_at_step(&self, k: usize, name: &str) -> Result<f64, Error> {
        let y = self.state(k).unwrap_or(&[]);
        if let Some(i) = self.state_names.iter().position(|n| *n == name) {
            return Ok(y[i]);
        }
        if let Some(i) = self.observable(name) {
            return Ok(self.observables.output(i, self.times[k], y));
        }
        Err(self.unknown_name(name))
    }

    /// A state or output at the last accepted step.
    pub fn last(&self, name: &str) -> Result<f64, Error> {
        match self.times.len() {
            0 => Err(Error::OutOfRange {
                t: f64::NAN,
                interval: (f64::NAN, f64::NAN),
            }),
            n => self.value_at_step(n - 1, name),
        }
    }

    /// A state or output at time `t`. Adaptive methods interpolate with
    /// their own continuous extension (order 4 for DOPRI5, 7 for DOP853,
    /// RADAU5's collocation polynomial); fixed-step methods, and runs with
    /// `dense_output(false)`, interpolate linearly between steps (second
    /// order in the step: for plotting, not for accuracy-critical values).
    /// A solution thinned by [`crate::Options::keep_every`] answers only at
    /// its stored times ([`Error::Thinned`] elsewhere).
    pub fn at(&self, t: f64, name: &str) -> Result<f64, Error> {
        let (first, last) = match (self.times.first(), self.times.last()) {
            (Some(&a), Some(&b)) => (a, b),
            _ => {
                return Err(Error::OutOfRange {
                    t,
                    interval: (f64::NAN, f64::NAN),
                })
            }
        };
        if !(first.min(last)..=first.max(last)).contains(&t) {
            return Err(Error::OutOfRange {
                t,
                interval: (first, last),
            });
        }
        if self.times.len() == 1 {
            return self.value_at_step(0, name);
        }
        if self.keep_every > 1 {
            // Only the kept steps are known; between them nothing is.
            return match self.times.iter().position(|&s| s == t) {
                Some(k) => self.value_at_step(k, name),
                None => Err(Error::Thinned {
                    t,
                    keep_every: self.keep_every,
                }),
            };
        }
        let forward = first <= last;
        let k = self
            .times
            .partition_point(|&s| if forward { s < t } else { s > t })
            .clamp(1, self.times.len() - 1);
        let state = |i: usize| self.interpolate(k, t, i);
        if let Some(i) = self.state_names.iter().position(|n| *n == name) {
            return Ok(state(i));
        }
        if let Some(o) = self.observable(name) {
            let y: Vec<f64> = (0..self.n).map(state).collect();
            return Ok(self.observables.output(o, t, &y));
        }
        Err(self.unknown_name(name))
    }
}
