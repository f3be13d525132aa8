//! `SampledPi` (`models/sampled_pi.rs`), a sampled controller, as an FMU:
//! `cargo fmu --example sampled_pi_fmu` writes
//! `target/fmu/sampled_pi_fmu.fmu` (FMI 3.0) and
//! `target/fmu/sampled_pi_fmu_fmi2.fmu` (FMI 2.0).

#[path = "models/sampled_pi.rs"]
mod model;

daegen_fmi::export_fmu!(model::SampledPi);
