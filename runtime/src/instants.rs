//! A model's instants for a driver that steps it itself (an FMI
//! importer's integrator, a co-simulation master): consistent states, the
//! rounds of actions at an event or clock instant, the clocks' instants,
//! and the projection of a DAE's state onto its constraints. The run API
//! does the same inside [`crate::simulate`]; these are its own functions,
//! so a model stepped from outside behaves as one run here.

use crate::error::Error;
use crate::info::EventDirection;
use crate::model::Model;
use crate::run::hybrid::{apply_instant, Clocks};
use crate::run::observables::solution_of;
use crate::step::projection::{Projector, INITIAL_ITERATIONS};

/// Makes `y` a consistent state of `model` at `t0`, as a run does before
/// its first step: the relations set as they hold there, the initial
/// equations solved for the starts they decide, a DAE's states projected
/// onto its constraints and their hidden levels (keeping the states
/// `state(x0).fixed()` fixes).
pub fn consistent_state<M: Model + Clone + Send + Sync + 'static>(
    model: &M,
    t0: f64,
    y: &mut [f64],
) -> Result<(), Error> {
    model.start_relations(t0, y);
    let solution = solution_of(model);
    let solution = crate::run::initialization::solve_initial_equations(model, t0, y, solution)?;
    let solution = crate::step::projection::consistent_initial_values(model, t0, y, solution)?;
    crate::step::projection::consistent_algebraic_components(model, t0, y, solution)?;
    Ok(())
}

/// Whether an event of `direction` fires when its function goes from
/// `before` to `after`: falling from above zero to zero or below, rising
/// from below zero to zero or above.
pub fn fires(direction: EventDirection, before: f64, after: f64) -> bool {
    let rising = before < 0.0 && after >= 0.0;
    let falling = before > 0.0 && after <= 0.0;
    match direction {
        EventDirection::Any => rising || falling,
        EventDirection::Rising => rising,
        EventDirection::Falling => falling,
    }
}

/// Applies the instant at `t` to `y`: the actions of `due` (triggers:
/// event `k` of [`crate::ModelInfo::events`], or clock `k − events`), then
/// the rounds of the events they fire (Modelica's event iteration, at most
/// [`crate::MAX_EVENT_ITERATIONS`]), then a DAE's projection holding the
/// values the actions set. Every trigger that acted, in order.
pub fn act<M: Model + Clone + Send + Sync + 'static>(
    model: &M,
    t: f64,
    y: &mut [f64],
    due: &[usize],
) -> Result<Vec<usize>, Error> {
    let mut projector = Projector::new(model);
    apply_instant(model, projector.as_mut(), t, y, due, solution_of(model)).map(|(f, _)| f)
}

/// Projects a DAE's state `y` at `t` onto its constraints and their hidden
/// levels (the correction a run makes after each step); nothing for an
/// ODE.
pub fn project<M: Model>(model: &M, t: f64, y: &mut [f64]) -> Result<(), String> {
    match Projector::new(model) {
        None => Ok(()),
        Some(mut p) => p.project(t, y, INITIAL_ITERATIONS, None).map(|_| ()).map_err(|f| {
            format!("`{}` cannot be satisfied: {}", M::CONSTRAINTS[f.row].equation, f.message)
        }),
    }
}

/// The largest |residual| of `model`'s constraints and hidden constraints
/// at `(t, y)`: 0 for an ODE.
pub fn constraint_residual<M: Model>(model: &M, t: f64, y: &[f64]) -> f64 {
    let mut residuals = vec![0.0; M::CONSTRAINTS.len()];
    model.constraints(t, y, &mut residuals);
    residuals.iter().fold(0.0f64, |m, r| if r.is_nan() { f64::NAN } else { m.max(r.abs()) })
}

/// The instants of a model's clocks, each `offset + k·period` computed
/// from k, never summed.
pub struct ClockInstants(Clocks);

impl ClockInstants {
    /// The clocks of `model` with this instance's parameters, for a run
    /// from `t0` towards `t1`; a period that is not positive and finite, or
    /// too short for the time to resolve, is refused.
    pub fn of<M: Model>(model: &M, t0: f64, t1: f64) -> Result<ClockInstants, Error> {
        Clocks::of(model, t0, t1).map(ClockInstants)
    }

    /// The first instant of any clock after `t`.
    pub fn next_after(&self, t: f64) -> Option<f64> {
        self.0.next_after(t)
    }

    /// The triggers (numbered after the events) of the clocks with an
    /// instant at exactly `t`.
    pub fn due(&self, t: f64) -> Vec<usize> {
        self.0.due(t)
    }
}
