//! A slider-crank mechanism (course notes Figure 4.7) described as a planar
//! scene: a crank turning about the ground, a massless connecting rod, a
//! slider on a horizontal guide, gravity, and a motor torque on the crank.
//! The macro writes the DAE (global formulation), finds index 3, and the run
//! keeps the joints closed by projection; the same scene in the recursive
//! formulation (joint coordinates) is run next to it.
//!
//! Run: `cargo run --release --example slider_crank`

use daegen::prelude::*;
use daegen_workprecision::Series;

#[path = "support/output.rs"]
mod output;

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
            let pin = position(crank, vec3(0.5 * r, 0.0, 0.0));
            /// Crank angle (rad), from the pin's position.
            let crank_angle = output(atan2(pin[1], pin[0]));
            /// Slider position (m).
            let slider_x = output(position(slider, vec3(0.0, 0.0, 0.0))[0]);
        }
    };
}
slider_crank!(slider_crank_global, scene = global);
slider_crank!(slider_crank_recursive, scene = recursive);

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let opts = Options::new()
        .method(Method::Dop853)
        .rtol(1e-10)
        .atol(1e-10);
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
    println!("\n  t (s)   crank (rad)   slider x (m)   rod multiplier   |x_global − x_recursive|");
    for k in 0..=10 {
        let t = 0.2 * k as f64;
        let (angle, x) = (global.at(t, "crank_angle")?, global.at(t, "slider_x")?);
        let rod = global.at(t, "rod[0]")?;
        let difference = (x - recursive.at(t, "slider_x")?).abs();
        println!("  {t:4.1}   {angle:11.6}   {x:12.6}   {rod:14.6}   {difference:.1e}");
    }
    println!(
        "\nmax |Φ| over the run: {:.1e} (global), {:.1e} (recursive); {} and {} steps",
        global.max_constraint_residual(),
        recursive.max_constraint_residual(),
        global.stats().steps,
        recursive.stats().steps
    );
    let rows: Vec<Vec<f64>> = (0..=400)
        .map(|k| {
            let t = 2.0 * k as f64 / 400.0;
            Ok(vec![
                t,
                global.at(t, "crank_angle")?,
                global.at(t, "slider_x")?,
                global.at(t, "rod[0]")?,
            ])
        })
        .collect::<Result<_, daegen::Error>>()?;
    output::write(
        "slider_crank",
        &["t", "crank_angle", "slider_x", "rod_multiplier"],
        &rows,
        (
            "Slider-crank driven by a motor torque",
            "t (s)",
            "slider x (m)",
        ),
        &[Series {
            name: "slider x (global formulation)",
            points: rows.iter().map(|r| (r[0], r[2])).collect(),
        }],
    )?;
    Ok(())
}
