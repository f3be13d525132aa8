//! Reduction to a first-order explicit system `y' = f(t, y)` (course notes
//! Example 1.1): each state of order k becomes k states `x, der(x), …,
//! der^(k-1)(x)`. The unknowns at a point are the highest derivatives `z`
//! and the algebraic variables `λ`; constraints are differentiated until
//! they involve one (`index_reduction`). The equations, then linear in the
//! unknowns (`E(t, y) (z, λ) = g(t, y)`), are solved block by block —
//! symbolically when a block is one equation or has constant coefficients,
//! by a dense solve at run time otherwise (the KKT system of a mechanism).

use crate::dae::structure::Structure;
use crate::dae::system::{AlgebraicValue, FirstOrder, Slot, SlotDerivative};
use crate::front::ctxt::Ctxt;
use crate::front::ir::{AlgebraicDecl, Init, ModelIr, StateDecl, UserInvariant};
use crate::{FxHashMap, Graph, Id, SymbolId};
use proc_macro2::TokenStream;

struct Equation {
    residual: Id,
    unknowns: Vec<usize>,
    origin: TokenStream,
    /// Its position among the model's equations.
    index: usize,
}

/// Solves the structured model for its unknowns, or reports why it
/// cannot: each pass below in turn, every mistake reported on the user's
/// tokens.
pub fn reduce(cx: &mut Ctxt, ir: &mut ModelIr, structure: Structure) -> Option<FirstOrder> {
    let Structure {
        order,
        mut z_symbols,
        algebraic_symbols,
        residuals,
        written,
        separated_combined,
        rank_conditions,
        reduction,
        texts,
        origins,
    } = structure;
    let g = &mut ir.graph;
    let n_states = z_symbols.len();
    let newton = newton_block(cx, g, &ir.algebraics, &reduction, &z_symbols, &texts, &origins)?;
    let in_newton = |s: &SymbolId| newton.as_ref().is_some_and(|b| b.unknowns.contains(s));
    // The unknowns: z, then λ (but for the Newton block's).
    let linear_algebraics: Vec<crate::front::ir::AlgebraicDecl> =
        ir.algebraics.iter().filter(|a| !in_newton(&a.symbol)).cloned().collect();
    z_symbols.extend(linear_algebraics.iter().map(|a| a.symbol));
    let z_index: FxHashMap<SymbolId, usize> =
        z_symbols.iter().enumerate().map(|(j, &s)| (s, j)).collect();
    let equations =
        equations_in_unknowns(g, &ir.equations, &reduction.residuals, newton.as_ref(), &z_index);
    let owner = matched(cx, g, &ir.states, &linear_algebraics, &equations, &z_symbols)?;
    let unknowns = Unknowns { z: &z_symbols, index: &z_index, states: n_states };
    let linear = linear_system(
        cx,
        g,
        (&ir.algebraics, !ir.events.is_empty()),
        &equations,
        &unknowns,
        &reduction.differentiations,
    )?;
    let solved = solve(cx, g, &linear, &owner, &equations, &z_symbols)?;
    let mut ok = true;
    let (slots, derivatives) = slots(
        g,
        (&ir.states, &ir.inits),
        &order,
        &reduction.explicit_highest,
        &solved,
        linear.mass_only,
    )?;
    ok &= inits_are_below_the_highest_derivatives(cx, g, (&ir.states, &ir.inits), &slots);
    let (outputs, events, observed) = observables(
        cx,
        g,
        (&ir.outputs, &ir.events),
        &z_symbols,
        &solved,
        &z_index,
        newton.as_ref(),
    )?;
    ok &= observed;
    let algebraics =
        algebraic_values(g, &ir.algebraics, &unknowns, &solved, newton.as_ref(), linear.mass_only)?;
    let (invariants, invariants_ok) =
        invariants(cx, g, &ir.invariants, &z_index, reduction.invariants);
    ok &= invariants_ok;
    // Run-time unknowns: the linear blocks', then the Newton block's.
    let newton_block_index = solved.blocks.len();
    let mut block_unknowns: Vec<(SymbolId, usize, usize)> = z_symbols
        .iter()
        .enumerate()
        .filter_map(|(j, &s)| solved.block_of[j].map(|(b, r)| (s, b, r)))
        .collect();
    if let Some(b) = &newton {
        for (k, &s) in b.unknowns.iter().enumerate() {
            block_unknowns.push((s, newton_block_index, k));
        }
    }
    ok.then_some(FirstOrder {
        slots,
        derivatives,
        blocks: solved.blocks,
        outputs,
        events,
        algebraics,
        invariants,
        projection: None,
        index: reduction.index,
        block_unknowns,
        residuals,
        combined: separated_combined,
        written,
        rank_conditions,
        differentiations: reduction.differentiations,
        highest: z_symbols[..n_states].to_vec(),
        algebraic_symbols,
        mass_only: linear.mass_only,
        newton,
    })
}

