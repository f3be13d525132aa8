//! Forward sensitivities as a first-order system of their own: the model's
//! states y, then for each quantity w asked for (a parameter p, or an
//! initial value y_k(t0)) the columns S_w = ∂y/∂w, with
//! S_w′ = (∂f/∂y)·S_w + ∂f/∂w and S_w(t0) = ∂y(t0)/∂w (the first
//! variational equations, Hairer–Nørsett–Wanner I, §I.14). The products
//! are built symbolically from the Jacobian's non-zeros, so they share
//! their subexpressions with the right-hand side when emitted, and every
//! method integrates the result as it integrates any model.

use crate::dae::system::Invariant;
use crate::dae::system::ProjectionLevel;
use crate::dae::system::{FirstOrder, Slot, SlotDerivative};
use crate::front::ctxt::Ctxt;
use crate::front::ir::ModelIr;
use crate::{Graph, Id, SymbolId};

/// What a sensitivity is taken with respect to.
#[derive(Clone, Debug)]
pub enum Wrt {
    /// A parameter: its symbol and name.
    Parameter(SymbolId, String),
    /// The initial value of a state: its slot and name.
    Initial(usize, String),
}

impl Wrt {
    /// `k` or `init(x)`, as the attribute writes it and
    /// `Solution::sensitivity` asks for it.
    pub fn name(&self) -> String {
        match self {
            Wrt::Parameter(_, name) => name.clone(),
            Wrt::Initial(_, name) => format!("init({name})"),
        }
    }
}

/// The attribute's `[k, init(x)]` against the model's parameters and
/// states; each entry that names neither is an error on its tokens.
pub fn resolve(cx: &mut Ctxt, written: &[syn::Expr], ir: &ModelIr, sys: &FirstOrder) -> Vec<Wrt> {
    let params: Vec<String> = ir.params.iter().map(|p| p.ident.to_string()).collect();
    let states: Vec<&str> = sys.slots.iter().map(|s| s.name.as_str()).collect();
    let mut out = Vec::new();
    for e in written {
        match e {
            syn::Expr::Path(p) if p.path.get_ident().is_some() => {
                let name = p.path.segments[0].ident.to_string();
                match ir.graph.symbol_named(&name) {
                    Some(s) if params.contains(&name) => out.push(Wrt::Parameter(s, name)),
                    _ if states.contains(&name.as_str()) => cx.error_at(
                        e,
                        format!("`{name}` is a state: write `init({name})` for the sensitivities to its initial value"),
                    ),
                    _ => cx.error_at(
                        e,
                        format!("`{name}` is not a parameter of this model (its parameters: {})", list(&params)),
                    ),
                }
            }
            syn::Expr::Call(c)
                if matches!(&*c.func, syn::Expr::Path(f) if f.path.is_ident("init"))
                    && c.args.len() == 1 =>
            {
                let arg = &c.args[0];
                let name = quote::ToTokens::to_token_stream(arg).to_string().replace(' ', "");
                match states.iter().position(|s| *s == name) {
                    Some(k) => out.push(Wrt::Initial(k, name)),
                    None => cx.error_at(
                        arg,
                        format!(
                            "`{name}` is not a state of this model (its states: {})",
                            list(&states)
                        ),
                    ),
                }
            }
            _ => cx.error_at(e, "write a parameter (`k`) or a state's initial value (`init(x)`)"),
        }
    }
    out
}

fn list<S: AsRef<str>>(names: &[S]) -> String {
    if names.is_empty() {
        return "none".into();
    }
    names.iter().map(|n| format!("`{}`", n.as_ref())).collect::<Vec<_>>().join(", ")
}

/// The name of the state ∂y/∂w: `d(x)/d(k)`, `d(x)/d(init(x))`.
pub fn sensitivity_name(state: &str, wrt: &str) -> String {
    format!("d({state})/d({wrt})")
}

const ACROSS_JUMPS: &str = "sensitivities across the jumps of events and clocks are not generated (they need the jump of the sensitivities at each event time, the saltation matrix): difference two runs, or compute sensitivities of a model without actions";
const UNSUPPORTED: &str = "sensitivities are generated for models whose derivatives solve symbolically; this one solves a linear or nonlinear system at run time (a mechanism's KKT system, an algebraic loop), whose sensitivities are not generated: write the model in independent coordinates (a pendulum in its angle), or difference two runs";

/// Why `sys` cannot have sensitivities generated, or `None`: its
/// derivatives must be explicit in the states (no system solved at run
/// time).
pub fn unsupported(sys: &FirstOrder) -> Option<&'static str> {
    if sys.actions.iter().any(|a| !a.is_empty()) {
        return Some(ACROSS_JUMPS);
    }
    let explicit = sys.derivatives.iter().all(|d| matches!(d, SlotDerivative::Explicit(_)));
    let solved = explicit && sys.blocks.is_empty() && sys.newton.is_none() && !sys.mass_only;
    (!solved).then_some(UNSUPPORTED)
}

