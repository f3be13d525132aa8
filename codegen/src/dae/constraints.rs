//! The constraint methods of a DAE model: the invariants that index
//! reduction left (a constraint and its derivatives below the level the
//! integrated system uses), grouped by level for projection, with each
//! level's Jacobian with respect to the states it corrects.
//!
//! Level k corrects the states that its invariants involve and no lower
//! level does: positions for `Φ = 0`, velocities for `Φ_q v + Φ_t = 0`
//! (Hairer–Wanner II §VII.2; Simbody's project-every-step policy), so a
//! correction at one level leaves the levels below it satisfied.

use crate::dae::reduce::FirstOrder;
use crate::{FxHashMap, Graph, Id, SymbolId};
use proc_macro2::{Literal, TokenStream};
use quote::quote;

/// Emits straight-line code for expressions, handing each value to `assign`.
pub type Emit<'a> =
    &'a dyn Fn(&mut Graph, &[Id], &dyn Fn(usize, TokenStream) -> TokenStream) -> TokenStream;

/// One projection level: which invariants and which states.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ProjectionLevel {
    /// Indices into the invariants.
    pub rows: Vec<usize>,
    /// Slot indices the level corrects, ascending.
    pub slots: Vec<usize>,
}

/// Groups the invariants by level and picks the states each level corrects.
pub fn projection_levels(
    g: &Graph,
    sys: &FirstOrder,
    slot_of: &FxHashMap<SymbolId, usize>,
) -> Vec<ProjectionLevel> {
    let deepest = sys.invariants.iter().map(|i| i.level).max();
    let mut levels = Vec::new();
    let mut lower: Vec<usize> = Vec::new();
    for level in 0..=deepest.unwrap_or(0) {
        let rows: Vec<usize> =
            (0..sys.invariants.len()).filter(|&r| sys.invariants[r].level == level).collect();
        if rows.is_empty() {
            continue;
        }
        let mut involved: Vec<usize> = rows
            .iter()
            .flat_map(|&r| g.free_symbols(sys.invariants[r].residual))
            .filter_map(|s| slot_of.get(&s).copied())
            .collect();
        involved.sort_unstable();
        involved.dedup();
        let new: Vec<usize> = involved.iter().copied().filter(|s| !lower.contains(s)).collect();
        lower.extend(&involved);
        // A velocity-level constraint (non-holonomic, A(q) v = 0) corrects
        // the velocities it is linear in, not the positions it reads.
        let velocities: Vec<usize> =
            new.iter().copied().filter(|&s| sys.slots[s].velocity_like).collect();
        let new =
            if !velocities.is_empty() && velocities.len() < new.len() { velocities } else { new };
        match levels.last_mut() {
            // Nothing of its own to correct (the hidden constraints of a
            // linear DAE involve every state): projected jointly with the
            // level below, which a correction of its own would undo.
            Some(below) if new.is_empty() => {
                let below: &mut ProjectionLevel = below;
                below.rows.extend(rows);
                below.slots.extend(&involved);
                below.slots.sort_unstable();
                below.slots.dedup();
            }
            _ => {
                let slots = if new.is_empty() { involved } else { new };
                levels.push(ProjectionLevel { rows, slots });
            }
        }
    }
    levels
}

/// `CONSTRAINTS`, `PROJECTION`, `constraints` and `constraint_jacobian`;
/// nothing for a model without constraints.
pub fn constraint_methods(
    g: &mut Graph,
    emit: Emit<'_>,
    slot_of: &FxHashMap<SymbolId, usize>,
    slot_symbols: &[SymbolId],
    sys: &FirstOrder,
) -> crate::Result<TokenStream> {
    if sys.invariants.is_empty() {
        return Ok(TokenStream::new());
    }
    let index = Literal::usize_unsuffixed;
    let n = index(slot_symbols.len());
    let infos = sys.invariants.iter().map(|inv| {
        let text = &inv.text;
        let level = index(inv.level);
        quote!(::daegen::ConstraintInfo { equation: #text, level: #level })
    });
    let levels = projection_levels(g, sys, slot_of);
    let level_infos = levels.iter().map(|l| {
        let rows = l.rows.iter().map(|&r| index(r));
        let slots = l.slots.iter().map(|&s| index(s));
        quote!(::daegen::ProjectionLevel { rows: &[#(#rows),*], slots: &[#(#slots),*] })
    });
    let residuals: Vec<Id> = sys.invariants.iter().map(|i| i.residual).collect();
    let m = index(residuals.len());
    let values = emit(g, &residuals, &|i, v| {
        let i = index(i);
        quote!(out[#i] = #v;)
    });
    let mut arms = Vec::new();
    for (k, level) in levels.iter().enumerate() {
        let cols = level.slots.len();
        let mut entries = Vec::new();
        let mut at = Vec::new();
        for (r, &row) in level.rows.iter().enumerate() {
            for (c, &slot) in level.slots.iter().enumerate() {
                let d = g.partial(sys.invariants[row].residual, slot_symbols[slot])?;
                if g.as_number(d).is_none_or(|v| !v.is_zero()) {
                    entries.push(d);
                    at.push(r * cols + c);
                }
            }
        }
        let len = index(level.rows.len() * cols);
        let code = emit(g, &entries, &|i, v| {
            let i = index(at[i]);
            quote!(out[#i] = #v;)
        });
        let k = index(k);
        arms.push(quote! {
            #k => {
                let ::core::result::Result::Ok(out) = <&mut [f64; #len]>::try_from(out) else { return };
                *out = [0.0; #len];
                #code
            }
        });
    }
    let fixed = sys.slots.iter().enumerate().filter(|(_, s)| s.fixed).map(|(i, _)| index(i));
    Ok(quote! {
        const FIXED_STATES: &'static [usize] = &[#(#fixed),*];
        const CONSTRAINTS: &'static [::daegen::ConstraintInfo] = &[#(#infos),*];
        const PROJECTION: &'static [::daegen::ProjectionLevel] = &[#(#level_infos),*];

        #[inline]
        fn constraints(&self, t: f64, y: &[f64], out: &mut [f64]) {
            let (::core::result::Result::Ok(y), ::core::result::Result::Ok(out)) =
                (<&[f64; #n]>::try_from(y), <&mut [f64; #m]>::try_from(out)) else { return };
            #values
        }

        #[inline]
        fn constraint_jacobian(&self, level: usize, t: f64, y: &[f64], out: &mut [f64]) {
            let ::core::result::Result::Ok(y) = <&[f64; #n]>::try_from(y) else { return };
            match level {
                #(#arms)*
                _ => {}
            }
        }
    })
}
