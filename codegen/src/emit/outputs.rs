//! `Model::output`: the outputs, then the algebraic variables, each an arm
//! of one match; a value that reads an unknown solved at run time solves
//! its blocks first.

use crate::dae::system::FirstOrder;
use crate::emit::layout::{index, straight_program, Layout};
use crate::emit::newton::block_solve_code;
use crate::programs::outputs::OutputPrograms;
use crate::Graph;
use proc_macro2::TokenStream;
use quote::quote;

/// The arms of `output`'s match, by index; `newton_solve` runs the Newton
/// block for the values that read its variables.
pub(crate) fn output_arms(
    g: &Graph,
    layout: &mut Layout,
    sys: &FirstOrder,
    newton_solve: &TokenStream,
    programs: &OutputPrograms,
) -> Vec<TokenStream> {
    let block_solve_for_outputs = {
        let linear =
            block_solve_code(g, layout, sys, &programs.block_solve, quote!(return f64::NAN));
        quote!(#newton_solve #linear)
    };
    layout.block_of = sys.block_unknowns.iter().map(|&(s, b, r)| (s, (b, r))).collect();
    let mut output_arms = Vec::new();
    for group in &programs.groups {
        let solve = match group.reads_block {
            true => block_solve_for_outputs.clone(),
            false => TokenStream::new(),
        };
        if let [k] = group.members[..] {
            let body = straight_program(g, layout, &group.program, &|_, v| v);
            let k = index(k);
            output_arms.push(quote!(#k => { #solve #body }));
            continue;
        }
        // The group computed together, the one asked for returned.
        let names: Vec<syn::Ident> =
            (0..group.members.len()).map(|j| quote::format_ident!("value{}", j)).collect();
        let body = straight_program(g, layout, &group.program, &|j, v| {
            let name = &names[j];
            quote!(let #name = #v;)
        });
        let ks: Vec<proc_macro2::Literal> = group.members.iter().map(|&k| index(k)).collect();
        output_arms.push(quote! {
            #(#ks)|* => {
                #solve
                #body
                match index {
                    #(#ks => #names,)*
                    _ => f64::NAN,
                }
            }
        });
    }
    layout.block_of.clear();
    output_arms
}
