//! Initialization as a system of its own (Modelica's `initial equation`):
//! the equations `initial(lhs == rhs)` hold at the start only, and decide
//! as many of the start values as they are. Each is matched to a state it
//! reads (through the dynamics: `initial(der(w) == 0.0)` reads what `der(w)`
//! is made of) whose start the model did not fix (`.fixed()`,
//! `init(part.x, v)`); those states are the unknowns the run solves for by
//! Newton's method before the first step, their starts the first guess,
//! every other state keeping its start. An equation that can move no
//! state, or more equations than the states they can move, is a compile
//! error on the equations in conflict.

use crate::dae::matching::{maximum_matching, over_determined};
use crate::dae::system::FirstOrder;
use crate::front::ctxt::Ctxt;
use crate::front::ir::ModelIr;
use crate::{FxHashMap, SymbolId};

/// What the run solves at the start.
pub struct Initialization {
    /// The slots the initial equations decide, in slot order.
    pub free: Vec<usize>,
    /// Each initial equation as written, for the run's messages.
    pub texts: Vec<String>,
}

/// The slots the initial equations of `sys` decide, or `Some(None)` where
/// the model has none; `None` where a mistake was reported to `cx`.
pub fn initialization(
    cx: &mut Ctxt,
    ir: &ModelIr,
    sys: &FirstOrder,
) -> Option<Option<Initialization>> {
    if sys.initial.is_empty() {
        return Some(None);
    }
    let g = &ir.graph;
    // A discrete value changes only at events: never an unknown here.
    let movable: Vec<usize> = (0..sys.slots.len())
        .filter(|&i| !sys.slots[i].fixed && !ir.discretes.contains(&sys.slots[i].symbol))
        .collect();
    let column_of: FxHashMap<SymbolId, usize> =
        movable.iter().enumerate().map(|(c, &i)| (sys.slots[i].symbol, c)).collect();
    let rows: Vec<Vec<usize>> = sys
        .initial
        .iter()
        .map(|&r| g.free_symbols(r).iter().filter_map(|s| column_of.get(s).copied()).collect())
        .collect();
    let texts: Vec<String> =
        ir.initial_equations.iter().map(|e| crate::front::names::source_text(&e.origin)).collect();
    let mut ok = true;
    for (e, row) in rows.iter().enumerate() {
        if row.is_empty() {
            let reads: Vec<String> = g
                .free_symbols(sys.initial[e])
                .iter()
                .filter(|s| sys.slots.iter().any(|slot| slot.symbol == **s))
                .map(|s| format!("`{}`", g.symbol(*s).name))
                .collect();
            let why = match reads.is_empty() {
                true => "it reads no state".to_string(),
                false => format!(
                    "every state it reads, {}, has a fixed start (`.fixed()` or `init(..)`)",
                    reads.join(", ")
                ),
            };
            cx.error_at(&ir.initial_equations[e].origin, format!("this initial equation can move no start value: {why}; let one of them move, or remove the equation"));
            ok = false;
        }
    }
    if !ok {
        return None;
    }
    let owner = maximum_matching(&rows, movable.len());
    let mut matched = vec![false; rows.len()];
    for r in owner.iter().flatten() {
        matched[*r] = true;
    }
    if let Some(r) = (0..rows.len()).find(|&r| !matched[r]) {
        let (equations, columns) = over_determined(r, &rows, &owner);
        let listed: Vec<String> = equations.iter().map(|&e| format!("`{}`", texts[e])).collect();
        let states: Vec<String> =
            columns.iter().map(|&c| format!("`{}`", sys.slots[movable[c]].name)).collect();
        cx.error_at(
            &ir.initial_equations[r].origin,
            format!(
                "these {} initial equations decide only {} start value{}, {}: {}; remove one of them",
                equations.len(),
                columns.len(),
                if columns.len() == 1 { "" } else { "s" },
                states.join(", "),
                listed.join(", ")
            ),
        );
        return None;
    }
    let mut free: Vec<usize> =
        owner.iter().enumerate().filter(|(_, o)| o.is_some()).map(|(c, _)| movable[c]).collect();
    free.sort_unstable();
    Some(Some(Initialization { free, texts }))
}
