//! Profiling aid: Kepler e = 0.9 over ten orbits with DOPRI5 at tol 1e-12,
//! repeated. Run: `cargo run --release --manifest-path bench/Cargo.toml --example profile_kepler`.

use daegen::prelude::*;

#[dae_model]
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
    let options = Options::new().method(Method::Dopri5).rtol(1e-12).atol(1e-12);
    let start = std::time::Instant::now();
    let mut steps = 0;
    for _ in 0..300 {
        let sol = Kepler::default().simulate(0.0, 20.0 * std::f64::consts::PI, &options)?;
        steps = sol.stats().steps;
    }
    println!("{steps} steps per run, {:.3} ms per run", start.elapsed().as_secs_f64() / 300.0 * 1e3);
    Ok(())
}