/// Each equation left to the linear solve (not the Newton block's) with
/// the unknowns it involves.
fn equations_in_unknowns(
    g: &Graph,
    written: &[crate::front::ir::Equation],
    residuals: &[Id],
    newton: Option<&crate::dae::system::NewtonBlock>,
    z_index: &FxHashMap<SymbolId, usize>,
) -> Vec<Equation> {
    let mut equations = Vec::with_capacity(residuals.len());
    for (e, (eq, &r)) in written.iter().zip(residuals).enumerate() {
        if newton.is_some_and(|b| b.equations.contains(&e)) {
            continue;
        }
        let unknowns: Vec<usize> =
            g.free_symbols(r).into_iter().filter_map(|s| z_index.get(&s).copied()).collect();
        equations.push(Equation { residual: r, unknowns, origin: eq.origin.clone(), index: e });
    }
    equations
}

/// The outputs and event functions with the highest derivatives replaced
/// by their solutions; an event that reads an unknown solved at run time
/// is an error (`false`), an output may solve the blocks it reads.
fn observables(
    cx: &mut Ctxt,
    g: &mut Graph,
    (declared_outputs, declared_events): (&[crate::front::ir::Output], &[crate::front::ir::Event]),
    z: &[SymbolId],
    solved: &crate::dae::solve_unknowns::Solved,
    z_index: &FxHashMap<SymbolId, usize>,
    newton: Option<&crate::dae::system::NewtonBlock>,
) -> Option<(Vec<Id>, Vec<Id>, bool)> {
    let in_newton = |s: &SymbolId| newton.is_some_and(|b| b.unknowns.contains(s));
    let replace: FxHashMap<SymbolId, Id> =
        z.iter().enumerate().filter_map(|(j, &s)| solved.symbolic[j].map(|v| (s, v))).collect();
    let mut ok = true;
    let mut observe = |value: Id, origin: &TokenStream, what: &str| -> Option<Id> {
        let v = g.substitute(value, &replace).ok()?;
        if what == "output" {
            // Outputs may solve the blocks they read (λ of a mechanism).
            return Some(v);
        }
        if let Some(s) =
            g.free_symbols(v).into_iter().find(|s| z_index.contains_key(s) || in_newton(s))
        {
            let name = g.symbol(s).name.clone();
            cx.error_at(origin, format!("this {what} reads `{name}`, which is only known after a numerical solve; compute it from the states instead"));
            ok = false;
        }
        Some(v)
    };
    let mut outputs = Vec::with_capacity(declared_outputs.len());
    for o in declared_outputs {
        outputs.push(observe(o.value, &o.origin, "output")?);
    }
    let mut events = Vec::with_capacity(declared_events.len());
    for e in declared_events {
        events.push(observe(e.value, &e.origin, "event")?);
    }
    Some((outputs, events, ok))
}

/// The unknowns at a point: the highest derivatives (the first `states`),
/// then the algebraic variables solved linearly.
struct Unknowns<'a> {
    z: &'a [SymbolId],
    index: &'a FxHashMap<SymbolId, usize>,
    states: usize,
}

/// Algebraic equations nonlinear in their variables: a Newton block, its
/// variables known to the rest of the reduction (`Some(None)`: there is
/// none; `None`: an error was reported).
fn newton_block(
    cx: &mut Ctxt,
    g: &mut Graph,
    algebraics: &[AlgebraicDecl],
    reduction: &crate::dae::index_reduction::IndexReduction,
    z: &[SymbolId],
    texts: &[String],
    origins: &[TokenStream],
) -> Option<Option<crate::dae::system::NewtonBlock>> {
    let candidates: Vec<(SymbolId, String, Id)> =
        algebraics.iter().map(|a| (a.symbol, a.name.clone(), a.init)).collect();
    let found = crate::dae::newton_block::find(
        g,
        &crate::dae::newton_block::Candidates {
            residuals: &reduction.residuals,
            differentiations: &reduction.differentiations,
            highest: z,
            algebraics: &candidates,
            texts,
        },
    );
    match found {
        Ok(newton) => Some(newton),
        Err(e) => {
            cx.error_at(&origins[0], e);
            None
        }
    }
}

