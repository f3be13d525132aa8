//! Reduction to a first-order explicit system `y' = f(t, y)` (course notes
//! Example 1.1): each state of order k becomes k states `x, der(x), …,
//! der^(k-1)(x)`. The unknowns at a point are the highest derivatives `z`
//! and the algebraic variables `λ`; constraints are differentiated until
//! they involve one (`index_reduction`). The equations, then linear in the
//! unknowns (`E(t, y) (z, λ) = g(t, y)`), are solved block by block —
//! symbolically when a block is one equation or has constant coefficients,
//! by a dense solve at run time otherwise (the KKT system of a mechanism).
//!
//! The reduction's steps, each one entry the pipeline calls in order
//! (`pipeline::reduction`): [`check`] (the structural check),
//! [`without_aliases`], [`sorted`] (the causal order), [`newton`] (the
//! Newton block and its tearing), [`solved_unknowns`] (the linear blocks)
//! and [`first_order`] (the system they make).

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

/// The structural check of the equations as index reduction left them,
/// over every highest derivative and algebraic variable; `false` where it
/// reported a mistake.
pub fn check(cx: &mut Ctxt, ir: &ModelIr, structure: &Structure) -> bool {
    check_structure(
        cx,
        &ir.graph,
        (&ir.states, &ir.algebraics),
        &structure.z_symbols,
        &structure.reduction,
        (&structure.texts, &structure.origins),
    )
}

/// The equations without their aliases, and the algebraic variables the
/// aliases left.
pub struct WithoutAliases {
    /// The aliases and the equations left.
    pub aliases: crate::dae::alias::Aliases,
    /// Each variable removed, with its value.
    pub removed: FxHashMap<SymbolId, Id>,
    /// The algebraic variables kept.
    pub kept_algebraics: Vec<AlgebraicDecl>,
}

/// Aliases (`a == b`, `a == -b`, …) removed, each variable with its
/// alias's value.
pub fn without_aliases(
    cx: &mut Ctxt,
    ir: &mut ModelIr,
    structure: &Structure,
) -> Option<WithoutAliases> {
    let reduction = &structure.reduction;
    let aliases = match crate::dae::alias::eliminate_aliases(
        &mut ir.graph,
        &reduction.residuals,
        &reduction.differentiations,
        &structure.algebraic_symbols,
    ) {
        Ok(aliases) => aliases,
        Err(e) => {
            cx.error_at(&structure.origins[0], e);
            return None;
        }
    };
    let removed: FxHashMap<SymbolId, Id> = aliases.removed.iter().copied().collect();
    let kept_algebraics: Vec<AlgebraicDecl> =
        ir.algebraics.iter().filter(|a| !removed.contains_key(&a.symbol)).cloned().collect();
    Some(WithoutAliases { aliases, removed, kept_algebraics })
}

/// The equations left after the aliases sorted into blocks in causal
/// order over the highest derivatives and the algebraic variables kept,
/// the single ones solved there.
pub fn sorted(
    cx: &mut Ctxt,
    ir: &mut ModelIr,
    structure: &Structure,
    left: &WithoutAliases,
) -> Option<crate::dae::sorting::Sorted> {
    sort(
        cx,
        &mut ir.graph,
        (&ir.states, &left.kept_algebraics),
        &structure.z_symbols,
        &left.aliases,
        (&structure.texts, &structure.origins),
    )
}

/// The Newton block of the algebraic equations nonlinear in their
/// variables, torn (`Some(None)`: there is none; `None`: an error was
/// reported).
pub fn newton(
    cx: &mut Ctxt,
    ir: &mut ModelIr,
    structure: &Structure,
    left: &WithoutAliases,
    sorted: &crate::dae::sorting::Sorted,
) -> Option<Option<crate::dae::system::NewtonBlock>> {
    newton_block(
        cx,
        &mut ir.graph,
        &left.kept_algebraics,
        sorted,
        &structure.reduction,
        &structure.z_symbols,
        &structure.texts,
        &structure.origins,
    )
}

