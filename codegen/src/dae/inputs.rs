//! Inputs in the reduced system: known functions of the time given only
//! by their values (and first rates) at run time, so an equation the index
//! reduction differentiated must not read one.

use crate::dae::system::FirstOrder;
use crate::front::ctxt::Ctxt;
use crate::front::ir::ModelIr;

/// Reports each equation that the index reduction differentiated and that
/// reads an input (its derivatives are not known); `true` when none does.
pub fn inputs_not_differentiated(cx: &mut Ctxt, ir: &ModelIr, sys: &FirstOrder) -> bool {
    if ir.inputs.is_empty() {
        return true;
    }
    let mut ok = true;
    for (e, equation) in ir.equations.iter().enumerate() {
        if sys.differentiations.get(e).copied().unwrap_or(0) == 0 {
            continue;
        }
        let g = &ir.graph;
        let reads = [equation.lhs, equation.rhs].into_iter().flat_map(|side| g.free_symbols(side));
        let input = reads.into_iter().find_map(|s| {
            matches!(g.symbol(s).kind, crate::SymbolKind::Input { .. })
                .then(|| g.symbol(s).name.clone())
        });
        if let Some(input) = input {
            cx.error_at(
                &equation.origin,
                format!("the index reduction differentiates this equation, which reads the input `{input}`, whose derivatives are not known: make the input drive a state (a force, a voltage), not a constraint"),
            );
            ok = false;
        }
    }
    ok
}
