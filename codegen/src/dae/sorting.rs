//! The causal order of the equations: each matched to the unknown it
//! determines (a highest derivative or an algebraic variable), sorted into
//! strongly connected blocks, each after the blocks whose unknowns it
//! reads (block-lower-triangular form, as OpenModelica and ModelingToolkit
//! sort; Duff & Reid 1978), and solved block by block with what the
//! earlier blocks determined. A block of one equation linear in its
//! unknown is solved symbolically here and its solution substituted into
//! every later equation, so an equation may use that unknown in any way
//! (`k4 * y6 * y6 * sqrt(y2)` after `0 == ks * y1 * y4 - y6`). The other
//! blocks (linear systems, nonlinear equations, and whatever reads their
//! unknowns) are left to `reduce`, which solves them symbolically, by a
//! run-time LU or by Newton's method.
//!
//! A system that does not match is reported on the user's tokens with the
//! part of it that is over- or under-determined (Dulmage–Mendelsohn).

use crate::dae::matching;
use crate::front::ctxt::Ctxt;
use crate::{FxHashMap, Graph, Id, SymbolId};
use proc_macro2::TokenStream;

/// What the sorting reads: the equations as residuals and the unknowns,
/// each with what the errors name.
pub struct Problem<'a> {
    /// Each equation's residual (after index reduction and aliases).
    pub residuals: &'a [Id],
    /// Equations already gone (aliases): neither matched nor sorted.
    pub gone: &'a [bool],
    /// Each equation as written, for the messages.
    pub texts: &'a [String],
    /// Each equation's tokens.
    pub origins: &'a [TokenStream],
    /// The unknowns: highest derivatives of the states, then algebraic
    /// variables.
    pub unknowns: &'a [Unknown],
}

/// One unknown and where it was declared.
pub struct Unknown {
    /// Its symbol.
    pub symbol: SymbolId,
    /// Its declaration, for "nothing determines it".
    pub origin: TokenStream,
    /// A highest derivative (its state's declaration is the origin).
    pub derivative: bool,
}

/// How one block of the causal order is solved.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum SortedSolution {
    /// One equation, linear in its unknown: solved symbolically here.
    Explicit,
    /// One equation, linear in its unknown, solved symbolically in terms
    /// of unknowns a block before it leaves to run time (a power `u²/r`
    /// from the node voltages of a linear block): evaluated after that
    /// block's solve.
    ExplicitAfterSolve,
    /// Left to `reduce`: a linear system, a nonlinear equation or system,
    /// or a block that reads such a block's unknowns.
    Deferred,
}

/// One block of the causal order.
#[derive(Clone, Debug)]
pub struct Block {
    /// Its equations (indices into the model's).
    pub equations: Vec<usize>,
    /// The unknowns they determine (indices into `Problem::unknowns`).
    pub unknowns: Vec<usize>,
    /// How it is solved.
    pub solution: SortedSolution,
}

/// The equations in causal order, the explicit blocks solved.
pub struct Sorted {
    /// The blocks, each after the ones whose unknowns it reads.
    pub blocks: Vec<Block>,
    /// The symbolic solution of each unknown of an explicit block: an
    /// expression of the time, the states and the parameters, and for an
    /// `ExplicitAfterSolve` block of the unknowns solved at run time.
    pub explicit: FxHashMap<SymbolId, Id>,
    /// Each equation's residual with the explicit solutions substituted
    /// (an explicit block's own equation is zero: it is solved).
    pub residuals: Vec<Id>,
    /// The equations an explicit block solved.
    pub solved_equations: Vec<bool>,
    /// `owner[j]`: the equation matched to unknown `j`.
    pub owner: Vec<usize>,
}

/// Reports each equation no unknown is left for and each unknown no
/// equation is left for, with the over- or under-determined part of the
/// system it belongs to; `true` when the system matches. Run on the
/// equations as written (before aliases), so the parts name them all.
pub fn check(cx: &mut Ctxt, g: &Graph, problem: &Problem<'_>) -> bool {
    let (live, rows) = incidence(g, problem);
    let owner = matching::maximum_matching(&rows, problem.unknowns.len());
    structural_errors(cx, g, problem, &live, &rows, &owner)
}

