//! Ties hidden behind algebraic variables: connected parts whose states
//! are related through the connections' potentials and flows, as two
//! capacitors in parallel (`c1.v = n.v = c2.v`), a loop of capacitors
//! (`c2.v = c1.v − c3.v`), a gear between an inertia and a damper (the
//! damper's relative angle is the load's angle less the rotor's over the
//! ratio), or a voltage source across a capacitor (`c.v = v(t)`).
//!
//! Taken alone, each equation determines an unknown; together they
//! over-determine them: with the states known, the equations reachable by
//! alternating paths from an equation a maximum matching leaves unmatched
//! are more than the unknowns they read (the over-determined part of the
//! Dulmage–Mendelsohn decomposition; Pantelides 1988 calls it a
//! structurally singular subset and differentiates it). Where that part is
//! linear with coefficients that read parameters only, eliminating its
//! unknowns from the unmatched equation leaves the relation among the
//! states it hides, `Σ c_k y_k + b(t) = 0`: the tie `tied_states`
//! eliminates one state by (static state selection, as Mattsson &
//! Söderlind's dummy derivatives pick one per tie), the unmatched equation
//! then implied by the others.

use crate::dae::linear_form::Linear;
use crate::dae::matching::{maximum_matching, over_determined};
use crate::front::ir::ModelIr;
use crate::{FxHashMap, Id, SymbolId, SymbolKind};

/// What an over-determined part hides.
pub(crate) enum Hidden {
    /// The relation `Σ c_k y_k + b(t) = 0` among carried values (states and
    /// derivatives below the highest) that `equation`, with the others of
    /// its part, makes; once a state is eliminated by it, `equation` is
    /// implied by the others.
    Tie { equation: usize, relation: Linear },
    /// `equation` repeats what the others of its part say.
    Redundant { equation: usize },
    /// The relation `residual = 0` among the states that `equation`, with
    /// the others of its part, makes is nonlinear: a constraint in place of
    /// `equation`, which the index reduction differentiates and the run
    /// projects onto, both states kept.
    Constraint { equation: usize, residual: Id },
}

/// An over-determined part of the equations: more equations than the
/// unknowns they read.
pub(crate) struct Part {
    /// Its equations, by index.
    pub(crate) equations: Vec<usize>,
    /// The unknowns they read.
    pub(crate) unknowns: Vec<SymbolId>,
}

/// The first tie an over-determined part of the equations hides, over the
/// unknowns `is_unknown` says (the highest derivatives and the algebraic
/// variables), with that part; `residuals[e]` is equation `e` after the
/// aliases, `passed` the equations to leave out.
pub(crate) fn hidden_tie(
    ir: &mut ModelIr,
    residuals: &[Id],
    passed: &[bool],
    is_unknown: &dyn Fn(&crate::Graph, SymbolId) -> bool,
) -> crate::Result<Option<(Hidden, Part)>> {
    let g = &ir.graph;
    let mut column_of: FxHashMap<SymbolId, usize> = FxHashMap::default();
    let mut columns: Vec<SymbolId> = Vec::new();
    let mut rows: Vec<Vec<usize>> = Vec::new();
    let mut equation_of: Vec<usize> = Vec::new();
    for (e, &r) in residuals.iter().enumerate() {
        if passed[e] || ir.equations[e].is_constraint || g.as_number(r).is_some() {
            continue;
        }
        let mut row = Vec::new();
        for s in g.free_symbols(r) {
            if is_unknown(g, s) {
                let next = columns.len();
                let c = *column_of.entry(s).or_insert(next);
                if c == next {
                    columns.push(s);
                }
                row.push(c);
            }
        }
        rows.push(row);
        equation_of.push(e);
    }
    let owner = maximum_matching(&rows, columns.len());
    let mut matched = vec![false; rows.len()];
    for r in owner.iter().flatten() {
        matched[*r] = true;
    }
    for r in (0..rows.len()).filter(|&r| !matched[r]) {
        let (part, unknowns) = over_determined(r, &rows, &owner);
        let unknowns: Vec<SymbolId> = unknowns.iter().map(|&c| columns[c]).collect();
        let equations: Vec<usize> = part.iter().map(|&k| equation_of[k]).collect();
        let part = Part { equations, unknowns };
        if let Some(hidden) = eliminated(ir, residuals, &part, equation_of[r])? {
            return Ok(Some((hidden, part)));
        }
    }
    Ok(None)
}

