//! Events: zero crossings of the model's event functions `g(t, y)`, found on
//! the dense output of each accepted step and located to machine precision.
//!
//! After each accepted step `[t_old, t_new]` the event functions are sampled
//! at the step's ends and, for methods with long steps (Taylor), at interior
//! points of the continuous extension; a sign change between two samples
//! brackets a crossing, which is then located by the Illinois variant of
//! regula falsi with a bisection safeguard (Dowell & Jarratt 1971) on
//! `φ(t) = g(t, y(t))`, `y(t)` the step's interpolant, until the bracket is
//! two adjacent floating-point numbers. Where g keeps its sign between two
//! samples but its generated rate dg/dt turns back towards zero, the
//! extremum is located and each side bracketed, so a pair of crossings
//! between samples is found too (models with a mass matrix solved at run
//! time have no rates: there such a pair is missed). A root where `g` only
//! touches zero is not a crossing. A run that starts exactly on a zero of `g` does not fire
//! there (restarting a bouncing ball from the ground does not bounce again).
//! Rising and falling refer to time: in a backward run a rising crossing is
//! one where g decreases along the integration.

use crate::error::Error;
use crate::info::EventDirection;
use crate::model::Model;
use crate::solution::{EventHit, Solution};

/// Watches a run's steps for events.
pub(crate) struct EventWatch<'m, M: Model> {
    model: &'m M,
    /// Event values and rates at the end of the last sample.
    g_old: Vec<f64>,
    rate_old: Vec<f64>,
    g_new: Vec<f64>,
    rate_new: Vec<f64>,
    /// Whether the model has the rates (explicit ODEs).
    has_rates: bool,
    y: Vec<f64>,
    scratch: Vec<f64>,
    /// Sub-intervals each step is sampled on.
    subdivisions: usize,
    /// Crossings this close to the start of the run are its initial condition.
    t_start: f64,
}

/// Whether event `i` interrupts the run: it is terminal, or it acts (the
/// run driver applies its actions and starts again from there).
fn stops<M: Model>(i: usize) -> bool {
    let event = &M::INFO.events[i];
    event.terminal || !event.resets.is_empty()
}

/// Checks the step just pushed to `solution` for events, if the model has
/// any: `true` when a terminal one ended the run there.
pub(crate) fn stop_after_step<M: Model>(
    watch: &mut Option<EventWatch<'_, M>>,
    solution: &mut Solution,
) -> Result<bool, Error> {
    match watch {
        Some(watch) => watch.after_step(solution),
        None => Ok(false),
    }
}

/// In an integrator's step loop, after an accepted step was pushed: checks
/// it for events if the model has any, shows it to the step callback and the progress
/// bar, and breaks out of the loop at a terminal event or when the
/// callback says stop.
macro_rules! after_accepted_step {
    ($events:ident, $solution:ident) => {
        if $events.is_some() {
            let stop = $crate::step::events::stop_after_step(&mut $events, &mut $solution)?;
            if stop {
                break;
            }
        }
        if $solution.after_accepted_step() {
            break;
        }
    };
}
pub(crate) use after_accepted_step;

