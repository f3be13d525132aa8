//! The initialization methods of a model with initial equations
//! (`INITIAL_FREE`, `INITIAL_EQUATIONS`, `initial_residuals`,
//! `initial_jacobian`), from the programs `programs::initialization`
//! scheduled.

use crate::emit::layout::{index, program_into, Layout};
use crate::programs::initialization::InitializationPrograms;
use crate::Graph;
use proc_macro2::TokenStream;
use quote::quote;

/// The four items; nothing for a model without initial equations.
pub(crate) fn initialization_methods(
    g: &Graph,
    layout: &Layout,
    n: usize,
    programs: Option<&InitializationPrograms>,
) -> TokenStream {
    let Some(p) = programs else { return TokenStream::new() };
    let (n, m) = (index(n), index(p.texts.len()));
    let entries = index(p.texts.len() * p.free.len());
    let free = p.free.iter().map(|&j| index(j));
    let texts = &p.texts;
    let residuals = program_into(g, layout, &p.residuals, "out");
    let jacobian = program_into(g, layout, &p.jacobian, "out");
    quote! {
        const INITIAL_FREE: &'static [usize] = &[#(#free),*];
        const INITIAL_EQUATIONS: &'static [&'static str] = &[#(#texts),*];

        fn initial_residuals(&self, t: f64, y: &[f64], out: &mut [f64]) {
            let (::core::result::Result::Ok(y), ::core::result::Result::Ok(out)) =
                (<&[f64; #n]>::try_from(y), <&mut [f64; #m]>::try_from(out)) else { return };
            #residuals
        }

        fn initial_jacobian(&self, t: f64, y: &[f64], out: &mut [f64]) {
            let (::core::result::Result::Ok(y), ::core::result::Result::Ok(out)) =
                (<&[f64; #n]>::try_from(y), <&mut [f64; #entries]>::try_from(out)) else { return };
            #jacobian
        }
    }
}