/// The unknowns of an over-determined part eliminated from its unmatched
/// equation by the others (Gaussian elimination over coefficients that
/// read parameters only, a numeric pivot first), or `None` where the part
/// is not linear so or the relation left reads an unknown.
fn eliminated(
    ir: &mut ModelIr,
    residuals: &[Id],
    part: &Part,
    unmatched: usize,
) -> crate::Result<Option<Hidden>> {
    let (equations, unknowns) = (&part.equations[..], &part.unknowns[..]);
    let time = ir.time;
    let g = &mut ir.graph;
    let mut forms: Vec<(usize, Linear)> = Vec::with_capacity(equations.len());
    let mut nonlinear = false;
    for &e in equations {
        match Linear::over_variables(g, residuals[e], time)? {
            Some(form) => forms.push((e, form)),
            None => {
                nonlinear = true;
                break;
            }
        }
    }
    if nonlinear {
        // Linear in the unknowns alone, nonlinear in the states: the
        // relation left is a constraint, not a tie; so is a lone equation
        // among states that the aliases of connected flanges leave (a
        // rod's `x.s² + y.s² = l²` on the positions of two masses).
        if equations.len() < 2 {
            return Ok(implied(g, residuals, equations, unmatched, unknowns)?
                .map(|residual| Hidden::Constraint { equation: unmatched, residual }));
        }
        forms.clear();
        for &e in equations {
            match Linear::over_symbols(g, residuals[e], unknowns)? {
                Some(form) => forms.push((e, form)),
                // Nonlinear in an unknown too (a rod's `x.s² + y.s² = l²`
                // on its flanges' positions): the unknowns the other
                // equations give linearly substituted away, if that is
                // all the unmatched equation reads.
                None => return substituted(g, residuals, part, unmatched),
            }
        }
    }
    // The unmatched equation last, so that it is never a pivot: the
    // relation left is it, plus multiples of the others.
    let Some(last) = forms.iter().position(|(e, _)| *e == unmatched) else { return Ok(None) };
    let end = forms.len() - 1;
    forms.swap(last, end);
    let mut pivoted = vec![false; end];
    for &u in unknowns {
        let nonzero = |f: &Linear| f.coefficient(u).filter(|&c| !is_zero(g, c));
        let candidates = (0..end).filter(|&k| !pivoted[k]);
        let numeric = candidates
            .clone()
            .find(|&k| nonzero(&forms[k].1).is_some_and(|c| g.as_number(c).is_some()));
        let Some(p) =
            numeric.or_else(|| candidates.clone().find(|&k| nonzero(&forms[k].1).is_some()))
        else {
            continue;
        };
        pivoted[p] = true;
        let Some(pivot) = forms[p].1.coefficient(u) else { continue };
        let pivot_form =
            std::mem::replace(&mut forms[p].1, Linear { terms: Vec::new(), constant: g.zero() });
        for (k, (_, form)) in forms.iter_mut().enumerate() {
            if k == p {
                continue;
            }
            let Some(c) = form.coefficient(u).filter(|&c| !is_zero(g, c)) else { continue };
            let factor = g.div(c, pivot)?;
            *form = form.minus_scaled(factor, &pivot_form, g)?;
        }
        forms[p].1 = pivot_form;
    }
    let Some((_, relation)) = forms.pop() else { return Ok(None) };
    let g = &ir.graph;
    if relation.terms.iter().any(|(y, _)| unknowns.contains(y)) {
        return Ok(None);
    }
    if nonlinear {
        let carried = |s: &SymbolId| {
            matches!(g.symbol(*s).kind, SymbolKind::State | SymbolKind::Derivative { .. })
        };
        let reads_a_state = g.free_symbols(relation.constant).iter().any(carried);
        let residual = relation.constant;
        return Ok(reads_a_state.then_some(Hidden::Constraint { equation: unmatched, residual }));
    }
    if relation.terms.is_empty() {
        let redundant = g.as_number(relation.constant).is_some_and(|n| n.is_zero());
        return Ok(redundant.then_some(Hidden::Redundant { equation: unmatched }));
    }
    // The relation must be among values the integrator carries.
    let carried = relation.terms.iter().all(|(y, _)| {
        matches!(g.symbol(*y).kind, SymbolKind::State | SymbolKind::Derivative { .. })
    });
    Ok(carried.then_some(Hidden::Tie { equation: unmatched, relation }))
}

