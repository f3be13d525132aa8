//! The result of a run: what it stored of its steps, statistics, and
//! values by name (states, algebraic variables, outputs) on request.
//!
//! `record.rs` is how a run fills a solution step by step (which steps it
//! keeps, the last step it always keeps, the output times it interpolates);
//! `stream.rs` the callback and progress bar that watch it; this file what
//! a user asks of the result.

mod record;
mod stream;

use crate::error::Error;
use crate::model::Model;
use crate::table::Table;
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
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
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

/// What a solution needs of its model after the run (outputs by name, and
/// the derivative that fixed-step methods interpolate with), so that
/// `Solution` has no type parameter.
trait Observables: Send + Sync {
    fn output(&self, index: usize, t: f64, y: &[f64]) -> f64;
    /// y' at `(t, y)`; `false` where the model has none to give (a mass
    /// matrix, or a failed evaluation).
    fn derivative(&self, t: f64, y: &[f64], dy: &mut [f64]) -> bool;
}

struct ModelObservables<M>(M);

impl<M: Model + Send + Sync> Observables for ModelObservables<M> {
    fn output(&self, index: usize, t: f64, y: &[f64]) -> f64 {
        self.0.output(index, t, y)
    }

    fn derivative(&self, t: f64, y: &[f64], dy: &mut [f64]) -> bool {
        !crate::model::has_mass_matrix::<M>() && self.0.rhs(t, y, dy).is_ok()
    }
}

