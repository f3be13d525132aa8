//! The benchmark's step-loop cases (`cases.rs`) as a
//! binary of their own, built for AVX2 at most so that `valgrind
//! --tool=callgrind` can count it (valgrind does not decode AVX-512):
//!
//! - `loop-subject count PROBLEM METHOD CASE TOL REPS` runs one case REPS
//!   times (`PROBLEM rhs - - REPS`: REPS right-hand-side evaluations), for
//!   callgrind to count;
//! - `loop-subject time PROBLEM METHOD CASE TOL` prints the case's steps,
//!   evaluations per step, median nanoseconds per step and heap
//!   allocations per step (a run twice as long, less this one, over the
//!   steps it added);
//! - `loop-subject time PROBLEM rhs` prints nanoseconds per evaluation.

#![allow(clippy::excessive_precision)]

use daegen::prelude::*;
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

include!("../../../tests/models/lorenz.rs");
include!("../../../tests/models/arenstorf.rs");
lorenz_model!([1.0, 0.0, 0.0], taylor = 1, unroll = [16, 18, 20]);
arenstorf_model!();

/// Counts allocations, so that a step's can be counted.
struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

// SAFETY: forwards every call to the system allocator unchanged.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        // SAFETY: the caller's contract is the system allocator's.
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: `ptr` came from `alloc`, that is from `System`.
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        // SAFETY: as for `alloc` and `dealloc`.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

fn allocations_so_far() -> usize {
    ALLOCATIONS.load(Ordering::Relaxed)
}

mod cases;
use cases::{chained_evaluations, evaluations, loop_one, run};

/// The median of `repeats` timings of `f`, in seconds.
fn median(repeats: usize, mut f: impl FnMut()) -> f64 {
    let mut times: Vec<f64> = (0..repeats)
        .map(|_| {
            let start = Instant::now();
            f();
            start.elapsed().as_secs_f64()
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[repeats / 2]
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match args.first().map(String::as_str) {
        Some("count") => loop_one(&args[1..]),
        Some("time") if args.get(2).is_some_and(|a| a == "chain") => {
            const CALLS: usize = 1_000_000;
            let seconds = median(31, || {
                std::hint::black_box(chained_evaluations(&args[1], CALLS));
            });
            println!("{}", seconds * 1e9 / CALLS as f64);
        }
        Some("time") if args.get(2).is_some_and(|a| a == "rhs") => {
            const CALLS: usize = 1_000_000;
            let seconds = median(31, || {
                std::hint::black_box(evaluations(&args[1], CALLS));
            });
            println!("{}", seconds * 1e9 / CALLS as f64);
        }
        Some("versus") => {
            // Ours (every step kept, as the sweep runs) and ode_solvers'
            // in alternation: medians per step and their ratio.
            let method = cases::method(&args[2]);
            let tol: f64 = args[3].parse().unwrap_or(1e-6);
            let (ours_steps, _, _) = run(&args[1], method, "every step kept", tol, 1.0);
            let (peer_steps, _, _) = run(&args[1], method, "ode_solvers", tol, 1.0);
            let (mut ours, mut peer) = (Vec::new(), Vec::new());
            for _ in 0..301 {
                ours.push(median(1, || {
                    std::hint::black_box(run(&args[1], method, "every step kept", tol, 1.0));
                }));
                peer.push(median(1, || {
                    std::hint::black_box(run(&args[1], method, "ode_solvers", tol, 1.0));
                }));
            }
            ours.sort_by(f64::total_cmp);
            peer.sort_by(f64::total_cmp);
            let (o, p) = (ours[150] * 1e9 / ours_steps as f64, peer[150] * 1e9 / peer_steps as f64);
            println!("{ours_steps} {peer_steps} {o} {p} {}", ours[150] / peer[150]);
        }
        Some("time") => {
            let method = cases::method(&args[2]);
            let tol: f64 = args[4].parse().unwrap_or(1e-6);
            let (steps, evals, allocations) = run(&args[1], method, &args[3], tol, 1.0);
            let (steps_twice, _, twice) = run(&args[1], method, &args[3], tol, 2.0);
            let seconds = median(201, || {
                std::hint::black_box(run(&args[1], method, &args[3], tol, 1.0));
            });
            let added = (twice as f64 - allocations as f64) / (steps_twice - steps).max(1) as f64;
            println!(
                "{steps} {} {} {added}",
                evals as f64 / steps as f64,
                seconds * 1e9 / steps as f64
            );
        }
        _ => eprintln!("loop-subject count|time ..."),
    }
}