/// Every unknown solved: the highest derivatives, then the algebraic
/// variables the Newton block does not determine.
pub struct SolvedUnknowns {
    /// The unknowns: z, then those algebraic variables.
    pub all: Vec<SymbolId>,
    /// Each one's position in `all`.
    pub z_index: FxHashMap<SymbolId, usize>,
    /// The variables the Newton block computes from its tearing variables.
    pub computed: FxHashMap<SymbolId, Id>,
    /// How each is solved: symbolically, by a run-time block, after one.
    pub solved: crate::dae::solve_unknowns::Solved,
    /// An algebraic equation is nonlinear in the algebraic variables: the
    /// model has only its mass-matrix form.
    pub mass_only: bool,
}

/// The unknowns the sorting and the Newton block left, solved as the
/// linear system they form, block by block (symbolically, or by a
/// run-time solve), with the sorting's solutions beside them.
pub fn solved_unknowns(
    cx: &mut Ctxt,
    ir: &mut ModelIr,
    structure: &Structure,
    left: &WithoutAliases,
    sorted: &crate::dae::sorting::Sorted,
    newton: Option<&crate::dae::system::NewtonBlock>,
) -> Option<SolvedUnknowns> {
    let g = &mut ir.graph;
    let (z_symbols, reduction) = (&structure.z_symbols, &structure.reduction);
    let n_states = z_symbols.len();
    let in_newton = |s: &SymbolId| newton.is_some_and(|b| b.determines(s));
    // The variables the Newton block computes from its tearing variables,
    // in every equation left.
    let computed: FxHashMap<SymbolId, Id> =
        newton.iter().flat_map(|b| b.computed.iter().copied()).collect();
    let residuals_left = match computed.is_empty() {
        true => sorted.residuals.clone(),
        false => g.substitute_all(&sorted.residuals, &computed).ok()?,
    };
    // The unknowns: z, then λ (but for the Newton block's); those the
    // sorting solved are known, the rest go to the linear solve.
    let linear_algebraics: Vec<AlgebraicDecl> =
        left.kept_algebraics.iter().filter(|a| !in_newton(&a.symbol)).cloned().collect();
    let mut all = z_symbols.clone();
    all.extend(linear_algebraics.iter().map(|a| a.symbol));
    let z_index: FxHashMap<SymbolId, usize> =
        all.iter().enumerate().map(|(j, &s)| (s, j)).collect();
    let rest: Vec<usize> =
        (0..all.len()).filter(|&j| !sorted.explicit.contains_key(&all[j])).collect();
    let rest_symbols: Vec<SymbolId> = rest.iter().map(|&j| all[j]).collect();
    let rest_index: FxHashMap<SymbolId, usize> =
        rest_symbols.iter().enumerate().map(|(k, &s)| (s, k)).collect();
    let done = |e: usize| {
        left.aliases.alias_equations[e]
            || sorted.solved_equations[e]
            || newton.is_some_and(|b| b.equations.contains(&e))
    };
    let equations = equations_in_unknowns(g, &ir.equations, &residuals_left, &done, &rest_index);
    let owner = local_owner(sorted, &equations, &rest_symbols, &z_index);
    let unknowns = Unknowns {
        z: &rest_symbols,
        index: &rest_index,
        states: rest.iter().filter(|&&j| j < n_states).count(),
    };
    let linear = linear_system(
        cx,
        g,
        (&ir.algebraics, !ir.events.is_empty()),
        &equations,
        &unknowns,
        &reduction.differentiations,
    )?;
    let local = solve(cx, g, &linear, &owner, &equations, &rest_symbols)?;
    let solved = with_explicit(g, local, (&rest, &all), (&sorted.explicit, &computed))?;
    Some(SolvedUnknowns { all, z_index, computed, solved, mass_only: linear.mass_only })
}

