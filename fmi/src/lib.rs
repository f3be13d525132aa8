//! daegen models as Functional Mock-up Units (FMI 2.0 and 3.0, Model
//! Exchange and Co-Simulation).
//!
//! A `cdylib` crate calls [`export_fmu!`] on its `#[dae_model]` type;
//! `cargo fmu` (this crate's binary) builds it and packages the library
//! into `<name>.fmu` (FMI 3.0) and `<name>_fmi2.fmu` (FMI 2.0).
//!
//! The pipeline: [`variables`] numbers every value a model has, the value
//! references both versions share; [`description`] writes
//! `modelDescription.xml` from them, with the model structure its
//! Jacobian's pattern gives; [`instance`] is one instance, what every call
//! computes; [`calls`] are the C functions both standards share, written
//! once over [`standard`]'s table of what differs between them (names,
//! phases, argument names, the boolean type), and [`fmi2`] and [`fmi3`]
//! each standard's row and the functions only it has, each checking its
//! state machine; [`fmu_state`] saves and restores instances;
//! [`boundary`] keeps the C boundary safe (handles, locks, no unwinding);
//! [`export`] makes the symbols; [`archive`] writes the FMUs.

#![warn(missing_docs)]

pub mod archive;
pub mod boundary;
pub mod calls;
pub mod description;
pub mod export;
pub mod fmi2;
pub mod fmi3;
pub mod fmu_state;
pub mod instance;
pub mod standard;
pub mod variables;

pub use description::{model_description, FmiVersion};
pub use variables::{fmi_variables, Causality, Initial, Variability, Variable};

/// The model description `export_fmu!` hands the packaging command: the
/// model's defaults, every capability the exported functions provide.
pub fn packaged_description<M: daegen_runtime::Model + Default>(
    version: FmiVersion,
    identifier: &str,
) -> std::ffi::CString {
    let xml =
        model_description(&M::default(), version, identifier, description::Capabilities::EXPORTED);
    std::ffi::CString::new(xml.replace('\0', " ")).unwrap_or_default()
}
