//! Profiling aid: Kepler e = 0.9 over ten orbits with the adaptive Taylor
//! method at tol 1e-15, repeated. Run: `cargo run --release --manifest-path
//! bench/Cargo.toml --example profile_taylor`.

use daegen::prelude::*;

#[dae_model(taylor = 1)]
fn kepler() {
    let e = param(0.9);
    let q1 = state(1.0 - e);
    let q2 = state(0.0);
    let p1 = state(0.0);
    let p2 = state(sqrt((1.0 + e) / (1.0 - e)));
    let r3 = (q1 * q1 + q2 * q2).powf(-1.5);
    der(q1) == p1;
    der(q2) == p2;
    der(p1) == -q1 * r3;
    der(p2) == -q2 * r3;
}

fn main() -> Result<(), daegen::Error> {
    for (tol, compact) in [(1e-9, false), (1e-9, true), (1e-15, false), (1e-15, true)] {
        let options = Options::new()
            .method(Method::Taylor)
            .rtol(tol)
            .atol(tol)
            .taylor_compact(compact);
        let runs = 1000;
        let start = std::time::Instant::now();
        let mut steps = 0;
        for _ in 0..runs {
            let sol = Kepler::default().simulate(0.0, 20.0 * std::f64::consts::PI, &options)?;
            steps = sol.stats().steps;
        }
        let seconds = start.elapsed().as_secs_f64() / runs as f64;
        println!(
            "tol {tol:e}, {}: {steps} steps per run, {:.3} ms per run, {:.0} ns per step",
            if compact { "compact" } else { "emitted" },
            seconds * 1e3,
            seconds / steps as f64 * 1e9
        );
    }
    Ok(())
}
