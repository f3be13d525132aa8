//! The Taylor methods' items of a model, from its Taylor analysis: the
//! economic scheme's derivatives (`taylor = p`), the adaptive method's tape
//! and unrolled jets, or why there are none.

use crate::emit::layout::{index, straight_program, Layout};
use crate::programs::schedule::Program;
use crate::programs::taylor::TaylorPrograms;
use crate::taylor::analysis::{EconomicDerivatives, TapeAnalysis, TaylorAnalysis};
use crate::Graph;
use proc_macro2::TokenStream;
use quote::quote;

/// The Taylor methods' items, and the reason `Method::Taylor` refuses a
/// model without a tape.
pub(crate) fn taylor_items(
    g: &Graph,
    layout: &mut Layout,
    n: usize,
    analysis: &TaylorAnalysis,
    programs: &TaylorPrograms,
) -> (TokenStream, Option<String>) {
    let constants = programs.constants.as_ref();
    match (analysis, constants) {
        (TaylorAnalysis::Scheme { economic, tape }, Some(constants)) => {
            let economic = economic_taylor(g, layout, n, economic, &programs.economic);
            let tape = taylor_tape_items(g, layout, n, tape, constants);
            (quote!(#tape #economic), None)
        }
        (TaylorAnalysis::Tape(tape), Some(constants)) => {
            (taylor_tape_items(g, layout, n, tape, constants), None)
        }
        (TaylorAnalysis::Refused(reason), _) => (TokenStream::new(), Some(reason.clone())),
        (_, None) => (TokenStream::new(), Some("the tape's constants were not scheduled".into())),
    }
}

/// `TAYLOR_ORDER` and `taylor_derivatives`: the k-th derivative of slot i
/// read from `out`, one program per order, each reading the lower orders
/// already written.
fn economic_taylor(
    g: &Graph,
    layout: &mut Layout,
    n: usize,
    economic: &EconomicDerivatives,
    levels: &[Program],
) -> TokenStream {
    let order = economic.order;
    for (i, symbols) in economic.symbols.iter().enumerate() {
        for (j, &s) in symbols.iter().enumerate() {
            layout.taylor_of.insert(s, j * n + i);
        }
    }
    let mut body = TokenStream::new();
    for (k, level) in levels.iter().enumerate() {
        let code = straight_program(g, layout, level, &|i, v| {
            let at = index(k * n + i);
            quote!(out[#at] = #v;)
        });
        let k1 = index(k + 1);
        body.extend(quote!(if order >= #k1 { #code }));
    }
    let (nn, np, p) = (index(n), index(n * order), index(order));
    quote! {
        const TAYLOR_ORDER: usize = #p;

        #[inline]
        fn taylor_derivatives(&self, t: f64, y: &[f64], order: usize, out: &mut [f64]) -> ::core::result::Result<(), ::daegen::EvalError> {
            let (::core::result::Result::Ok(y), ::core::result::Result::Ok(out)) =
                (<&[f64; #nn]>::try_from(y), <&mut [f64; #np]>::try_from(out))
            else {
                return ::core::result::Result::Ok(());
            };
            #body
            ::core::result::Result::Ok(())
        }
    }
}

/// `taylor_tape`, the AD tape of the adaptive Taylor method (compact
/// layout, interpreted at run time), and the straight-line jets of the
/// orders in `unroll`.
fn taylor_tape_items(
    g: &Graph,
    layout: &Layout,
    n: usize,
    analysis: &TapeAnalysis,
    constants: &Program,
) -> TokenStream {
    let nn = index(n);
    let (tape, consts, jets) = (&analysis.tape, &analysis.constants, &analysis.jets);
    let const_code = straight_program(g, layout, constants, &|i, v| {
        let name = quote::format_ident!("c{}", i);
        quote!(let #name: f64 = #v;)
    });
    let (ops, outs) = (&tape.ops, &tape.outputs);
    let (n_ops, n_outs, n_consts) = (index(ops.len()), index(outs.len()), index(consts.len()));
    let const_names = (0..consts.len()).map(|i| quote::format_ident!("c{}", i));
    let jet_lengths = jets.iter().map(|(order, jet)| {
        let (order, buffer) = (index(*order), index(jet.buffer));
        quote!(#order => #buffer,)
    });
    let unrolled_arms = jets.iter().map(|(order, jet)| {
        let body = &jet.body;
        let (order_lit, len) = (index(*order), index(jet.buffer));
        quote! {
            #order_lit => {
                let ::core::option::Option::Some(out) = out.get_mut(..#len) else { return false };
                let (::core::result::Result::Ok(y), ::core::result::Result::Ok(out)) =
                    (<&[f64; #nn]>::try_from(y), <&mut [f64; #len]>::try_from(out)) else { return false };
                #const_code
                #body
                true
            }
        }
    });
    let unrolled_orders = jets.iter().map(|(o, _)| index(*o));
    let by_coefficient: Vec<_> =
        jets.iter().filter(|(_, jet)| jet.by_coefficient).map(|(order, _)| index(*order)).collect();
    let by_coefficient = if by_coefficient.is_empty() {
        TokenStream::new()
    } else {
        quote! {
            fn taylor_jet_by_coefficient(&self, order: usize) -> bool {
                matches!(order, #(#by_coefficient)|*)
            }
        }
    };
    let unrolled = if jets.is_empty() {
        TokenStream::new()
    } else {
        quote! {
            const TAYLOR_UNROLLED: &'static [usize] = &[#(#unrolled_orders),*];

            fn taylor_jet_len(&self, order: usize) -> usize {
                match order {
                    #(#jet_lengths)*
                    _ => #nn * (order + 1),
                }
            }

            #by_coefficient

            #[allow(clippy::all)]
            fn taylor_jet_unrolled(&self, t: f64, y: &[f64], order: usize, out: &mut [f64]) -> bool {
                match order {
                    #(#unrolled_arms)*
                    _ => false,
                }
            }
        }
    };
    quote! {
        #unrolled

        fn taylor_tape(&self) -> ::core::option::Option<(
            ::std::vec::Vec<::daegen::runtime::taylor_tape::TapeOp>,
            ::std::vec::Vec<::daegen::runtime::taylor_tape::Operand>,
        )> {
            // Short names: a large model's tape runs to thousands of operations.
            #[allow(unused_imports)]
            use ::daegen::runtime::taylor_tape::{Inverse as I, Operand as O, TapeOp as T};
            // The operations as a table with their constants by slot: code
            // that built them one by one would take rustc minutes for a
            // model of thousands of states.
            static OPS: [T<u32>; #n_ops] = [#(#ops),*];
            static OUTPUTS: [O<u32>; #n_outs] = [#(#outs),*];
            #const_code
            let constants: [f64; #n_consts] = [#(#const_names),*];
            let value = |k: &u32| constants.get(*k as usize).copied().unwrap_or(f64::NAN);
            ::core::option::Option::Some((
                OPS.iter().map(|op| op.map_constants(value)).collect(),
                OUTPUTS.iter().map(|o| o.map_constant(value)).collect(),
            ))
        }
    }
}
