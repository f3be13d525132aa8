//! How a run fills its solution: the steps it stores (every one, every
//! k-th, or none but the requested output times), the latest step it
//! always keeps with its continuous extension (events are located on it,
//! output times interpolated in it), and the end of the run.

use super::stream::Stream;
use super::{Interpolant, Segment, Solution};
use crate::options::Options;
use std::sync::Arc;

/// What a run keeps of its steps.
#[derive(Clone)]
pub(super) enum Storage {
    /// Every accepted step, with its dense output if the method has one.
    All,
    /// Every `k`-th accepted step and the latest; `tail`: the last stored
    /// entry is the latest but not one to keep, and the next step
    /// overwrites it.
    KeepEvery { k: usize, tail: bool },
    /// Only these times, each interpolated in the step that covers it;
    /// `next` is the first not yet reached.
    OutputTimes { times: Arc<[f64]>, next: usize },
}

/// The latest accepted step, from `(t_old, y_old)` to `(t_new, y_new)` as
/// computed, with what interpolates inside it.
#[derive(Clone)]
pub(super) struct LastStep {
    t_old: f64,
    y_old: Vec<f64>,
    t_new: f64,
    pub(super) y_new: Vec<f64>,
    /// The method's dense-output coefficients of this step, read by
    /// `interpolant` (`None`: the step came without them).
    coefficients: Vec<f64>,
    interpolant: Option<Interpolant>,
    /// y' at either end, for the cubic Hermite polynomial of a step without
    /// dense output, once computed (`f_new` carries over as the next
    /// step's `f_old`).
    f_old: Vec<f64>,
    f_new: Vec<f64>,
    has_f_old: bool,
    has_f_new: bool,
}

impl LastStep {
    pub(super) fn new(n: usize) -> LastStep {
        LastStep {
            t_old: f64::NAN,
            y_old: vec![0.0; n],
            t_new: f64::NAN,
            y_new: vec![0.0; n],
            coefficients: Vec::new(),
            interpolant: None,
            f_old: vec![0.0; n],
            f_new: vec![0.0; n],
            has_f_old: false,
            has_f_new: false,
        }
    }

    /// The state at `t` inside the step: the method's continuous extension,
    /// else the cubic Hermite polynomial if the end derivatives are known,
    /// else the straight line.
    fn interpolate(&self, t: f64, y: &mut [f64]) {
        let h = self.t_new - self.t_old;
        let s = if h == 0.0 { 0.0 } else { (t - self.t_old) / h };
        if s == 1.0 {
            y.copy_from_slice(&self.y_new);
            return;
        }
        match self.interpolant {
            Some(f) => {
                let n = y.len();
                for (i, yi) in y.iter_mut().enumerate() {
                    *yi = f(&self.coefficients, n, i, s);
                }
            }
            None => {
                let slopes =
                    (self.has_f_old && self.has_f_new).then_some((&self.f_old, &self.f_new));
                hermite_or_linear(&self.y_old, &self.y_new, slopes, h, s, y);
            }
        }
    }
}

/// The cubic Hermite polynomial through `(0, y0)` and `(1, y1)` with
/// slopes `h·f0`, `h·f1`, at `s` (fourth-order accurate in the step), or
/// the straight line without slopes.
pub(super) fn hermite_or_linear(
    y0: &[f64],
    y1: &[f64],
    slopes: Option<(&Vec<f64>, &Vec<f64>)>,
    h: f64,
    s: f64,
    y: &mut [f64],
) {
    match slopes {
        Some((f0, f1)) => {
            let (s2, s3) = (s * s, s * s * s);
            let h00 = 2.0 * s3 - 3.0 * s2 + 1.0;
            let h10 = s3 - 2.0 * s2 + s;
            let h01 = 3.0 * s2 - 2.0 * s3;
            let h11 = s3 - s2;
            for i in 0..y.len() {
                y[i] = h00 * y0[i] + h10 * h * f0[i] + h01 * y1[i] + h11 * h * f1[i];
            }
        }
        None => {
            for i in 0..y.len() {
                y[i] = y0[i] + s * (y1[i] - y0[i]);
            }
        }
    }
}

