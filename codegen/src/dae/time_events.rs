//! Instants where a model is not smooth in the time alone: the switch of
//! `heaviside(t − t0)` (the library's steps, ramps and pulses) and the
//! kink of `abs(t − t0)`, each an affine function of the time with
//! coefficients of parameters. The run steps to each exactly and restarts
//! there, as at an input's breakpoint, instead of stepping across the
//! switch (Modelica's time events).

use crate::dae::linear_form::is_constant;
use crate::{Func, FxHashMap, Graph, Id, Node, SymbolId, SymbolKind};

/// The instants, as expressions of the parameters, of every switch in the
/// expressions `roots` that is a function of the time alone, each once, in
/// the graph's order.
pub fn breakpoints(g: &mut Graph, roots: &[Id], time: SymbolId) -> crate::Result<Vec<Id>> {
    let switches: Vec<Id> = g
        .reachable(roots)
        .into_iter()
        .filter_map(|n| match *g.node(n) {
            Node::Call(Func::Sign | Func::Abs, argument) => Some(argument),
            _ => None,
        })
        .collect();
    let mut instants = Vec::new();
    for argument in switches {
        let free = g.free_symbols(argument);
        let of_time_alone = free.contains(&time)
            && free.iter().all(|&s| s == time || g.symbol(s).kind == SymbolKind::Parameter);
        if !of_time_alone {
            continue;
        }
        // a t + b: a switch at −b/a.
        let a = g.partial(argument, time)?;
        if !is_constant(g, a) || g.as_number(a).is_some_and(|n| n.is_zero()) {
            continue;
        }
        let zero = g.zero();
        let b = g.substitute(argument, &FxHashMap::from_iter([(time, zero)]))?;
        let minus_b = g.neg(b)?;
        let instant = g.div(minus_b, a)?;
        if !instants.contains(&instant) {
            instants.push(instant);
        }
    }
    Ok(instants)
}
