//! Emission, which only prints: the programs the pipeline scheduled
//! (`crate::programs`) as Rust tokens (`program`) reading symbols as
//! `layout` says, and the items of a model type: `model` assembles them
//! from one emitter per item (`rhs`, `jacobian`, `events`, `outputs`,
//! `taylor_items`, `newton`, `constraints`, `initialization`, `mass_form`,
//! `docs`), `batch`
//! steps several members at once, and `benchmark` registers it.

pub mod actions;
pub mod batch;
pub mod benchmark;
pub mod constraints;
pub mod docs;
pub mod events;
pub mod initialization;
pub mod jacobian;
pub mod layout;
pub mod mass_form;
pub mod model;
pub mod newton;
pub mod outputs;
pub mod program;
pub mod rhs;
pub mod taylor_items;
