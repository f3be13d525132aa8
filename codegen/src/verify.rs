//! The checks between passes, in debug builds, as cranelift's verifier
//! runs after each pass: the graph's invariants after every stage
//! ([`crate::Graph::verify`]), and after the reduction, every symbol the
//! first-order system's expressions read defined by the system: a slot, a
//! parameter, the time, an input or its rate, an intermediate, an unknown
//! a run-time block or the Newton block solves, or (in an action) the
//! value just before the instant. A failure is the pipeline's bug, said
//! on the model's name with the stage it followed.

use crate::dae::system::{FirstOrder, SlotDerivative};
use crate::front::ctxt::Ctxt;
use crate::front::ir::ModelIr;
use crate::{FxHashMap, Graph, Id, SymbolId, SymbolKind};

/// Reports to `cx` what is wrong after `stage`, in debug builds; `true`
/// where nothing is.
pub fn after(cx: &mut Ctxt, stage: &str, ir: &ModelIr, system: Option<&FirstOrder>) -> bool {
    if !cfg!(debug_assertions) || std::env::var_os("DAEGEN_NO_VERIFY").is_some() {
        return true;
    }
    let found = ir.graph.verify().and_then(|()| match system {
        Some(sys) => symbols_defined(&ir.graph, sys, &ir.pre),
        None => Ok(()),
    });
    match found {
        Ok(()) => true,
        Err(what) => {
            let message = format!("daegen's own mistake, found after {stage}: {what} (please report it with this model)");
            cx.error_at(&ir.fn_name, message);
            false
        }
    }
}

/// Every symbol `sys`'s expressions read is one it defines (see the module's
/// documentation); `pre` pairs each `pre(x)` with `x`.
fn symbols_defined(
    g: &Graph,
    sys: &FirstOrder,
    pre: &[(SymbolId, SymbolId)],
) -> Result<(), String> {
    if sys.mass_only {
        // Its highest derivatives and algebraic variables are components.
        return Ok(());
    }
    let mut defined: FxHashMap<SymbolId, ()> = FxHashMap::default();
    defined.extend(sys.slots.iter().map(|s| (s.symbol, ())));
    defined.extend(sys.block_unknowns.iter().map(|&(s, _, _)| (s, ())));
    if let Some(newton) = &sys.newton {
        defined.extend(newton.unknowns.iter().map(|&s| (s, ())));
    }
    let known_kind = |s: SymbolId| {
        matches!(
            g.symbol(s).kind,
            SymbolKind::Parameter
                | SymbolKind::Time
                | SymbolKind::Input { .. }
                | SymbolKind::Intermediate { .. }
        )
    };
    let check = |what: &str, id: Id, extra: &dyn Fn(SymbolId) -> bool| -> Result<(), String> {
        match g
            .free_symbols(id)
            .into_iter()
            .find(|&s| !defined.contains_key(&s) && !known_kind(s) && !extra(s))
        {
            Some(s) => Err(format!("{what} reads `{}`, which nothing defines", g.symbol(s).name)),
            None => Ok(()),
        }
    };
    let none = |_: SymbolId| false;
    let value = |d: &SlotDerivative| match d {
        SlotDerivative::Explicit(e) | SlotDerivative::AfterSolve(e) => Some(*e),
        SlotDerivative::Block { .. } => None,
    };
    for (slot, d) in sys.slots.iter().zip(&sys.derivatives) {
        if let Some(e) = value(d) {
            check(&format!("the derivative of `{}`", slot.name), e, &none)?;
        }
    }
    for (k, a) in sys.algebraics.iter().enumerate() {
        if let Some(e) = value(a) {
            check(&format!("algebraic variable {k}"), e, &none)?;
        }
    }
    for block in &sys.blocks {
        for &e in block.matrix.iter().chain(&block.rhs) {
            check("a run-time block", e, &none)?;
        }
    }
    for &e in sys.outputs.iter().chain(&sys.events) {
        check("an output or event function", e, &none)?;
    }
    for inv in &sys.invariants {
        check(&format!("the constraint `{}`", inv.text), inv.residual, &none)?;
    }
    if let Some(newton) = &sys.newton {
        for &e in newton.residuals.iter().chain(&newton.guesses) {
            check("the Newton block", e, &none)?;
        }
    }
    let before_instant = |s: SymbolId| pre.iter().any(|&(p, _)| p == s);
    for action in sys.actions.iter().flatten() {
        check("an action", action.value, &before_instant)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::front::components::definitions::Definitions;
    use quote::quote;

    /// x' = −k x reduced, with its IR.
    fn reduced() -> (ModelIr, FirstOrder) {
        let mut cx = Ctxt::default();
        let item: syn::ItemFn = syn::parse2(quote! {
            fn decay() {
                let k = param(0.5);
                let x = state(1.0);
                der(x) == -k * x;
                let twice = output(2.0 * x);
            }
        })
        .unwrap();
        let mut ir = crate::pipeline::lower(&mut cx, &item, false, Definitions::default());
        let sys = crate::pipeline::structure_and_reduction(&mut cx, &mut ir).unwrap();
        let _ = cx.into_messages();
        (ir, sys)
    }

    #[test]
    fn a_sound_system_passes() {
        let (ir, sys) = reduced();
        assert_eq!(ir.graph.verify(), Ok(()));
        assert_eq!(symbols_defined(&ir.graph, &sys, &ir.pre), Ok(()));
    }

    #[test]
    fn an_output_reading_what_nothing_defines_is_found() {
        let (mut ir, mut sys) = reduced();
        let stray = ir.graph.state("stray").unwrap();
        sys.outputs[0] = ir.graph.mul(sys.outputs[0], stray).unwrap();
        assert_eq!(
            symbols_defined(&ir.graph, &sys, &ir.pre),
            Err("an output or event function reads `stray`, which nothing defines".into())
        );
        let mut cx = Ctxt::default();
        assert!(!after(&mut cx, "the reduction", &ir, Some(&sys)));
        let messages = cx.into_messages();
        assert!(messages[0].starts_with("daegen's own mistake, found after the reduction: an output or event function reads `stray`"), "{messages:?}");
    }
}
