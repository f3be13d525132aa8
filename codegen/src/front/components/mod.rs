//! Components: parts defined once (in the standard library,
//! `library.dae`, or by the user with `#[component]`) and instantiated by
//! name, their connectors, and the connections between them.
//!
//! Lowering flattens an instance into the model: its variables and
//! equations under its path (`motor.emf.i`), its parameters as fields
//! (`motor_emf_k`). `connect(a, b)` only records a connection; after the
//! last statement `connections` turns the sets of connected connectors
//! into equations: equal potentials, flows summing to zero (Kirchhoff),
//! and a zero flow through each connector left unconnected.

pub mod connections;
pub mod connectors;
pub mod definitions;
pub mod diagnostics;

use crate::front::lower::Binding;
use crate::Id;
use connectors::ConnectorKind;
use proc_macro2::TokenStream;

/// One instance of a component, flattened into the model.
pub struct Instance {
    /// Its path: `motor.emf`, `r[2]`.
    pub path: String,
    /// The part it instantiates: `emf`, `parts::dc_motor`.
    pub part: String,
    /// The instance it was declared in; `None` at the model's level.
    pub parent: Option<usize>,
    /// The names its body declared, by name.
    pub(crate) members: Vec<(String, Binding)>,
    /// The declaration, for errors.
    pub origin: TokenStream,
    /// The equations its body wrote, its sub-instances' among them
    /// (indices into the model's equations).
    pub equations: std::ops::Range<usize>,
}

/// A connector: a pin, a flange, a heat port or a signal.
pub struct Connector {
    /// Its path: `r1.p`.
    pub path: String,
    /// What it connects.
    pub kind: ConnectorKind,
    /// Its potential variable (a signal's value).
    pub potential: Id,
    /// Its flow variable; `None` for a signal.
    pub flow: Option<Id>,
    /// The instance whose body declared it; `None` at the model's level.
    pub owner: Option<usize>,
    /// A support (`flange().support()`, MSL's `useSupport`): held at
    /// potential zero, the housing, where nothing connects it, rather than
    /// carrying no flow.
    pub support: bool,
    /// The declaration, for errors.
    pub origin: TokenStream,
}

/// `connect(a, b, ...)`: connectors joined at one level of the hierarchy.
pub struct Connection {
    /// The instance whose body wrote it; `None` at the model's level.
    pub level: Option<usize>,
    /// The connectors joined.
    pub members: Vec<usize>,
    /// The statement, for errors.
    pub origin: TokenStream,
}