/// The first-order system: the slots `x, der(x), …` and their
/// derivatives, the outputs and event functions in them, the actions on
/// the slots, the algebraic variables' values, the invariants, and how
/// each block was solved; every mistake reported on the user's tokens.
pub fn first_order(
    cx: &mut Ctxt,
    ir: &mut ModelIr,
    structure: Structure,
    left: WithoutAliases,
    sorted: crate::dae::sorting::Sorted,
    newton: Option<crate::dae::system::NewtonBlock>,
    unknowns: SolvedUnknowns,
) -> Option<FirstOrder> {
    let Structure {
        order,
        z_symbols,
        algebraic_symbols,
        residuals,
        written,
        separated_combined,
        rank_conditions,
        reduction,
        ..
    } = structure;
    let SolvedUnknowns { all, z_index, computed, solved, mass_only } = unknowns;
    let g = &mut ir.graph;
    let n_states = z_symbols.len();
    let unknowns = Unknowns { z: &all, index: &z_index, states: n_states };
    let mut ok = true;
    let (slots, derivatives) =
        slots(g, (&ir.states, &ir.inits), &order, &reduction.explicit_highest, &solved, mass_only)?;
    ok &= inits_are_below_the_highest_derivatives(cx, g, (&ir.states, &ir.inits), &slots);
    let known = known_values(g, &all, &solved, (&computed, &left.removed))?;
    let (outputs, events, observed) =
        observables(cx, g, (&ir.outputs, &ir.events), &known, &z_index, newton.as_ref())?;
    ok &= observed;
    let (initial, initial_ok) =
        initial_residuals(cx, g, &ir.initial_equations, &known, &z_index, newton.as_ref())?;
    ok &= initial_ok;
    let solved_at_run_time =
        |s: SymbolId| z_index.contains_key(&s) || newton.as_ref().is_some_and(|b| b.determines(&s));
    let actions = crate::dae::actions::slot_actions(
        cx,
        g,
        (&ir.events, &ir.clocks),
        &slots,
        &known,
        &solved_at_run_time,
    )?;
    let algebraics = algebraic_values(
        g,
        &ir.algebraics,
        &unknowns,
        &solved,
        newton.as_ref(),
        (&known, mass_only),
    )?;
    let (invariants, invariants_ok) =
        invariants(cx, g, &ir.invariants, &z_index, reduction.invariants);
    ok &= invariants_ok;
    // Run-time unknowns: the linear blocks', then the Newton block's.
    let newton_block_index = solved.blocks.len();
    let mut block_unknowns: Vec<(SymbolId, usize, usize)> = all
        .iter()
        .enumerate()
        .filter_map(|(j, &s)| solved.block_of[j].map(|(b, r)| (s, b, r)))
        .collect();
    if let Some(b) = &newton {
        for (k, &s) in b.unknowns.iter().enumerate() {
            block_unknowns.push((s, newton_block_index, k));
        }
    }
    let sorted_symbols: Vec<SymbolId> =
        z_symbols.iter().copied().chain(left.kept_algebraics.iter().map(|a| a.symbol)).collect();
    let structure = structure_report(
        &sorted,
        &sorted_symbols,
        (&solved, &z_index),
        newton.as_ref(),
        mass_only,
        left.aliases.removed.clone(),
    );
    ok.then_some(FirstOrder {
        structure,
        slots,
        derivatives,
        blocks: solved.blocks,
        outputs,
        events,
        initial,
        actions,
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
        mass_only,
        newton,
    })
}

