//! Tied states: connections tie the states of different parts by
//! equations linear in them alone (an EMF's shaft angle to the rotor's,
//! two inertias joined rigidly, the two sides of a gear, an inertia to a
//! fixed flange). Each such tie is solved for one of the states, which is
//! replaced, with its derivatives, everywhere: the connected model keeps
//! the states a hand-written one has, instead of a constraint between
//! states that index reduction would differentiate and projection hold.
//! Modelica tools reach the same by index reduction and dummy derivatives
//! (Mattsson & Söderlind 1993); a linear tie with constant coefficients
//! needs neither.
//!
//! A tie is found after alias substitution (`a == ±b`, so the chain
//! `emf.phi == emf.flange.phi == rotor.flange_a.phi == rotor.phi`
//! reads `emf.phi == rotor.phi`), or from two equations that give the
//! same highest derivative from states (`der(phi) == w1` and
//! `der(phi) == w2` tie `w1` and `w2`), or from an over-determined part
//! of the equations that hides a tie behind algebraic variables
//! (`hidden_ties`). Only states declared in components are eliminated;
//! `state(x0).avoid()` marks the one to eliminate, `.prefer()` one to
//! keep, and of two the later declared goes. The eliminated state stays
//! readable by name.

use crate::dae::hidden_ties::{Hidden, Part};
use crate::dae::linear_form::{is_constant, Linear};
use crate::front::ctxt::Ctxt;
use crate::front::ir::{ModelIr, Output};
use crate::{FxHashMap, Graph, Id, SymbolId, SymbolKind};
use proc_macro2::TokenStream;

/// Eliminates every tie among the states of `ir`'s components; what it
/// found, in order.
pub fn eliminate_tied_states(cx: &mut Ctxt, ir: &mut ModelIr) -> Vec<TieFound> {
    match eliminate(ir) {
        Ok((found, conflicts)) => {
            for (at, message) in conflicts {
                cx.error_at(at, message);
            }
            found
        }
        Err(e) => {
            let at = ir.equations.first().map(|e| e.origin.clone());
            match at {
                Some(at) => cx.error_at(at, e),
                None => cx.error_at(&ir.fn_name, e),
            }
            Vec::new()
        }
    }
}

/// A tie the pass found: where, and what it did with it.
#[derive(Clone, Debug, PartialEq)]
pub struct TieFound {
    /// The over-determined part of the equations that hid it, empty for a
    /// tie one equation states.
    pub part: Vec<String>,
    /// The unknowns of that part.
    pub unknowns: Vec<String>,
    /// The equation the tie makes implied by the others (or a constraint).
    pub equation: String,
    /// What became of it.
    pub outcome: TieOutcome,
}

/// What the pass did with a tie.
#[derive(Clone, Debug, PartialEq)]
pub enum TieOutcome {
    /// A state eliminated.
    Eliminated {
        /// The state.
        state: String,
        /// Its value among the states kept.
        value: String,
    },
    /// The equation repeats the others and is dropped.
    Redundant,
    /// The relation among states, not linear: a constraint.
    Constraint {
        /// The relation, `residual = 0`.
        residual: String,
    },
}

impl std::fmt::Display for TieFound {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if !self.part.is_empty() {
            writeln!(f, "over-determined part over {}:", self.unknowns.join(", "))?;
            for e in &self.part {
                writeln!(f, "  {e}")?;
            }
        }
        match &self.outcome {
            TieOutcome::Eliminated { state, value } => {
                write!(f, "`{}` ties {state} = {value}: {state} eliminated", self.equation)
            }
            TieOutcome::Redundant => write!(f, "`{}` repeats the others: dropped", self.equation),
            TieOutcome::Constraint { residual } => {
                write!(f, "`{}` is the constraint {residual} = 0", self.equation)
            }
        }
    }
}

