//! A slider-crank mechanism (course notes Figure 4.7) described as a planar
//! scene: a crank turning about the ground, a massless connecting rod, a
//! slider on a horizontal guide, gravity, and a motor torque on the crank.
//! The macro writes the DAE (body coordinates), finds index 3, and the run
//! keeps the joints closed by projection; the same scene in the recursive
//! formulation (joint coordinates) is run next to it. Both answer to the
//! same names: the bodies' coordinates (`crank.theta`, `slider.x`), the
//! joints' coordinates (`revolute1.q`, `prismatic3.q`) and reactions
//! (`rod[0]`). The run is written as CSV and drawn as SVG under
//! `target/example-output/`.
//!
//! Run: `cargo run --release --example slider_crank`

use daegen::prelude::*;
use std::path::PathBuf;

// tests/scenes.rs checks this mechanism; an example is read alone, so it
// writes its model out rather than share the test's.
macro_rules! slider_crank {
    ($name:ident, $($attr:tt)*) => {
        /// Crank 0.15 m (1 kg), rod 0.4 m, slider 0.5 kg, motor torque 0.5 N·m.
        #[dae_model($($attr)*)]
        fn $name() {
            let r = param(0.15);
            let l = param(0.4);
            let m1 = param(1.0);
            let m2 = param(0.5);
            let g = param(9.81);
            let motor = param(0.5);
            let ground = ground();
            // Started at a crank angle of 1 rad with the joints closed (at 0
            // the crank and the rod align: a dead point, where the
            // constraint Jacobian is singular and the run stops with an Err).
            let crank = body(m1, m1 * r * r / 12.0, [0.04052267294011048, 0.06311032386059223, 1.0]);
            let slider = body(m2, 1.0, [0.4606087109312288, 0.0, 0.0]);
            revolute(ground, vec3(0.0, 0.0, 0.0), crank, vec3(-0.5 * r, 0.0, 0.0));
            let rod = distance(crank, vec3(0.5 * r, 0.0, 0.0), slider, vec3(0.0, 0.0, 0.0), l);
            prismatic(ground, vec3(0.0, 0.0, 0.0), slider, vec3(0.0, 0.0, 0.0), vec3(1.0, 0.0, 0.0));
            gravity(vec3(0.0, -g, 0.0));
            torque(crank, motor);
        }
    };
}
slider_crank!(slider_crank_global, scene = global);
slider_crank!(slider_crank_recursive, scene = recursive);

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let opts = Options::new().method(Method::Dop853).tolerance(1e-10);
    let global = SliderCrankGlobal::default().simulate(0.0, 2.0, &opts)?;
    let recursive = SliderCrankRecursive::default().simulate(0.0, 2.0, &opts)?;
    println!(
        "Slider-crank: index {} in global coordinates ({} states), {} in joint coordinates ({} states); {} degree(s) of freedom",
        <SliderCrankGlobal as Model>::INDEX,
        SliderCrankGlobal::STATES,
        <SliderCrankRecursive as Model>::INDEX,
        SliderCrankRecursive::STATES,
        global.degrees_of_freedom().unwrap_or(0),
    );
    let grid: Vec<f64> = (0..=10).map(|k| 0.2 * k as f64).collect();
    let names = ["crank.theta", "slider.x", "rod[0]", "prismatic3.q"];
    println!("\nbody coordinates:\n{}", global.sample(&names, &grid)?);
    let largest = |name: &str| -> Result<f64, daegen::Error> {
        let (a, b) = (global.sample(&[name], &grid)?, recursive.sample(&[name], &grid)?);
        let (a, b) = (a.column(name).unwrap_or(&[]), b.column(name).unwrap_or(&[]));
        Ok(a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max))
    };
    println!("\nlargest difference from joint coordinates on that grid:");
    for name in names {
        println!("  {name:13} {:.1e}", largest(name)?);
    }
    println!(
        "\nmax |Φ| over the run: {:.1e} (global), {:.1e} (recursive); {} and {} steps",
        global.max_constraint_residual(),
        recursive.max_constraint_residual(),
        global.stats().steps,
        recursive.stats().steps
    );
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target/example-output");
    std::fs::create_dir_all(&dir)?;
    global.write_csv(std::fs::File::create(dir.join("slider_crank.csv"))?, &global.names())?;
    daegen::plot::time_series(&global, &["slider.x", "revolute1.q"], dir.join("slider_crank.svg"))?;
    println!("wrote slider_crank.csv and slider_crank.svg in {}", dir.display());
    Ok(())
}