/// How each block of the sorting ended up solved, blocks that share a
/// run-time solve (the Newton block, one LU) reported once, where the
/// first of them stands in the causal order.
fn structure_report(
    sorted: &crate::dae::sorting::Sorted,
    symbols: &[SymbolId],
    (solved, all_index): (&crate::dae::solve_unknowns::Solved, &FxHashMap<SymbolId, usize>),
    newton: Option<&crate::dae::system::NewtonBlock>,
    mass_only: bool,
    aliases: Vec<(SymbolId, Id)>,
) -> crate::dae::system::StructureInfo {
    use crate::dae::sorting::SortedSolution;
    use crate::dae::system::{BlockInfo, BlockSolution};
    let mut report = crate::dae::system::StructureInfo { aliases, ..Default::default() };
    // Where each shared solve's report is, by its key.
    let mut shared: FxHashMap<(u8, usize), usize> = FxHashMap::default();
    for block in &sorted.blocks {
        let unknowns: Vec<SymbolId> = block.unknowns.iter().map(|&j| symbols[j]).collect();
        if block.solution == SortedSolution::Explicit {
            report.one_at_a_time.push(unknowns[0]);
            continue;
        }
        let run_time_block = unknowns
            .iter()
            .find_map(|s| all_index.get(s).and_then(|&j| solved.block_of[j]).map(|(b, _)| b));
        let (key, solution) = if mass_only {
            ((0, 0), BlockSolution::MassMatrix)
        } else if let Some(b) = newton.filter(|b| unknowns.iter().any(|s| b.determines(s))) {
            let c = newton_part(b, &unknowns);
            (
                (1, c),
                BlockSolution::Newton { tearing: b.components.get(c).map_or(0, |p| p.0.len()) },
            )
        } else if let Some(b) = run_time_block {
            ((2, b), BlockSolution::Linear { lu: solved.blocks[b].unknowns.len() })
        } else if unknowns.len() == 1 {
            // Solved symbolically after a block it reads.
            report.one_at_a_time.push(unknowns[0]);
            continue;
        } else {
            report.blocks.push(BlockInfo { unknowns, solution: BlockSolution::Symbolic });
            continue;
        };
        match shared.get(&key) {
            Some(&k) => report.blocks[k].unknowns.extend(unknowns),
            None => {
                shared.insert(key, report.blocks.len());
                report.blocks.push(BlockInfo { unknowns, solution });
            }
        }
    }
    report
}

/// The part of the Newton block that solves `unknowns`: the part of the
/// first of them it iterates on, else of the first tearing variable a
/// computed one reads.
fn newton_part(b: &crate::dae::system::NewtonBlock, unknowns: &[SymbolId]) -> usize {
    let part_of = |s: &SymbolId| {
        let k = b.unknowns.iter().position(|u| u == s)?;
        b.components.iter().position(|(variables, _)| variables.contains(&k))
    };
    unknowns.iter().find_map(part_of).unwrap_or(0)
}

/// The structural check of the equations as index reduction left them,
/// over every highest derivative and algebraic variable.
fn check_structure(
    cx: &mut Ctxt,
    g: &Graph,
    (states, algebraics): (&[StateDecl], &[AlgebraicDecl]),
    z: &[SymbolId],
    reduction: &crate::dae::index_reduction::IndexReduction,
    (texts, origins): (&[String], &[TokenStream]),
) -> bool {
    let unknowns = sorting_unknowns(states, algebraics, z);
    let problem = crate::dae::sorting::Problem {
        residuals: &reduction.residuals,
        gone: &vec![false; reduction.residuals.len()],
        texts,
        origins,
        unknowns: &unknowns,
    };
    crate::dae::sorting::check(cx, g, &problem)
}

/// The unknowns of the sorting: the highest derivatives, then the
/// algebraic variables, each with its declaration.
fn sorting_unknowns(
    states: &[StateDecl],
    algebraics: &[AlgebraicDecl],
    z: &[SymbolId],
) -> Vec<crate::dae::sorting::Unknown> {
    use crate::dae::sorting::Unknown;
    let mut unknowns: Vec<Unknown> = states
        .iter()
        .zip(z)
        .map(|(s, &symbol)| Unknown { symbol, origin: s.origin.clone(), derivative: true })
        .collect();
    unknowns.extend(algebraics.iter().map(|a| Unknown {
        symbol: a.symbol,
        origin: a.origin.clone(),
        derivative: false,
    }));
    unknowns
}

/// The sorting of the equations left after the aliases, over the highest
/// derivatives and the algebraic variables kept.
fn sort(
    cx: &mut Ctxt,
    g: &mut Graph,
    (states, algebraics): (&[StateDecl], &[AlgebraicDecl]),
    z: &[SymbolId],
    aliases: &crate::dae::alias::Aliases,
    (texts, origins): (&[String], &[TokenStream]),
) -> Option<crate::dae::sorting::Sorted> {
    let unknowns = sorting_unknowns(states, algebraics, z);
    let problem = crate::dae::sorting::Problem {
        residuals: &aliases.residuals,
        gone: &aliases.alias_equations,
        texts,
        origins,
        unknowns: &unknowns,
    };
    crate::dae::sorting::sort(cx, g, &problem)
}

