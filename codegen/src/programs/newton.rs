//! The Newton block's programs: for the block as a whole, or for each of
//! its parts in causal order, the residuals with their non-zero
//! derivatives ∂g_i/∂z_j in one program, and the guesses in another.

use crate::dae::system::{FirstOrder, NewtonBlock};
use crate::programs::schedule::Program;
use crate::{Graph, Id, SymbolId};

/// Where a value of a Newton program goes: `residual[i]` or
/// `jacobian[i][j]`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NewtonEntry {
    /// Residual `i`.
    Residual(usize),
    /// ∂g_i/∂z_j.
    Jacobian(usize, usize),
}

/// One Newton iteration's programs: the block's, or one part's.
pub struct NewtonPart {
    /// The block's variables it solves for (positions in
    /// [`NewtonBlock::unknowns`]).
    pub variables: Vec<usize>,
    /// Where each value of `equations` goes.
    pub entries: Vec<NewtonEntry>,
    /// The residuals, then their non-zero derivatives.
    pub equations: Program,
    /// The variables' guesses.
    pub guesses: Program,
}

/// The Newton block's iterations: one for the whole block, or one per
/// part where it splits (`whole` false).
pub struct NewtonPrograms {
    /// Whether one iteration solves the whole block.
    pub whole: bool,
    /// The iterations, in causal order.
    pub parts: Vec<NewtonPart>,
}

/// The programs of the model's Newton block; `None` without one.
pub fn newton_programs(g: &mut Graph, sys: &FirstOrder) -> Option<NewtonPrograms> {
    let newton = sys.newton.as_ref()?;
    if newton.components.len() > 1 {
        let parts = newton
            .components
            .iter()
            .map(|(variables, rows)| part(g, newton, variables.clone(), rows))
            .collect();
        return Some(NewtonPrograms { whole: false, parts });
    }
    let all: Vec<usize> = (0..newton.unknowns.len()).collect();
    let (entries, values) = residuals_and_jacobian(g, &newton.residuals, &newton.unknowns);
    let equations = g.schedule(&values);
    let guesses = g.schedule(&newton.guesses);
    Some(NewtonPrograms {
        whole: true,
        parts: vec![NewtonPart { variables: all, entries, equations, guesses }],
    })
}

/// One part of a block that splits: its equations `rows` for its
/// `variables`, the parts before it known.
fn part(g: &mut Graph, newton: &NewtonBlock, variables: Vec<usize>, rows: &[usize]) -> NewtonPart {
    let residuals: Vec<Id> = rows.iter().map(|&r| newton.residuals[r]).collect();
    let unknowns: Vec<SymbolId> = variables.iter().map(|&v| newton.unknowns[v]).collect();
    let (entries, values) = residuals_and_jacobian(g, &residuals, &unknowns);
    let equations = g.schedule(&values);
    let guess_values: Vec<Id> = variables.iter().map(|&v| newton.guesses[v]).collect();
    let guesses = g.schedule(&guess_values);
    NewtonPart { variables, entries, equations, guesses }
}

/// The residuals and their non-zero derivatives `∂g_i/∂z_j`, each with
/// where it goes.
fn residuals_and_jacobian(
    g: &mut Graph,
    residuals: &[Id],
    unknowns: &[SymbolId],
) -> (Vec<NewtonEntry>, Vec<Id>) {
    let mut values = residuals.to_vec();
    let mut entries: Vec<NewtonEntry> = (0..residuals.len()).map(NewtonEntry::Residual).collect();
    for (i, &r) in residuals.iter().enumerate() {
        for (j, &z) in unknowns.iter().enumerate() {
            let Ok(d) = g.partial(r, z) else { continue };
            if g.as_number(d).is_some_and(|v| v.is_zero()) {
                continue;
            }
            values.push(d);
            entries.push(NewtonEntry::Jacobian(i, j));
        }
    }
    (entries, values)
}