/// A tie that must eliminate a state whose start is fixed (every state of
/// the tie is): the starts conflict, as the run could honour only one.
/// Said where the eliminated state's start was set, naming the others.
fn start_conflict(ir: &ModelIr, state: SymbolId, value: Id) -> Option<(TokenStream, String)> {
    let decl = ir.states.iter().find(|s| s.symbol == state && s.fixed)?;
    let g = &ir.graph;
    let others: Vec<String> = g
        .free_symbols(value)
        .iter()
        .filter_map(|s| ir.states.iter().find(|d| d.symbol == *s && d.fixed))
        .map(|d| format!("`{}`", d.name))
        .collect();
    let at = ir.fixed_starts.iter().find(|(s, _)| *s == state).map(|(_, at)| at.clone());
    let at = at.unwrap_or_else(|| decl.origin.clone());
    Some((
        at,
        format!(
            "the start of `{}` conflicts with the start of {}: the connections tie them (`{}` = {}), so only one can be set; set the start of one",
            decl.name,
            others.join(" and "),
            decl.name,
            g.show(value)
        ),
    ))
}

/// An equation of more operations than this is no tie (a tie is linear in
/// a few states with constant coefficients): a scene's equation of motion,
/// thousands of operations for a robot, is passed by rather than searched
/// again at every tie found.
const TIE_OPERATIONS: usize = 1000;

/// What `eliminate` found, and the start conflicts it met.
type Eliminated = (Vec<TieFound>, Vec<(TokenStream, String)>);

fn eliminate(ir: &mut ModelIr) -> crate::Result<Eliminated> {
    let mut conflicts = Vec::new();
    let mut found = Vec::new();
    let mut gone = vec![false; ir.equations.len()];
    // An equation of one mode ties nothing for good, nor does a large
    // one: the search passes them by, as if gone, and they stay.
    let in_a_mode: Vec<bool> = ir
        .equations
        .iter()
        .map(|e| !e.mode.is_empty() || ir.graph.reachable(&[e.lhs, e.rhs]).len() > TIE_OPERATIONS)
        .collect();
    loop {
        let orders = highest_orders(ir);
        let passed: Vec<bool> = gone.iter().zip(&in_a_mode).map(|(g, m)| *g || *m).collect();
        let residuals = residuals_after_aliases(ir, &passed)?;
        let Some((tie, part)) = find_tie(ir, &residuals, &passed, &orders)? else { break };
        found.push(tie_found(ir, &tie, part));
        match tie {
            Tie::Redundant { equation } => gone[equation] = true,
            Tie::Constraint { equation, residual } => {
                let zero = ir.graph.zero();
                let eq = &mut ir.equations[equation];
                (eq.lhs, eq.rhs, eq.is_constraint) = (residual, zero, true);
                say_why_kept(ir, residual);
            }
            Tie::State { equation, state, value } => {
                gone[equation] = true;
                conflicts.extend(start_conflict(ir, state, value));
                carry_start(ir, state, value)?;
                replace_state(ir, state, value, orders.get(&state).copied().unwrap_or(1))?;
            }
        }
    }
    let mut k = 0;
    ir.equations.retain(|_| {
        k += 1;
        !gone[k - 1]
    });
    Ok((found, conflicts))
}

/// `tie` as the pass reports it, before it is acted on.
fn tie_found(ir: &ModelIr, tie: &Tie, part: Option<Part>) -> TieFound {
    let g = &ir.graph;
    let text = |e: usize| {
        let eq = &ir.equations[e];
        format!("{} == {}", g.show(eq.lhs), g.show(eq.rhs))
    };
    let (part, unknowns) = match part {
        Some(p) => (
            p.equations.iter().map(|&e| text(e)).collect(),
            p.unknowns.iter().map(|&u| g.symbol(u).name.clone()).collect(),
        ),
        None => (Vec::new(), Vec::new()),
    };
    let (equation, outcome) = match *tie {
        Tie::State { equation, state, value } => (
            equation,
            TieOutcome::Eliminated {
                state: g.symbol(state).name.clone(),
                value: g.show(value).to_string(),
            },
        ),
        Tie::Redundant { equation } => (equation, TieOutcome::Redundant),
        Tie::Constraint { equation, residual } => {
            (equation, TieOutcome::Constraint { residual: g.show(residual).to_string() })
        }
    };
    TieFound { part, unknowns, equation: text(equation), outcome }
}

