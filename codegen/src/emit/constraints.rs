//! The constraint methods of a DAE model (`CONSTRAINTS`, `PROJECTION`,
//! `constraints`, `constraint_jacobian`), from the invariants and the
//! projection levels that `dae::constraints` found.

use crate::dae::system::{FirstOrder, ProjectionLevel};
use crate::{Graph, Id, SymbolId};
use proc_macro2::{Literal, TokenStream};
use quote::quote;

/// Emits straight-line code for expressions, handing each value to `assign`.
pub type Emit<'a> =
    &'a dyn Fn(&mut Graph, &[Id], &dyn Fn(usize, TokenStream) -> TokenStream) -> TokenStream;

/// `CONSTRAINTS`, `PROJECTION`, `constraints` and `constraint_jacobian`;
/// nothing for a model without constraints.
pub fn constraint_methods(
    g: &mut Graph,
    emit: Emit<'_>,
    slot_symbols: &[SymbolId],
    sys: &FirstOrder,
    levels: &[ProjectionLevel],
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
    // Positions (slots whose derivative is another slot, their rate) that
    // no level corrects: free coordinates, which the rank of Φ_q does not
    // count.
    let in_levels: std::collections::BTreeSet<usize> =
        levels.iter().flat_map(|l| l.slots.iter().copied()).collect();
    let unconstrained = (0..sys.slots.len())
        .filter(|&i| !in_levels.contains(&i))
        .filter(|&i| match sys.derivatives.get(i) {
            Some(crate::dae::system::SlotDerivative::Explicit(e)) => {
                g.as_symbol(*e).is_some_and(|s| slot_symbols.contains(&s))
            }
            _ => false,
        })
        .count();
    let unconstrained = match unconstrained {
        0 => TokenStream::new(),
        k => {
            let k = index(k);
            quote!(const UNCONSTRAINED_COORDINATES: usize = #k;)
        }
    };
    let fixed = sys.slots.iter().enumerate().filter(|(_, s)| s.fixed).map(|(i, _)| index(i));
    Ok(quote! {
        const FIXED_STATES: &'static [usize] = &[#(#fixed),*];
        const CONSTRAINTS: &'static [::daegen::ConstraintInfo] = &[#(#infos),*];
        const PROJECTION: &'static [::daegen::ProjectionLevel] = &[#(#level_infos),*];
        #unconstrained

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
