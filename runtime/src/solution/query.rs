//! What a user asks of a solution: values by name at the stored times, at
//! any time through the method's continuous extension, on a grid, as CSV.

use super::record::{hermite_or_linear, Storage};
use super::Solution;
use crate::error::Error;
use crate::solution::table::Table;

impl Solution {
    /// The times of the crossings of the event called `name`.
    pub fn event_times(&self, name: &str) -> Result<Vec<f64>, Error> {
        let Some(info) = self.names.events.iter().position(|e| e.name == name) else {
            return Err(Error::UnknownName {
                name: name.to_string(),
                known: self.names.events.iter().map(|e| e.name).collect(),
            });
        };
        Ok(self.events.iter().filter(|e| e.index == info).map(|e| e.t).collect())
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
        let readers =
            names.iter().map(|name| self.reader(name)).collect::<Result<Vec<_>, Error>>()?;
        let mut columns = vec![Vec::with_capacity(times.len()); names.len()];
        let mut y = vec![0.0; self.n];
        for &t in times {
            self.state_at(t, &mut y)?;
            for (column, value) in columns.iter_mut().zip(&readers) {
                column.push(value.read(self, t, &y));
            }
        }
        Ok(Table::new(names.iter().map(|s| s.to_string()).collect(), times.to_vec(), columns))
    }

    /// `names` at every stored time, as a [`Table`].
    pub fn table(&self, names: &[&str]) -> Result<Table, Error> {
        let columns =
            names.iter().map(|name| self.column(name)).collect::<Result<Vec<_>, Error>>()?;
        Ok(Table::new(names.iter().map(|s| s.to_string()).collect(), self.times.clone(), columns))
    }

    /// Writes `names` at every stored time as CSV: a header row (`t` and
    /// the names), then one row per stored time. `&sol.names()` writes
    /// every value.
    pub fn write_csv<W: std::io::Write>(&self, writer: W, names: &[&str]) -> Result<(), Error> {
        self.table(names)?.write_csv(writer)
    }

    /// A state, algebraic variable or output at the end of the run.
    pub fn last(&self, name: &str) -> Result<f64, Error> {
        // Nothing recorded yet (a model without states records an empty
        // state at each time).
        if self.end_t.is_nan() {
            return Err(Error::OutOfRange { t: f64::NAN, interval: (f64::NAN, f64::NAN) });
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
    ///
    /// At the time of a jump (an event's or a clock's actions,
    /// [`Solution::jumps`]) it is the value just after; the value just
    /// before is [`Solution::at_left`]'s. Nothing is interpolated across a
    /// jump.
    pub fn at(&self, t: f64, name: &str) -> Result<f64, Error> {
        let value = self.reader(name)?;
        let mut y = vec![0.0; self.n];
        self.state_at(t, &mut y)?;
        Ok(value.read(self, t, &y))
    }

    /// Like [`Solution::at`], but at the time of a jump the value just
    /// before it (the left limit); elsewhere the same as `at`.
    pub fn at_left(&self, t: f64, name: &str) -> Result<f64, Error> {
        let value = self.reader(name)?;
        match self.jumps.iter().find(|j| j.t == t) {
            Some(jump) => Ok(value.read(self, t, &jump.before)),
            None => self.at(t, name),
        }
    }

    /// The forward sensitivity ∂`name`/∂`wrt` at time `t`, where `wrt` is a
    /// parameter's name or `init(x)` for a state's initial value: a run of
    /// a model made by `with_sensitivities()` (`#[dae_model(sensitivities
    /// = [k, init(x)])]`) keeps them as the states `d(x)/d(k)`, read like
    /// [`Solution::at`] reads any state. An [`Error::UnknownName`] lists
    /// what the run has where it has no such sensitivity. For a DAE they
    /// are those of the consistent solution: projected, as the state is,
    /// onto the linearised constraints, so `init(x)` of a constrained `x`
    /// is the sensitivity to the value initialization starts from, not to
    /// a value the constraints would not let the state take.
    pub fn sensitivity(&self, t: f64, name: &str, wrt: &str) -> Result<f64, Error> {
        self.at(t, &format!("d({name})/d({wrt})"))
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
            return Err(Error::OutOfRange { t, interval: (f64::NAN, f64::NAN) });
        };
        if !(first.min(end)..=first.max(end)).contains(&t) {
            return Err(Error::OutOfRange { t, interval: (first, end) });
        }
        if t == end {
            y.copy_from_slice(&self.end_y);
            return Ok(());
        }
        // At a jump, the value after; the last jump at that time if
        // several acted at one instant.
        if let Some(jump) = self.jumps.iter().rev().find(|j| j.t == t) {
            y.copy_from_slice(&jump.after);
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
        // At a stored time, the stored state: a step's interpolant ends at
        // the state as computed, before projection onto the constraints.
        for j in [k - 1, k] {
            if self.times[j] == t {
                y.copy_from_slice(self.stored_state(j));
                return Ok(());
            }
        }
        self.interpolate_stored(k, t, y);
        Ok(())
    }

    /// The state at `t` within stored step `k` (from `times[k - 1]` to
    /// `times[k]`), by the step's interpolant.
    fn interpolate_stored(&self, k: usize, t: f64, y: &mut [f64]) {
        self.interpolate_continuous(k, t, y);
        // Discrete values hold between events: read, not interpolated.
        for name in self.names.discrete {
            if let Some(i) = self.names.states.iter().position(|s| s == name) {
                y[i] = self.stored_state(k - 1)[i];
            }
        }
    }

    /// [`Solution::interpolate_stored`] by the step's interpolant alone.
    fn interpolate_continuous(&self, k: usize, t: f64, y: &mut [f64]) {
        let n = self.n;
        let t0 = self.times[k - 1];
        let is_last = k == self.times.len() - 1;
        // The step as computed: a step an event cut keeps its computed end.
        let cut = self.cuts.iter().find(|(j, _, _)| *j == k);
        let (t1, y1) = match (self.cut_from, cut) {
            (Some(end), _) if is_last => (end, &self.last.y_new[..]),
            (_, Some((_, end, y_end))) => (*end, &y_end[..]),
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
                hermite_or_linear(y0, y1, slopes.then_some((&f0, &f1)), t1 - t0, s, y);
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
        Error::UnknownName { name: name.to_string(), known: self.names() }
    }
}

impl Storage {
    /// The error for a time this storage did not keep.
    fn not_stored(&self, t: f64) -> Error {
        match self {
            Storage::KeepEvery { k, .. } => Error::Thinned { t, keep_every: *k },
            _ => Error::NotStored { t },
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