/// What `describe()` says of the states a nonlinear tie `residual = 0`
/// reads: why each is kept, though the connections tie it to the others.
fn say_why_kept(ir: &mut ModelIr, residual: Id) {
    let g = &ir.graph;
    let read: Vec<SymbolId> = g
        .free_symbols(residual)
        .into_iter()
        .filter(|&s| ir.states.iter().any(|d| d.symbol == s))
        .collect();
    let relation = g.show(residual);
    for &state in &read {
        let others: Vec<String> = read
            .iter()
            .filter(|&&s| s != state)
            .map(|&s| format!("`{}`", g.symbol(s).name))
            .collect();
        let with = match others.is_empty() {
            true => String::new(),
            false => format!(" to {}", others.join(", ")),
        };
        let why = format!(
            "Kept: the connections tie it{with} by `{relation} = 0`, which is not linear, so no \
             state is solved for by it; the run holds it as a constraint, projected onto after \
             each step."
        );
        let Some(decl) = ir.states.iter_mut().find(|d| d.symbol == state) else { continue };
        decl.doc = match decl.doc.is_empty() {
            true => why,
            false => format!("{} {why}", decl.doc),
        };
    }
}

/// What `find_tie` found.
enum Tie {
    /// The equation ties `state` to `value`.
    State { equation: usize, state: SymbolId, value: Id },
    /// The equation repeats another.
    Redundant { equation: usize },
    /// The equation, with others, makes a nonlinear relation among the
    /// states: it becomes that constraint.
    Constraint { equation: usize, residual: Id },
}

/// Each equation's residual `lhs − rhs` with the algebraic aliases
/// substituted (zero for an alias equation or a removed one).
fn residuals_after_aliases(ir: &mut ModelIr, gone: &[bool]) -> crate::Result<Vec<Id>> {
    let g = &mut ir.graph;
    let mut residuals = Vec::with_capacity(ir.equations.len());
    for (e, eq) in ir.equations.iter().enumerate() {
        residuals.push(if gone[e] { g.zero() } else { g.sub(eq.lhs, eq.rhs)? });
    }
    let algebraics: Vec<SymbolId> = ir.algebraics.iter().map(|a| a.symbol).collect();
    let differentiations = vec![0; residuals.len()];
    let aliases =
        crate::dae::alias::eliminate_aliases(g, &residuals, &differentiations, &algebraics)?;
    Ok(aliases.residuals)
}

/// The highest derivative each state reaches in the equations (1 for a
/// state whose derivative appears, or none does).
fn highest_orders(ir: &ModelIr) -> FxHashMap<SymbolId, u32> {
    let g = &ir.graph;
    let mut orders: FxHashMap<SymbolId, u32> = ir.states.iter().map(|s| (s.symbol, 1)).collect();
    let roots: Vec<Id> = ir.equations.iter().flat_map(|e| [e.lhs, e.rhs]).collect();
    for n in g.reachable(&roots) {
        if let Some(s) = g.as_symbol(n) {
            if let SymbolKind::Derivative { of, order } = g.symbol(s).kind {
                let k = orders.entry(of).or_insert(1);
                *k = (*k).max(order);
            }
        }
    }
    orders
}

/// What a symbol is to a tie: a state or a derivative below the highest
/// (a value the integrator carries), or a highest derivative.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Role {
    Carried,
    Highest,
    Other,
}

fn role(g: &Graph, s: SymbolId, orders: &FxHashMap<SymbolId, u32>) -> Role {
    match g.symbol(s).kind {
        SymbolKind::State => Role::Carried,
        SymbolKind::Derivative { of, order } => match orders.get(&of) {
            Some(&top) if order < top => Role::Carried,
            Some(_) => Role::Highest,
            None => Role::Other,
        },
        _ => Role::Other,
    }
}