impl Solution {
    /// Applies the options that decide what the run stores and who
    /// watches it, for a run from `t0` to `t1`.
    pub(crate) fn configure(&mut self, options: &Options, t0: f64, t1: f64) {
        self.storage = match (&options.output_times, options.keep_every) {
            (Some(times), _) => {
                self.times = Vec::with_capacity(times.len());
                self.states = Vec::with_capacity(times.len() * self.n);
                Storage::OutputTimes { times: times.clone(), next: 0 }
            }
            (None, k) if k > 1 => Storage::KeepEvery { k, tail: false },
            _ => Storage::All,
        };
        self.stream = Stream::new(options, t0, t1);
        // Only events and output times read the latest step's interior:
        // a run with neither does not copy it.
        self.track_last = !self.names.events.is_empty() || !matches!(self.storage, Storage::All);
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

    /// The initial point of the run.
    pub(crate) fn push_initial(&mut self, t: f64, y: &[f64]) {
        self.end_t = t;
        self.end_y = y.to_vec();
        self.last.t_old = t;
        self.last.t_new = t;
        self.last.y_old.copy_from_slice(y);
        self.last.y_new.copy_from_slice(y);
        match &mut self.storage {
            Storage::OutputTimes { times, next } => {
                while *next < times.len() && times[*next] == t {
                    self.times.push(t);
                    self.states.extend_from_slice(y);
                    *next += 1;
                }
            }
            _ => {
                self.times.push(t);
                self.states.extend_from_slice(y);
            }
        }
    }

    /// An accepted step to `(t, y)` with its dense-output coefficients.
    /// Inlined as `push` is: called, its copies of the
    /// coefficients went through `memcpy` at run-time lengths (Lorenz with
    /// DOPRI5 and dense output, the defaults: 116 ns a step, 90 inlined).
    #[inline(always)]
    pub(crate) fn push_dense(&mut self, t: f64, y: &[f64], coefficients: &[f64]) {
        self.advance(t, y);
        if self.track_last {
            self.last.coefficients.clear();
            self.last.coefficients.extend_from_slice(coefficients);
            self.last.interpolant = self.segments.last().map(|s| s.interpolant);
        }
        if matches!(self.storage, Storage::All) {
            self.dense.extend_from_slice(coefficients);
        }
        self.store_step(t, y);
    }

    /// An accepted step to `(t, y)` without dense output. Inlined (with
    /// what it calls) into the generic step loops, so that its copies run
    /// over the model's fixed length instead of calling `memcpy`.
    #[inline(always)]
    pub(crate) fn push(&mut self, t: f64, y: &[f64]) {
        self.advance(t, y);
        self.store_step(t, y);
    }

    /// Makes `(t, y)` the end of the latest step and of the run.
    #[inline(always)]
    fn advance(&mut self, t: f64, y: &[f64]) {
        let last = &mut self.last;
        last.t_old = self.end_t;
        if self.track_last {
            last.y_old.copy_from_slice(&self.end_y);
            last.y_new.copy_from_slice(y);
        }
        // The old end's derivative serves again, unless a cut moved the end.
        last.has_f_old = last.has_f_new && last.t_new == self.end_t;
        if last.has_f_old {
            std::mem::swap(&mut last.f_old, &mut last.f_new);
        }
        last.has_f_new = false;
        last.t_new = t;
        last.interpolant = None;
        self.end_t = t;
        self.end_y.copy_from_slice(y);
        self.steps += 1;
    }

    /// Stores the step just advanced to, as the storage asks: the common
    /// case, every step, in the caller's loop; the others out of it.
    #[inline(always)]
    fn store_step(&mut self, t: f64, y: &[f64]) {
        match &mut self.storage {
            Storage::All => {
                self.times.push(t);
                self.states.extend_from_slice(y);
            }
            Storage::KeepEvery { .. } => self.store_every_kth(t, y),
            Storage::OutputTimes { .. } => self.store_output_times(t),
        }
    }

    /// Every k-th step, and the latest one provisionally.
    fn store_every_kth(&mut self, t: f64, y: &[f64]) {
        let Storage::KeepEvery { k, tail } = &mut self.storage else { return };
        if *tail && self.times.len() >= 2 {
            // Overwrite the provisional latest step: memory stays
            // at one entry per k steps plus one.
            let last = self.times.len() - 1;
            self.times[last] = t;
            self.states[last * self.n..(last + 1) * self.n].copy_from_slice(y);
        } else {
            self.times.push(t);
            self.states.extend_from_slice(y);
        }
        *tail = self.steps % *k != 0;
    }

    /// The output times the step to `t` reached, interpolated in it.
    fn store_output_times(&mut self, t: f64) {
        let Storage::OutputTimes { times, next } = &mut self.storage else { return };
        let forward = t >= self.last.t_old;
        let reached = |tau: f64| if forward { tau <= t } else { tau >= t };
        let due = times[*next..].iter().take_while(|&&tau| reached(tau)).count();
        if due == 0 {
            return;
        }
        let (first, times) = (*next, times.clone());
        *next += due;
        self.prepare_last_step();
        for &tau in &times[first..first + due] {
            let start = self.states.len();
            self.states.resize(start + self.n, 0.0);
            self.last.interpolate(tau, &mut self.states[start..]);
            self.times.push(tau);
        }
    }

    /// Readies the latest step's interpolation: without the method's dense
    /// output, the derivatives at its ends for the Hermite polynomial.
    pub(crate) fn prepare_last_step(&mut self) {
        let last = &mut self.last;
        if last.interpolant.is_some() || last.has_f_new {
            return;
        }
        if !last.has_f_old {
            last.has_f_old = self.observables.derivative(last.t_old, &last.y_old, &mut last.f_old);
            self.interpolation_evals += 1;
        }
        last.has_f_new = self.observables.derivative(last.t_new, &last.y_new, &mut last.f_new);
        self.interpolation_evals += 1;
    }

    /// The interval of the latest step, `None` before the first.
    pub(crate) fn last_step(&self) -> Option<(f64, f64)> {
        (self.steps > 0).then_some((self.last.t_old, self.last.t_new))
    }

    /// The state at the end of the latest step, as computed.
    pub(crate) fn last_step_end(&self) -> &[f64] {
        &self.last.y_new
    }

    /// State at `t` within the latest step, from its continuous extension
    /// (call [`Solution::prepare_last_step`] first for a step without one).
    pub(crate) fn interpolate_last_step(&self, t: f64, y: &mut [f64]) {
        self.last.interpolate(t, y);
    }

    /// Ends the run at `t` inside the latest step, with state `y` there.
    pub(crate) fn end_last_step_at(&mut self, t: f64, y: &[f64]) {
        if self.steps == 0 {
            return;
        }
        // Discrete values hold through the step: the interpolant's
        // rounding must not move them.
        let restored: Vec<f64>;
        let y = if self.names.discrete.is_empty() {
            y
        } else {
            let mut held = y.to_vec();
            for name in self.names.discrete {
                if let Some(i) = self.names.states.iter().position(|s| s == name) {
                    held[i] = self.last.y_old[i];
                }
            }
            restored = held;
            &restored[..]
        };
        self.cut_from = Some(self.last.t_new);
        self.end_t = t;
        self.end_y.copy_from_slice(y);
        let forward = self.last.t_new >= self.last.t_old;
        match self.storage {
            Storage::All | Storage::KeepEvery { .. } => {
                let k = self.times.len() - 1;
                self.times[k] = t;
                self.states[k * self.n..(k + 1) * self.n].copy_from_slice(y);
            }
            Storage::OutputTimes { .. } => {
                // The output times past the cut were never reached.
                let beyond = |tau: f64| if forward { tau > t } else { tau < t };
                while self.times.last().is_some_and(|&tau| beyond(tau)) {
                    self.times.pop();
                    self.states.truncate(self.states.len() - self.n);
                }
            }
        }
    }

    pub(crate) fn push_event(&mut self, hit: crate::solution::EventHit) {
        self.events.push(hit);
    }

    /// The run stopped at the events `instant` it last recorded (the
    /// crossings at one instant): at a terminal one, or for the actions of
    /// those that act, which the driver applies before going on.
    pub(crate) fn stop_at_last_events(&mut self, instant: usize) {
        let events = self.names.events;
        let first = self.events.len().saturating_sub(instant);
        let at = first..self.events.len();
        if let Some(k) =
            at.clone().find(|&k| events.get(self.events[k].index).is_some_and(|e| e.terminal))
        {
            self.stopped = Some(k);
        }
        self.pending_actions = at
            .map(|k| self.events[k].index)
            .filter(|&i| events.get(i).is_some_and(|e| !e.resets.is_empty()))
            .collect();
    }

    /// A terminal event fired by the actions at the end of the run ends it.
    pub(crate) fn stop_at_terminal_hit(&mut self) {
        let events = self.names.events;
        self.stopped =
            self.events.iter().rposition(|h| events.get(h.index).is_some_and(|e| e.terminal));
    }

    /// The events whose actions interrupted the run, in time order (once).
    pub(crate) fn take_pending_actions(&mut self) -> Vec<usize> {
        std::mem::take(&mut self.pending_actions)
    }

    /// Whether the run ended for good: a terminal event, or the step callback.
    pub(crate) fn ended(&self) -> bool {
        self.stopped.is_some() || self.cancelled_at.is_some()
    }

    /// Actions changed the state at the end of the run to `y`: the run
    /// goes on from there. The value before stays stored (with every step
    /// stored, the time appears twice), and the next step starts afresh.
    pub(crate) fn push_jump(&mut self, y: &[f64], triggers: Vec<&'static str>) {
        let t = self.end_t;
        if let Some(end) = self.cut_from.take() {
            let computed = self.last.y_new.clone();
            self.cuts.push((self.times.len().saturating_sub(1), end, computed));
        }
        let before = std::mem::replace(&mut self.end_y, y.to_vec());
        match &mut self.storage {
            Storage::All => {
                self.times.push(t);
                self.states.extend_from_slice(y);
            }
            Storage::KeepEvery { tail, .. } => {
                self.times.push(t);
                self.states.extend_from_slice(y);
                *tail = false;
            }
            Storage::OutputTimes { .. } => {
                // An output time at the instant reads the value after.
                if self.times.last() == Some(&t) {
                    let k = self.times.len() - 1;
                    self.states[k * self.n..(k + 1) * self.n].copy_from_slice(y);
                }
            }
        }
        let last = &mut self.last;
        last.t_old = t;
        last.t_new = t;
        last.y_old.copy_from_slice(y);
        last.y_new.copy_from_slice(y);
        last.coefficients.clear();
        last.interpolant = None;
        last.has_f_old = false;
        last.has_f_new = false;
        self.jumps.push(super::Jump { t, before, after: y.to_vec(), triggers });
    }

    /// After an accepted step (and its events): shows it to the step
    /// callback and the progress bar; `true` when the callback ended the run.
    pub(crate) fn after_accepted_step(&mut self) -> bool {
        let Some(stream) = &mut self.stream else {
            return false;
        };
        if stream.see(self.end_t, &self.end_y, self.steps, self.names.states) {
            self.cancelled_at = Some(self.end_t);
            return true;
        }
        false
    }

    /// Ends the run: the progress bar is finished, and the derivatives
    /// evaluated to interpolate are counted in the statistics.
    pub(crate) fn finish_run(&mut self) {
        if let Some(stream) = self.stream.take() {
            stream.finish(self.end_t, self.steps);
        }
        self.stats.rhs_evals += self.interpolation_evals;
        self.interpolation_evals = 0;
    }
}