/// The equations not gone, and for each (row k is equation `live[k]`) the
/// unknowns it involves.
fn incidence(g: &Graph, problem: &Problem<'_>) -> (Vec<usize>, Vec<Vec<usize>>) {
    let column: FxHashMap<SymbolId, usize> =
        problem.unknowns.iter().enumerate().map(|(j, u)| (u.symbol, j)).collect();
    let live: Vec<usize> = (0..problem.residuals.len()).filter(|&e| !problem.gone[e]).collect();
    let rows: Vec<Vec<usize>> = live
        .iter()
        .map(|&e| {
            g.free_symbols(problem.residuals[e])
                .into_iter()
                .filter_map(|s| column.get(&s).copied())
                .collect()
        })
        .collect();
    (live, rows)
}

/// Matches, sorts and solves the explicit blocks; `None` once a structural
/// error is reported to `cx`.
pub fn sort(cx: &mut Ctxt, g: &mut Graph, problem: &Problem<'_>) -> Option<Sorted> {
    let n = problem.unknowns.len();
    let column: FxHashMap<SymbolId, usize> =
        problem.unknowns.iter().enumerate().map(|(j, u)| (u.symbol, j)).collect();
    let (live, rows) = incidence(g, problem);
    let owner = matching::maximum_matching(&rows, n);
    if !structural_errors(cx, g, problem, &live, &rows, &owner) {
        return None;
    }
    let owner: Vec<usize> = owner.into_iter().map(|r| r.unwrap_or(0)).collect();
    let mut column_of = vec![0; live.len()];
    for (j, &k) in owner.iter().enumerate() {
        column_of[k] = j;
    }
    let successors: Vec<Vec<usize>> = rows
        .iter()
        .enumerate()
        .map(|(k, cols)| cols.iter().map(|&j| owner[j]).filter(|&o| o != k).collect())
        .collect();
    let zero = g.zero();
    let mut residuals = problem.residuals.to_vec();
    let mut explicit: FxHashMap<SymbolId, Id> = FxHashMap::default();
    let mut deferred = vec![false; n];
    let mut blocks = Vec::new();
    let mut solved_equations = vec![false; residuals.len()];
    for component in matching::strongly_connected(&successors) {
        let equations: Vec<usize> = component.iter().map(|&k| live[k]).collect();
        let unknowns: Vec<usize> = component.iter().map(|&k| column_of[k]).collect();
        for &e in &equations {
            if !explicit.is_empty() {
                residuals[e] = g.substitute(residuals[e], &explicit).ok()?;
            }
        }
        let solved = match (&equations[..], &unknowns[..]) {
            ([e], [j]) => solve_linear(g, residuals[*e], problem.unknowns[*j].symbol, &column),
            _ => None,
        };
        let solution = match solved {
            Some(value) => {
                let after = g
                    .free_symbols(value)
                    .iter()
                    .any(|s| column.get(s).is_some_and(|&j| deferred[j]));
                explicit.insert(problem.unknowns[unknowns[0]].symbol, value);
                residuals[equations[0]] = zero;
                solved_equations[equations[0]] = true;
                match after {
                    true => SortedSolution::ExplicitAfterSolve,
                    false => SortedSolution::Explicit,
                }
            }
            None => {
                unknowns.iter().for_each(|&j| deferred[j] = true);
                SortedSolution::Deferred
            }
        };
        blocks.push(Block { equations, unknowns, solution });
    }
    let owner = owner.iter().map(|&k| live[k]).collect();
    Some(Sorted { blocks, explicit, residuals, solved_equations, owner })
}

/// `u` from `r(u) = 0` when `r` is linear in `u` with a coefficient that
/// reads no unknown (else `None`): `u = −r|_{u=0} / (∂r/∂u)`.
fn solve_linear(
    g: &mut Graph,
    r: Id,
    u: SymbolId,
    unknowns: &FxHashMap<SymbolId, usize>,
) -> Option<Id> {
    let c = g.partial(r, u).ok()?;
    if g.as_number(c).is_some_and(|v| v.is_zero())
        || g.free_symbols(c).iter().any(|s| unknowns.contains_key(s))
        || g.reads_switching(c)
    {
        return None;
    }
    let zero = g.zero();
    let r0 = g.substitute(r, &FxHashMap::from_iter([(u, zero)])).ok()?;
    let numerator = g.negate_terms(r0).ok()?;
    g.div(numerator, c).ok()
}

