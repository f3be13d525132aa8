//! Runs of models with instants where something acts (an event with
//! `.reinit(..)` actions, a clock): the method integrates from one instant
//! to the next, the instant's actions change the state, and the method
//! starts afresh from the new state.
//!
//! Restarting is what makes every method correct across a jump: a fresh
//! start forgets the step size and error history (the first step is chosen
//! again, as at the start of a run), RADAU5's and RODAS5P's Jacobian and
//! factorised Newton matrices, Taylor's jet, the stiffness detector and
//! `Method::Auto`'s choice, and the dense output (each stretch has its own
//! interpolants; the solution keeps the value on either side of the jump
//! and interpolates on neither across it). Clock instants are the ends of
//! the stretches, so they are stepped to exactly, never over.
//!
//! At one instant the actions run in rounds (Modelica's event iteration):
//! the events and clocks due act, each action in the order written and on
//! the state the ones before it left; then every event function is
//! evaluated again, and an event whose function crossed zero in its
//! direction because of the actions fires in the next round, until a round
//! fires nothing, or [`MAX_EVENT_ITERATIONS`] rounds end in
//! [`Error::EventLoop`]. An event firing again within
//! [`Options::min_event_interval`] of its last firing ends the run with
//! [`Error::ZenoEvents`], which extrapolates where its firings accumulate.

use crate::error::Error;
use crate::info::EventDirection;
use crate::methods::Integrate;
use crate::model::Model;
use crate::solution::{EventHit, Solution};
use crate::step::projection::INITIAL_ITERATIONS;
use crate::step::Problem;

/// Most rounds of actions at one instant before [`Error::EventLoop`].
pub const MAX_EVENT_ITERATIONS: usize = 64;

/// Integrates `problem` with `integrate` between the instants where the
/// model's events and clocks act, applying their actions there.
pub(crate) fn integrate_hybrid<M: Model>(
    integrate: Integrate<M>,
    problem: Problem<'_, M>,
    mut solution: Solution,
) -> Result<Solution, Error> {
    let Problem { model, t0, t1, y0, options } = problem;
    let clocks = Clocks::of(model, t0, t1)?;
    let breakpoints = Breakpoints::of(model, t0, t1);
    let mut zeno = Zeno::new(M::INFO.events.len(), options.min_event_interval, t1 - t0);
    let mut projector = crate::step::projection::Projector::new(model);
    let (mut t, mut y) = (t0, y0.to_vec());
    let fixed_step = options.step.unwrap_or((t1 - t0).abs() / 1000.0);
    // Clocks whose grid holds the start act before the first step, unless
    // the run that ended here acted them.
    let mut due: Vec<usize> = if options.continues { Vec::new() } else { clocks.due(t) };
    loop {
        if !due.is_empty() {
            let (fired, next) =
                apply_instant(model, projector.as_mut(), t, &mut y, &due, solution)?;
            solution = next;
            let names = fired.iter().map(|&k| trigger_name::<M>(k)).collect();
            solution.push_jump(&y, names);
            if let Some((event, accumulation, count)) = zeno.fired(t, &fired) {
                return Err(Error::ZenoEvents {
                    t,
                    event: M::INFO.events[event].name,
                    accumulation,
                    count,
                    partial: Box::new(solution),
                });
            }
            let terminal =
                fired.iter().any(|&k| k < M::INFO.events.len() && M::INFO.events[k].terminal);
            if terminal {
                solution.stop_at_terminal_hit();
            }
            if terminal || solution.ended() {
                return Ok(solution);
            }
        }
        if t == t1 {
            return Ok(solution);
        }
        let next_clock = clocks.next_after(t).map_or(t1, |c| c.min(t1));
        let t_stop = breakpoints.next_after(t, t1).map_or(next_clock, |b| b.min(next_clock));
        // The run's limits, not each stretch's: fixed steps of the whole
        // interval over 1000 by default, and max_steps over all stretches.
        let taken = solution.stats().steps;
        if taken >= options.max_steps {
            let max_steps = options.max_steps;
            return Err(Error::MaxSteps { t, max_steps, partial: Box::new(solution) });
        }
        let stretch_options = options.step(fixed_step).max_steps(options.max_steps - taken);
        let stretch = Problem { model, t0: t, t1: t_stop, y0: &y, options: &stretch_options };
        solution = integrate(stretch, solution)?;
        t = solution.final_time();
        y.copy_from_slice(solution.final_state());
        due = solution.take_pending_actions();
        if due.is_empty() && solution.ended() {
            return Ok(solution);
        }
        for c in clocks.due(t) {
            if !due.contains(&c) {
                due.push(c);
            }
        }
        if due.is_empty() && t != t_stop {
            // The method ended short of the stretch without saying why:
            // nothing more to do.
            return Ok(solution);
        }
        if due.is_empty() && t != t1 {
            // A breakpoint of an input: the run starts afresh from it, the
            // state continuous (no jump is recorded).
            continue;
        }
    }
}

