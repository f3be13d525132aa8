//! How generated code reads each symbol (states from `y`, parameters
//! from `self`, time from `t`, run-time unknowns from their solve's
//! arrays), and straight-line programs written with it.

use crate::dae::system::FirstOrder;
use crate::emit::program::emit_rolled_program;
use crate::programs::schedule::Program;
use crate::{emit_program, Graph, SymbolId, SymbolKind};
use proc_macro2::{Literal, TokenStream};
use quote::{format_ident, quote};

/// How generated code reads each symbol: states from `y`, parameters from
/// `self`, time from `t`.
pub(crate) struct Layout {
    pub(crate) slot_of: crate::FxHashMap<SymbolId, usize>,
    /// Unknowns solved at run time, read after the solve: symbol -> (block, row).
    pub(crate) block_of: crate::FxHashMap<SymbolId, (usize, usize)>,
    /// Taylor coefficients read by higher orders: symbol -> index in `out`.
    pub(crate) taylor_of: crate::FxHashMap<SymbolId, usize>,
}

impl Layout {
    /// The first-order system's slots read from `y`, and the Newton
    /// block's variables (known throughout the right-hand side) from the
    /// array its solve returns.
    pub(crate) fn of_system(sys: &FirstOrder) -> Layout {
        let mut layout = Layout {
            slot_of: sys.slots.iter().enumerate().map(|(i, s)| (s.symbol, i)).collect(),
            block_of: Default::default(),
            taylor_of: Default::default(),
        };
        if let Some(newton) = &sys.newton {
            for (k, &s) in newton.unknowns.iter().enumerate() {
                layout.block_of.insert(s, (sys.blocks.len(), k));
            }
        }
        layout
    }

    /// Component `i` of the state read as `y[i]`.
    pub(crate) fn of_components(components: &[SymbolId]) -> Layout {
        Layout {
            slot_of: components.iter().enumerate().map(|(i, &s)| (s, i)).collect(),
            block_of: Default::default(),
            taylor_of: Default::default(),
        }
    }

    pub(crate) fn tokens(&self, g: &Graph, s: SymbolId) -> TokenStream {
        if let Some(&i) = self.slot_of.get(&s) {
            let i = Literal::usize_unsuffixed(i);
            return quote!(y[#i]);
        }
        if let Some(&i) = self.taylor_of.get(&s) {
            let i = Literal::usize_unsuffixed(i);
            return quote!(out[#i]);
        }
        if let Some(&(b, row)) = self.block_of.get(&s) {
            let (gv, row) = (format_ident!("rhs{}", b), Literal::usize_unsuffixed(row));
            return quote!(#gv[#row]);
        }
        match g.symbol(s).kind {
            SymbolKind::Parameter => {
                let field = format_ident!("{}", g.symbol(s).name);
                quote!(self.#field)
            }
            SymbolKind::Time => quote!(t),
            SymbolKind::Input { rate_of: None } => {
                let field = format_ident!("{}", g.symbol(s).name);
                quote!(self.#field.at(t))
            }
            SymbolKind::Input { rate_of: Some(of) } => {
                let field = format_ident!("{}", g.symbol(of).name);
                quote!(self.#field.rate(t))
            }
            // Reduction replaced every other symbol; NaN would surface at run time.
            _ => quote!(f64::NAN),
        }
    }
}

/// The body of a method that reads `y` (`n` states) and writes the slice
/// `out` (`len` entries): both become arrays first, so every index in `code`
/// is checked at compile time and the method cannot panic. The runtime
/// always passes the right lengths; were it not to, nothing is written.
pub(crate) fn fixed_size_body(
    n: &Literal,
    out: &str,
    len: &Literal,
    code: TokenStream,
) -> TokenStream {
    let out = format_ident!("{}", out);
    quote! {
        let (::core::result::Result::Ok(y), ::core::result::Result::Ok(#out)) =
            (<&[f64; #n]>::try_from(y), <&mut [f64; #len]>::try_from(#out))
        else {
            return ::core::result::Result::Ok(());
        };
        #code
        ::core::result::Result::Ok(())
    }
}

pub(crate) fn index(i: usize) -> Literal {
    Literal::usize_unsuffixed(i)
}

/// Code computing `program`'s outputs into `array[targets[i]]`, outputs
/// that differ only in the states they read rolled into loops
/// ([`crate::emit::program::emit_rolled_program`]); straight-line where
/// some symbol is read from elsewhere than `y`, `self` and `t` (a run-time
/// block's solution, a Taylor coefficient).
pub(crate) fn rolled_program(
    g: &Graph,
    layout: &Layout,
    program: &Program,
    (array, targets): (&str, &[usize]),
) -> TokenStream {
    if !layout.block_of.is_empty() || !layout.taylor_of.is_empty() {
        let array = format_ident!("{}", array);
        return straight_program(g, layout, program, &|i, v| {
            let i = index(targets[i]);
            quote!(#array[#i] = #v;)
        });
    }
    let state_slot = |s: SymbolId| layout.slot_of.get(&s).copied();
    emit_rolled_program(g, program, &|s| layout.tokens(g, s), &state_slot, (array, targets), "y")
}

/// Straight-line code computing `program`'s outputs into `array[0..]`, in
/// the program's order.
pub(crate) fn program_into(
    g: &Graph,
    layout: &Layout,
    program: &Program,
    array: &str,
) -> TokenStream {
    let array = format_ident!("{}", array);
    straight_program(g, layout, program, &|i, v| {
        let i = index(i);
        quote!(#array[#i] = #v;)
    })
}

/// Straight-line code computing `program`'s outputs and handing each to
/// `assign`.
pub(crate) fn straight_program(
    g: &Graph,
    layout: &Layout,
    program: &Program,
    assign: &dyn Fn(usize, TokenStream) -> TokenStream,
) -> TokenStream {
    emit_program(g, program, &|s| layout.tokens(g, s), assign)
}
