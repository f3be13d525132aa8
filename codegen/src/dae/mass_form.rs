//! The mass-matrix form of a DAE, for RADAU5 with a singular mass matrix:
//! `M w' = F(t, w)` with `w = (y, λ, μ)`, `M = diag(1, …, 1, 0, …, 0)`.
//!
//! For a mechanism (constraints differentiated twice) this is the
//! Gear–Gupta–Leimkuhler index-2 form (Gear, Leimkuhler, Gupta 1985;
//! Hairer & Wanner II §VII.1): `q' = v − Φ_qᵀ μ`, `M v' = f − Φ_qᵀ λ`,
//! `0 = Φ`, `0 = Φ_q v + Φ_t`, where μ vanishes on the solution and keeps
//! the positions on `Φ = 0` without projection. A velocity-level
//! constraint (differentiated once) stays as it is (index 2); an algebraic
//! equation in λ stays as it is (index 1). The differential equations are
//! solved for the highest derivatives with λ known; only when that solve
//! is symbolic is the form emitted.

use crate::dae::system::{FirstOrder, SlotDerivative};
use crate::{FxHashMap, Graph, Id, SymbolId, SymbolKind};

/// The mass-matrix form's components and right-hand side.
pub struct MassForm {
    /// One row per component: slots, then the algebraic rows.
    pub rows: Vec<Id>,
    /// The components: slots, algebraic variables, multipliers μ.
    pub components: Vec<SymbolId>,
    /// Their names.
    pub names: Vec<String>,
    /// Number of differential components (the slots).
    pub differential: usize,
    /// Components that are index-2 variables.
    pub index2: Vec<usize>,
    /// A general mass matrix `(row, column, entry)`, entries of the
    /// parameters; `None`: diagonal, 1 on the differential components.
    pub general: Option<Vec<(usize, usize, Id)>>,
}