/// The first tie, with the over-determined part that hid it, if one did.
fn find_tie(
    ir: &mut ModelIr,
    residuals: &[Id],
    gone: &[bool],
    orders: &FxHashMap<SymbolId, u32>,
) -> crate::Result<Option<(Tie, Option<Part>)>> {
    // Equations that give a highest derivative `d` from carried values,
    // `c d + Σ a_k y_k + b = 0`, by `d`.
    let mut by_highest: FxHashMap<SymbolId, (Id, Linear)> = FxHashMap::default();
    for (e, &r) in residuals.iter().enumerate() {
        if gone[e] || ir.equations[e].is_constraint || ir.graph.as_number(r).is_some() {
            continue;
        }
        let Some(linear) = Linear::of(&mut ir.graph, r)? else { continue };
        let g = &ir.graph;
        if linear.terms.iter().any(|(y, _)| role(g, *y, orders) == Role::Other) {
            continue;
        }
        let highest: Vec<(SymbolId, Id)> = linear
            .terms
            .iter()
            .copied()
            .filter(|(y, _)| role(g, *y, orders) == Role::Highest)
            .collect();
        match highest.as_slice() {
            [] => {
                if let Some((state, value)) = solve_for_component_state(ir, &linear)? {
                    return Ok(Some((Tie::State { equation: e, state, value }, None)));
                }
            }
            &[(d, c)] if is_constant(g, c) && integrable(ir, &linear, d, orders) => {
                // c s' + Σ a_k y_k' = 0, the y_k carried: c s + Σ a_k y_k
                // keeps its initial value.
                if let Some(tie) = integrated(ir, &linear)? {
                    if let Some((state, value)) = solve_for_component_state(ir, &tie)? {
                        return Ok(Some((Tie::State { equation: e, state, value }, None)));
                    }
                }
            }
            &[(d, c)] if is_constant(g, c) => match by_highest.get(&d) {
                Some((c_first, first)) => {
                    let tie = first.difference(*c_first, &linear, c, &mut ir.graph)?;
                    let g = &ir.graph;
                    let constant_zero = g.as_number(tie.constant).is_some_and(|n| n.is_zero());
                    if tie.terms.is_empty() && constant_zero {
                        return Ok(Some((Tie::Redundant { equation: e }, None)));
                    }
                    if let Some((state, value)) = solve_for_component_state(ir, &tie)? {
                        return Ok(Some((Tie::State { equation: e, state, value }, None)));
                    }
                }
                None => {
                    by_highest.insert(d, (c, linear));
                }
            },
            _ => {}
        }
    }
    // Ties behind algebraic variables: an over-determined part of the
    // equations, its unknowns eliminated.
    let is_unknown = |g: &Graph, s: SymbolId| {
        g.symbol(s).kind == SymbolKind::Algebraic || role(g, s, orders) == Role::Highest
    };
    let Some((hidden, part)) =
        crate::dae::hidden_ties::hidden_tie(ir, residuals, gone, &is_unknown)?
    else {
        return Ok(None);
    };
    let tie = match hidden {
        Hidden::Tie { equation, relation } => solve_for_component_state(ir, &relation)?
            .map(|(state, value)| Tie::State { equation, state, value }),
        Hidden::Redundant { equation } => Some(Tie::Redundant { equation }),
        Hidden::Constraint { equation, residual } => Some(Tie::Constraint { equation, residual }),
    };
    Ok(tie.map(|tie| (tie, Some(part))))
}

/// Whether `c d + Σ a_k y_k' = 0` (`d = s'`, each other term the first
/// derivative of a state, no constant) is the derivative of a tie, each
/// `y_k` and `s` a state with its declared initial value.
fn integrable(
    ir: &ModelIr,
    linear: &Linear,
    d: SymbolId,
    orders: &FxHashMap<SymbolId, u32>,
) -> bool {
    let g = &ir.graph;
    let first_of_state = |y: SymbolId| match g.symbol(y).kind {
        SymbolKind::Derivative { of, order: 1 } => {
            ir.states.iter().any(|s| s.symbol == of).then_some(of)
        }
        _ => None,
    };
    let constant_zero = g.as_number(linear.constant).is_some_and(|n| n.is_zero());
    let Some(s) = first_of_state(d) else { return false };
    constant_zero
        && orders.get(&s) == Some(&1)
        && linear.terms.len() > 1
        && linear.terms.iter().all(|&(y, _)| y == d || first_of_state(y).is_some())
}