/// The instant at `t`: the rounds of actions starting with `due`, then a
/// DAE's projection onto its constraints holding the values the actions
/// set. Every trigger that acted, in order, and the solution with the
/// events the rounds fired.
pub(crate) fn apply_instant<M: Model>(
    model: &M,
    projector: Option<&mut crate::step::projection::Projector<'_, M>>,
    t: f64,
    y: &mut [f64],
    due: &[usize],
    mut solution: Solution,
) -> Result<(Vec<usize>, Solution), Error> {
    let fired = match act(model, t, y, due, &mut solution) {
        Ok(fired) => fired,
        Err(events) => return Err(Error::EventLoop { t, events, partial: Box::new(solution) }),
    };
    if let Some(i) = y.iter().position(|v| !v.is_finite()) {
        return Err(Error::NonFinite {
            t,
            variable: M::INFO.states[i],
            partial: Box::new(solution),
        });
    }
    if let Some(p) = projector {
        // A DAE's state after the actions is consistent again: the values
        // the actions set are kept, the others corrected onto the
        // constraints and their hidden levels, as at the start of a run.
        let hold = set_by::<M>(&fired);
        let projected = p
            .project(t, y, INITIAL_ITERATIONS, Some(&hold))
            .or_else(|_| p.project(t, y, INITIAL_ITERATIONS, None));
        match projected {
            Ok(r) => solution.note_constraint_residuals(r),
            Err(f) => {
                let names: Vec<&str> = fired.iter().map(|&k| trigger_name::<M>(k)).collect();
                return Err(Error::Constraint {
                    t,
                    constraint: M::CONSTRAINTS[f.row].equation,
                    level: M::CONSTRAINTS[f.row].level,
                    message: format!(
                        "after the actions of `{}`, the state cannot be made consistent: {}",
                        names.join("`, `"),
                        f.message
                    ),
                    partial: Box::new(solution),
                });
            }
        }
    }
    Ok((fired, solution))
}

/// Which states the actions of `fired` set (held by the projection after
/// them).
fn set_by<M: Model>(fired: &[usize]) -> Vec<bool> {
    let mut hold = vec![false; M::STATES];
    for &k in fired {
        let resets = match M::INFO.events.get(k) {
            Some(e) => e.resets,
            None => M::INFO.clocks[k - M::INFO.events.len()].resets,
        };
        for name in resets {
            if let Some(i) = M::INFO.states.iter().position(|s| s == name) {
                hold[i] = true;
            }
        }
    }
    hold
}

/// The name of trigger `k`: event `k`, or clock `k − events`.
pub(crate) fn trigger_name<M: Model>(k: usize) -> &'static str {
    match M::INFO.events.get(k) {
        Some(e) => e.name,
        None => M::INFO.clocks[k - M::INFO.events.len()].name,
    }
}

/// The rounds of actions at `t`, starting with `first` (triggers: events,
/// then clocks): `y` is changed in place, the events fired by a round are
/// recorded in `solution`. Every trigger that acted, in order; the last
/// round's names if the rounds do not end.
fn act<M: Model>(
    model: &M,
    t: f64,
    y: &mut [f64],
    first: &[usize],
    solution: &mut Solution,
) -> Result<Vec<usize>, Vec<&'static str>> {
    let m = M::INFO.events.len();
    let (mut g_before, mut g_after) = (vec![0.0; m], vec![0.0; m]);
    model.events(t, y, &mut g_before);
    let mut round: Vec<usize> = first.to_vec();
    let mut fired = Vec::new();
    let mut pre = y.to_vec();
    for _ in 0..MAX_EVENT_ITERATIONS {
        pre.copy_from_slice(y);
        for &k in &round {
            model.act(k, t, &pre, y);
        }
        fired.extend_from_slice(&round);
        if m == 0 {
            return Ok(fired);
        }
        model.events(t, y, &mut g_after);
        round.clear();
        for (i, info) in M::INFO.events.iter().enumerate() {
            let (a, b) = (g_before[i], g_after[i]);
            let rising = a < 0.0 && b >= 0.0;
            let falling = a > 0.0 && b <= 0.0;
            let fires = match info.direction {
                EventDirection::Any => rising || falling,
                EventDirection::Rising => rising,
                EventDirection::Falling => falling,
            };
            if fires {
                round.push(i);
                solution.push_event(EventHit {
                    name: info.name,
                    index: i,
                    t,
                    rising,
                    state: y.to_vec(),
                });
            }
        }
        if round.is_empty() {
            return Ok(fired);
        }
        std::mem::swap(&mut g_before, &mut g_after);
    }
    Err(round.iter().map(|&k| trigger_name::<M>(k)).collect())
}

/// The instants of a model's clocks.
pub(crate) struct Clocks {
    /// `(period, offset)` of each.
    grids: Vec<(f64, f64)>,
    /// Where trigger numbers of clocks start (after the events).
    first: usize,
}

