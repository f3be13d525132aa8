//! daegen models as Functional Mock-up Units (FMI 2.0 and 3.0).
//!
//! `variables` numbers every value a model has, the value references
//! both versions share; `description` writes `modelDescription.xml` from
//! them, with the model structure its Jacobian's pattern gives.

pub mod description;
pub mod variables;

pub use description::{model_description, FmiVersion};
pub use variables::{fmi_variables, Causality, Initial, Variability, Variable};
