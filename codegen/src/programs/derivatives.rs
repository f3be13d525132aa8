//! The programs of the items that differentiate the model: the symbolic
//! Jacobian ∂f/∂y with ∂f/∂t, the event functions' rates along the
//! solution, and the constraints with their Jacobian rows by projection
//! level.

use crate::dae::system::{FirstOrder, ProjectionLevel};
use crate::programs::schedule::Program;
use crate::{Graph, Id, SymbolId};

/// `jacobian` and `time_derivative`.
pub struct JacobianPrograms {
    /// The non-zero entries (row, column), in the order `values` writes
    /// them.
    pub pattern: Vec<(usize, usize)>,
    /// The entries.
    pub values: Program,
    /// ∂f/∂t, slot by slot.
    pub time: Program,
}

/// The Jacobian ∂f/∂y and ∂f/∂t where f is explicit and a symbolic
/// Jacobian pays (see [`crate::expr::jacobian::SYMBOLIC_JACOBIAN_ROW`]),
/// without the columns of discrete values; `None` otherwise (the runtime
/// differences it).
pub fn jacobian_programs(
    g: &mut Graph,
    slots: &[SymbolId],
    (time, inputs, discrete): (SymbolId, &[(SymbolId, SymbolId)], &[SymbolId]),
    explicit: Option<&[Id]>,
) -> crate::Result<Option<JacobianPrograms>> {
    let Some(f) = explicit.filter(|f| crate::expr::jacobian::symbolic_jacobian_pays(g, f)) else {
        return Ok(None);
    };
    let mut j = g.jacobian(f, slots)?;
    // A discrete value is constant between the instants where it jumps,
    // and each stretch starts afresh: its column is left out, so no row of
    // a Newton matrix mixes into its own, which then keeps it exactly.
    j.entries.retain(|&(_, c, _)| !discrete.contains(&slots[c]));
    let pattern = j.entries.iter().map(|&(r, c, _)| (r, c)).collect();
    let values = g.schedule(&j.expressions());
    let mut dfdt: Vec<Id> = f.iter().map(|&e| g.partial(e, time)).collect::<crate::Result<_>>()?;
    // An input is a function of the time: ∂f/∂t + Σ ∂f/∂u · u'.
    for &(u, rate) in inputs {
        let rate = g.symbol_node(rate);
        for d in dfdt.iter_mut().zip(f) {
            let through = g.partial(*d.1, u)?;
            let through = g.mul(through, rate)?;
            *d.0 = g.add(*d.0, through)?;
        }
    }
    let time = g.schedule(&dfdt);
    Ok(Some(JacobianPrograms { pattern, values, time }))
}

/// The event functions' rates dg/dt = ∂g/∂t + ∇g·f, where f is explicit
/// and the model has events.
pub fn event_rates_program(
    g: &mut Graph,
    sys: &FirstOrder,
    (time, inputs): (SymbolId, &[(SymbolId, SymbolId)]),
    explicit: Option<&[Id]>,
) -> crate::Result<Option<Program>> {
    let (Some(f), false) = (explicit, sys.events.is_empty()) else { return Ok(None) };
    // An event that reads a block's unknown has no rate from f alone.
    if events_read_blocks(g, sys) {
        return Ok(None);
    }
    let mut field = crate::VectorField::new();
    let one = g.one();
    field.set(time, one);
    // An input moves with the time at its rate.
    for &(u, rate) in inputs {
        let rate = g.symbol_node(rate);
        field.set(u, rate);
    }
    for (slot, &fi) in sys.slots.iter().zip(f) {
        field.set(slot.symbol, fi);
    }
    let rates = sys
        .events
        .iter()
        .map(|&e| g.total_derivative(e, &mut field))
        .collect::<crate::Result<Vec<Id>>>()?;
    Ok(Some(g.schedule(&rates)))
}

/// Whether an event function reads an unknown a run-time block solves.
pub fn events_read_blocks(g: &Graph, sys: &FirstOrder) -> bool {
    let solved: Vec<SymbolId> = sys.block_unknowns.iter().map(|&(s, _, _)| s).collect();
    sys.events.iter().any(|&e| g.free_symbols(e).iter().any(|s| solved.contains(s)))
}

/// The constraints and their Jacobian rows.
pub struct ConstraintPrograms {
    /// The residuals.
    pub residuals: Program,
    /// Per projection level, the position of each entry in its row-major
    /// rows × slots matrix, and the entries' program.
    pub levels: Vec<(Vec<usize>, Program)>,
    /// Positions no level corrects (slots whose derivative is another
    /// slot): free coordinates, which the rank of Φ_q does not count.
    pub unconstrained: usize,
}

/// The programs of the constraints; `None` without any.
pub fn constraint_programs(
    g: &mut Graph,
    slots: &[SymbolId],
    sys: &FirstOrder,
    levels: &[ProjectionLevel],
) -> crate::Result<Option<ConstraintPrograms>> {
    if sys.invariants.is_empty() {
        return Ok(None);
    }
    let residuals: Vec<Id> = sys.invariants.iter().map(|i| i.residual).collect();
    let residuals = g.schedule(&residuals);
    let mut level_programs = Vec::new();
    for level in levels {
        let cols = level.slots.len();
        let mut entries = Vec::new();
        let mut at = Vec::new();
        for (r, &row) in level.rows.iter().enumerate() {
            for (c, &slot) in level.slots.iter().enumerate() {
                let d = g.partial(sys.invariants[row].residual, slots[slot])?;
                if g.as_number(d).is_none_or(|v| !v.is_zero()) {
                    entries.push(d);
                    at.push(r * cols + c);
                }
            }
        }
        level_programs.push((at, g.schedule(&entries)));
    }
    let in_levels: std::collections::BTreeSet<usize> =
        levels.iter().flat_map(|l| l.slots.iter().copied()).collect();
    let unconstrained = (0..sys.slots.len())
        .filter(|&i| !in_levels.contains(&i))
        .filter(|&i| match sys.derivatives.get(i) {
            Some(crate::dae::system::SlotDerivative::Explicit(e)) => {
                g.as_symbol(*e).is_some_and(|s| slots.contains(&s))
            }
            _ => false,
        })
        .count();
    Ok(Some(ConstraintPrograms { residuals, levels: level_programs, unconstrained }))
}
