//! Profiling aid: Kepler e = 0.9 over ten orbits with the adaptive Taylor
//! method at tol 1e-9 and 1e-15 (orders 14 and 24), interpreted tape
//! against unrolled recurrences, repeated. Run: `cargo run --release --manifest-path
//! bench/Cargo.toml --example profile_taylor`.

use daegen::prelude::*;

include!("../../tests/models/kepler.rs");
kepler_model!(taylor = 1, unroll = [14, 24]);

fn main() -> Result<(), daegen::Error> {
    let only_unrolled = std::env::args().any(|a| a == "--unrolled");
    for (tol, compact) in [(1e-9, false), (1e-9, true), (1e-15, false), (1e-15, true)] {
        if only_unrolled && compact {
            continue;
        }
        let options = Options::new()
            .method(Method::Taylor)
            .rtol(tol)
            .atol(tol)
            .taylor_compact(compact)
            .dense_output(false);
        // The fastest of ten batches: this shared machine's noise only slows runs down.
        let runs = 100;
        let mut seconds = f64::INFINITY;
        let mut steps = 0;
        for _ in 0..10 {
            let start = std::time::Instant::now();
            for _ in 0..runs {
                let sol = Kepler::default().simulate(0.0, 20.0 * std::f64::consts::PI, &options)?;
                steps = sol.stats().steps;
            }
            seconds = seconds.min(start.elapsed().as_secs_f64() / runs as f64);
        }
        println!(
            "tol {tol:e}, {}: {steps} steps per run, {:.3} ms per run, {:.0} ns per step",
            if compact { "compact" } else { "unrolled" },
            seconds * 1e3,
            seconds / steps as f64 * 1e9
        );
    }
    Ok(())
}
