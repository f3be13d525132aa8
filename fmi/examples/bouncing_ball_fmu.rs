//! `BouncingBall` (`models/bouncing_ball.rs`) as an FMU: `cargo fmu --example bouncing_ball_fmu`
//! writes `target/fmu/bouncing_ball_fmu.fmu` (FMI 3.0) and
//! `target/fmu/bouncing_ball_fmu_fmi2.fmu` (FMI 2.0).

#[path = "models/bouncing_ball.rs"]
mod model;

daegen_fmi::export_fmu!(model::BouncingBall);