/// The equations as `E (z, λ) = g`, linear in the unknowns.
struct LinearSystem {
    /// `E`'s nonzero entries, row by row: (unknown, coefficient).
    e: Vec<Vec<(usize, Id)>>,
    /// `g = −r|_{z=0}`.
    g: Vec<Id>,
    /// An algebraic equation is nonlinear in the algebraic variables: the
    /// model has only its mass-matrix form.
    mass_only: bool,
}

/// `E_ij = ∂r_i/∂z_j`, which must not contain z, and `g = −r|_{z=0}`; an
/// equation nonlinear in a highest derivative is an error.
/// `model` is the algebraic variables and whether the model has events.
fn linear_system(
    cx: &mut Ctxt,
    g: &mut Graph,
    (algebraics, has_events): (&[AlgebraicDecl], bool),
    equations: &[Equation],
    unknowns: &Unknowns,
    differentiations: &[usize],
) -> Option<LinearSystem> {
    let n = unknowns.z.len();
    let zero = g.zero();
    let mut e_matrix: Vec<Vec<(usize, Id)>> = Vec::with_capacity(n);
    let z_zero: FxHashMap<SymbolId, Id> = unknowns.z.iter().map(|&s| (s, zero)).collect();
    let mut g_vec = Vec::with_capacity(n);
    // An algebraic equation (no derivative, not a differentiated
    // constraint) nonlinear in the algebraic variables has no index-1 form
    // here: the model is integrated in its mass-matrix form instead.
    let mut mass_only = false;
    for eq in equations {
        let mut row = Vec::new();
        let algebraic_equation =
            differentiations[eq.index] == 0 && eq.unknowns.iter().all(|&j| j >= unknowns.states);
        for &j in &eq.unknowns {
            let c = g.partial(eq.residual, unknowns.z[j]).ok()?;
            if let Some(bad) =
                g.free_symbols(c).into_iter().find(|s| unknowns.index.contains_key(s))
            {
                if algebraic_equation && !has_events {
                    mass_only = true;
                    continue;
                }
                let name = g.symbol(bad).name.clone();
                let message = if algebraics.iter().any(|a| a.symbol == bad) {
                    format!("this equation is not linear in the algebraic variable `{name}`: daegen needs the algebraic variables to enter linearly (Newton on a nonlinear algebraic equation is not there yet); solve the equation for `{name}` by hand or make `{name}` an output")
                } else {
                    format!("this equation is not linear in `{name}`: daegen needs the form `E(t, y) * der(..) == g(t, y)`")
                };
                cx.error_at(&eq.origin, message);
                return None;
            }
            if c != zero {
                row.push((j, c));
            }
        }
        let r0 = g.substitute(eq.residual, &z_zero).ok()?;
        g_vec.push(g.negate_terms(r0).ok()?);
        e_matrix.push(row);
    }
    Some(LinearSystem { e: e_matrix, g: g_vec, mass_only })
}

/// The unknowns solved block by block (nothing for a mass-matrix-only
/// model); linearly dependent equations are an error.
fn solve(
    cx: &mut Ctxt,
    g: &mut Graph,
    linear: &LinearSystem,
    owner: &[usize],
    equations: &[Equation],
    z: &[SymbolId],
) -> Option<crate::dae::solve_unknowns::Solved> {
    let n = z.len();
    let names: Vec<String> = z.iter().map(|&s| g.symbol(s).name.clone()).collect();
    let solved = if linear.mass_only {
        Ok(crate::dae::solve_unknowns::Solved {
            symbolic: vec![None; n],
            block_of: vec![None; n],
            blocks: Vec::new(),
            after_solve: vec![None; n],
        })
    } else {
        crate::dae::solve_unknowns::solve_unknowns(g, &linear.e, &linear.g, owner, z, &names)
    };
    match solved {
        Ok(solved) => Some(solved),
        Err(crate::dae::solve_unknowns::Unsolvable::Dependent { equation, unknowns }) => {
            let names: Vec<String> = unknowns.iter().map(|&j| format!("`{}`", names[j])).collect();
            cx.error_at(
                &equations[equation].origin,
                format!(
                    "the equations for {} are linearly dependent: one of them repeats the others",
                    names.join(", ")
                ),
            );
            None
        }
        Err(crate::dae::solve_unknowns::Unsolvable::Graph(e)) => {
            cx.error_at(&equations[0].origin, e);
            None
        }
    }
}