/// The unknowns of an over-determined part substituted away from one of
/// its equations: each other equation linear in one of them, with a
/// coefficient that reads parameters only, solved for it and put into the
/// rest, until no equation gives another. The equation tried first is one
/// nonlinear in the unknowns (a rod's `x.s² + y.s² = l²` on its flanges'
/// positions, given by the connections): the part is over-determined by
/// one, so any of its equations may be the one the others imply. A
/// constraint in place of the first equation left free of unknowns and
/// reading a state; `None` where there is none.
fn substituted(
    g: &mut crate::Graph,
    residuals: &[Id],
    Part { equations, unknowns }: &Part,
    unmatched: usize,
) -> crate::Result<Option<Hidden>> {
    let mut candidates: Vec<usize> = Vec::with_capacity(equations.len());
    for &e in equations {
        if Linear::over_symbols(g, residuals[e], unknowns)?.is_none() {
            candidates.push(e);
        }
    }
    candidates.push(unmatched);
    for candidate in candidates {
        if let Some(residual) = implied(g, residuals, equations, candidate, unknowns)? {
            return Ok(Some(Hidden::Constraint { equation: candidate, residual }));
        }
    }
    Ok(None)
}

/// Equation `chosen` with the unknowns the other equations of its part give
/// linearly substituted away, if that leaves it free of unknowns and
/// reading a state.
fn implied(
    g: &mut crate::Graph,
    residuals: &[Id],
    equations: &[usize],
    chosen: usize,
    unknowns: &[SymbolId],
) -> crate::Result<Option<Id>> {
    let mut current: Vec<(usize, Id)> = equations.iter().map(|&e| (e, residuals[e])).collect();
    let mut left: Vec<SymbolId> = unknowns.to_vec();
    let mut used = vec![false; current.len()];
    loop {
        let mut solved = None;
        'search: for (k, &(e, r)) in current.iter().enumerate() {
            if e == chosen || used[k] {
                continue;
            }
            for u in g.free_symbols(r).into_iter().filter(|u| left.contains(u)) {
                let Some(form) = Linear::over_symbols(g, r, &[u])? else { continue };
                let Some(c) = form.coefficient(u).filter(|&c| !is_zero(g, c)) else { continue };
                // r = c u + b: u = −b / c.
                let quotient = g.div(form.constant, c)?;
                solved = Some((k, u, g.neg(quotient)?));
                break 'search;
            }
        }
        let Some((k, u, value)) = solved else { break };
        used[k] = true;
        left.retain(|&s| s != u);
        let replace: FxHashMap<SymbolId, Id> = [(u, value)].into_iter().collect();
        for (_, r) in current.iter_mut() {
            *r = g.substitute(*r, &replace)?;
        }
    }
    let Some(&(_, rest)) = current.iter().find(|(e, _)| *e == chosen) else { return Ok(None) };
    let free = g.free_symbols(rest);
    let carried = |s: &SymbolId| {
        matches!(g.symbol(*s).kind, SymbolKind::State | SymbolKind::Derivative { .. })
    };
    let constraint = !free.iter().any(|s| unknowns.contains(s)) && free.iter().any(carried);
    Ok(constraint.then_some(rest))
}

fn is_zero(g: &crate::Graph, c: Id) -> bool {
    g.as_number(c).is_some_and(|n| n.is_zero())
}
