//! `Model::rhs`: the explicit entries of the first-order system, then each
//! linear block's matrix and right-hand side, solved at run time.

use crate::dae::system::{FirstOrder, SlotDerivative};
use crate::emit::layout::{index, program, rolled_program, Layout};
use crate::{Graph, Id};
use proc_macro2::TokenStream;
use quote::{format_ident, quote};

/// The body of `rhs` in three parts: the blocks' arrays, the straight-line
/// code writing `dy` and the arrays, and the blocks' solves.
pub(crate) fn rhs_items(
    g: &mut Graph,
    layout: &Layout,
    sys: &FirstOrder,
) -> (TokenStream, TokenStream, TokenStream) {
    // Right-hand side: explicit entries, then each mass block's E and g.
    let mut outputs = Vec::new();
    let mut targets: Vec<TokenStream> = Vec::new();
    let mut explicit_slots = Vec::new();
    for (i, d) in sys.derivatives.iter().enumerate() {
        if let SlotDerivative::Explicit(e) = d {
            outputs.push(*e);
            explicit_slots.push(i);
            let i = index(i);
            targets.push(quote!(dy[#i]));
        }
    }
    let mut block_setup = TokenStream::new();
    let mut block_solve = TokenStream::new();
    for (b, block) in sys.blocks.iter().enumerate() {
        let k = block.rhs.len();
        let (m, gv) = (format_ident!("mass{}", b), format_ident!("rhs{}", b));
        let kk = index(k);
        block_setup.extend(quote!(let mut #m = [[0.0f64; #kk]; #kk]; let mut #gv = [0.0f64; #kk];));
        // The arrays start at zero: zero entries are not written.
        let is_zero = |g: &Graph, e: Id| g.as_number(e).is_some_and(|v| v.is_zero());
        for (r, &e) in block.rhs.iter().enumerate() {
            let rl = index(r);
            if !is_zero(g, e) {
                outputs.push(e);
                targets.push(quote!(#gv[#rl]));
            }
            for c in 0..k {
                let entry = block.matrix[r * k + c];
                if is_zero(g, entry) {
                    continue;
                }
                outputs.push(entry);
                let cl = index(c);
                targets.push(quote!(#m[#rl][#cl]));
            }
        }
        let unknowns = &block.unknowns;
        block_solve.extend(quote! {
            if !::daegen::runtime::linalg::solve_in_place(&mut #m, &mut #gv) {
                return ::core::result::Result::Err(::daegen::EvalError::SingularMassMatrix {
                    unknowns: ::std::vec![#(#unknowns),*],
                });
            }
        });
    }
    for (i, d) in sys.derivatives.iter().enumerate() {
        if let SlotDerivative::Block { block, row } = d {
            let (i, gv, row) = (index(i), format_ident!("rhs{}", block), index(*row));
            block_solve.extend(quote!(dy[#i] = #gv[#row];));
        }
    }
    // Accelerations eliminated from a KKT block, from its multipliers.
    let after: Vec<(usize, Id)> = sys
        .derivatives
        .iter()
        .enumerate()
        .filter_map(|(i, d)| match d {
            SlotDerivative::AfterSolve(e) => Some((i, *e)),
            _ => None,
        })
        .collect();
    if !after.is_empty() {
        let after_layout = Layout {
            slot_of: layout.slot_of.clone(),
            block_of: sys.block_unknowns.iter().map(|&(s, b, r)| (s, (b, r))).collect(),
            taylor_of: Default::default(),
        };
        let ids: Vec<Id> = after.iter().map(|x| x.1).collect();
        block_solve.extend(program(g, &after_layout, &ids, &|k, v| {
            let i = index(after[k].0);
            quote!(dy[#i] = #v;)
        }));
    }
    // Every entry explicit in the states: entries that differ only in the
    // states they read (a grid's cells) are rolled into loops.
    let rhs_body = if sys.blocks.is_empty() && block_solve.is_empty() {
        rolled_program(g, layout, &outputs, ("dy", &explicit_slots))
    } else {
        let targets_for_rhs = targets.clone();
        program(g, layout, &outputs, &move |i, v| {
            let target = &targets_for_rhs[i];
            quote!(#target = #v;)
        })
    };

    (block_setup, rhs_body, block_solve)
}

/// f slot by slot when every derivative is explicit in the states (not
/// through a Newton solve's variables): what the symbolic Jacobian and the
/// event rates differentiate.
pub(crate) fn explicit_derivatives(sys: &FirstOrder) -> Option<Vec<Id>> {
    sys.derivatives
        .iter()
        .map(|d| match d {
            SlotDerivative::Explicit(e) if sys.newton.is_none() => Some(*e),
            _ => None,
        })
        .collect()
}
