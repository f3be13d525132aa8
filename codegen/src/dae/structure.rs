//! The model's structure before it is solved: the equations as residuals,
//! each state's order, equations whose highest derivatives cancel combined
//! (`derivative_free`), and the index reduced (`index_reduction`): what
//! `reduce` solves for the highest derivatives and algebraic variables.

use crate::dae::index_reduction::IndexReduction;
use crate::dae::system::RankCondition;
use crate::front::ctxt::Ctxt;
use crate::front::ir::ModelIr;
use crate::{FxHashMap, Graph, Id, SymbolId, SymbolKind};
use proc_macro2::TokenStream;

/// The equations after combination and index reduction, with the unknowns
/// they are to be solved for.
pub struct Structure {
    /// Each state's order: the highest derivative any equation uses.
    pub order: Vec<u32>,
    /// The highest derivatives, one per state.
    pub z_symbols: Vec<SymbolId>,
    /// The algebraic variables.
    pub algebraic_symbols: Vec<SymbolId>,
    /// The residuals, a dependent equation's replaced by its combination.
    pub residuals: Vec<Id>,
    /// The user's equations as residuals, as written.
    pub written: Vec<Id>,
    /// Equations replaced by a combination, each with the ones it combines.
    pub separated_combined: Vec<(usize, Vec<usize>)>,
    /// Pivots of that combination.
    pub rank_conditions: Vec<RankCondition>,
    /// The equations after index reduction.
    pub reduction: IndexReduction,
    /// Each equation as source text.
    pub texts: Vec<String>,
    /// Each equation's tokens, for the errors.
    pub origins: Vec<TokenStream>,
}

/// The structure of the model, or why it has none, its three steps in
/// order ([`equations`], [`separated`], [`index_reduced`], which the
/// pipeline calls by name): every mistake reported on the user's tokens.
pub fn structure(cx: &mut Ctxt, ir: &mut ModelIr) -> Option<Structure> {
    let equations = equations(cx, ir)?;
    let separated = separated(cx, ir, &equations)?;
    index_reduced(cx, ir, equations, separated)
}

/// The equations as residuals over their unknowns, before any is
/// combined or differentiated.
pub struct Equations {
    /// Each equation as a residual `lhs − rhs`.
    pub residuals: Vec<Id>,
    /// Each state's order.
    pub order: Vec<u32>,
    /// The highest derivatives, one per state.
    pub z_symbols: Vec<SymbolId>,
    /// The algebraic variables.
    pub algebraic_symbols: Vec<SymbolId>,
    /// Each equation as source text.
    pub texts: Vec<String>,
    /// Each equation's tokens, for the errors.
    pub origins: Vec<TokenStream>,
}

/// The equations as residuals, each state's order and the unknowns: the
/// highest derivatives and the algebraic variables.
pub fn equations(cx: &mut Ctxt, ir: &mut ModelIr) -> Option<Equations> {
    let (residuals, order) = residuals_and_orders(cx, ir)?;
    let g = &mut ir.graph;
    let mut z_symbols = Vec::with_capacity(ir.states.len() + ir.algebraics.len());
    for (i, s) in ir.states.iter().enumerate() {
        let id = g.derivative(s.symbol, order[i]).ok()?;
        z_symbols.push(g.as_symbol(id)?);
    }
    let algebraic_symbols: Vec<SymbolId> = ir.algebraics.iter().map(|a| a.symbol).collect();
    let origins: Vec<TokenStream> = ir.equations.iter().map(|e| e.origin.clone()).collect();
    let texts: Vec<String> = origins.iter().map(crate::front::names::source_text).collect();
    Some(Equations { residuals, order, z_symbols, algebraic_symbols, texts, origins })
}

/// Equations whose highest derivatives cancel in a combination of others
/// replaced by it (`derivative_free`). Only a square system (as many
/// equations as unknowns) is separated: in another, a repeated or missing
/// equation is the mistake to report.
pub fn separated(
    cx: &mut Ctxt,
    ir: &mut ModelIr,
    equations: &Equations,
) -> Option<crate::dae::derivative_free::Separated> {
    let Equations { residuals, z_symbols, texts, origins, .. } = equations;
    let square = residuals.len() == z_symbols.len() + ir.algebraics.len();
    derivative_free(cx, &mut ir.graph, residuals, z_symbols, texts, origins, square)
}

/// The index reduced: constraints differentiated until every equation
/// involves an unknown (`index_reduction`).
pub fn index_reduced(
    cx: &mut Ctxt,
    ir: &mut ModelIr,
    equations: Equations,
    separated: crate::dae::derivative_free::Separated,
) -> Option<Structure> {
    let Equations { residuals: written, order, z_symbols, algebraic_symbols, texts, origins } =
        equations;
    let residuals = separated.residuals;
    let state_orders: Vec<(SymbolId, u32)> =
        ir.states.iter().zip(&order).map(|(s, &k)| (s.symbol, k)).collect();
    let reduction = crate::dae::index_reduction::reduce_index(
        cx,
        &mut ir.graph,
        &crate::dae::index_reduction::Unknowns {
            time: ir.time,
            states: &state_orders,
            z: &z_symbols,
            algebraics: &algebraic_symbols,
        },
        &residuals,
        &origins,
    )?;
    Some(Structure {
        order,
        z_symbols,
        algebraic_symbols,
        residuals,
        written,
        separated_combined: separated.combined,
        rank_conditions: separated.conditions,
        reduction,
        texts,
        origins,
    })
}