/// Each equation left to the linear solve (not solved by the sorting, not
/// the Newton block's) with the unknowns it involves.
fn equations_in_unknowns(
    g: &Graph,
    written: &[crate::front::ir::Equation],
    residuals: &[Id],
    done: &dyn Fn(usize) -> bool,
    z_index: &FxHashMap<SymbolId, usize>,
) -> Vec<Equation> {
    let mut equations = Vec::with_capacity(residuals.len());
    for (e, (eq, &r)) in written.iter().zip(residuals).enumerate() {
        if done(e) {
            continue;
        }
        let unknowns: Vec<usize> =
            g.free_symbols(r).into_iter().filter_map(|s| z_index.get(&s).copied()).collect();
        equations.push(Equation { residual: r, unknowns, origin: eq.origin.clone(), index: e });
    }
    equations
}

/// The sorting's matching restricted to the linear solve: `owner[k]` is
/// the position in `equations` of the equation matched to `rest[k]`.
fn local_owner(
    sorted: &crate::dae::sorting::Sorted,
    equations: &[Equation],
    rest: &[SymbolId],
    all_index: &FxHashMap<SymbolId, usize>,
) -> Vec<usize> {
    let position: FxHashMap<usize, usize> =
        equations.iter().enumerate().map(|(k, eq)| (eq.index, k)).collect();
    rest.iter().map(|s| position.get(&sorted.owner[all_index[s]]).copied().unwrap_or(0)).collect()
}

/// The linear solve's result over the unknowns `rest` (indices into
/// `all`), with the sorting's explicit solutions for the others: those
/// that read an unknown the linear solve left to run time are evaluated
/// after it, with what it solved symbolically substituted.
fn with_explicit(
    g: &mut Graph,
    local: crate::dae::solve_unknowns::Solved,
    (rest, all): (&[usize], &[SymbolId]),
    (explicit, computed): (&FxHashMap<SymbolId, Id>, &FxHashMap<SymbolId, Id>),
) -> Option<crate::dae::solve_unknowns::Solved> {
    let n = all.len();
    let mut solved = crate::dae::solve_unknowns::Solved {
        symbolic: vec![None; n],
        block_of: vec![None; n],
        blocks: local.blocks,
        after_solve: vec![None; n],
    };
    // What the linear solve and the Newton block determined, symbolically.
    let mut replace: FxHashMap<SymbolId, Id> = computed.clone();
    for (k, &j) in rest.iter().enumerate() {
        solved.symbolic[j] = local.symbolic[k];
        solved.block_of[j] = local.block_of[k];
        solved.after_solve[j] = local.after_solve[k];
        if let Some(v) = local.symbolic[k].or(local.after_solve[k]) {
            replace.insert(all[j], v);
        }
    }
    // The Newton block is solved first, before every expression that reads
    // it; a linear block's unknowns are known only after its solve.
    let rest_symbols: FxHashMap<SymbolId, ()> = rest.iter().map(|&j| (all[j], ())).collect();
    let at_run_time = |s: &SymbolId| rest_symbols.contains_key(s);
    for (j, s) in all.iter().enumerate() {
        let Some(&value) = explicit.get(s) else { continue };
        let reads_run_time =
            g.free_symbols(value).iter().any(|x| replace.contains_key(x) || at_run_time(x));
        if !reads_run_time {
            solved.symbolic[j] = Some(value);
            continue;
        }
        let value = g.substitute(value, &replace).ok()?;
        match g.free_symbols(value).iter().any(at_run_time) {
            true => solved.after_solve[j] = Some(value),
            false => solved.symbolic[j] = Some(value),
        }
    }
    Some(solved)
}