/// The slots `x, der(x), …, der^(k-1)(x)` per state and their derivatives;
/// the last one's is the solved highest derivative.
fn slots(
    g: &mut Graph,
    (states, inits): (&[StateDecl], &[Init]),
    order: &[u32],
    explicit_highest: &[bool],
    solved: &crate::dae::solve_unknowns::Solved,
    mass_only: bool,
) -> Option<(Vec<Slot>, Vec<SlotDerivative>)> {
    let zero = g.zero();
    let mut slots = Vec::new();
    let mut derivatives = Vec::new();
    let init_of: FxHashMap<SymbolId, Id> = inits.iter().map(|i| (i.target, i.value)).collect();
    for (i, s) in states.iter().enumerate() {
        for k in 0..order[i] {
            let id = g.derivative(s.symbol, k).ok()?;
            let symbol = g.as_symbol(id)?;
            let init = if k == 0 { s.init } else { init_of.get(&symbol).copied().unwrap_or(zero) };
            slots.push(Slot {
                name: g.symbol(symbol).name.clone(),
                symbol,
                init,
                fixed: k == 0 && s.fixed,
                velocity_like: k + 1 == order[i] && !explicit_highest[i],
            });
            derivatives.push(if k + 1 < order[i] {
                SlotDerivative::Explicit(g.derivative(s.symbol, k + 1).ok()?)
            } else {
                match (solved.symbolic[i], solved.block_of[i]) {
                    (Some(z), _) => SlotDerivative::Explicit(z),
                    (None, Some((block, row))) => SlotDerivative::Block { block, row },
                    (None, None) if solved.after_solve[i].is_some() => {
                        SlotDerivative::AfterSolve(solved.after_solve[i]?)
                    }
                    // The mass-matrix form computes it with λ as a component.
                    (None, None) if mass_only => SlotDerivative::Explicit(zero),
                    (None, None) => return None,
                }
            });
        }
    }
    Some((slots, derivatives))
}

/// `init(der(x), v)` is for a derivative below the highest one the
/// equations use (which follows from them); reports the others.
fn inits_are_below_the_highest_derivatives(
    cx: &mut Ctxt,
    g: &Graph,
    (states, inits): (&[StateDecl], &[Init]),
    slots: &[Slot],
) -> bool {
    let mut ok = true;
    for init in inits {
        let valid = slots.iter().any(|s| s.symbol == init.target)
            && !states.iter().any(|s| s.symbol == init.target);
        if !valid {
            let name = g.symbol(init.target).name.clone();
            cx.error_at(&init.origin, format!("`{name}` follows from its equation, so it takes no initial value: `init` is for derivatives below the highest one the equations use"));
            ok = false;
        }
    }
    ok
}

/// Each algebraic variable in declaration order: from the linear solve, or
/// from the Newton block (read as block `solved.blocks.len()`).
fn algebraic_values(
    g: &mut Graph,
    declared: &[AlgebraicDecl],
    unknowns: &Unknowns,
    solved: &crate::dae::solve_unknowns::Solved,
    newton: Option<&crate::dae::system::NewtonBlock>,
    mass_only: bool,
) -> Option<Vec<AlgebraicValue>> {
    let newton_block_index = solved.blocks.len();
    let mut algebraics = Vec::with_capacity(declared.len());
    for a in declared {
        if let Some(k) = newton.and_then(|b| b.unknowns.iter().position(|&s| s == a.symbol)) {
            algebraics.push(SlotDerivative::Block { block: newton_block_index, row: k });
            continue;
        }
        let j = *unknowns.index.get(&a.symbol)?;
        algebraics.push(match (solved.symbolic[j], solved.block_of[j]) {
            (Some(v), _) => SlotDerivative::Explicit(v),
            (None, Some((block, row))) => SlotDerivative::Block { block, row },
            (None, None) if solved.after_solve[j].is_some() => {
                SlotDerivative::AfterSolve(solved.after_solve[j]?)
            }
            (None, None) if mass_only => SlotDerivative::Explicit(g.symbol_node(unknowns.z[j])),
            (None, None) => return None,
        });
    }
    Some(algebraics)
}

