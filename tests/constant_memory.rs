//! A run streamed through `Options::on_step` and stored at
//! `Options::output_times` only uses the same memory for 10⁵ steps as for
//! 10⁷: nothing grows with the number of steps. Measured by an allocator
//! that counts the bytes alive (this test binary's own global allocator),
//! on the thread that runs the model only: the test harness's own threads
//! allocate when they please.

use daegen::prelude::*;
use daegen::{Flow, Step};
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

struct Counting;

static LIVE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

thread_local! {
    static COUNTED: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

fn counted() -> bool {
    COUNTED.try_with(|c| c.get()).unwrap_or(false)
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if counted() {
            let live = LIVE.fetch_add(layout.size(), Ordering::SeqCst) + layout.size();
            PEAK.fetch_max(live, Ordering::SeqCst);
        }
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        if counted() {
            LIVE.fetch_sub(layout.size(), Ordering::SeqCst);
        }
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

mod support;
use support::Oscillator;

/// Peak bytes alive above the start during a run of `steps` Euler steps to
/// t = 10, streamed to a callback that keeps the largest |x|, stored at 11
/// output times; with that largest |x|.
fn peak_bytes(steps: usize) -> (usize, f64) {
    let largest = std::sync::Arc::new(std::sync::Mutex::new(0.0f64));
    let seen = largest.clone();
    let opts = Options::new()
        .method(Method::Euler)
        .step(10.0 / steps as f64)
        .max_steps(steps + 1)
        .output_times((0..=10).map(f64::from).collect())
        .on_step(move |step: &Step| {
            let mut m = seen.lock().unwrap();
            *m = m.max(step.y[0].abs());
            Flow::Continue
        });
    let model = Oscillator::default();
    let before = LIVE.load(Ordering::SeqCst);
    PEAK.store(before, Ordering::SeqCst);
    COUNTED.with(|c| c.set(true));
    let sol = model.simulate(0.0, 10.0, &opts).unwrap();
    COUNTED.with(|c| c.set(false));
    let peak = PEAK.load(Ordering::SeqCst) - before;
    assert_eq!(sol.stats().steps, steps);
    assert_eq!(sol.times().len(), 11);
    let largest = *largest.lock().unwrap();
    (peak, largest)
}

#[test]
fn a_streamed_run_uses_the_same_memory_for_a_hundred_times_the_steps() {
    let (small, _) = peak_bytes(100_000);
    let (large, largest) = peak_bytes(10_000_000);
    // The callback saw the steps: explicit Euler on the oscillator grows
    // the amplitude by sqrt(1 + h²) per step (h = 1e-6), and |x| is
    // largest at t = 3π, after 3π/h steps.
    let amplitude = (1.0 + 1e-12f64).powf(0.5 * 3.0 * std::f64::consts::PI / 1e-6);
    assert!((largest - amplitude).abs() < 1e-9, "{largest}");
    assert_eq!(small, large, "peak bytes alive: {small} for 1e5 steps, {large} for 1e7");
    println!("peak bytes alive: {small} for 1e5 steps, {large} for 1e7");
    // And little of it: the solution, the model and the scratch vectors.
    assert!(large < 64 * 1024, "{large} bytes");
}
