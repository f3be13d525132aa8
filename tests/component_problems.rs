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

/// The RLC circuit's state against the exact ringing at t = 10, the
/// drive's and the wall's against their exact steady states, the heating
/// resistor's against its exact exponential, and the geared slider-crank
/// against the same machine written flat.
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
    add(
        run_every_method(&Problem {
            name: "heating_up",
            model: HeatingUp::default(),
            t1: 200.0,
            error: |s| {
                // C T' = I² R0 (1 + α (T − T_ref)) − G (T − T_amb): linear.
                let (lambda, b) = (
                    (4.0 * 10.0 * 0.004 - 1.5) / 50.0,
                    (4.0 * 10.0 * (1.0 - 0.004 * 293.15) + 1.5 * 293.15) / 50.0,
                );
                let t_star = -b / lambda;
                let exact = t_star + (293.15 - t_star) * (lambda * 200.0f64).exp();
                support::mixed_error(&[s.last("body.t").unwrap_or(f64::NAN)], &[exact], 1.0)
            },
            tolerances: &[1e-6, 1e-8, 1e-10],
            atol_scale: 1.0,
            // A single decaying mode: errors shrink as e^(λ t).
            bound: 10.0,
            // 1/|λ| = 37 s.
            time_scale: 37.0,
            settled_time_scale: None,
            stiffness: 0.027,
            gmres: false,
        }),
        "heating_up",
    );
    add(
        run_every_method(&Problem {
            name: "thermal_wall",
            model: ThermalWall::default(),
            t1: 1e5,
            error: |s| {
                // The series-conduction profile at rest.
                let g = [2.0, 5.0, 1.0, 4.0, 3.0];
                let q = 40.0 / g.iter().map(|g| 1.0 / g).sum::<f64>();
                let mut t = 313.15;
                let mut exact = Vec::new();
                let mut got = Vec::new();
                for k in 0..4 {
                    t -= q / g[k];
                    exact.push(t);
                    got.push(s.last(&format!("layers[{k}].t")).unwrap_or(f64::NAN));
                }
                support::mixed_error(&got, &exact, 1.0)
            },
            tolerances: &[1e-6, 1e-8, 1e-10],
            atol_scale: 1.0,
            // Decaying modes only.
            bound: 10.0,
            // The fastest layer: c / (g_left + g_right) = 500 / 7 ≈ 70 s.
            time_scale: 70.0,
            // Settled after a few slowest time constants (about 2000 s):
            // ρ(J) = 0.014 against 1e5 s of rest is stiff.
            settled_time_scale: Some(1e5),
            stiffness: 0.014,
            gmres: false,
        }),
        "thermal_wall",
    );
    add(
        run_every_method(&Problem {
            name: "geared_slider_crank",
            model: GearedSliderCrankGlobal::default(),
            t1: 0.5,
            error: |s| {
                // The same machine written flat, in its crank angle.
                let opts = Options::new().method(Method::Radau5).rtol(1e-12).atol(1e-12);
                let flat = GearedSliderCrankFlat::default().simulate(0.0, 0.5, &opts);
                let Ok(flat) = flat else { return f64::NAN };
                let reference =
                    [flat.last("phi").unwrap_or(f64::NAN), flat.last("i").unwrap_or(f64::NAN)];
                let got = [
                    s.last("crank.theta").unwrap_or(f64::NAN),
                    s.last("drive.motor.winding.i").unwrap_or(f64::NAN),
                ];
                support::mixed_error(&got, &reference, 1.0)
            },
            tolerances: &[1e-6, 1e-8, 1e-10],
            atol_scale: 1.0,
            // A driven mechanism: errors grow slowly with the crank's turns.
            bound: 1e3,
            // The winding: L/R = 10 ms.
            time_scale: 0.01,
            settled_time_scale: None,
            // R/L = 100 s⁻¹.
            stiffness: 100.0,
            gmres: false,
        }),
        "geared_slider_crank",
    );
    assert!(beyond.is_empty(), "{beyond:#?}");
    for (name, table) in tables {
        insta::assert_snapshot!(name, table);
    }
}
