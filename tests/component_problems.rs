//! Every method on models built from components, through the harness of
//! `support::harness` (as `reference_problems` runs the reference
//! problems): each method meets its bound against the exact solution,
//! fails as documented, or is refused with its reason. The statistics of
//! every run are pinned by a snapshot.

use daegen::prelude::*;

include!("models/drives.rs");

include!("models/rlc_exact.rs");

mod support;

use support::harness::{run_every_method, Problem};

/// The RLC circuit's state against the exact ringing at t = 10, and the
/// drive's against its exact steady state at t = 20.
#[test]
fn every_method_runs_every_connected_model() {
    let mut tables = Vec::new();
    let mut beyond = Vec::new();
    let mut add = |(table, mut wrong): (String, Vec<String>), name: &str| {
        println!("{name}\n{table}");
        tables.push((name.to_string(), table));
        beyond.append(&mut wrong);
    };
    add(
        run_every_method(&Problem {
            name: "rlc_series",
            model: RlcSeries::default(),
            t1: 10.0,
            error: |s| {
                let y = [s.last("c.v").unwrap_or(f64::NAN), s.last("l.i").unwrap_or(f64::NAN)];
                support::mixed_error(&y, &rlc_exact(10.0), 1.0)
            },
            tolerances: &[1e-6, 1e-8, 1e-10],
            atol_scale: 1.0,
            // Damped ringing: errors decay as e^(−t/2).
            bound: 10.0,
            // ω0 = 2 rad/s: a period of π.
            time_scale: 0.5,
            settled_time_scale: None,
            stiffness: 2.0,
            gmres: false,
        }),
        "rlc_series",
    );
    add(
        run_every_method(&Problem {
            name: "speed_drive",
            model: SpeedDrive::default(),
            t1: 20.0,
            error: |s| {
                // ω = ω_ref and i = (b ω_ref + τ_L) / k at rest.
                let y = [
                    s.last("sensor.w").unwrap_or(f64::NAN),
                    s.last("motor.winding.i").unwrap_or(f64::NAN),
                ];
                support::mixed_error(&y, &[100.0, (1e-5 * 100.0 + 0.02) / 0.05], 1.0)
            },
            tolerances: &[1e-6, 1e-8, 1e-10],
            atol_scale: 1.0,
            // The closed loop damps every error (poles −9.95 and −25.2).
            bound: 100.0,
            // The speed's rise, 1/25 s.
            time_scale: 0.04,
            // At rest once the load step has passed: time scale ~ 1 s.
            settled_time_scale: Some(1.0),
            // The winding: R/L = 2000 s⁻¹.
            stiffness: 2000.0,
            gmres: false,
        }),
        "speed_drive",
    );
    assert!(beyond.is_empty(), "{beyond:#?}");
    for (name, table) in tables {
        insta::assert_snapshot!(name, table);
    }
}
