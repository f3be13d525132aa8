//! Profiling aid: Kepler e = 0.9 over ten orbits with DOPRI5 at tol 1e-12,
//! repeated. Run: `cargo run --release --manifest-path bench/Cargo.toml --example profile_kepler`.

use daegen::prelude::*;

include!("../../tests/models/kepler.rs");
kepler_model!();

fn main() -> Result<(), daegen::Error> {
    let options = Options::new().method(Method::Dopri5).rtol(1e-12).atol(1e-12);
    let start = std::time::Instant::now();
    let mut steps = 0;
    for _ in 0..300 {
        let sol = Kepler::default().simulate(0.0, 20.0 * std::f64::consts::PI, &options)?;
        steps = sol.stats().steps;
    }
    println!(
        "daegen: {steps} steps per run, {:.3} ms per run",
        start.elapsed().as_secs_f64() / 300.0 * 1e3
    );
    peer::run();
    Ok(())
}

/// The same run with `ode_solvers`, for the step count and time per step.
mod peer {
    use ode_solvers::{Dopri5, System, Vector4};

    pub struct Kepler;
    impl System<f64, Vector4<f64>> for Kepler {
        fn system(&self, _t: f64, y: &Vector4<f64>, dy: &mut Vector4<f64>) {
            let r2 = y[0] * y[0] + y[1] * y[1];
            let r3 = r2 * r2.sqrt();
            dy[0] = y[2];
            dy[1] = y[3];
            dy[2] = -y[0] / r3;
            dy[3] = -y[1] / r3;
        }
    }

    pub fn run() {
        let t1 = 20.0 * std::f64::consts::PI;
        let y0 = Vector4::new(0.1, 0.0, 0.0, 19f64.sqrt());
        let start = std::time::Instant::now();
        let mut stats = None;
        for _ in 0..300 {
            let mut s = Dopri5::new(Kepler, 0.0, t1, t1 / 1000.0, y0, 1e-12, 1e-12);
            stats = s.integrate().ok();
        }
        println!(
            "ode_solvers: {stats:?}, {:.3} ms per run",
            start.elapsed().as_secs_f64() / 300.0 * 1e3
        );
    }
}
