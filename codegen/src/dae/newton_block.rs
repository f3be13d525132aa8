//! Algebraic equations nonlinear in their algebraic variables, solved by
//! Newton's method at each evaluation: a reaction rate quadratic in a
//! concentration at quasi-steady state, a diode's exponential in a node
//! voltage. With their values known, the rest of the model is linear in
//! its unknowns and reduces as before, so every method runs the model (an
//! explicit pair solves them at every stage), not only RADAU5 on the
//! mass-matrix form.
//!
//! The block is the smallest set of algebraic variables closed under the
//! derivative-free, undifferentiated equations that involve them, starting
//! from the variables that enter some such equation nonlinearly; it must
//! have as many equations as variables. It is torn: Newton iterates on a
//! few tearing variables, and the others are computed from them, one
//! equation each, in order (`tear`). The Jacobian of the torn residuals
//! with respect to the tearing variables is generated; where it is
//! singular the model is not of index 1 there, and the run says so naming
//! the equations.

use crate::dae::system::NewtonBlock;
use crate::{FxHashMap, Graph, Id, SymbolId};

/// What the finder reads of the reduced model.
pub struct Candidates<'a> {
    /// Each equation's residual after index reduction.
    pub residuals: &'a [Id],
    /// How often each was differentiated.
    pub differentiations: &'a [usize],
    /// The highest derivatives of the states.
    pub highest: &'a [SymbolId],
    /// The algebraic variables, their names and guesses.
    pub algebraics: &'a [(SymbolId, String, Id)],
    /// The equations as written.
    pub texts: &'a [String],
}

/// The Newton block of the model, `None` when no algebraic equation is
/// nonlinear in an algebraic variable, or when the closure does not square
/// (the mass-matrix form then remains the only way).
pub fn find(g: &mut Graph, model: &Candidates<'_>) -> crate::Result<Option<NewtonBlock>> {
    let algebraic_index = |s: SymbolId| model.algebraics.iter().position(|a| a.0 == s);
    // Derivative-free, undifferentiated equations, with their variables.
    let mut algebraic_equations: Vec<(usize, Vec<usize>)> = Vec::new();
    for (e, &r) in model.residuals.iter().enumerate() {
        if model.differentiations[e] > 0 {
            continue;
        }
        let symbols = g.free_symbols(r);
        if symbols.iter().any(|s| model.highest.contains(s)) {
            continue;
        }
        let variables: Vec<usize> = symbols.iter().filter_map(|&s| algebraic_index(s)).collect();
        if !variables.is_empty() {
            algebraic_equations.push((e, variables));
        }
    }
    // The seeds: variables some algebraic equation is nonlinear in.
    let mut in_block = vec![false; model.algebraics.len()];
    for (e, variables) in &algebraic_equations {
        for &a in variables {
            let d = g.partial(model.residuals[*e], model.algebraics[a].0)?;
            let nonlinear = g.free_symbols(d).iter().any(|&s| algebraic_index(s).is_some());
            if nonlinear {
                for &b in variables {
                    in_block[b] = true;
                }
            }
        }
    }
    if !in_block.contains(&true) {
        return Ok(None);
    }
    // Close over the algebraic equations that involve a block variable.
    let mut equations: Vec<usize> = Vec::new();
    loop {
        let mut grew = false;
        for (e, variables) in &algebraic_equations {
            if equations.contains(e) || !variables.iter().any(|&a| in_block[a]) {
                continue;
            }
            equations.push(*e);
            for &a in variables {
                grew |= !in_block[a];
                in_block[a] = true;
            }
        }
        if !grew {
            break;
        }
    }
    equations.sort_unstable();
    let members: Vec<usize> = (0..in_block.len()).filter(|&a| in_block[a]).collect();
    if members.len() != equations.len() {
        return Ok(None);
    }
    let symbols: Vec<SymbolId> = members.iter().map(|&a| model.algebraics[a].0).collect();
    let residuals: Vec<Id> = equations.iter().map(|&e| model.residuals[e]).collect();
    let torn = tear(g, &residuals, &symbols)?;
    let tearing: Vec<SymbolId> = torn.tearing.iter().map(|&k| symbols[k]).collect();
    let components = components(g, &torn.residuals, &tearing);
    Ok(Some(NewtonBlock {
        components,
        unknowns: torn.tearing.iter().map(|&k| symbols[k]).collect(),
        names: torn.tearing.iter().map(|&k| model.algebraics[members[k]].1.clone()).collect(),
        guesses: torn.tearing.iter().map(|&k| model.algebraics[members[k]].2).collect(),
        residuals: torn.residuals,
        computed: torn.computed,
        size: members.len(),
        texts: equations.iter().map(|&e| model.texts[e].clone()).collect(),
        equations,
    }))
}

