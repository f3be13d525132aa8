//! `Model::jacobian` and `Model::time_derivative`: the sparse Jacobian
//! ∂f/∂y and ∂f/∂t, symbolic when f is explicit, else left to the
//! runtime's differences.

use crate::emit::layout::{fixed_size_body, index, rolled_program, Layout};
use crate::programs::derivatives::JacobianPrograms;
use crate::Graph;
use proc_macro2::TokenStream;
use quote::quote;

/// `JACOBIAN` with `jacobian` and `time_derivative` where the programs
/// have a symbolic Jacobian; nothing otherwise (`Jacobian::Differenced`,
/// the default).
pub(crate) fn jacobian_items(
    g: &Graph,
    layout: &Layout,
    n: usize,
    programs: Option<&JacobianPrograms>,
) -> TokenStream {
    let Some(programs) = programs else { return TokenStream::new() };
    let nnz = index(programs.pattern.len());
    let nn = index(n);
    let pattern: Vec<TokenStream> = programs
        .pattern
        .iter()
        .map(|&(r, c)| {
            let (r, c) = (index(r), index(c));
            quote!((#r, #c))
        })
        .collect();
    let entries: Vec<usize> = (0..programs.pattern.len()).collect();
    let values = rolled_program(g, layout, &programs.values, ("values", &entries));
    let components: Vec<usize> = (0..n).collect();
    let time = rolled_program(g, layout, &programs.time, ("dfdt", &components));
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
