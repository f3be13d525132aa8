//! The right-hand side's programs: the explicit entries of the
//! first-order system and each run-time block's matrix and right-hand
//! side in one program, and the accelerations a block's solve gives; the
//! same blocks assembled for `output`; the model's own entries of a model
//! with sensitivity columns.

use crate::dae::system::{FirstOrder, SlotDerivative};
use crate::programs::schedule::Program;
use crate::{Graph, Id};

/// Where a value of the right-hand side's program goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RhsEntry {
    /// `dy[i]`.
    Derivative(usize),
    /// Row `r` of block `b`'s right-hand side.
    BlockRhs(usize, usize),
    /// Entry `(r, c)` of block `b`'s matrix.
    BlockMatrix(usize, usize, usize),
}

/// The right-hand side's programs.
pub struct RhsPrograms {
    /// Where each value of `body` goes.
    pub entries: Vec<RhsEntry>,
    /// The slots whose derivative `after` computes once the blocks are
    /// solved, and its program.
    pub after: Option<(Vec<usize>, Program)>,
    /// The explicit entries and the blocks' arrays.
    pub body: Program,
}

/// The blocks' non-zero matrix and right-hand-side entries, each with
/// where it goes.
fn block_entries(g: &Graph, sys: &FirstOrder) -> (Vec<Id>, Vec<RhsEntry>) {
    let is_zero = |e: Id| g.as_number(e).is_some_and(|v| v.is_zero());
    let mut values = Vec::new();
    let mut entries = Vec::new();
    for (b, block) in sys.blocks.iter().enumerate() {
        let k = block.rhs.len();
        for (r, &e) in block.rhs.iter().enumerate() {
            if !is_zero(e) {
                values.push(e);
                entries.push(RhsEntry::BlockRhs(b, r));
            }
            for c in 0..k {
                let entry = block.matrix[r * k + c];
                if !is_zero(entry) {
                    values.push(entry);
                    entries.push(RhsEntry::BlockMatrix(b, r, c));
                }
            }
        }
    }
    (values, entries)
}

/// The right-hand side's programs (the arrays start at zero: zero entries
/// are not written).
pub fn rhs_programs(g: &mut Graph, sys: &FirstOrder) -> RhsPrograms {
    let mut values = Vec::new();
    let mut entries = Vec::new();
    for (i, d) in sys.derivatives.iter().enumerate() {
        if let SlotDerivative::Explicit(e) = d {
            values.push(*e);
            entries.push(RhsEntry::Derivative(i));
        }
    }
    let (block_values, block_entries) = block_entries(g, sys);
    values.extend(block_values);
    entries.extend(block_entries);
    // Accelerations eliminated from a KKT block, from its multipliers.
    let after: Vec<(usize, Id)> = sys
        .derivatives
        .iter()
        .enumerate()
        .filter_map(|(i, d)| match d {
            SlotDerivative::AfterSolve(e) => Some((i, *e)),
            _ => None,
        })
        .collect();
    let after = (!after.is_empty()).then(|| {
        let ids: Vec<Id> = after.iter().map(|x| x.1).collect();
        (after.iter().map(|x| x.0).collect(), g.schedule(&ids))
    });
    let body = g.schedule(&values);
    RhsPrograms { entries, after, body }
}

/// Every run-time block assembled for a solve: where each value goes, and
/// its program.
pub fn block_solve_programs(g: &mut Graph, sys: &FirstOrder) -> (Vec<RhsEntry>, Program) {
    let (values, entries) = block_entries(g, sys);
    (entries, g.schedule(&values))
}

/// The model's own derivatives of a model with `columns` sensitivity
/// columns (the first `n / (1 + columns)` slots, explicit in a
/// variational system) without the columns'; `None` for other models.
pub fn own_rhs_program(g: &mut Graph, sys: &FirstOrder, columns: usize) -> Option<Program> {
    if columns == 0 {
        return None;
    }
    let own = sys.slots.len() / (1 + columns);
    let mut outputs = Vec::with_capacity(own);
    for d in &sys.derivatives[..own] {
        match d {
            SlotDerivative::Explicit(e) => outputs.push(*e),
            _ => return None,
        }
    }
    Some(g.schedule(&outputs))
}

/// f slot by slot when every derivative is explicit in the states (not
/// through a Newton solve's variables): what the symbolic Jacobian and the
/// event rates differentiate.
pub fn explicit_derivatives(sys: &FirstOrder) -> Option<Vec<Id>> {
    sys.derivatives
        .iter()
        .map(|d| match d {
            SlotDerivative::Explicit(e) if sys.newton.is_none() => Some(*e),
            _ => None,
        })
        .collect()
}
