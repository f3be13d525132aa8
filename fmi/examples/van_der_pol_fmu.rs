//! `VanDerPol` (`models/van_der_pol.rs`) as an FMU: `cargo fmu --example van_der_pol_fmu`
//! writes `target/fmu/van_der_pol_fmu.fmu` (FMI 3.0) and
//! `target/fmu/van_der_pol_fmu_fmi2.fmu` (FMI 2.0).

#[path = "models/van_der_pol.rs"]
mod model;

daegen_fmi::export_fmu!(model::VanDerPol);
