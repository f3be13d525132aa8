//! Models with modes (`if on { .. } else { .. }` on discrete booleans):
//! each mode's equations are sorted, reduced and solved alone, at compile
//! time, and the reduced systems joined into one that reads the booleans,
//! `Σ_modes [the booleans have the mode's values] · f_mode`, where each
//! bracket is a product of `b` and `1 − b`: exact, since a boolean is 0 or
//! 1 between events. Every mode must reduce to an explicit ODE in the same
//! states (a diode conducting or blocking, a contact sticking or
//! slipping); at most [`MAX_MODE_BOOLEANS`] booleans select equations.

use crate::dae::system::{FirstOrder, SlotAction, SlotDerivative};
use crate::front::ctxt::Ctxt;
use crate::front::ir::ModelIr;
use crate::{Graph, Id, SymbolId};

/// The most discrete booleans that may select equations (2⁶ modes).
pub const MAX_MODE_BOOLEANS: usize = 6;

/// The structure and reduction of `ir`: at once for a model without
/// modes, mode by mode and joined for one with.
pub fn reduce_modes(cx: &mut Ctxt, ir: &mut ModelIr) -> Option<FirstOrder> {
    let mut booleans: Vec<SymbolId> = Vec::new();
    for e in &ir.equations {
        for &(b, _) in &e.mode {
            if !booleans.contains(&b) {
                booleans.push(b);
            }
        }
    }
    let reduce_all = |cx: &mut Ctxt, ir: &mut ModelIr| {
        crate::dae::structure::structure(cx, ir)
            .and_then(|structure| crate::dae::reduce::reduce(cx, ir, structure))
    };
    if booleans.is_empty() {
        return reduce_all(cx, ir);
    }
    let first_guarded = ir.equations.iter().find(|e| !e.mode.is_empty())?.origin.clone();
    if booleans.len() > MAX_MODE_BOOLEANS {
        cx.error_at(&first_guarded, format!("{} discrete booleans select equations, more than the {MAX_MODE_BOOLEANS} (64 modes) each analysed at compile time: combine modes into fewer booleans", booleans.len()));
        return None;
    }
    let all = std::mem::take(&mut ir.equations);
    let mut systems = Vec::with_capacity(1 << booleans.len());
    for bits in 0..(1usize << booleans.len()) {
        let holds =
            |b: SymbolId| booleans.iter().position(|&x| x == b).is_some_and(|j| bits >> j & 1 == 1);
        ir.equations = all
            .iter()
            .filter(|e| e.mode.iter().all(|&(b, value)| holds(b) == value))
            .cloned()
            .collect();
        let system = reduce_all(cx, ir).filter(|_| cx.is_ok());
        let mode_name = mode_name(&ir.graph, &booleans, bits);
        let system = match system.map(|s| explicit(s, &mode_name)) {
            Some(Ok(s)) => s,
            Some(Err(message)) => {
                cx.error_at(&first_guarded, message);
                ir.equations = all;
                return None;
            }
            None => {
                cx.error_at(&first_guarded, format!("in the mode {mode_name}, the equations that hold do not determine the model (the errors above): each mode needs one equation per unknown"));
                ir.equations = all;
                return None;
            }
        };
        systems.push(system);
    }
    ir.equations = all;
    match join(&mut ir.graph, &booleans, systems) {
        Ok(joined) => Some(joined),
        Err(e) => {
            cx.error_at(&first_guarded, e);
            None
        }
    }
}

/// `on` and `!stuck`, for messages.
fn mode_name(g: &Graph, booleans: &[SymbolId], bits: usize) -> String {
    let parts: Vec<String> = booleans
        .iter()
        .enumerate()
        .map(|(j, &b)| format!("`{}` is {}", g.symbol(b).name, bits >> j & 1 == 1))
        .collect();
    format!("where {}", parts.join(" and "))
}

