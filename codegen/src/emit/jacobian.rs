//! `Model::jacobian` and `Model::time_derivative`: the sparse Jacobian
//! ∂f/∂y and ∂f/∂t, symbolic when f is explicit, else left to the
//! runtime's differences.

use crate::emit::layout::{fixed_size_body, index, rolled_program, Layout};
use crate::{Graph, Id, SymbolId};
use proc_macro2::TokenStream;
use quote::quote;

/// `JACOBIAN` with `jacobian` and `time_derivative` where f is explicit
/// and worth it (see [`crate::expr::jacobian::SYMBOLIC_JACOBIAN_ROW`]); nothing
/// otherwise (`Jacobian::Differenced`, the default).
pub(crate) fn jacobian_items(
    g: &mut Graph,
    layout: &Layout,
    slots: &[SymbolId],
    (time, inputs, discrete): (SymbolId, &[(SymbolId, SymbolId)], &[SymbolId]),
    explicit: Option<Vec<Id>>,
) -> crate::Result<TokenStream> {
    let n = slots.len();
    let explicit = explicit.filter(|f| crate::expr::jacobian::symbolic_jacobian_pays(g, f));
    Ok(match explicit {
        Some(f) => {
            let wrt: Vec<SymbolId> = slots.to_vec();
            let mut j = g.jacobian(&f, &wrt)?;
            // A discrete value is constant between the instants where it
            // jumps, and each stretch starts afresh: its column is left out,
            // so no row of a Newton matrix mixes into its own, which then
            // keeps it exactly.
            j.entries.retain(|&(_, c, _)| !discrete.contains(&wrt[c]));
            let nnz = index(j.entries.len());
            let nn = index(n);
            let pattern: Vec<TokenStream> = j
                .entries
                .iter()
                .map(|&(r, c, _)| {
                    let (r, c) = (index(r), index(c));
                    quote!((#r, #c))
                })
                .collect();
            let expressions = j.expressions();
            let entries: Vec<usize> = (0..expressions.len()).collect();
            let values = rolled_program(g, layout, &expressions, ("values", &entries));
            let mut dfdt: Vec<Id> =
                f.iter().map(|&e| g.partial(e, time)).collect::<crate::Result<_>>()?;
            // An input is a function of the time: ∂f/∂t + Σ ∂f/∂u · u'.
            for &(u, rate) in inputs {
                let rate = g.symbol_node(rate);
                for d in dfdt.iter_mut().zip(&f) {
                    let through = g.partial(*d.1, u)?;
                    let through = g.mul(through, rate)?;
                    *d.0 = g.add(*d.0, through)?;
                }
            }
            let components: Vec<usize> = (0..dfdt.len()).collect();
            let time = rolled_program(g, layout, &dfdt, ("dfdt", &components));
            let values = fixed_size_body(&nn, "values", &nnz, values);
            let time = fixed_size_body(&nn, "dfdt", &nn, time);
            quote! {
                const JACOBIAN: ::daegen::Jacobian = ::daegen::Jacobian::Symbolic {
                    pattern: &[#(#pattern),*],
                    time_derivative: true,
                };

                #[inline]
                fn jacobian(&self, t: f64, y: &[f64], values: &mut [f64]) -> ::core::result::Result<(), ::daegen::EvalError> {
                    #values
                }

                #[inline]
                fn time_derivative(&self, t: f64, y: &[f64], dfdt: &mut [f64]) -> ::core::result::Result<(), ::daegen::EvalError> {
                    #time
                }
            }
        }
        None => TokenStream::new(),
    })
}