/// The torn system split into its strongly connected parts in causal
/// order, each `(tearing variables, residuals)` by index: independent
/// cells of a grid are solved one by one, each part with the values of
/// the parts before it. One part when the residuals do not match their
/// variables one to one.
fn components(g: &Graph, residuals: &[Id], tearing: &[SymbolId]) -> Vec<(Vec<usize>, Vec<usize>)> {
    let index: FxHashMap<SymbolId, usize> =
        tearing.iter().enumerate().map(|(k, &s)| (s, k)).collect();
    let rows: Vec<Vec<usize>> = residuals
        .iter()
        .map(|&r| g.free_symbols(r).into_iter().filter_map(|s| index.get(&s).copied()).collect())
        .collect();
    let whole = vec![((0..tearing.len()).collect(), (0..residuals.len()).collect())];
    let owner = crate::dae::matching::maximum_matching(&rows, tearing.len());
    let Some(owner) = owner.into_iter().collect::<Option<Vec<usize>>>() else { return whole };
    let mut variable_of = vec![0; rows.len()];
    for (k, &r) in owner.iter().enumerate() {
        variable_of[r] = k;
    }
    let successors: Vec<Vec<usize>> = rows
        .iter()
        .enumerate()
        .map(|(r, vars)| vars.iter().map(|&k| owner[k]).filter(|&o| o != r).collect())
        .collect();
    crate::dae::matching::strongly_connected(&successors)
        .into_iter()
        .map(|rows| {
            let mut variables: Vec<usize> = rows.iter().map(|&r| variable_of[r]).collect();
            variables.sort_unstable();
            (variables, rows)
        })
        .collect()
}

/// A block torn: the variables Newton iterates on, the others computed
/// from them, and the residuals left in the tearing variables alone.
struct Torn {
    /// The tearing variables (indices into the block's variables).
    tearing: Vec<usize>,
    /// The computed variables in the order computed, each an expression
    /// of the tearing variables, the states and the parameters.
    computed: Vec<(SymbolId, Id)>,
    /// The equations not used to compute a variable, with the computed
    /// variables substituted: as many as tearing variables.
    residuals: Vec<Id>,
}

/// Tears a square block of `residuals` in `variables` with the greedy
/// heuristic of Cellier & Kofman (Continuous System Simulation, 2006,
/// §7.3; after Elmqvist & Otter 1994): while some equation has one
/// variable left that it determines explicitly (linearly, with a
/// coefficient that reads only variables already known: `fx` from
/// `fx * r³ == -x` once `r` is), compute that variable from it; when none
/// has, make the variable that appears in most of the equations left a
/// tearing variable, and go on. Every block squares: each computed
/// variable uses one equation, so the equations left are as many as the
/// tearing variables.
fn tear(g: &mut Graph, residuals: &[Id], variables: &[SymbolId]) -> crate::Result<Torn> {
    let index: FxHashMap<SymbolId, usize> =
        variables.iter().enumerate().map(|(k, &s)| (s, k)).collect();
    let incidence: Vec<Vec<usize>> = residuals
        .iter()
        .map(|&r| g.free_symbols(r).into_iter().filter_map(|s| index.get(&s).copied()).collect())
        .collect();
    let n = variables.len();
    let mut known = vec![false; n];
    let mut used = vec![false; residuals.len()];
    let (mut tearing, mut computed) = (Vec::new(), Vec::new());
    let mut value: FxHashMap<SymbolId, Id> = FxHashMap::default();
    while known.contains(&false) {
        let mut progress = false;
        for (e, vars) in incidence.iter().enumerate() {
            let left: Vec<usize> = vars.iter().copied().filter(|&k| !known[k]).collect();
            let [k] = left[..] else { continue };
            if used[e] {
                continue;
            }
            let r = g.substitute(residuals[e], &value)?;
            let unknown: FxHashMap<SymbolId, usize> = index
                .iter()
                .filter(|&(_, &j)| !known[j] || j == k)
                .map(|(&s, &j)| (s, j))
                .collect();
            let Some(v) = solve_explicitly(g, r, variables[k], &unknown)? else { continue };
            value.insert(variables[k], v);
            computed.push((variables[k], v));
            known[k] = true;
            used[e] = true;
            progress = true;
        }
        if progress {
            continue;
        }
        let appearances = |k: usize| {
            incidence.iter().enumerate().filter(|(e, vars)| !used[*e] && vars.contains(&k)).count()
        };
        let Some(k) = (0..n).filter(|&k| !known[k]).max_by_key(|&k| (appearances(k), n - k)) else {
            break;
        };
        tearing.push(k);
        known[k] = true;
    }
    tearing.sort_unstable();
    let mut left = Vec::new();
    for (e, &r) in residuals.iter().enumerate() {
        if !used[e] {
            left.push(g.substitute(r, &value)?);
        }
    }
    Ok(Torn { tearing, computed, residuals: left })
}

/// `u` from `r = 0` when `r` is linear in `u` with a coefficient that
/// reads none of the block's variables still `unknown` (and is not zero).
fn solve_explicitly(
    g: &mut Graph,
    r: Id,
    u: SymbolId,
    unknown: &FxHashMap<SymbolId, usize>,
) -> crate::Result<Option<Id>> {
    let c = g.partial(r, u)?;
    if g.as_number(c).is_some_and(|v| v.is_zero())
        || g.free_symbols(c).iter().any(|s| unknown.contains_key(s))
    {
        return Ok(None);
    }
    let zero = g.zero();
    let r0 = g.substitute(r, &FxHashMap::from_iter([(u, zero)]))?;
    let numerator = g.negate_terms(r0)?;
    Ok(Some(g.div(numerator, c)?))
}