/// `sys` if it is an explicit ODE, or why a mode must be one.
fn explicit(sys: FirstOrder, mode: &str) -> Result<FirstOrder, String> {
    let explicit = sys.derivatives.iter().all(|d| matches!(d, SlotDerivative::Explicit(_)))
        && sys.algebraics.iter().all(|d| matches!(d, SlotDerivative::Explicit(_)));
    if !explicit || !sys.blocks.is_empty() || sys.newton.is_some() || sys.mass_only {
        return Err(format!("in the mode {mode}, the equations are solved at run time (a linear or nonlinear block): each mode must solve symbolically to an explicit ODE"));
    }
    if !sys.invariants.is_empty() {
        return Err(format!("in the mode {mode}, the equations have index {} (constraints the states must keep): each mode must be an ODE in the same states; write the constrained mode with its constraint differentiated (a sticking contact as `der(v) == a_belt`)", sys.index));
    }
    Ok(sys)
}

/// The systems of every mode (mode `bits` at index `bits`) as one.
fn join(
    g: &mut Graph,
    booleans: &[SymbolId],
    systems: Vec<FirstOrder>,
) -> crate::Result<FirstOrder> {
    let indicators: Vec<Id> = (0..systems.len())
        .map(|bits| {
            let factors = booleans
                .iter()
                .enumerate()
                .map(|(j, &b)| {
                    let on = g.symbol_node(b);
                    if bits >> j & 1 == 1 {
                        Ok(on)
                    } else {
                        let one = g.one();
                        g.sub(one, on)
                    }
                })
                .collect::<crate::Result<Vec<Id>>>()?;
            g.product(&factors)
        })
        .collect::<crate::Result<_>>()?;
    let names = |s: &FirstOrder| s.slots.iter().map(|x| x.name.clone()).collect::<Vec<_>>();
    if systems.iter().any(|s| names(s) != names(&systems[0])) {
        return Err(crate::Error::Unsupported {
            message: "the modes reduce to different states: each mode must keep the same states"
                .into(),
        });
    }
    let blend = |g: &mut Graph, values: Vec<Id>| -> crate::Result<Id> {
        if values.iter().all(|&v| v == values[0]) {
            return Ok(values[0]);
        }
        let terms = values
            .iter()
            .zip(&indicators)
            .map(|(&v, &i)| g.mul(i, v))
            .collect::<crate::Result<Vec<Id>>>()?;
        g.sum(&terms)
    };
    let explicit_of = |d: &SlotDerivative| match d {
        SlotDerivative::Explicit(e) | SlotDerivative::AfterSolve(e) => *e,
        // `explicit` let no block through.
        SlotDerivative::Block { .. } => Id(0),
    };
    let first = &systems[0];
    let mut derivatives = Vec::with_capacity(first.derivatives.len());
    for i in 0..first.derivatives.len() {
        let values = systems.iter().map(|s| explicit_of(&s.derivatives[i])).collect();
        derivatives.push(SlotDerivative::Explicit(blend(g, values)?));
    }
    let mut algebraics = Vec::with_capacity(first.algebraics.len());
    for i in 0..first.algebraics.len() {
        let values = systems.iter().map(|s| explicit_of(&s.algebraics[i])).collect();
        algebraics.push(SlotDerivative::Explicit(blend(g, values)?));
    }
    let mut outputs = Vec::with_capacity(first.outputs.len());
    for i in 0..first.outputs.len() {
        outputs.push(blend(g, systems.iter().map(|s| s.outputs[i]).collect())?);
    }
    let mut events = Vec::with_capacity(first.events.len());
    for i in 0..first.events.len() {
        events.push(blend(g, systems.iter().map(|s| s.events[i]).collect())?);
    }
    let mut actions = first.actions.clone();
    for (t, trigger) in actions.iter_mut().enumerate() {
        for (a, action) in trigger.iter_mut().enumerate() {
            let value = blend(g, systems.iter().map(|s| s.actions[t][a].value).collect())?;
            *action = SlotAction { slot: action.slot, value };
        }
    }
    let mut joined = systems.into_iter().next().ok_or_else(|| crate::Error::Unsupported {
        message: "a model with modes has at least one".into(),
    })?;
    joined.derivatives = derivatives;
    joined.algebraics = algebraics;
    joined.outputs = outputs;
    joined.events = events;
    joined.actions = actions;
    Ok(joined)
}
