//! What the analyses found of one first-order system, the model's own or
//! its variational system's: the system, its mass-matrix form, its
//! Taylor analysis and its projection levels; and the forward
//! sensitivities' system with what they are taken against.

use crate::dae::mass_form::MassForm;
use crate::dae::system::{FirstOrder, ProjectionLevel};
use crate::dae::variational::Wrt;
use crate::front::attributes::Attributes;
use crate::taylor::analysis::TaylorAnalysis;

/// A first-order system and what is derived from it. Analyses that can
/// fail keep their error, raised where emission needs them, so a model
/// with several problems reports the same one first as it always has.
pub struct SystemAnalysis {
    /// The reduced system.
    pub system: FirstOrder,
    /// The mass-matrix form, where the model has one and it is wanted
    /// (never for a model with sensitivity columns).
    pub mass_form: crate::Result<Option<MassForm>>,
    /// The Taylor methods' part.
    pub taylor: crate::Result<TaylorAnalysis>,
    /// The invariants grouped by level, each with the states it corrects.
    pub projection: Vec<ProjectionLevel>,
    /// The start values the initial equations decide, where it has any.
    pub initialization: Option<crate::dae::initialization::Initialization>,
}

/// The variational system of the forward sensitivities.
pub struct SensitivityAnalysis {
    /// The parameters and initial values differentiated against.
    pub wrt: Vec<Wrt>,
    /// The attributes it is expanded with: the model's, with its columns.
    pub attributes: Attributes,
    /// The model with the sensitivities as states, and its analyses.
    pub model: crate::Result<SystemAnalysis>,
}
