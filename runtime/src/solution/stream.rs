//! Watching a run as it goes: the step callback of
//! [`crate::Options::on_step`] and the progress bar of
//! [`crate::Options::progress`].

use crate::options::{Flow, Options, Step, StepCallback};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::time::{Duration, Instant};

/// A run's watchers.
#[derive(Clone)]
pub(super) struct Stream {
    callback: Option<StepCallback>,
    progress: Option<Progress>,
}

impl Stream {
    /// The watchers `options` ask for, `None` if none.
    pub(super) fn new(options: &Options, t0: f64, t1: f64) -> Option<Stream> {
        let progress = options
            .progress
            .then(|| Progress::new(t0, t1, ProgressDrawTarget::stderr, Instant::now()));
        (options.on_step.is_some() || progress.is_some())
            .then(|| Stream { callback: options.on_step.clone(), progress })
    }

    /// Shows the step that ended at `(t, y)`; `true` when the callback asks
    /// to stop.
    pub(super) fn see(
        &mut self,
        t: f64,
        y: &[f64],
        steps: usize,
        names: &'static [&'static str],
    ) -> bool {
        if let Some(progress) = &mut self.progress {
            progress.update(t, steps, Instant::now());
        }
        let Some(callback) = &self.callback else {
            return false;
        };
        let step = Step { t, y, steps, names };
        // A callback that panicked once has poisoned its lock; it is still
        // the user's callback, so it keeps being called.
        let mut callback = callback.lock().unwrap_or_else(|e| e.into_inner());
        callback(&step) == Flow::Stop
    }

    /// The run ended at `t` after `steps` steps.
    pub(super) fn finish(self, t: f64, steps: usize) {
        if let Some(mut progress) = self.progress {
            progress.finish(t, steps, Instant::now());
        }
    }
}

/// How long a run goes before its bar appears: short runs draw nothing.
const SHOW_AFTER: Duration = Duration::from_secs(1);
/// How often the bar is redrawn.
const REDRAW_EVERY: Duration = Duration::from_millis(100);
/// The bar's resolution.
const TICKS: u64 = 1000;

/// The progress bar: time reached of the interval, steps, steps per second.
#[derive(Clone)]
struct Progress {
    t0: f64,
    t1: f64,
    started: Instant,
    last_drawn: Instant,
    /// Where the bar is drawn (stderr; nowhere in tests).
    target: fn() -> ProgressDrawTarget,
    bar: Option<ProgressBar>,
}

impl Progress {
    fn new(t0: f64, t1: f64, target: fn() -> ProgressDrawTarget, now: Instant) -> Progress {
        Progress { t0, t1, started: now, last_drawn: now, target, bar: None }
    }

    /// The bar's position for time `t`: the fraction of the interval done.
    fn position(&self, t: f64) -> u64 {
        let fraction = if self.t1 == self.t0 {
            1.0
        } else {
            ((t - self.t0) / (self.t1 - self.t0)).clamp(0.0, 1.0)
        };
        (fraction * TICKS as f64).round() as u64
    }

    /// The line beside the bar.
    fn message(&self, t: f64, steps: usize, now: Instant) -> String {
        let seconds = now.duration_since(self.started).as_secs_f64();
        let rate = if seconds > 0.0 { steps as f64 / seconds } else { 0.0 };
        format!("t = {} of {} · {steps} steps · {} steps/s", short(t), short(self.t1), short(rate))
    }

    fn update(&mut self, t: f64, steps: usize, now: Instant) {
        if now.duration_since(self.last_drawn) < REDRAW_EVERY {
            return;
        }
        if self.bar.is_none() {
            if now.duration_since(self.started) < SHOW_AFTER {
                return;
            }
            let bar = ProgressBar::with_draw_target(Some(TICKS), (self.target)());
            if let Ok(style) = ProgressStyle::with_template("{bar:30} {percent:>3}% {msg}") {
                bar.set_style(style);
            }
            self.bar = Some(bar);
        }
        self.last_drawn = now;
        if let Some(bar) = &self.bar {
            bar.set_position(self.position(t));
            bar.set_message(self.message(t, steps, now));
        }
    }

    fn finish(&mut self, t: f64, steps: usize, now: Instant) {
        if let Some(bar) = &self.bar {
            bar.set_position(self.position(t));
            bar.finish_with_message(self.message(t, steps, now));
        }
    }
}

/// A number in four significant digits.
fn short(x: f64) -> String {
    let a = x.abs();
    if a != 0.0 && !(1e-3..1e6).contains(&a) {
        format!("{x:.3e}")
    } else {
        let digits = if a == 0.0 { 0 } else { (3 - a.log10().floor() as i32).max(0) as usize };
        format!("{x:.digits$}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn no_bar_for_a_run_shorter_than_a_second() {
        let start = Instant::now();
        let mut p = Progress::new(0.0, 10.0, ProgressDrawTarget::hidden, start);
        p.update(2.0, 100, start + Duration::from_millis(500));
        assert!(p.bar.is_none());
        p.update(4.0, 200, start + Duration::from_millis(1200));
        let bar = p.bar.as_ref().expect("drawn after a second");
        assert_eq!(bar.position(), 400);
        let message = bar.message();
        assert!(message.contains("t = 4.000 of 10.00"), "{message}");
        assert!(message.contains("200 steps"), "{message}");
        // 200 steps in 1.2 s.
        assert!(message.contains("166.7 steps/s"), "{message}");
    }

    #[test]
    fn backward_runs_fill_the_bar_too() {
        let start = Instant::now();
        let p = Progress::new(10.0, 0.0, ProgressDrawTarget::hidden, start);
        assert_eq!(p.position(10.0), 0);
        assert_eq!(p.position(2.5), 750);
        assert_eq!(p.position(-1.0), TICKS);
    }

    #[test]
    fn short_numbers() {
        assert_eq!(short(0.0), "0");
        assert_eq!(short(12345.678), "12346");
        assert_eq!(short(1.5), "1.500");
        assert_eq!(short(2.5e7), "2.500e7");
    }
}