/// Reports each equation no unknown is left for (with the over-determined
/// part it belongs to) and each unknown no equation is left for (with the
/// under-determined part); `true` when there is none.
fn structural_errors(
    cx: &mut Ctxt,
    g: &Graph,
    problem: &Problem<'_>,
    live: &[usize],
    rows: &[Vec<usize>],
    owner: &[Option<usize>],
) -> bool {
    let name = |j: usize| format!("`{}`", g.symbol(problem.unknowns[j].symbol).name);
    let text = |k: usize| format!("`{}`", problem.texts[live[k]]);
    let origin = |k: usize| &problem.origins[live[k]];
    let mut ok = true;
    let mut matched_row = vec![false; rows.len()];
    let mut column_of = vec![None; rows.len()];
    for (j, o) in owner.iter().enumerate() {
        if let Some(k) = *o {
            matched_row[k] = true;
            column_of[k] = Some(j);
        }
    }
    for k in (0..rows.len()).filter(|&k| !matched_row[k]) {
        ok = false;
        let (part_rows, part_columns) = matching::over_determined(k, rows, owner);
        let message = match (&part_rows[..], &part_columns[..]) {
            (_, []) => "this equation determines no unknown: it involves no highest derivative and no algebraic variable, and differentiating it does not help".to_string(),
            ([a, b], [j]) => {
                let other = if *a == k { *b } else { *a };
                cx.error_at(origin(k), format!("{} already has an equation: remove one of the two (or there are more equations than unknowns)", name(*j)));
                cx.error_at(origin(other), format!("the other equation that determines {}", name(*j)));
                continue;
            }
            _ => {
                let texts: Vec<String> = part_rows.iter().map(|&r| text(r)).collect();
                let names: Vec<String> = part_columns.iter().map(|&j| name(j)).collect();
                // Through connections, the part ties states that the index
                // reduction could not free (it is nonlinear in these
                // unknowns): removing a `connect` is not the fix.
                let connected =
                    part_rows.iter().any(|&r| problem.texts[live[r]].starts_with("connect("));
                let fix = match connected {
                    true => "the connections tie the states these equations read in a way the index reduction does not reduce (it is not linear in these unknowns): write that relation among the states as a `constraint(..)` of the model, or check the parts' equations",
                    false => "remove one of them or add an unknown they determine",
                };
                format!(
                    "these {} equations determine only {} unknowns, {}: {}; {fix}",
                    part_rows.len(),
                    part_columns.len(),
                    names.join(", "),
                    texts.join(", ")
                )
            }
        };
        cx.error_at(origin(k), message);
    }
    let mut rows_of_column = vec![Vec::new(); owner.len()];
    for (k, cols) in rows.iter().enumerate() {
        cols.iter().for_each(|&j| rows_of_column[j].push(k));
    }
    for j in (0..owner.len()).filter(|&j| owner[j].is_none()) {
        ok = false;
        let (part_rows, part_columns) = matching::under_determined(j, &rows_of_column, &column_of);
        let unknown = &problem.unknowns[j];
        let who = name(j);
        let message = if part_rows.is_empty() {
            match unknown.derivative {
                true => format!("nothing determines {who}: add `{} == ...;` (there are fewer equations than unknowns)", &who[1..who.len() - 1]),
                false => format!("nothing determines {who}: no equation involves it; add one, or remove the variable"),
            }
        } else {
            let texts: Vec<String> = part_rows.iter().map(|&r| text(r)).collect();
            let names: Vec<String> = part_columns.iter().map(|&c| name(c)).collect();
            format!(
                "nothing determines {who}: {} {} left for {} unknowns, {}; add an equation",
                texts.join(", "),
                if part_rows.len() == 1 { "is" } else { "are" },
                part_columns.len(),
                names.join(", ")
            )
        };
        cx.error_at(&unknown.origin, message);
    }
    ok
}