/// The mass-matrix form of `sys`, if it has algebraic variables and its
/// differential equations solve symbolically for the highest derivatives.
pub fn mass_form(g: &mut Graph, sys: &FirstOrder) -> crate::Result<Option<MassForm>> {
    if !sys.combined.is_empty() {
        return linearly_implicit(g, sys);
    }
    if sys.algebraic_symbols.is_empty() {
        return Ok(None);
    }
    let z = &sys.highest;
    let z_index: FxHashMap<SymbolId, usize> = z.iter().enumerate().map(|(j, &s)| (s, j)).collect();
    let is_z = |s: &SymbolId| z_index.contains_key(s);
    let mut differential = Vec::new();
    let mut algebraic = Vec::new();
    let mut constraints = Vec::new();
    for (e, &r) in sys.residuals.iter().enumerate() {
        if sys.differentiations[e] > 0 {
            constraints.push(e);
        } else if g.free_symbols(r).iter().any(is_z) {
            differential.push(e);
        } else {
            algebraic.push(e);
        }
    }
    if differential.len() != z.len() {
        return Ok(None);
    }
    // E z = g(t, y, λ), solved with λ known.
    let zero = g.zero();
    let replace_zero: FxHashMap<SymbolId, Id> = z.iter().map(|&s| (s, zero)).collect();
    let mut e_rows = Vec::with_capacity(z.len());
    let mut rhs = Vec::with_capacity(z.len());
    for &e in &differential {
        let r = sys.residuals[e];
        let mut row = Vec::new();
        for (j, s) in highest_in(g, r, &z_index) {
            let c = g.partial(r, s)?;
            if g.free_symbols(c).iter().any(is_z) {
                return Ok(None);
            }
            if c != zero {
                row.push((j, c));
            }
        }
        let r0 = g.substitute(r, &replace_zero)?;
        rhs.push(g.negate_terms(r0)?);
        e_rows.push(row);
    }
    let Some(owner) = perfect_matching(&e_rows, z.len()) else {
        return Ok(None);
    };
    let names: Vec<String> = z.iter().map(|&s| g.symbol(s).name.clone()).collect();
    let Ok(solved) =
        crate::dae::solve_unknowns::solve_unknowns(g, &e_rows, &rhs, &owner, z, &names)
    else {
        return Ok(None);
    };
    if !solved.blocks.is_empty() || solved.after_solve.iter().any(Option::is_some) {
        return Ok(None);
    }
    // Slot rows: the next slot, or the solved highest derivative.
    let mut rows = Vec::new();
    for (slot, derivative) in sys.slots.iter().zip(&sys.derivatives) {
        // A top slot's derivative with λ as a component (not the index-1
        // form's, which eliminated it); a lower slot's is the next slot.
        let row = match (next_of(g, slot.symbol, &z_index), derivative) {
            (Some(j), _) => match solved.symbolic[j] {
                Some(w) => w,
                None => return Ok(None),
            },
            (None, SlotDerivative::Explicit(e)) => *e,
            (None, SlotDerivative::Block { .. } | SlotDerivative::AfterSolve(_)) => {
                return Ok(None)
            }
        };
        rows.push(row);
    }
    let mut components: Vec<SymbolId> = sys.slots.iter().map(|s| s.symbol).collect();
    let mut names: Vec<String> = sys.slots.iter().map(|s| s.name.clone()).collect();
    let differential_count = components.len();
    for &a in &sys.algebraic_symbols {
        components.push(a);
        names.push(g.symbol(a).name.clone());
    }
    // Algebraic rows; a multiplier μ for each position-level constraint.
    let mut algebraic_rows = Vec::new();
    for &e in &constraints {
        let levels: Vec<Id> =
            sys.invariants.iter().filter(|i| i.equation == e).map(|i| i.residual).collect();
        match sys.differentiations[e] {
            1 => algebraic_rows.push(levels[0]),
            2 => {
                let k = names.len() - differential_count - sys.algebraic_symbols.len();
                let name = format!("mu[{k}]");
                let mu = g.add_symbol(&format!("__mu{k}"), SymbolKind::Algebraic)?;
                let mu_symbol = g.as_symbol(mu).unwrap_or(components[0]);
                for (i, slot) in sys.slots.iter().enumerate() {
                    let d = g.partial(levels[0], slot.symbol)?;
                    if d != zero {
                        let t = g.mul(d, mu)?;
                        rows[i] = g.sub(rows[i], t)?;
                    }
                }
                components.push(mu_symbol);
                names.push(name);
                algebraic_rows.push(levels[0]);
                algebraic_rows.push(levels[1]);
            }
            _ => return Ok(None),
        }
    }
    for &e in &algebraic {
        algebraic_rows.push(sys.residuals[e]);
    }
    if differential_count + algebraic_rows.len() != components.len() {
        return Ok(None);
    }
    rows.extend(algebraic_rows);
    let index2 = if constraints.is_empty() {
        Vec::new()
    } else {
        (differential_count..components.len()).collect()
    };
    Ok(Some(MassForm {
        rows,
        components,
        names,
        differential: differential_count,
        index2,
        general: None,
    }))
}