/// The tie `c s + Σ a_k y_k − (c s0 + Σ a_k y_k0) = 0` that
/// `c s' + Σ a_k y_k' = 0` integrates to.
fn integrated(ir: &mut ModelIr, linear: &Linear) -> crate::Result<Option<Linear>> {
    let mut terms = Vec::with_capacity(linear.terms.len());
    let mut start = Vec::with_capacity(linear.terms.len());
    for &(y, c) in &linear.terms {
        let SymbolKind::Derivative { of, .. } = ir.graph.symbol(y).kind else { return Ok(None) };
        let Some(init) = ir.states.iter().find(|s| s.symbol == of).map(|s| s.init) else {
            return Ok(None);
        };
        terms.push((of, c));
        start.push(ir.graph.mul(c, init)?);
    }
    let g = &mut ir.graph;
    let total = g.sum(&start)?;
    let constant = g.neg(total)?;
    Ok(Some(Linear { terms, constant }))
}

/// Which state of a tie goes: `.avoid()` and not `.fixed()`, not
/// `.fixed()`, not `.prefer()`, a numeric coefficient, the declaration's
/// position; the largest goes.
type Preference = (bool, bool, bool, bool, usize);

/// The tie `Σ c_k y_k + b = 0` solved for a state of a component (an
/// `.avoid()` one first, never a `.fixed()` or `.prefer()` one while
/// another will do, then one with a numeric coefficient, then the latest
/// declared):
/// `y = −(Σ_{k≠y} c_k y_k + b) / c_y`.
fn solve_for_component_state(
    ir: &mut ModelIr,
    tie: &Linear,
) -> crate::Result<Option<(SymbolId, Id)>> {
    // A joint's flange is a pseudo-instance: the scene's coordinates under
    // its name stay, its integrated angle (`.avoid()`) may go.
    let in_component = |name: &str| {
        ir.instances.iter().any(|i| {
            name.len() > i.path.len() + 1
                && name.starts_with(&i.path)
                && name.as_bytes()[i.path.len()] == b'.'
                && !matches!(i.part.as_str(), "revolute" | "prismatic")
        })
    };
    // A numeric coefficient is best; a parameter's (a gear's ratio) is
    // divided by, as the physics does.
    let mut best: Option<(Preference, SymbolId, Id)> = None;
    // What actions set, and discrete values, stay states: an action needs
    // a slot to write.
    let sets = |target: SymbolId, y: SymbolId| {
        target == y
            || matches!(ir.graph.symbol(target).kind, crate::SymbolKind::Derivative { of, .. } if of == y)
    };
    let acted_on = |y: SymbolId| {
        ir.discretes.contains(&y)
            || ir.events.iter().flat_map(|e| &e.actions).any(|a| sets(a.target, y))
            || ir.clocks.iter().flat_map(|c| &c.actions).any(|a| sets(a.target, y))
    };
    for &(y, c) in &tie.terms {
        if acted_on(y) {
            continue;
        }
        let Some(k) = ir.states.iter().position(|s| s.symbol == y) else { continue };
        let decl = &ir.states[k];
        let numeric = ir.graph.as_number(c).map(|n| !n.is_zero());
        if !(in_component(&decl.name) || decl.avoid) || numeric == Some(false) {
            continue;
        }
        // A `.fixed()` state keeps its start value: it stays.
        let key = (decl.avoid && !decl.fixed, !decl.fixed, !decl.prefer, numeric.is_some(), k);
        if best.as_ref().is_none_or(|(b, _, _)| key > *b) {
            best = Some((key, y, c));
        }
    }
    let Some((_, y, c)) = best else { return Ok(None) };
    let g = &mut ir.graph;
    let minus_one = g.int(-1);
    let scale = g.div(minus_one, c)?;
    let mut terms = Vec::with_capacity(tie.terms.len());
    for &(z, a) in &tie.terms {
        if z != y {
            terms.push((z, g.mul(scale, a)?));
        }
    }
    let constant = g.mul(scale, tie.constant)?;
    let value = Linear { terms, constant }.value(g)?;
    Ok(Some((y, value)))
}

