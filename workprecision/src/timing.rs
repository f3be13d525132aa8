//! Timing by the median of repeats after a warm-up: sub-millisecond solves
//! on a shared 2-core machine vary by ±30 % from one batch to the next, so
//! one run says little.

use std::time::{Duration, Instant};

/// How long to time each run, and what to sweep.
#[derive(Clone, Debug)]
pub struct Settings {
    /// At least this many timed repeats…
    pub min_repeats: usize,
    /// …and at most this many…
    pub max_repeats: usize,
    /// …stopping after this much time once `min_repeats` are done.
    pub budget: Duration,
    /// Keep only tolerances at or above this (a quick sweep).
    pub tightest: f64,
    /// A problem's runs are timed in this many rounds, and in each round a
    /// tolerance's runs, ours and the peers' in this process, one right
    /// after another, ours first in odd rounds and last in even ones; a
    /// run's time is the median of its rounds' (each round with a share of
    /// the repeats and the budget). Timed minutes apart, one run after
    /// another, the same solve moved by up to 1.3× on this shared machine;
    /// side by side, both sides move together. Always first, ours paid for
    /// it: the outer solar system's DOP853 read 0.81× `ode_solvers`' time
    /// that way, 0.73× with the order alternating, as in the benchmark's
    /// alternation of single solves (0.73–0.79×).
    pub rounds: usize,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            min_repeats: 5,
            max_repeats: 200,
            budget: Duration::from_millis(500),
            tightest: 0.0,
            rounds: 3,
        }
    }
}

/// The median wall time of `run` over repeats after one warm-up, and the
/// result of the last run.
pub fn median_time<T>(settings: &Settings, mut run: impl FnMut() -> T) -> (f64, T) {
    let mut result = run();
    let mut times = Vec::with_capacity(settings.min_repeats);
    let start = Instant::now();
    while times.len() < settings.max_repeats.max(1)
        && (times.len() < settings.min_repeats.max(1) || start.elapsed() < settings.budget)
    {
        let t = Instant::now();
        result = run();
        times.push(t.elapsed().as_secs_f64());
    }
    (median(times), result)
}

/// The median of `times` (the upper one of an even count); NaN if empty.
pub fn median(mut times: Vec<f64>) -> f64 {
    times.sort_by(f64::total_cmp);
    times.get(times.len() / 2).copied().unwrap_or(f64::NAN)
}

impl Settings {
    /// The settings of one of `rounds` rounds: that share of the repeats
    /// and the budget.
    pub fn one_round(&self) -> Settings {
        let rounds = self.rounds.max(1);
        Settings {
            min_repeats: self.min_repeats.div_ceil(rounds),
            max_repeats: self.max_repeats.div_ceil(rounds),
            budget: self.budget / rounds as u32,
            tightest: self.tightest,
            rounds: 1,
        }
    }
}
