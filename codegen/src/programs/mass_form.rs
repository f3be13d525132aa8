//! The programs of a model's mass-matrix form (`dae::mass_form`): its
//! right-hand side, the analytic Jacobian with its pattern, the mass
//! matrix where it is general; and, for a model that runs in that form
//! only, its initial values and outputs.

use crate::dae::mass_form::MassForm;
use crate::programs::schedule::Program;
use crate::{Graph, Id};

/// The programs of the form's `Model` items.
pub struct MassFormPrograms {
    /// F(t, w).
    pub rhs: Program,
    /// The Jacobian's non-zero entries (row, column).
    pub pattern: Vec<(usize, usize)>,
    /// Its entries.
    pub jacobian: Program,
    /// A general mass matrix's pattern and entries.
    pub mass: Option<(Vec<(usize, usize)>, Program)>,
}

/// The programs of `form`'s items.
pub fn mass_form_programs(g: &mut Graph, form: &MassForm) -> crate::Result<MassFormPrograms> {
    let rhs = g.schedule(&form.rows);
    let jacobian = g.jacobian(&form.rows, &form.components)?;
    let pattern = jacobian.entries.iter().map(|&(r, c, _)| (r, c)).collect();
    let jacobian = g.schedule(&jacobian.expressions());
    let mass = form.general.as_ref().map(|entries| {
        let ids: Vec<Id> = entries.iter().map(|e| e.2).collect();
        (entries.iter().map(|&(r, c, _)| (r, c)).collect(), g.schedule(&ids))
    });
    Ok(MassFormPrograms { rhs, pattern, jacobian, mass })
}

/// The programs of a model that runs in its mass-matrix form only.
pub struct PrimaryPrograms {
    /// The form's items.
    pub form: MassFormPrograms,
    /// The initial values: states, the algebraic variables' guesses, then
    /// μ = 0.
    pub initial: Program,
    /// Each output, from the components.
    pub outputs: Vec<Program>,
}

/// The programs of a model whose own `Model` implementation is its
/// mass-matrix form `form`, with the initial values `inits` (padded with
/// zeros) and `outputs`.
pub fn primary_programs(
    g: &mut Graph,
    form: &MassForm,
    mut inits: Vec<Id>,
    outputs: &[Id],
) -> crate::Result<PrimaryPrograms> {
    let zero = g.zero();
    inits.resize(form.components.len(), zero);
    let form_programs = mass_form_programs(g, form)?;
    let initial = g.schedule(&inits);
    let outputs = outputs.iter().map(|&o| g.schedule(&[o])).collect();
    Ok(PrimaryPrograms { form: form_programs, initial, outputs })
}