/// Where `state` is tied to a derivative of another, `c der(x) + b`, and
/// nothing sets that derivative's start, the start of `state` becomes
/// its start: a rotor's speed `w0` kept when a sensor that reads
/// `der(der(phi))` makes `der(phi)` the slot its speed ties to.
fn carry_start(ir: &mut ModelIr, state: SymbolId, value: Id) -> crate::Result<()> {
    let Some(linear) = Linear::of(&mut ir.graph, value)? else { return Ok(()) };
    let [(d, c)] = linear.terms[..] else { return Ok(()) };
    let is_derivative = matches!(ir.graph.symbol(d).kind, SymbolKind::Derivative { .. });
    if !is_derivative || ir.inits.iter().any(|i| i.target == d) {
        return Ok(());
    }
    let Some(decl) = ir.states.iter().find(|s| s.symbol == state) else { return Ok(()) };
    let (start, origin) = (decl.init, decl.origin.clone());
    let g = &mut ir.graph;
    let rest = g.sub(start, linear.constant)?;
    let value = g.div(rest, c)?;
    ir.inits.push(crate::front::ir::Init { target: d, value, origin });
    Ok(())
}

/// Replaces `state` (reaching derivative `top`) by `value` and its
/// derivatives everywhere, and keeps it readable as an output.
fn replace_state(ir: &mut ModelIr, state: SymbolId, value: Id, top: u32) -> crate::Result<()> {
    let g = &mut ir.graph;
    let mut replace = FxHashMap::from_iter([(state, value)]);
    let mut current = value;
    for k in 1..=top {
        current = time_derivative_of_linear(g, current, ir.time)?;
        if let Some(d) = g.existing_derivative(state, k) {
            replace.insert(d, current);
        }
    }
    // Every expression of the model at once, so that what they share is
    // rewritten once.
    let mut slots: Vec<&mut Id> = Vec::new();
    for eq in &mut ir.equations {
        slots.push(&mut eq.lhs);
        slots.push(&mut eq.rhs);
    }
    for eq in &mut ir.initial_equations {
        slots.push(&mut eq.lhs);
        slots.push(&mut eq.rhs);
    }
    slots.extend(ir.outputs.iter_mut().map(|o| &mut o.value));
    for e in &mut ir.events {
        slots.push(&mut e.value);
        slots.extend(e.actions.iter_mut().map(|a| &mut a.value));
    }
    for c in &mut ir.clocks {
        slots.extend(c.actions.iter_mut().map(|a| &mut a.value));
    }
    slots.extend(ir.invariants.iter_mut().map(|i| &mut i.value));
    let roots: Vec<Id> = slots.iter().map(|x| **x).collect();
    let replaced = g.substitute_all(&roots, &replace)?;
    for (slot, new) in slots.into_iter().zip(replaced) {
        *slot = new;
    }
    ir.inits.retain(|i| !replace.contains_key(&i.target));
    let Some(k) = ir.states.iter().position(|s| s.symbol == state) else { return Ok(()) };
    let decl = ir.states.remove(k);
    let (name, doc, origin) = (decl.name, decl.doc, decl.origin);
    // What `describe()` says of it: why it is no state.
    let why =
        format!("Not a state: the connections tie it to the states kept, `{}`.", g.show(value));
    let doc = match doc.is_empty() {
        true => why,
        false => format!("{doc} {why}"),
    };
    ir.outputs.push(Output { name, value, doc, origin, declared: false });
    Ok(())
}

/// d/dt of `Σ c_k y_k + b` with constant `c_k`: `Σ c_k y_k' + ∂b/∂t`
/// (`b` a function of the time where a source ties a state).
fn time_derivative_of_linear(g: &mut Graph, v: Id, time: SymbolId) -> crate::Result<Id> {
    if g.free_symbols(v).contains(&time) {
        let Some(linear) = Linear::over_variables(g, v, time)? else {
            return Err(crate::Error::Unsupported {
                message: format!("`{}` ties states nonlinearly", g.show(v)),
            });
        };
        let mut sum = Vec::with_capacity(linear.terms.len() + 1);
        for (y, c) in linear.terms {
            let d = g.derivative(y, 1)?;
            sum.push(g.mul(c, d)?);
        }
        sum.push(g.partial(linear.constant, time)?);
        return g.sum(&sum);
    }
    let Some(linear) = Linear::of(g, v)? else {
        return Err(crate::Error::Unsupported {
            message: format!("`{}` ties states nonlinearly", g.show(v)),
        });
    };
    let mut sum = Vec::with_capacity(linear.terms.len());
    for (y, c) in linear.terms {
        let d = g.derivative(y, 1)?;
        sum.push(g.mul(c, d)?);
    }
    g.sum(&sum)
}
