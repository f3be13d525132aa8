//! `SpeedDrive` (`tests/models/speed_drive.rs`) as an FMU: `cargo fmu --example speed_drive_fmu`
//! writes `target/fmu/speed_drive_fmu.fmu` (FMI 3.0) and
//! `target/fmu/speed_drive_fmu_fmi2.fmu` (FMI 2.0).

#[path = "../../tests/models/speed_drive.rs"]
mod model;

daegen_fmi::export_fmu!(model::SpeedDrive);
