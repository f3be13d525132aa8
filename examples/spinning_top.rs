//! A heavy symmetric top on a spherical joint, described as a spatial
//! scene: its attitude a unit quaternion, its body rates ω, the pivot's
//! reaction as three algebraic variables. The macro writes the Newton–Euler
//! equations with the constraint torque `Lᵀ Φ_qᵀ λ`, finds index 3, and the
//! run keeps the pivot closed and |q| = 1 by projection. Printed: the tilt
//! of the axis (nutation), its azimuth (precession), the pivot force, and
//! the drift of the energy over some 800 Taylor steps.
//!
//! Run: `cargo run --release --example spinning_top`

use daegen::prelude::*;
use daegen_workprecision::Series;

#[path = "support/output.rs"]
mod output;

/// Mass 1 kg, centre 0.5 m above the pivot, inertia 0.75 / 0.75 / 0.5 kg·m²
/// about the centre, started tilted by 0.5 rad and spinning at 5 rad/s.
#[dae_model(taylor = 1)]
fn spinning_top() {
    let m = param(1.0);
    let l = param(0.5);
    let g = param(2.0);
    let ground = ground();
    let top = spatial_body(
        m,
        vec3(0.75, 0.75, 0.5),
        [0.0, -l * sin(0.5), l * cos(0.5)],
        [cos(0.25), sin(0.25), 0.0, 0.0],
        [0.25, 0.0, 0.0],
        [0.0, 0.5, 5.0],
    );
    let pivot = spherical(ground, vec3(0.0, 0.0, 0.0), top, vec3(0.0, 0.0, -l));
    gravity(vec3(0.0, 0.0, -g));
    let axis = orientation(top) * vec3(0.0, 0.0, 1.0);
    /// Tilt of the symmetry axis from the vertical (rad).
    let tilt = output(acos(axis[2]));
    /// Azimuth of the symmetry axis (rad).
    let azimuth = output(atan2(axis[1], axis[0]));
    /// The tip of the unit symmetry axis, seen from above.
    let tip_x = output(axis[0]);
    let tip_y = output(axis[1]);
    /// Kinetic plus potential energy (J).
    let energy = output(
        0.5 * m * (der(top.x) * der(top.x) + der(top.y) * der(top.y) + der(top.z) * der(top.z))
            + 0.5 * (0.75 * top.wx * top.wx + 0.75 * top.wy * top.wy + 0.5 * top.wz * top.wz)
            + m * g * top.z,
    );
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let tol = 1e-15;
    let opts = Options::new().method(Method::Taylor).rtol(tol).atol(tol);
    let sol = SpinningTop::default().simulate(0.0, 300.0, &opts)?;
    println!(
        "Spinning top: index {}, {} states, {} degrees of freedom; {} Taylor steps over 300 s",
        <SpinningTop as Model>::INDEX,
        SpinningTop::STATES,
        sol.degrees_of_freedom().unwrap_or(0),
        sol.stats().steps,
    );
    println!("\n  t (s)   tilt (rad)   azimuth (rad)   pivot force (N)");
    for k in 0..=10 {
        let t = 0.5 * k as f64;
        let force: f64 = (0..3)
            .map(|i| sol.at(t, &format!("pivot[{i}]")).map(|f| f * f))
            .sum::<Result<f64, _>>()?
            .sqrt();
        println!(
            "  {t:5.1}   {:10.6}   {:13.6}   {force:15.6}",
            sol.at(t, "tilt")?,
            sol.at(t, "azimuth")?
        );
    }
    let e0 = sol.at(0.0, "energy")?;
    let mut drift = 0.0f64;
    for &t in sol.times() {
        drift = drift.max((sol.at(t, "energy")? - e0).abs());
    }
    println!(
        "\nenergy {e0:.12} J, largest drift {drift:.1e} J; max |Φ| {:.1e}",
        sol.max_constraint_residual()
    );
    // The axis tip seen from above over 10 s: precession with nutation loops.
    let rows: Vec<Vec<f64>> = (0..=2000)
        .map(|k| {
            let t = 10.0 * k as f64 / 2000.0;
            Ok(vec![
                t,
                sol.at(t, "tip_x")?,
                sol.at(t, "tip_y")?,
                sol.at(t, "tilt")?,
            ])
        })
        .collect::<Result<_, daegen::Error>>()?;
    output::write(
        "spinning_top",
        &["t", "tip_x", "tip_y", "tilt"],
        &rows,
        ("Heavy top: the symmetry axis seen from above", "x", "y"),
        &[Series {
            name: "axis tip, 0–10 s",
            points: rows.iter().map(|r| (r[1], r[2])).collect(),
        }],
    )?;
    Ok(())
}
