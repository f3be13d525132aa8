//! `Tank` (`models/tank.rs`), a model with an input, as an FMU: `cargo
//! fmu --example tank_fmu` writes `target/fmu/tank_fmu.fmu` (FMI 3.0) and
//! `target/fmu/tank_fmu_fmi2.fmu` (FMI 2.0).

#[path = "models/tank.rs"]
mod model;

daegen_fmi::export_fmu!(model::Tank);
