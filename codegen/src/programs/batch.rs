//! `#[dae_model(batch = L)]`: whether the model's right-hand side runs on
//! lanes of `L` members (an explicit ODE without events, clocks or
//! inputs, whose program lanes can compute), and that program.

use crate::dae::system::{FirstOrder, SlotDerivative};
use crate::expr::node::Node;
use crate::front::ir::ModelIr;
use crate::programs::schedule::Program;
use crate::{Graph, Id, SymbolKind};

/// The right-hand side's program for lanes, or what to do instead.
pub fn batch_program(ir: &mut ModelIr, sys: &FirstOrder) -> Result<Program, String> {
    let fix = "batch lanes run explicit ODEs without events, clocks or inputs: drop `batch`, and run the members one by one with `daegen::Ensemble`";
    let what = if sys.index > 0 || !ir.algebraics.is_empty() || sys.mass_only {
        Some("is a DAE")
    } else if !sys.blocks.is_empty() || sys.newton.is_some() {
        Some("has equations solved for their derivatives at run time")
    } else if !ir.events.is_empty() || !ir.clocks.is_empty() {
        Some("has events or clocks")
    } else if !ir.inputs.is_empty() {
        Some("reads inputs")
    } else if !sys.invariants.is_empty() || !ir.invariants.is_empty() {
        Some("has invariants to project onto")
    } else {
        None
    };
    if let Some(what) = what {
        return Err(format!("this model {what}; {fix}"));
    }
    let outputs: Vec<Id> = sys
        .derivatives
        .iter()
        .filter_map(|d| match d {
            SlotDerivative::Explicit(e) => Some(*e),
            _ => None,
        })
        .collect();
    if outputs.len() != sys.slots.len() {
        return Err(format!("this model has derivatives solved at run time; {fix}"));
    }
    if let Some(why) = not_on_lanes(&ir.graph, &outputs) {
        return Err(format!(
            "its right-hand side has {why}, which lanes do not compute yet; {fix}"
        ));
    }
    Ok(ir.graph.schedule(&outputs))
}

/// What in the program of `outputs` lanes cannot compute, if anything: a
/// sign (an `if` on a value), or a power or `atan2` whose first operand is
/// the same in every lane while the second differs (`2^x`, with `x` a
/// state: a number's method would be called with lanes).
fn not_on_lanes(g: &Graph, outputs: &[Id]) -> Option<&'static str> {
    let varies = |id: Id| {
        g.free_symbols(id).iter().any(|&s| {
            matches!(
                g.symbol(s).kind,
                SymbolKind::State | SymbolKind::Parameter | SymbolKind::Derivative { .. }
            )
        })
    };
    for id in g.reachable(outputs) {
        match g.node(id) {
            Node::Call(f, _) if *f == crate::Func::Sign => {
                return Some("a sign (`sign` or `abs`'s derivative)")
            }
            Node::Pow([b, e]) if g.as_number(*e).is_none() && !varies(*b) && varies(*e) => {
                return Some("a number raised to a varying power")
            }
            Node::Atan2([y, x]) if !varies(*y) && varies(*x) => {
                return Some("an `atan2` of a number")
            }
            _ => {}
        }
    }
    None
}