/// The equations as residuals `lhs − rhs`, and each state's order (the
/// highest derivative any equation uses); an algebraic variable no
/// equation reads, or a state without an equation for its derivative, is
/// an error.
fn residuals_and_orders(cx: &mut Ctxt, ir: &mut ModelIr) -> Option<(Vec<Id>, Vec<u32>)> {
    let g = &mut ir.graph;
    let mut order = vec![0u32; ir.states.len()];
    let state_of: FxHashMap<SymbolId, usize> =
        ir.states.iter().enumerate().map(|(i, s)| (s.symbol, i)).collect();
    let mut residuals = Vec::with_capacity(ir.equations.len());
    let mut read: FxHashMap<SymbolId, ()> = FxHashMap::default();
    for eq in &ir.equations {
        let r = match g.sub(eq.lhs, eq.rhs) {
            Ok(r) => r,
            Err(e) => {
                cx.error_at(&eq.origin, e);
                return None;
            }
        };
        for s in g.free_symbols(r) {
            read.insert(s, ());
            if let SymbolKind::Derivative { of, order: k } = g.symbol(s).kind {
                if let Some(&i) = state_of.get(&of) {
                    order[i] = order[i].max(k);
                }
            }
        }
        residuals.push(r);
    }
    let mut ok = true;
    // An algebraic variable no equation reads has nothing to determine it
    // (a constraint force left out of the dynamics).
    for a in &ir.algebraics {
        if !read.contains_key(&a.symbol) {
            let name = &a.name;
            cx.error_at(&a.origin, format!("algebraic variable `{name}` appears in no equation: use it where its constraint acts (a pendulum's `der(u) == -{name} * x;`), or remove it"));
            ok = false;
        }
    }
    for (i, s) in ir.states.iter().enumerate() {
        if order[i] == 0 {
            let name = &s.name;
            cx.error_at(
                &s.origin,
                format!(
                    "state `{name}` has no equation for its derivative: add `der({name}) == ...;`"
                ),
            );
            ok = false;
        }
    }
    ok.then_some((residuals, order))
}

/// Equations whose highest derivatives cancel in a combination become that
/// combination (a circuit's node equations: `0 == f1 + f2`); a dependent
/// equation is an error.
fn derivative_free(
    cx: &mut Ctxt,
    g: &mut Graph,
    residuals: &[Id],
    z: &[SymbolId],
    texts: &[String],
    origins: &[TokenStream],
    square: bool,
) -> Option<crate::dae::derivative_free::Separated> {
    let z_names: Vec<String> = z.iter().map(|&s| g.symbol(s).name.clone()).collect();
    let separated = if !square {
        Ok(crate::dae::derivative_free::Separated {
            residuals: residuals.to_vec(),
            combined: Vec::new(),
            conditions: Vec::new(),
        })
    } else {
        crate::dae::derivative_free::separate(g, residuals, z, texts, &z_names)
    };
    match separated {
        Ok(separated) => Some(separated),
        Err(crate::dae::derivative_free::Failure::Dependent { equation, of }) => {
            let others: Vec<String> = of.iter().map(|&i| format!("`{}`", texts[i])).collect();
            cx.error_at(
                &origins[equation],
                format!(
                    "this equation is a combination of {}: it adds nothing; remove it or state what it was meant to add",
                    others.join(" and ")
                ),
            );
            None
        }
        Err(crate::dae::derivative_free::Failure::Graph(e)) => {
            cx.error_at(&origins[0], e);
            None
        }
    }
}

/// The structure as its tests read it: each state's order, each equation
/// after combination and index reduction with how often it was
/// differentiated, and the invariants index reduction left.
impl std::fmt::Display for crate::expr::display::WithGraph<'_, Structure> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (g, s) = (self.graph, self.value);
        writeln!(f, "index {}", s.reduction.index)?;
        for (&z, order) in s.z_symbols.iter().zip(&s.order) {
            writeln!(f, "unknown {} (order {order})", g.symbol(z).name)?;
        }
        for &a in &s.algebraic_symbols {
            writeln!(f, "unknown {}", g.symbol(a).name)?;
        }
        for (e, (&r, &k)) in
            s.reduction.residuals.iter().zip(&s.reduction.differentiations).enumerate()
        {
            writeln!(f, "equation {e} differentiated {k}: {} = 0", g.show(r))?;
        }
        for (e, of) in &s.separated_combined {
            writeln!(f, "equation {e} combines {of:?}")?;
        }
        for inv in &s.reduction.invariants {
            writeln!(
                f,
                "invariant of {} level {}: {} = 0",
                inv.equation,
                inv.level,
                g.show(inv.residual)
            )?;
        }
        Ok(())
    }
}
