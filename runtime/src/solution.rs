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
    observables: Arc<dyn Observables>,
    stats: Stats,
}

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
            observables: Arc::new(ModelObservables(model.clone())),
            stats: Stats::default(),
        }
    }

    pub(crate) fn push(&mut self, t: f64, y: &[f64]) {
        self.times.push(t);
        self.states.extend_from_slice(y);
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

    /// Counters of the run.
    pub fn stats(&self) -> Stats {
        self.stats
    }

    /// Largest |constraint| over the accepted steps; 0 for an ODE, which has
    /// no constraints.
    pub fn max_constraint_residual(&self) -> f64 {
        0.0
    }

    fn value_at_step(&self, k: usize, name: &str) -> Result<f64, Error> {
        let y = self.state(k).unwrap_or(&[]);
        if let Some(i) = self.state_names.iter().position(|n| *n == name) {
            return Ok(y[i]);
        }
        if let Some(i) = self.output_names.iter().position(|n| *n == name) {
            return Ok(self.observables.output(i, self.times[k], y));
        }
        Err(Error::UnknownName {
            name: name.to_string(),
            known: self
                .state_names
                .iter()
                .chain(self.output_names)
                .copied()
                .collect(),
        })
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

    /// A state or output at time `t`, interpolated linearly between the two
    /// accepted steps around it (second-order accurate in the step: use it
    /// for plotting, not for accuracy-critical values, until dense output lands).
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
        let (lo, hi) = if first <= last {
            (first, last)
        } else {
            (last, first)
        };
        if !(lo..=hi).contains(&t) {
            return Err(Error::OutOfRange {
                t,
                interval: (first, last),
            });
        }
        let forward = first <= last;
        let k = self
            .times
            .partition_point(|&s| if forward { s <= t } else { s >= t });
        let k = k
            .clamp(1, self.times.len().max(2) - 1)
            .min(self.times.len() - 1);
        if self.times.len() == 1 {
            return self.value_at_step(0, name);
        }
        let (t0, t1) = (self.times[k - 1], self.times[k]);
        let (v0, v1) = (
            self.value_at_step(k - 1, name)?,
            self.value_at_step(k, name)?,
        );
        let w = if t1 == t0 { 0.0 } else { (t - t0) / (t1 - t0) };
        Ok(v0 + w * (v1 - v0))
    }
}