/// The equations as written, `M w' = F(t, w)` with `w` the slots and the
/// algebraic variables and `M` the coefficients of the highest
/// derivatives: a singular matrix of the parameters (a circuit's
/// capacitances between nodes) that RADAU5 takes as it is, as Hairer's
/// RADAU5 does. A lower slot's row is `der^k(x)' = der^(k+1)(x)`. `None`
/// when a coefficient depends on the states or time (RADAU5 needs `M`
/// constant) or the equations do not square with the components.
fn linearly_implicit(g: &mut Graph, sys: &FirstOrder) -> crate::Result<Option<MassForm>> {
    let z = &sys.highest;
    let z_index: FxHashMap<SymbolId, usize> = z.iter().enumerate().map(|(j, &s)| (s, j)).collect();
    let zero = g.zero();
    let one = g.one();
    let mut components: Vec<SymbolId> = sys.slots.iter().map(|s| s.symbol).collect();
    let mut names: Vec<String> = sys.slots.iter().map(|s| s.name.clone()).collect();
    let differential = components.len();
    for &a in &sys.algebraic_symbols {
        components.push(a);
        names.push(g.symbol(a).name.clone());
    }
    // The slot each highest derivative is the derivative of.
    let mut top_slot = vec![usize::MAX; z.len()];
    let mut rows = Vec::new();
    let mut entries = Vec::new();
    for (i, (slot, derivative)) in sys.slots.iter().zip(&sys.derivatives).enumerate() {
        match next_of(g, slot.symbol, &z_index) {
            Some(j) => top_slot[j] = i,
            None => {
                let SlotDerivative::Explicit(next) = derivative else {
                    return Ok(None);
                };
                entries.push((rows.len(), i, one));
                rows.push(*next);
            }
        }
    }
    if top_slot.contains(&usize::MAX) {
        return Ok(None);
    }
    let replace_zero: FxHashMap<SymbolId, Id> = z.iter().map(|&s| (s, zero)).collect();
    for &r in &sys.written {
        let row = rows.len();
        for (j, s) in highest_in(g, r, &z_index) {
            let c = g.partial(r, s)?;
            if c == zero {
                continue;
            }
            let constant = g
                .free_symbols(c)
                .iter()
                .all(|&s| matches!(g.symbol(s).kind, SymbolKind::Parameter));
            if !constant {
                return Ok(None);
            }
            entries.push((row, top_slot[j], c));
        }
        let r0 = g.substitute(r, &replace_zero)?;
        rows.push(g.negate_terms(r0)?);
    }
    if rows.len() != components.len() {
        return Ok(None);
    }
    Ok(Some(MassForm {
        rows,
        components,
        names,
        differential,
        index2: Vec::new(),
        general: Some(entries),
    }))
}

/// The highest derivatives `r` reads, with their positions, in the order
/// of the positions.
fn highest_in(g: &Graph, r: Id, z_index: &FxHashMap<SymbolId, usize>) -> Vec<(usize, SymbolId)> {
    let mut found: Vec<(usize, SymbolId)> =
        g.free_symbols(r).into_iter().filter_map(|s| z_index.get(&s).map(|&j| (j, s))).collect();
    found.sort_unstable();
    found
}

/// The position of the highest derivative that is the derivative of the
/// slot `slot` (`der^(k+1)(x)` of `der^k(x)`), if one is.
fn next_of(g: &Graph, slot: SymbolId, z_index: &FxHashMap<SymbolId, usize>) -> Option<usize> {
    let (of, order) = match g.symbol(slot).kind {
        SymbolKind::Derivative { of, order } => (of, order),
        _ => (slot, 0),
    };
    z_index.get(&g.existing_derivative(of, order + 1)?).copied()
}

/// A perfect matching of rows to columns, as the row of each column.
fn perfect_matching(rows: &[Vec<(usize, Id)>], n: usize) -> Option<Vec<usize>> {
    let columns: Vec<Vec<usize>> =
        rows.iter().map(|r| r.iter().map(|&(c, _)| c).collect()).collect();
    crate::dae::matching::maximum_matching(&columns, n).into_iter().collect()
}

/// The mass-matrix form as its tests read it: each component with its
/// row of `M w' = F(t, w)`.
impl std::fmt::Display for crate::expr::display::WithGraph<'_, MassForm> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (g, form) = (self.graph, self.value);
        for (i, (name, &row)) in form.names.iter().zip(&form.rows).enumerate() {
            let kind = match (i < form.differential, form.index2.contains(&i)) {
                (true, _) => "differential",
                (false, true) => "index 2",
                (false, false) => "algebraic",
            };
            writeln!(f, "{name} ({kind}): {}", g.show(row))?;
        }
        if let Some(general) = &form.general {
            for &(r, c, e) in general {
                writeln!(f, "M[{r}, {c}] = {}", g.show(e))?;
            }
        }
        Ok(())
    }
}