impl<'m, M: Model> EventWatch<'m, M> {
    /// A watch for `model`'s events from `(t0, y0)`, or `None` if it has none.
    /// `subdivisions` ≥ 1 sub-intervals of each step are checked for a sign change.
    pub(crate) fn new(
        model: &'m M,
        t0: f64,
        y0: &[f64],
        subdivisions: usize,
    ) -> Option<EventWatch<'m, M>> {
        let m = M::INFO.events.len();
        if m == 0 {
            return None;
        }
        let (mut g_old, mut rate_old) = (vec![0.0; m], vec![0.0; m]);
        model.events(t0, y0, &mut g_old);
        let has_rates = M::EVENT_RATES.is_available();
        if has_rates {
            model.event_rates(t0, y0, &mut rate_old);
        }
        Some(EventWatch {
            model,
            g_old,
            rate_old,
            g_new: vec![0.0; m],
            rate_new: vec![0.0; m],
            has_rates,
            y: vec![0.0; M::STATES],
            scratch: vec![0.0; m],
            subdivisions: subdivisions.max(1),
            t_start: t0,
        })
    }

    /// Checks the last step of `solution` for events, records them in it and,
    /// at a terminal one, cuts the solution there (and says so with `true`).
    pub(crate) fn after_step(&mut self, solution: &mut Solution) -> Result<bool, Error> {
        let Some((t_old, t_new)) = solution.last_step() else {
            return Ok(false);
        };
        solution.prepare_last_step();
        let mut hits: Vec<EventHit> = Vec::new();
        let mut a = t_old;
        for j in 1..=self.subdivisions {
            let b = if j == self.subdivisions {
                t_new
            } else {
                t_old + (t_new - t_old) * (j as f64 / self.subdivisions as f64)
            };
            if j == self.subdivisions {
                self.y.copy_from_slice(solution.last_step_end());
            } else {
                solution.interpolate_last_step(b, &mut self.y);
            }
            self.model.events(b, &self.y, &mut self.g_new);
            if self.has_rates {
                self.model.event_rates(b, &self.y, &mut self.rate_new);
            }
            let bad = self.g_new.iter().chain(&self.rate_new).position(|g| !g.is_finite());
            if let Some(i) = bad {
                // The solution ends where the event function stopped being
                // finite: past it nothing was checked.
                if j < self.subdivisions {
                    solution.end_last_step_at(b, &self.y);
                }
                return Err(Error::NonFinite {
                    t: b,
                    variable: M::INFO.events[i % M::INFO.events.len()].name,
                    partial: solution.take(),
                });
            }
            for i in 0..M::INFO.events.len() {
                self.crossings(solution, i, a, b, &mut hits);
            }
            std::mem::swap(&mut self.g_old, &mut self.g_new);
            std::mem::swap(&mut self.rate_old, &mut self.rate_new);
            a = b;
            if hits.iter().any(|h| stops::<M>(h.index)) {
                break;
            }
        }
        // Crossings in time order; a terminal one ends the run and the later ones never happen.
        let forward = t_new >= t_old;
        hits.sort_by(|p, q| {
            let order = p.t.total_cmp(&q.t);
            if forward {
                order
            } else {
                order.reverse()
            }
        });
        let stop = hits.iter().position(|h| stops::<M>(h.index));
        if let Some(k) = stop {
            // Fired again right after a restart: the crossings accumulate
            // and one more restart would not move.
            let after = (hits[k].t - self.t_start).abs();
            if after <= 1e3 * f64::EPSILON * hits[k].t.abs().max(1.0) {
                let hit = &hits[k];
                solution.end_last_step_at(hit.t, &hit.state);
                return Err(Error::EventChatter {
                    t: hit.t,
                    event: M::INFO.events[hit.index].name,
                    after,
                    partial: solution.take(),
                });
            }
            hits.truncate(k + 1);
            let last = &hits[k];
            solution.end_last_step_at(last.t, &last.state);
        }
        let stopping = stop.map(|k| &M::INFO.events[hits[k].index]);
        for hit in hits {
            solution.push_event(hit);
        }
        if let Some(event) = stopping {
            solution.stop_at_last_event(event.terminal, !event.resets.is_empty());
        }
        Ok(stop.is_some())
    }

    /// The crossings of event `i` between samples `a` and `b`: one where g
    /// changes sign; where it does not but its rate does, g has an extremum
    /// inside and may cross twice, once on each side of it.
    fn crossings(
        &mut self,
        solution: &Solution,
        i: usize,
        a: f64,
        b: f64,
        hits: &mut Vec<EventHit>,
    ) {
        let (g_a, g_b) = (self.g_old[i], self.g_new[i]);
        let (r_a, r_b) = (self.rate_old[i], self.rate_new[i]);
        let mut pieces = [(a, g_a), (b, g_b), (b, g_b)];
        let mut count = 2;
        let same_side = g_a * g_b > 0.0 || (g_a == 0.0 && g_b != 0.0);
        // Only an extremum turning back towards zero (a minimum of a positive
        // g, a maximum of a negative one) can hide two crossings.
        let turns_to_zero = r_a * g_b < 0.0 && r_b * g_b > 0.0;
        if self.has_rates && same_side && turns_to_zero {
            let t_m = bracketed_root(|t| self.along(solution, i, t, true), a, b, r_a, r_b);
            let g_m = self.along(solution, i, t_m, false);
            pieces = [(a, g_a), (t_m, g_m), (b, g_b)];
            count = 3;
        }
        for k in 1..count {
            let ((lo, g_lo), (hi, g_hi)) = (pieces[k - 1], pieces[k]);
            // Up or down along the integration; rising and falling are in
            // time, so a backward run swaps them.
            let up = g_lo < 0.0 && g_hi >= 0.0;
            let down = g_lo > 0.0 && g_hi <= 0.0;
            let (rising, falling) = if hi >= lo { (up, down) } else { (down, up) };
            let fires = match M::INFO.events[i].direction {
                EventDirection::Any => rising || falling,
                EventDirection::Rising => rising,
                EventDirection::Falling => falling,
            };
            if !fires {
                continue;
            }
            let t = bracketed_root(|t| self.along(solution, i, t, false), lo, hi, g_lo, g_hi);
            let t_new = solution.last_step().map_or(t, |(_, t_new)| t_new);
            let start_tolerance =
                16.0 * f64::EPSILON * self.t_start.abs().max((t_new - self.t_start).abs());
            if (t - self.t_start).abs() <= start_tolerance {
                continue;
            }
            let mut state = vec![0.0; M::STATES];
            solution.interpolate_last_step(t, &mut state);
            hits.push(EventHit { name: M::INFO.events[i].name, index: i, t, rising, state });
        }
    }

    /// Event `i` (or its rate) along the last step's interpolant at `t`.
    fn along(&mut self, solution: &Solution, i: usize, t: f64, rate: bool) -> f64 {
        solution.interpolate_last_step(t, &mut self.y);
        if rate {
            self.model.event_rates(t, &self.y, &mut self.scratch);
        } else {
            self.model.events(t, &self.y, &mut self.scratch);
        }
        self.scratch[i]
    }
}