/// Every unknown solved symbolically (or by the sorting, in terms of the
/// run-time unknowns), by its symbol, each variable the
/// Newton block computes from its tearing variables, and each alias with
/// its variable's value in those terms: what outputs, events and the
/// algebraic variables read in place of the unknowns.
fn known_values(
    g: &mut Graph,
    all: &[SymbolId],
    solved: &crate::dae::solve_unknowns::Solved,
    (computed, removed): (&FxHashMap<SymbolId, Id>, &FxHashMap<SymbolId, Id>),
) -> Option<FxHashMap<SymbolId, Id>> {
    // The values evaluated after a run-time solve too: an output, an
    // algebraic variable or an alias may read them (the blocks are solved
    // first); an event may not, and still reads the solve's unknowns then.
    let value = |j: usize| solved.symbolic[j].or(solved.after_solve[j]);
    let mut known: FxHashMap<SymbolId, Id> =
        all.iter().enumerate().filter_map(|(j, &s)| value(j).map(|v| (s, v))).collect();
    known.extend(computed.iter().map(|(&s, &v)| (s, v)));
    let mut aliases: Vec<(SymbolId, Id)> = removed.iter().map(|(&s, &v)| (s, v)).collect();
    aliases.sort_unstable();
    for &(s, v) in &aliases {
        let v = g.substitute(v, &known).ok()?;
        known.insert(s, v);
    }
    // An alias of an alias met later in that order still reads it: those
    // substituted again, until none does (the aliases form a forest, so
    // as many rounds as the longest chain).
    for _ in 0..aliases.len() {
        let pending: Vec<SymbolId> = aliases
            .iter()
            .map(|&(s, _)| s)
            .filter(|s| g.free_symbols(known[s]).iter().any(|x| removed.contains_key(x)))
            .collect();
        if pending.is_empty() {
            break;
        }
        for s in pending {
            let v = g.substitute(known[&s], &known).ok()?;
            known.insert(s, v);
        }
    }
    Some(known)
}

