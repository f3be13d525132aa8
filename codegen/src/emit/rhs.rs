//! `Model::rhs`: the explicit entries of the first-order system, then each
//! linear block's matrix and right-hand side, solved at run time.

use crate::dae::system::{FirstOrder, SlotDerivative};
use crate::emit::layout::{index, rolled_program, straight_program, Layout};
use crate::emit::newton::block_target;
use crate::programs::rhs::{RhsEntry, RhsPrograms};
use crate::Graph;
use proc_macro2::TokenStream;
use quote::{format_ident, quote};

/// The body of `rhs` in three parts: the blocks' arrays, the straight-line
/// code writing `dy` and the arrays, and the blocks' solves.
pub(crate) fn rhs_items(
    g: &Graph,
    layout: &Layout,
    sys: &FirstOrder,
    programs: &RhsPrograms,
) -> (TokenStream, TokenStream, TokenStream) {
    let mut block_setup = TokenStream::new();
    let mut block_solve = TokenStream::new();
    for (b, block) in sys.blocks.iter().enumerate() {
        let k = block.rhs.len();
        let (m, gv) = (format_ident!("mass{}", b), format_ident!("rhs{}", b));
        let kk = index(k);
        block_setup.extend(quote!(let mut #m = [[0.0f64; #kk]; #kk]; let mut #gv = [0.0f64; #kk];));
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
    if let Some((slots, program)) = &programs.after {
        let after_layout = Layout {
            slot_of: layout.slot_of.clone(),
            block_of: sys.block_unknowns.iter().map(|&(s, b, r)| (s, (b, r))).collect(),
            taylor_of: Default::default(),
        };
        block_solve.extend(straight_program(g, &after_layout, program, &|k, v| {
            let i = index(slots[k]);
            quote!(dy[#i] = #v;)
        }));
    }
    // Every entry explicit in the states: entries that differ only in the
    // states they read (a grid's cells) are rolled into loops.
    let rhs_body = if sys.blocks.is_empty() && block_solve.is_empty() {
        let slots: Vec<usize> = programs
            .entries
            .iter()
            .map(|e| match e {
                RhsEntry::Derivative(i) => *i,
                _ => usize::MAX,
            })
            .collect();
        rolled_program(g, layout, &programs.body, ("dy", &slots))
    } else {
        straight_program(g, layout, &programs.body, &|i, v| block_target(programs.entries[i], v))
    };
    (block_setup, rhs_body, block_solve)
}
