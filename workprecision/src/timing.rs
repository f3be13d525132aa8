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
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            min_repeats: 5,
            max_repeats: 200,
            budget: Duration::from_millis(500),
            tightest: 0.0,
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
    times.sort_by(f64::total_cmp);
    (times[times.len() / 2], result)
}
