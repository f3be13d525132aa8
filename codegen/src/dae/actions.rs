//! The actions of events and clocks on the reduced system: each
//! `.reinit(x, value)` as the slot it writes and its value in the slots
//! (algebraic variables and highest derivatives replaced by their
//! solutions, as for event functions).

use crate::dae::system::{Slot, SlotAction};
use crate::front::ctxt::Ctxt;
use crate::front::ir::{Action, Clock, Event};
use crate::{FxHashMap, Graph, Id, SymbolId};

/// The actions of every event, then of every clock; `None` once a
/// mistake is reported (a target that reduction made no state, a value
/// that needs a numerical solve).
pub(crate) fn slot_actions(
    cx: &mut Ctxt,
    g: &mut Graph,
    (events, clocks): (&[Event], &[Clock]),
    slots: &[Slot],
    known: &FxHashMap<SymbolId, Id>,
    solved_at_run_time: &dyn Fn(SymbolId) -> bool,
) -> Option<Vec<Vec<SlotAction>>> {
    let triggers = events.iter().map(|e| &e.actions).chain(clocks.iter().map(|c| &c.actions));
    let mut all = Vec::with_capacity(events.len() + clocks.len());
    let mut ok = true;
    for actions in triggers {
        let mut written = Vec::with_capacity(actions.len());
        for a in actions {
            match slot_action(g, a, slots, known, solved_at_run_time) {
                Ok(action) => written.push(action),
                Err(message) => {
                    cx.error_at(&a.origin, message);
                    ok = false;
                }
            }
        }
        all.push(written);
    }
    ok.then_some(all)
}

fn slot_action(
    g: &mut Graph,
    a: &Action,
    slots: &[Slot],
    known: &FxHashMap<SymbolId, Id>,
    solved_at_run_time: &dyn Fn(SymbolId) -> bool,
) -> Result<SlotAction, String> {
    let target = g.symbol(a.target).name.clone();
    let Some(slot) = slots.iter().position(|s| s.symbol == a.target) else {
        return Err(format!(
            "`{target}` is not a state of the reduced model (its equations determine it from the others): reinit one of the states it depends on"
        ));
    };
    let value = g.substitute(a.value, known).map_err(|e| e.to_string())?;
    if let Some(s) = g.free_symbols(value).into_iter().find(|&s| solved_at_run_time(s)) {
        let name = g.symbol(s).name.clone();
        return Err(format!(
            "this action reads `{name}`, which is only known after a numerical solve; compute the new value from the states instead"
        ));
    }
    Ok(SlotAction { slot, value })
}