/// `sys` with the sensitivities with respect to `wrt` appended as states,
/// in the order `wrt` lists them, each column in the order of the states.
///
/// A DAE reduced to an explicit index-1 form keeps its constraints by
/// projection; its sensitivities must keep theirs too. Differentiating an
/// invariant Φ(t, y, p) = 0 along a column gives the linear invariant
/// Φ_y·S_w + Φ_w = 0 (Φ_w = 0 for an initial value), projected after the
/// model's own levels, level by level on the column's states with the same
/// Jacobian: the minimal-norm correction of S_w, exact in one step (the
/// derivative of the state's projection at the projected state; Hairer,
/// Lubich, Wanner, *Geometric Numerical Integration* §IV.4).
pub fn variational_system(
    g: &mut Graph,
    sys: &FirstOrder,
    wrt: &[Wrt],
) -> Result<FirstOrder, String> {
    let explicit: Option<Vec<Id>> = sys
        .derivatives
        .iter()
        .map(|d| match d {
            SlotDerivative::Explicit(e) => Some(*e),
            _ => None,
        })
        .collect();
    let f = match explicit {
        Some(f) if unsupported(sys).is_none() => f,
        _ => return Err(unsupported(sys).unwrap_or(UNSUPPORTED).into()),
    };
    let n = sys.slots.len();
    let slots: Vec<SymbolId> = sys.slots.iter().map(|s| s.symbol).collect();
    let jacobian = g.jacobian(&f, &slots).map_err(|e| e.to_string())?;
    let mut rows: Vec<Vec<(usize, Id)>> = vec![Vec::new(); n];
    for &(r, c, e) in &jacobian.entries {
        rows[r].push((c, e));
    }
    let slot_of: crate::FxHashMap<SymbolId, usize> =
        slots.iter().enumerate().map(|(i, &s)| (s, i)).collect();
    let levels = crate::dae::constraints::projection_levels(g, sys, &slot_of);
    let mut out = FirstOrder {
        algebraics: sys.algebraics.clone(),
        invariants: sys.invariants.clone(),
        projection: None,
        index: sys.index,
        block_unknowns: Vec::new(),
        residuals: sys.residuals.clone(),
        combined: sys.combined.clone(),
        written: sys.written.clone(),
        rank_conditions: sys.rank_conditions.clone(),
        differentiations: sys.differentiations.clone(),
        highest: sys.highest.clone(),
        algebraic_symbols: sys.algebraic_symbols.clone(),
        mass_only: false,
        newton: None,
        slots: sys.slots.clone(),
        derivatives: sys.derivatives.clone(),
        blocks: Vec::new(),
        outputs: sys.outputs.clone(),
        events: sys.events.clone(),
        initial: sys.initial.clone(),
        actions: sys.actions.clone(),
        structure: sys.structure.clone(),
    };
    let mut projection = levels.clone();
    for (c, w) in wrt.iter().enumerate() {
        let wrt_name = w.name();
        // The column's states first: each derivative reads all of them.
        let mut column = Vec::with_capacity(n);
        for slot in &sys.slots {
            let name = sensitivity_name(&slot.name, &wrt_name);
            let id = g.state(&name).map_err(|e| e.to_string())?;
            column.push((name, id, g.as_symbol(id).ok_or("a state without a symbol")?));
        }
        for (i, slot) in sys.slots.iter().enumerate() {
            // S_i′ = Σ_k ∂f_i/∂y_k · S_k (+ ∂f_i/∂p).
            let mut terms = Vec::with_capacity(rows[i].len() + 1);
            // Each entry ∂f_i/∂y_k is one node, shared by every column
            // (distributing a sum over S_k shares the state–column products
            // between rows instead, but costs a Taylor tape more operations
            // than the convolutions it saves).
            for &(k, entry) in &rows[i] {
                terms.push(g.mul(entry, column[k].1).map_err(|e| e.to_string())?);
            }
            let init = match w {
                Wrt::Parameter(p, _) => {
                    terms.push(g.partial(f[i], *p).map_err(|e| e.to_string())?);
                    g.partial(slot.init, *p).map_err(|e| e.to_string())?
                }
                Wrt::Initial(k, _) => {
                    if *k == i {
                        g.int(1)
                    } else {
                        g.zero()
                    }
                }
            };
            let derivative = g.sum(&terms).map_err(|e| e.to_string())?;
            out.slots.push(Slot {
                name: column[i].0.clone(),
                symbol: column[i].2,
                init,
                // A fixed initial value's sensitivity is its own too.
                fixed: slot.fixed,
                velocity_like: slot.velocity_like,
            });
            out.derivatives.push(SlotDerivative::Explicit(derivative));
        }
        // Φ_y·S_w + Φ_w for each invariant, projected as its level is.
        for invariant in &sys.invariants {
            let mut terms = Vec::new();
            for (k, column_state) in column.iter().enumerate() {
                let d = g.partial(invariant.residual, slots[k]).map_err(|e| e.to_string())?;
                if g.as_number(d).is_none_or(|v| !v.is_zero()) {
                    terms.push(g.mul(d, column_state.1).map_err(|e| e.to_string())?);
                }
            }
            if let Wrt::Parameter(p, _) = w {
                terms.push(g.partial(invariant.residual, *p).map_err(|e| e.to_string())?);
            }
            out.invariants.push(Invariant {
                equation: invariant.equation,
                level: invariant.level,
                residual: g.sum(&terms).map_err(|e| e.to_string())?,
                text: format!("d({})/d({wrt_name})", invariant.text),
            });
        }
        let (m, shift) = (sys.invariants.len(), c + 1);
        for level in &levels {
            projection.push(ProjectionLevel {
                rows: level.rows.iter().map(|r| r + shift * m).collect(),
                slots: level.slots.iter().map(|s| s + shift * n).collect(),
            });
        }
    }
    out.projection = Some(projection);
    Ok(out)
}
