//! `Model::jacobian` and `Model::time_derivative`: the sparse Jacobian
//! ∂f/∂y and ∂f/∂t, symbolic when f is explicit, else refused at run time.

use crate::emit::layout::{fixed_size_body, index, rolled_program, Layout};
use crate::{Graph, Id, SymbolId};
use proc_macro2::TokenStream;
use quote::quote;

/// `JACOBIAN_PATTERN` and the bodies of `jacobian` and `time_derivative`.
pub(crate) fn jacobian_items(
    g: &mut Graph,
    layout: &Layout,
    slots: &[SymbolId],
    time: SymbolId,
    explicit: Option<Vec<Id>>,
) -> crate::Result<(TokenStream, TokenStream, TokenStream)> {
    let n = slots.len();
    Ok(match explicit {
        Some(f) => {
            let wrt: Vec<SymbolId> = slots.to_vec();
            let j = g.jacobian(&f, &wrt)?;
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
            let dfdt: Vec<Id> =
                f.iter().map(|&e| g.partial(e, time)).collect::<crate::Result<_>>()?;
            let components: Vec<usize> = (0..dfdt.len()).collect();
            let time = rolled_program(g, layout, &dfdt, ("dfdt", &components));
            (
                quote!(&[#(#pattern),*]),
                fixed_size_body(&nn, "values", &nnz, values),
                fixed_size_body(&nn, "dfdt", &nn, time),
            )
        }
        None => (
            quote!(&[]),
            quote!(::core::result::Result::Err(::daegen::EvalError::JacobianUnavailable)),
            quote!(::core::result::Result::Err(::daegen::EvalError::JacobianUnavailable)),
        ),
    })
}
