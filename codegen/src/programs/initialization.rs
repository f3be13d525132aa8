//! The programs of a model's initialization: its initial equations'
//! residuals at `(t, y)`, and their Jacobian in the start values they
//! decide, dense, row by row.

use crate::dae::initialization::Initialization;
use crate::dae::system::FirstOrder;
use crate::programs::schedule::Program;
use crate::Graph;

/// What `initial_residuals` and `initial_jacobian` compute.
pub struct InitializationPrograms {
    /// The residuals.
    pub residuals: Program,
    /// `∂r_e/∂y_j` for each equation `e`, then each decided slot `j`.
    pub jacobian: Program,
    /// The slots decided, in slot order.
    pub free: Vec<usize>,
    /// Each equation as written.
    pub texts: Vec<String>,
}

/// The initialization's programs.
pub fn initialization_programs(
    g: &mut Graph,
    sys: &FirstOrder,
    initialization: &Initialization,
) -> crate::Result<InitializationPrograms> {
    let residuals = g.schedule(&sys.initial);
    let mut entries = Vec::with_capacity(sys.initial.len() * initialization.free.len());
    for &r in &sys.initial {
        for &j in &initialization.free {
            entries.push(g.partial(r, sys.slots[j].symbol)?);
        }
    }
    let jacobian = g.schedule(&entries);
    Ok(InitializationPrograms {
        residuals,
        jacobian,
        free: initialization.free.clone(),
        texts: initialization.texts.clone(),
    })
}
