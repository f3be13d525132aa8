//! `Pendulum` (`models/pendulum.rs`) as an FMU: `cargo fmu --example pendulum_fmu`
//! writes `target/fmu/pendulum_fmu.fmu` (FMI 3.0) and
//! `target/fmu/pendulum_fmu_fmi2.fmu` (FMI 2.0).

#[path = "models/pendulum.rs"]
mod model;

daegen_fmi::export_fmu!(model::Pendulum);
