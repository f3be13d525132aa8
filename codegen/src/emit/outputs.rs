//! `Model::output`: the outputs, then the algebraic variables, each an arm
//! of one match; a value that reads an unknown solved at run time solves
//! its blocks first.

use crate::dae::system::{FirstOrder, SlotDerivative};
use crate::emit::layout::{index, program, Layout};
use crate::emit::newton::block_solve_code;
use crate::Graph;
use proc_macro2::TokenStream;
use quote::quote;

/// The arms of `output`'s match, by index; `newton_solve` runs the Newton
/// block for the values that read its variables.
pub(crate) fn output_arms(
    g: &mut Graph,
    layout: &mut Layout,
    sys: &FirstOrder,
    newton_solve: &TokenStream,
) -> crate::Result<Vec<TokenStream>> {
    // Outputs, then the algebraic variables; a value that reads an unknown
    // solved at run time solves its blocks first.
    let mut observables = sys.outputs.clone();
    for a in &sys.algebraics {
        match a {
            SlotDerivative::Explicit(e) | SlotDerivative::AfterSolve(e) => observables.push(*e),
            SlotDerivative::Block { block, row } => {
                let (_, symbol) = sys
                    .block_unknowns
                    .iter()
                    .map(|&(s, b, r)| ((b, r), s))
                    .find(|&(at, _)| at == (*block, *row))
                    .ok_or_else(|| crate::Error::Unsupported {
                        message: "an algebraic variable lost its block".into(),
                    })?;
                observables.push(g.symbol_node(symbol));
            }
        }
    }
    let block_solve_for_outputs = {
        let linear = block_solve_code(g, layout, sys, quote!(return f64::NAN));
        quote!(#newton_solve #linear)
    };
    layout.block_of = sys.block_unknowns.iter().map(|&(s, b, r)| (s, (b, r))).collect();
    let output_arms: Vec<TokenStream> = observables
        .iter()
        .enumerate()
        .map(|(k, &o)| {
            let reads_block = g.free_symbols(o).iter().any(|s| layout.block_of.contains_key(s));
            let solve =
                if reads_block { block_solve_for_outputs.clone() } else { TokenStream::new() };
            let body = program(g, layout, &[o], &|_, v| v);
            let k = index(k);
            quote!(#k => { #solve #body })
        })
        .collect();
    layout.block_of.clear();
    Ok(output_arms)
}