impl Clocks {
    /// The clocks of `model` for a run from `t0` to `t1`; a clock with a
    /// period that is not positive and finite, or a backward run with
    /// clocks, is refused.
    pub(crate) fn of<M: Model>(model: &M, t0: f64, t1: f64) -> Result<Clocks, Error> {
        let grids: Vec<(f64, f64)> = (0..M::INFO.clocks.len()).map(|k| model.clock(k)).collect();
        for (k, &(h, offset)) in grids.iter().enumerate() {
            let name = M::INFO.clocks[k].name;
            if !(h > 0.0 && h.is_finite() && offset.is_finite()) {
                return Err(Error::InvalidOptions {
                    message: format!("the clock `{name}` has period {h} and offset {offset}: its period must be positive and finite, its offset finite"),
                });
            }
        }
        // A period below the time's resolution over the run would make
        // instants that do not advance.
        let resolution = 64.0 * f64::EPSILON * t0.abs().max(t1.abs()).max(1.0);
        for (k, &(h, _)) in grids.iter().enumerate() {
            if h < resolution {
                let name = M::INFO.clocks[k].name;
                return Err(Error::InvalidOptions {
                    message: format!("the clock `{name}` has period {h}, below what the time resolves over this run ({resolution:e}): a longer period, or a shorter run"),
                });
            }
        }
        if !grids.is_empty() && t1 < t0 {
            return Err(Error::InvalidOptions {
                message: format!("{} has clocks, which run forward in time: integrate from the earlier time to the later", M::INFO.name),
            });
        }
        Ok(Clocks { grids, first: M::INFO.events.len() })
    }

    /// Instant `k` of clock `c`: computed from the grid, never accumulated,
    /// so a long run's instants do not drift.
    fn instant(&self, c: usize, k: f64) -> f64 {
        let (h, offset) = self.grids[c];
        offset + k * h
    }

    /// The first instant of any clock after `t`.
    pub(crate) fn next_after(&self, t: f64) -> Option<f64> {
        (0..self.grids.len())
            .map(|c| {
                let (h, offset) = self.grids[c];
                let mut k = ((t - offset) / h).floor().max(0.0);
                // The period is above the time's resolution: a few
                // increments pass t.
                for _ in 0..8 {
                    if self.instant(c, k) > t {
                        break;
                    }
                    k += 1.0;
                }
                self.instant(c, k)
            })
            .min_by(f64::total_cmp)
    }

    /// The triggers of the clocks with an instant at exactly `t`.
    pub(crate) fn due(&self, t: f64) -> Vec<usize> {
        (0..self.grids.len())
            .filter(|&c| {
                let (h, offset) = self.grids[c];
                let k = ((t - offset) / h).round();
                k >= 0.0 && self.instant(c, k) == t
            })
            .map(|c| self.first + c)
            .collect()
    }
}

/// The breakpoints of the model's inputs inside a run, in its direction.
struct Breakpoints {
    times: Vec<f64>,
}

impl Breakpoints {
    fn of<M: Model>(model: &M, t0: f64, t1: f64) -> Breakpoints {
        let (lo, hi) = (t0.min(t1), t0.max(t1));
        // One a few ulps from an end is that end (a step from 0.2 by 0.1
        // ends an ulp past a breakpoint at 0.3): a restart there would
        // leave an interval no step can take.
        let resolution = 64.0 * f64::EPSILON * lo.abs().max(hi.abs());
        let mut times: Vec<f64> = model
            .input_breakpoints()
            .into_iter()
            .filter(|&b| b > lo + resolution && b < hi - resolution)
            .collect();
        times.sort_by(f64::total_cmp);
        times.dedup();
        if t1 < t0 {
            times.reverse();
        }
        Breakpoints { times }
    }

    /// The first breakpoint strictly after `t` towards `t1`.
    fn next_after(&self, t: f64, t1: f64) -> Option<f64> {
        let forward = t1 >= t;
        self.times.iter().copied().find(|&b| if forward { b > t } else { b < t })
    }
}

/// Watches the intervals between firings of each event for accumulation.
struct Zeno {
    /// Per event: its last firing, the interval before it, how many.
    last: Vec<(f64, f64, usize)>,
    min_interval: f64,
}

impl Zeno {
    fn new(events: usize, min_interval: Option<f64>, length: f64) -> Zeno {
        Zeno {
            last: vec![(f64::NAN, f64::NAN, 0); events],
            min_interval: min_interval.unwrap_or(1e-10 * length.abs()),
        }
    }

    /// Notes the firings of `fired` (triggers) at `t`; for an event that
    /// fired again too soon, `(event, where its firings accumulate, how
    /// often it fired)`.
    fn fired(&mut self, t: f64, fired: &[usize]) -> Option<(usize, f64, usize)> {
        for &k in fired {
            let Some((last, previous, count)) = self.last.get_mut(k) else { continue };
            let interval = (t - *last).abs();
            *count += 1;
            // A second firing at the same instant (a later round) is not
            // a new one.
            if interval == 0.0 {
                continue;
            }
            if interval < self.min_interval {
                // Aitken's Δ²: intervals shrinking by r sum to r·Δ/(1 − r).
                let r = interval / *previous;
                let rest = if r < 1.0 { interval * r / (1.0 - r) } else { 0.0 };
                let direction = if t >= *last { 1.0 } else { -1.0 };
                return Some((k, t + direction * rest, *count));
            }
            if last.is_finite() {
                *previous = interval;
            }
            *last = t;
        }
        None
    }
}