/// The zero of `f` in the bracket `[a, b]` (`f(a)`, `f(b)` of opposite signs,
/// `f(b)` possibly 0): the Illinois variant of regula falsi, with a bisection
/// whenever an iteration does not halve the bracket, until the bracket is two
/// neighbouring floating-point numbers. Returns the end past the zero.
pub(crate) fn bracketed_root(
    mut f: impl FnMut(f64) -> f64,
    a: f64,
    b: f64,
    f_a: f64,
    f_b: f64,
) -> f64 {
    let (mut lo, mut hi, mut f_lo, mut f_hi) = (a, b, f_a, f_b);
    if f_hi == 0.0 || f_hi.signum() == f_lo.signum() {
        return b;
    }
    let mut side = 0i8;
    for _ in 0..400 {
        let width = (hi - lo).abs();
        let mid = lo + (hi - lo) / 2.0;
        if mid == lo || mid == hi {
            break;
        }
        let mut t = hi - f_hi * (hi - lo) / (f_hi - f_lo);
        if !(t.is_finite() && (t - lo) * (hi - t) > 0.0) {
            t = mid;
        }
        for bisect in [false, true] {
            let probe = if bisect {
                if (hi - lo).abs() <= 0.5 * width {
                    break;
                }
                lo + (hi - lo) / 2.0
            } else {
                t
            };
            let inside = (probe - lo) * (hi - probe);
            if inside <= 0.0 || inside.is_nan() {
                break;
            }
            let value = f(probe);
            if value == 0.0 {
                return probe;
            }
            if value.signum() == f_lo.signum() {
                lo = probe;
                f_lo = value;
                if side == -1 {
                    f_hi /= 2.0;
                }
                side = -1;
            } else {
                hi = probe;
                f_hi = value;
                if side == 1 {
                    f_lo /= 2.0;
                }
                side = 1;
            }
        }
    }
    hi
}

#[cfg(test)]
mod tests {
    use super::bracketed_root;

    #[test]
    fn roots_to_neighbouring_floats() {
        let r = bracketed_root(|t| t * t - 2.0, 0.0, 2.0, -2.0, 2.0);
        assert!((r - 2f64.sqrt()).abs() <= 2.0 * f64::EPSILON * r);
        // A flat function regula falsi alone creeps on.
        let r = bracketed_root(|t| (t - 0.3).powi(9), 0.0, 1.0, (-0.3f64).powi(9), 0.7f64.powi(9));
        assert!((r - 0.3).abs() <= 1e-15, "{r}");
        // Backwards brackets work alike.
        let r = bracketed_root(|t| t.cos(), 3.0, 1.0, 3f64.cos(), 1f64.cos());
        assert!((r - std::f64::consts::FRAC_PI_2).abs() <= 4.0 * f64::EPSILON);
    }
}