/// The outputs and event functions with the highest derivatives replaced
/// by their solutions; an output may solve the blocks and the Newton
/// block it reads, an event the linear blocks (a piecewise-linear
/// diode's curve parameter in a bridge), and an event that reads a Newton
/// block's unknown is an error (`false`).
fn observables(
    cx: &mut Ctxt,
    g: &mut Graph,
    (declared_outputs, declared_events): (&[crate::front::ir::Output], &[crate::front::ir::Event]),
    replace: &FxHashMap<SymbolId, Id>,
    z_index: &FxHashMap<SymbolId, usize>,
    newton: Option<&crate::dae::system::NewtonBlock>,
) -> Option<(Vec<Id>, Vec<Id>, bool)> {
    let in_newton = |s: &SymbolId| newton.is_some_and(|b| b.determines(s));
    let mut ok = true;
    let mut observe = |value: Id, origin: &TokenStream, what: &str| -> Option<Id> {
        let v = g.substitute(value, replace).ok()?;
        if what == "output" {
            // Outputs may solve the blocks they read (λ of a mechanism).
            return Some(v);
        }
        let run_time = |s: &SymbolId| match what {
            "event" => in_newton(s),
            _ => z_index.contains_key(s) || in_newton(s),
        };
        if let Some(s) = g.free_symbols(v).into_iter().find(run_time) {
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

/// The initial equations' residuals with the highest derivatives and the
/// algebraic variables replaced by their solutions; one that reads an
/// unknown solved at run time is an error (`false`).
fn initial_residuals(
    cx: &mut Ctxt,
    g: &mut Graph,
    equations: &[crate::front::ir::InitialEquation],
    replace: &FxHashMap<SymbolId, Id>,
    z_index: &FxHashMap<SymbolId, usize>,
    newton: Option<&crate::dae::system::NewtonBlock>,
) -> Option<(Vec<Id>, bool)> {
    let mut ok = true;
    let mut residuals = Vec::with_capacity(equations.len());
    for e in equations {
        let r = g.sub(e.lhs, e.rhs).ok()?;
        let r = g.substitute(r, replace).ok()?;
        let solved_at_run_time =
            |s: &SymbolId| z_index.contains_key(s) || newton.is_some_and(|b| b.determines(s));
        if let Some(s) = g.free_symbols(r).into_iter().find(solved_at_run_time) {
            let name = g.symbol(s).name.clone();
            cx.error_at(&e.origin, format!("this initial equation reads `{name}`, which is only known after a numerical solve; write it in the states instead"));
            ok = false;
        }
        residuals.push(r);
    }
    Some((residuals, ok))
}

/// The unknowns at a point: the highest derivatives (the first `states`),
/// then the algebraic variables solved linearly.
struct Unknowns<'a> {
    z: &'a [SymbolId],
    index: &'a FxHashMap<SymbolId, usize>,
    states: usize,
}

/// Algebraic equations nonlinear in their algebraic variables: a Newton
/// block, its variables known to the rest of the reduction (`Some(None)`:
/// there is none; `None`: an error was reported). It is looked for among
/// the equations the sorting left, with its solutions substituted.
#[allow(clippy::too_many_arguments)]
fn newton_block(
    cx: &mut Ctxt,
    g: &mut Graph,
    algebraics: &[AlgebraicDecl],
    sorted: &crate::dae::sorting::Sorted,
    reduction: &crate::dae::index_reduction::IndexReduction,
    z: &[SymbolId],
    texts: &[String],
    origins: &[TokenStream],
) -> Option<Option<crate::dae::system::NewtonBlock>> {
    let candidates: Vec<(SymbolId, String, Id)> = algebraics
        .iter()
        .filter(|a| !sorted.explicit.contains_key(&a.symbol))
        .map(|a| (a.symbol, a.name.clone(), a.init))
        .collect();
    let found = crate::dae::newton_block::find(
        g,
        &crate::dae::newton_block::Candidates {
            residuals: &sorted.residuals,
            differentiations: &reduction.differentiations,
            highest: z,
            algebraics: &candidates,
            texts,
        },
    );
    match found {
        Ok(Some(newton))
            if newton.components.iter().any(|(v, _)| v.len() > NEWTON_VARIABLES_MAX) =>
        {
            let k = newton.components.iter().map(|(v, _)| v.len()).max().unwrap_or(0);
            let n = newton.equations.len();
            cx.error_at(
                &origins[newton.equations[0]],
                format!("this equation is one of the model's {n} nonlinear algebraic equations, which tearing leaves coupled through {k} variables; Newton solves at most {NEWTON_VARIABLES_MAX} at once (its Jacobian lives on the stack): make some of them linear in a variable of their own, or their variables states"),
            );
            None
        }
        Ok(newton) => Some(newton),
        Err(e) => {
            cx.error_at(&origins[0], e);
            None
        }
    }
}

/// Most variables one part of the Newton block iterates on: its dense
/// Jacobian and the
/// copies the iteration makes live on the stack (320 KB each at 200), of
/// which a rayon worker has 2 MB.
const NEWTON_VARIABLES_MAX: usize = 200;

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
                    format!("this equation is nonlinear in the algebraic variable `{name}` and is solved together with a highest derivative: Newton solves nonlinear blocks of algebraic equations only; determine `{name}` by equations without derivatives, or solve this one for it by hand")
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

/// Each algebraic variable in declaration order: from the sorting or the
/// linear solve, from its alias, or from the Newton block (read as block
/// `solved.blocks.len()`).
fn algebraic_values(
    g: &mut Graph,
    declared: &[AlgebraicDecl],
    unknowns: &Unknowns,
    solved: &crate::dae::solve_unknowns::Solved,
    newton: Option<&crate::dae::system::NewtonBlock>,
    (known, mass_only): (&FxHashMap<SymbolId, Id>, bool),
) -> Option<Vec<AlgebraicValue>> {
    let newton_block_index = solved.blocks.len();
    let mut algebraics = Vec::with_capacity(declared.len());
    for a in declared {
        if let Some(k) = newton.and_then(|b| b.unknowns.iter().position(|&s| s == a.symbol)) {
            algebraics.push(SlotDerivative::Block { block: newton_block_index, row: k });
            continue;
        }
        let Some(&j) = unknowns.index.get(&a.symbol) else {
            // An alias: its variable's value.
            algebraics.push(SlotDerivative::Explicit(*known.get(&a.symbol)?));
            continue;
        };
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
