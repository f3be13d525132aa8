//! `Pendulum`, the contract's pendulum (`tests/models/items.rs`), as an
//! FMU: `cargo fmu --example pendulum_fmu` writes
//! `target/fmu/pendulum_fmu.fmu` (FMI 3.0) and
//! `target/fmu/pendulum_fmu_fmi2.fmu` (FMI 2.0).

mod model {
    use daegen::prelude::*;
    include!("../../tests/models/items.rs");
    contract_pendulum!(dae_model_with! { () });
}

daegen_fmi::export_fmu!(model::Pendulum);