/// The names of a model's values, fixed at compile time.
#[derive(Clone, Copy)]
struct Names {
    model: &'static str,
    states: &'static [&'static str],
    outputs: &'static [&'static str],
    algebraics: &'static [&'static str],
    events: &'static [crate::model::EventInfo],
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
    /// The end of the run: the latest step's end, or where a terminal
    /// event or the step callback ended it.
    end_t: f64,
    end_y: Vec<f64>,
    /// Steps accepted (the initial point not counted).
    steps: usize,
    /// The end the last step was computed for, when a terminal event cut it
    /// short (its interpolant is scaled to that end).
    cut_from: Option<f64>,
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
    pub(crate) fn new<M: Model + Clone + Send + Sync + 'static>(
        model: &M,
        capacity: usize,
    ) -> Solution {
        Solution {
            n: M::STATES,
            names: Names {
                model: M::INFO.name,
                states: M::INFO.states,
                outputs: M::INFO.outputs,
                algebraics: M::INFO.algebraics,
                events: M::INFO.events,
            },
            observables: Arc::new(ModelObservables(model.clone())),
            times: Vec::with_capacity(capacity),
            states: Vec::with_capacity(capacity * M::STATES),
            dense: Vec::new(),
            segments: Vec::new(),
            storage: Storage::All,
            last: LastStep::new(M::STATES),
            end_t: f64::NAN,
            end_y: Vec::new(),
            steps: 0,
            cut_from: None,
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

    /// The times of the crossings of the event called `name`.
    pub fn event_times(&self, name: &str) -> Result<Vec<f64>, Error> {
        let Some(info) = self.names.events.iter().position(|e| e.name == name) else {
            return Err(Error::UnknownName {
                name: name.to_string(),
                known: self.names.events.iter().map(|e| e.name).collect(),
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

    /// Every name a value can be read by, in order: the states (declared
    /// states, each followed by the derivatives `der(x)`, … a higher-order
    /// state brings), the algebraic variables, the outputs.
    pub fn names(&self) -> Vec<&'static str> {
        self.names
            .states
            .iter()
            .chain(self.names.algebraics)
            .chain(self.names.outputs)
            .copied()
            .collect()
    }

    /// The values of `name` at the stored times ([`Solution::times`]).
    pub fn column(&self, name: &str) -> Result<Vec<f64>, Error> {
        let value = self.reader(name)?;
        Ok((0..self.times.len())
            .map(|k| value.read(self, self.times[k], self.stored_state(k)))
            .collect())
    }

    /// `names` at `times`, by the method's continuous extension (DOPRI5's
    /// of order 4, DOP853's of order 7, RADAU5's collocation polynomial,
    /// the Taylor polynomial of the step; cubic Hermite from y' at the
    /// ends of the step for the other fixed-step methods). A solution that
    /// stores only some times (`keep_every`, `output_times`) answers at
    /// those only. Each time must lie in the integrated interval.
    pub fn sample(&self, names: &[&str], times: &[f64]) -> Result<Table, Error> {
        let readers = names
            .iter()
            .map(|name| self.reader(name))
            .collect::<Result<Vec<_>, Error>>()?;
        let mut columns = vec![Vec::with_capacity(times.len()); names.len()];
        let mut y = vec![0.0; self.n];
        for &t in times {
            self.state_at(t, &mut y)?;
            for (column, value) in columns.iter_mut().zip(&readers) {
                column.push(value.read(self, t, &y));
            }
        }
        Ok(Table::new(
            names.iter().map(|s| s.to_string()).collect(),
            times.to_vec(),
            columns,
        ))
    }

    /// `names` at every stored time, as a [`Table`].
    pub fn table(&self, names: &[&str]) -> Result<Table, Error> {
        let columns = names
            .iter()
            .map(|name| self.column(name))
            .collect::<Result<Vec<_>, Error>>()?;
        Ok(Table::new(
            names.iter().map(|s| s.to_string()).collect(),
            self.times.clone(),
            columns,
        ))
    }

    /// Writes `names` at every stored time as CSV: a header row (`t` and
    /// the names), then one row per stored time. `&sol.names()` writes
    /// every value.
    pub fn write_csv<W: std::io::Write>(&self, writer: W, names: &[&str]) -> Result<(), Error> {
        self.table(names)?.write_csv(writer)
    }

    /// A state, algebraic variable or output at the end of the run.
    pub fn last(&self, name: &str) -> Result<f64, Error> {
        if self.end_y.is_empty() {
            return Err(Error::OutOfRange {
                t: f64::NAN,
                interval: (f64::NAN, f64::NAN),
            });
        }
        Ok(self.reader(name)?.read(self, self.end_t, &self.end_y))
    }

    /// A state, algebraic variable or output at time `t`. Adaptive methods
    /// interpolate with their own continuous extension (order 4 for
    /// DOPRI5, 7 for DOP853, RADAU5's collocation polynomial, the Taylor
    /// polynomial); the fixed-step methods by the cubic Hermite polynomial
    /// through both ends of the step and their derivatives (linear for a
    /// model with a mass matrix, and for runs with `dense_output(false)`).
    /// A solution thinned by [`crate::Options::keep_every`] or stored at
    /// [`crate::Options::output_times`] answers only at its stored times
    /// ([`Error::Thinned`], [`Error::NotStored`] elsewhere).
    pub fn at(&self, t: f64, name: &str) -> Result<f64, Error> {
        let value = self.reader(name)?;
        let mut y = vec![0.0; self.n];
        self.state_at(t, &mut y)?;
        Ok(value.read(self, t, &y))
    }

    /// The stored state at `k` (the end state for the last entry of a run
    /// that stores every step).
    fn stored_state(&self, k: usize) -> &[f64] {
        &self.states[k * self.n..(k + 1) * self.n]
    }

    /// The interval the solution covers, in the direction of the run.
    fn interval(&self) -> Option<(f64, f64)> {
        let first = *self.times.first()?;
        Some((first, self.end_t))
    }

    /// The state at `t` into `y`.
    fn state_at(&self, t: f64, y: &mut [f64]) -> Result<(), Error> {
        let Some((first, end)) = self.interval() else {
            return Err(Error::OutOfRange {
                t,
                interval: (f64::NAN, f64::NAN),
            });
        };
        if !(first.min(end)..=first.max(end)).contains(&t) {
            return Err(Error::OutOfRange {
                t,
                interval: (first, end),
            });
        }
        if t == end {
            y.copy_from_slice(&self.end_y);
            return Ok(());
        }
        match self.storage {
            Storage::All => {}
            _ => {
                // Only the stored times are known; between them nothing is.
                return match self.times.iter().position(|&s| s == t) {
                    Some(k) => {
                        y.copy_from_slice(self.stored_state(k));
                        Ok(())
                    }
                    None => Err(self.storage.not_stored(t)),
                };
            }
        }
        if self.times.len() == 1 {
            y.copy_from_slice(self.stored_state(0));
            return Ok(());
        }
        let forward = first <= end;
        let k = self
            .times
            .partition_point(|&s| if forward { s < t } else { s > t })
            .clamp(1, self.times.len() - 1);
        self.interpolate_stored(k, t, y);
        Ok(())
    }

    /// The state at `t` within stored step `k` (from `times[k - 1]` to
    /// `times[k]`), by the step's interpolant.
    fn interpolate_stored(&self, k: usize, t: f64, y: &mut [f64]) {
        let n = self.n;
        let t0 = self.times[k - 1];
        let is_last = k == self.times.len() - 1;
        // The step as computed: a cut last step keeps its computed end.
        let (t1, y1) = match self.cut_from {
            Some(end) if is_last => (end, &self.last.y_new[..]),
            _ => (self.times[k], self.stored_state(k)),
        };
        let y0 = self.stored_state(k - 1);
        let s = if t1 == t0 { 0.0 } else { (t - t0) / (t1 - t0) };
        match self.segments.iter().rev().find(|seg| seg.first <= k) {
            Some(seg) => {
                let width = seg.width * n;
                let start = seg.offset + (k - seg.first) * width;
                let c = &self.dense[start..start + width];
                for (i, yi) in y.iter_mut().enumerate() {
                    *yi = (seg.interpolant)(c, n, i, s);
                }
            }
            None => {
                let (mut f0, mut f1) = (vec![0.0; n], vec![0.0; n]);
                let slopes = self.observables.derivative(t0, y0, &mut f0)
                    && self.observables.derivative(t1, y1, &mut f1);
                record::hermite_or_linear(y0, y1, slopes.then_some((&f0, &f1)), t1 - t0, s, y);
            }
        }
    }

    /// How to read `name`: a state, an output or an algebraic variable.
    fn reader(&self, name: &str) -> Result<Reader, Error> {
        if let Some(i) = self.names.states.iter().position(|n| *n == name) {
            return Ok(Reader::State(i));
        }
        self.names
            .outputs
            .iter()
            .chain(self.names.algebraics)
            .position(|n| *n == name)
            .map(Reader::Observable)
            .ok_or_else(|| self.unknown_name(name))
    }

    /// The error for a name the model does not have.
    fn unknown_name(&self, name: &str) -> Error {
        Error::UnknownName {
            name: name.to_string(),
            known: self.names(),
        }
    }
}

/// Where a named value comes from.
#[derive(Clone, Copy)]
enum Reader {
    State(usize),
    /// Outputs, then algebraic variables (the generated `output` numbers them so).
    Observable(usize),
}

impl Reader {
    fn read(self, solution: &Solution, t: f64, y: &[f64]) -> f64 {
        match self {
            Reader::State(i) => y[i],
            Reader::Observable(o) => solution.observables.output(o, t, y),
        }
    }
}

#[cfg(feature = "serde")]
impl serde::Serialize for Solution {
    /// The stored times, every named value at them, the statistics and
    /// the events.
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        use serde::ser::{Error as _, SerializeStruct};
        let table = self.table(&self.names()).map_err(S::Error::custom)?;
        let mut s = serializer.serialize_struct("Solution", 5)?;
        s.serialize_field("model", self.names.model)?;
        s.serialize_field("table", &table)?;
        s.serialize_field("stats", &self.stats)?;
        s.serialize_field("events", &self.events)?;
        s.serialize_field("initial_corrections", &self.initial_corrections)?;
        s.end()
    }
}
