//! `Model::output`: the outputs, then the algebraic variables, each an arm
//! of one match; a value that reads an unknown solved at run time solves
//! its blocks first.

use crate::dae::system::{FirstOrder, SlotDerivative};
use crate::emit::layout::{index, program, Layout};
use crate::emit::newton::block_solve_code;
use crate::{Graph, Id};
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
    let mut output_arms = Vec::new();
    for group in groups_sharing_work(g, &observables) {
        let values: Vec<Id> = group.iter().map(|&k| observables[k]).collect();
        let reads_block = values
            .iter()
            .any(|&o| g.free_symbols(o).iter().any(|s| layout.block_of.contains_key(s)));
        let solve = if reads_block { block_solve_for_outputs.clone() } else { TokenStream::new() };
        if let [k] = group[..] {
            let body = program(g, layout, &values, &|_, v| v);
            let k = index(k);
            output_arms.push(quote!(#k => { #solve #body }));
            continue;
        }
        // The group computed together, the one asked for returned.
        let names: Vec<syn::Ident> =
            (0..group.len()).map(|j| quote::format_ident!("value{}", j)).collect();
        let body = program(g, layout, &values, &|j, v| {
            let name = &names[j];
            quote!(let #name = #v;)
        });
        let ks: Vec<proc_macro2::Literal> = group.iter().map(|&k| index(k)).collect();
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
    Ok(output_arms)
}

/// Outputs read one at a time, each computing what it needs, except
/// where consecutive outputs share most of their work (a body's position,
/// attitude and velocity at the end of a chain of joints): those form a
/// group computed together, so the chain is written once per group rather
/// than once per output. Small outputs stay alone.
fn groups_sharing_work(g: &Graph, observables: &[Id]) -> Vec<Vec<usize>> {
    const ALONE_BELOW: usize = 64;
    const MOST: usize = 16;
    let mut groups: Vec<Vec<usize>> = Vec::new();
    let mut seen: crate::FxHashMap<Id, ()> = Default::default();
    for (k, &o) in observables.iter().enumerate() {
        let needs = g.reachable(&[o]);
        let shared = needs.iter().filter(|id| seen.contains_key(id)).count();
        let joins = needs.len() >= ALONE_BELOW
            && 2 * shared >= needs.len()
            && groups.last().is_some_and(|last| last.len() < MOST);
        match (joins, groups.last_mut()) {
            (true, Some(last)) => last.push(k),
            _ => {
                groups.push(vec![k]);
                seen.clear();
            }
        }
        seen.extend(needs.into_iter().map(|id| (id, ())));
    }
    groups
}