/// The constraints index reduction found, then the user's invariants
/// (functions of the states, projected onto); an invariant that reads a
/// derivative or an algebraic variable is an error (`false`).
fn invariants(
    cx: &mut Ctxt,
    g: &Graph,
    user: &[UserInvariant],
    z_index: &FxHashMap<SymbolId, usize>,
    mut invariants: Vec<crate::dae::system::Invariant>,
) -> (Vec<crate::dae::system::Invariant>, bool) {
    let mut ok = true;
    for inv in user {
        if let Some(s) = g.free_symbols(inv.value).into_iter().find(|s| z_index.contains_key(s)) {
            let name = g.symbol(s).name.clone();
            cx.error_at(&inv.origin, format!("an invariant is a function of the states, and this one reads `{name}`: write it without derivatives or algebraic variables"));
            ok = false;
        }
        invariants.push(crate::dae::system::Invariant {
            equation: usize::MAX,
            level: 0,
            residual: inv.value,
            text: crate::front::names::source_text(&inv.origin),
        });
    }
    (invariants, ok)
}

/// A perfect matching of equations to unknowns (highest derivatives, then
/// algebraic variables; Kuhn's augmenting paths). An equation left over is
/// reported with the structurally singular subsystem it belongs to (the
/// equations reached by alternating paths, which share fewer unknowns than
/// they number); an unknown left over has no equation.
fn matched(
    cx: &mut Ctxt,
    g: &crate::Graph,
    states: &[crate::front::ir::StateDecl],
    algebraics: &[crate::front::ir::AlgebraicDecl],
    equations: &[Equation],
    unknowns: &[SymbolId],
) -> Option<Vec<usize>> {
    let n = unknowns.len();
    let mut owner: Vec<Option<usize>> = vec![None; n];
    let columns = |e: usize| equations[e].unknowns.iter().copied();
    let name = |j: usize| format!("`{}`", g.symbol(unknowns[j]).name);
    let text = |e: usize| format!("`{}`", crate::front::names::source_text(&equations[e].origin));
    let mut ok = true;
    for e in 0..equations.len() {
        let mut seen = vec![false; n];
        if crate::dae::matching::augment(e, &columns, &mut owner, &mut seen) {
            continue;
        }
        ok = false;
        let reached: Vec<usize> = (0..n).filter(|&j| seen[j]).collect();
        let mut subsystem: Vec<usize> = reached.iter().filter_map(|&j| owner[j]).collect();
        subsystem.sort_unstable();
        if let ([j], [other]) = (&reached[..], &subsystem[..]) {
            let name = name(*j);
            cx.error_at(&equations[e].origin, format!("{name} already has an equation: remove one of the two (or there are more equations than unknowns)"));
            cx.error_at(
                &equations[*other].origin,
                format!("the other equation that determines {name}"),
            );
            continue;
        }
        let listed: Vec<String> = subsystem.iter().map(|&k| text(k)).collect();
        let unknown_names: Vec<String> = reached.iter().map(|&j| name(j)).collect();
        let message = if reached.is_empty() {
            "this equation determines no unknown: it involves no highest derivative and no algebraic variable, and differentiating it does not help".to_string()
        } else {
            format!(
                "the system is structurally singular: this equation and {} determine only {} ({} equations for {} unknowns); remove an equation or add an algebraic variable",
                listed.join(", "),
                unknown_names.join(", "),
                subsystem.len() + 1,
                reached.len()
            )
        };
        cx.error_at(&equations[e].origin, message);
    }
    for (j, o) in owner.iter().enumerate() {
        if o.is_some() {
            continue;
        }
        ok = false;
        let name = name(j);
        match states.get(j) {
            Some(state) => {
                // unknowns[j] is the highest derivative of state j.
                let message = format!("no equation determines {name}: add `{} == ...;` (there are fewer equations than unknowns)", &name[1..name.len() - 1]);
                cx.error_at(&state.origin, message);
            }
            None => {
                let a = &algebraics[j - states.len()];
                cx.error_at(&a.origin, format!("no equation determines the algebraic variable {name}: add an equation or a constraint that involves it (there are fewer equations than unknowns)"));
            }
        }
    }
    if ok {
        owner.into_iter().collect()
    } else {
        None
    }
}
