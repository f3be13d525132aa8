//! The constraint methods of a DAE model (`CONSTRAINTS`, `PROJECTION`,
//! `constraints`, `constraint_jacobian`), from the invariants and the
//! projection levels that `dae::constraints` found.

use crate::dae::system::{FirstOrder, ProjectionLevel};
use crate::emit::layout::{program_into, straight_program, Layout};
use crate::programs::derivatives::ConstraintPrograms;
use crate::Graph;
use proc_macro2::{Literal, TokenStream};
use quote::quote;

/// `CONSTRAINTS`, `PROJECTION`, `constraints` and `constraint_jacobian`;
/// nothing for a model without constraints.
pub(crate) fn constraint_methods(
    g: &Graph,
    layout: &Layout,
    sys: &FirstOrder,
    levels: &[ProjectionLevel],
    programs: Option<&ConstraintPrograms>,
) -> TokenStream {
    let Some(programs) = programs else { return TokenStream::new() };
    let index = Literal::usize_unsuffixed;
    let n = index(sys.slots.len());
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
    let m = index(sys.invariants.len());
    let values = program_into(g, layout, &programs.residuals, "out");
    let mut arms = Vec::new();
    for (k, (level, (at, program))) in levels.iter().zip(&programs.levels).enumerate() {
        let len = index(level.rows.len() * level.slots.len());
        let code = straight_program(g, layout, program, &|i, v| {
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
    // Positions no level corrects: free coordinates, which the rank of
    // Φ_q does not count.
    let unconstrained = programs.unconstrained;
    let unconstrained = match unconstrained {
        0 => TokenStream::new(),
        k => {
            let k = index(k);
            quote!(const UNCONSTRAINED_COORDINATES: usize = #k;)
        }
    };
    let fixed = sys.slots.iter().enumerate().filter(|(_, s)| s.fixed).map(|(i, _)| index(i));
    quote! {
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
    }
}
