//! The slider-crank scene of `tests/models/slider_crank_scene.rs` as an FMU:
//! `cargo fmu --example slider_crank_fmu` writes
//! `target/fmu/slider_crank_fmu.fmu` (FMI 3.0) and
//! `target/fmu/slider_crank_fmu_fmi2.fmu` (FMI 2.0).

#[path = "../../tests/models/slider_crank_scene.rs"]
mod model;

daegen_fmi::export_fmu!(model::SliderCrankScene);
