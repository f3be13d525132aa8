//! The `#[dae_model]` front end as a plain library: attribute input in,
//! tokens out. The proc-macro crate only forwards to [`expand_dae_model`].
//!
//! The pipeline, one pass per module:
//! `parse (syn) → lower → reduce → expand`, each mistake collected in a
//! [`ctxt::Ctxt`] with the user's tokens; on error the expansion is the
//! errors plus a stub of the type, so the user sees one error per mistake.

pub mod constraints;
pub mod ctxt;
pub mod derivative_free;
pub mod expand;
pub mod index_reduction;
pub mod ir;
pub mod linear_pencil;
pub mod lower;
pub mod mass_form;
pub mod names;
pub mod newton_block;
pub mod reduce;
pub mod solve_unknowns;
pub mod taylor_factoring;
pub mod taylor_folding;
pub mod taylor_groups;
pub mod taylor_lanes;
pub mod taylor_layout;
pub mod taylor_shared;
pub mod taylor_tape;
pub mod taylor_unrolled;
pub mod warnings;

use proc_macro2::TokenStream;

/// Expands `#[dae_model(attr)] item`.
pub fn expand_dae_model(attr: TokenStream, item: TokenStream) -> TokenStream {
    let mut cx = ctxt::Ctxt::default();
    let attributes = attributes(&mut cx, attr);
    let item: syn::ItemFn = match syn::parse2(item) {
        Ok(item) => item,
        Err(e) => {
            return syn::Error::new(
                e.span(),
                "`#[dae_model]` goes on a function: `fn pendulum() { ... }`",
            )
            .to_compile_error()
        }
    };
    let mut ir = lower::lower_with(&mut cx, &item, attributes.recursive);
    let system = if cx.is_ok() {
        reduce::reduce(&mut cx, &mut ir)
    } else {
        None
    };
    if let (Some(system), true) = (&system, cx.is_ok()) {
        match expand::expand(&mut ir, system, &attributes) {
            Ok(mut tokens) => {
                tokens.extend(benchmark_impl(&item, &ir, &attributes));
                tokens.extend(warnings::odd_unrolled_orders(&attributes.odd_unrolled));
                return tokens;
            }
            Err(e @ crate::Error::NotSmooth { node, .. }) => {
                // The call itself when the right-hand side kept the node the
                // user wrote; else the first such call.
                let call = ir
                    .non_smooth_calls
                    .iter()
                    .find(|(id, _)| *id == node)
                    .or(ir.non_smooth_calls.first());
                match call {
                    Some((_, tokens)) => cx.error_at(tokens, e),
                    None => cx.error_at(&item.sig.ident, e),
                }
            }
            Err(e) => cx.error_at(&item.sig.ident, e),
        }
    }
    let mut out = cx.to_compile_errors();
    out.extend(expand::stub(&ir));
    out
}

/// What `#[dae_model(...)]` asks for besides the model.
#[derive(Clone, Default)]
pub struct Attributes {
    /// `taylor = p`, 1 ≤ p ≤ 8: the economic Taylor derivatives up to order
    /// p and the AD tape of the adaptive Taylor method (which every model
    /// that allows it has anyway).
    pub taylor: Option<usize>,
    /// `taylor = 0`: no Taylor code at all, not even the tape.
    pub taylor_off: bool,
    /// `unroll = [p, ...]`, 2 ≤ p ≤ 40: orders of the adaptive Taylor method
    /// to emit as straight-line code (see `taylor_unrolled`).
    pub unroll: Vec<usize>,
    /// The odd orders of `unroll`, where they were written: `Method::Taylor`
    /// never picks them (see `warnings`).
    pub odd_unrolled: Vec<(usize, proc_macro2::Span)>,
    /// `scene = recursive`: a scene in relative joint coordinates (the
    /// default, `scene = global`, keeps each body's coordinates).
    pub recursive: bool,
    /// `bench = Bench::until(t1)...`: the model's benchmark problem; the
    /// model then implements `daegen::runtime::bench::Benchmark`.
    pub bench: Option<syn::Expr>,
    /// The other arguments, as written (for re-expanding the model when the
    /// benchmark times its expansion).
    pub written: String,
}

/// Reads `#[dae_model]`, `#[dae_model(taylor = p)]`, `#[dae_model(unroll = [14, 18])]`
/// or both (only what is asked for is generated).
fn attributes(cx: &mut ctxt::Ctxt, attr: TokenStream) -> Attributes {
    let mut out = Attributes::default();
    if attr.is_empty() {
        return out;
    }
    let fix = "`#[dae_model]` takes `taylor = p` (p from 0 to 8), `unroll = [p, ...]` (orders from 2 to 40), `scene = global` or `scene = recursive`, and `bench = Bench::until(t1)...`";
    let parser =
        syn::punctuated::Punctuated::<syn::MetaNameValue, syn::Token![,]>::parse_terminated;
    let Ok(args) = syn::parse::Parser::parse2(parser, attr.clone()) else {
        cx.error_at(&attr, fix);
        return out;
    };
    let integer = |e: &syn::Expr| match e {
        syn::Expr::Lit(syn::ExprLit {
            lit: syn::Lit::Int(i),
            ..
        }) => i.base10_parse::<usize>().ok(),
        _ => None,
    };
    for arg in &args {
        if arg.path.is_ident("taylor") && out.taylor.is_none() {
            match integer(&arg.value) {
                Some(p) if (1..=8).contains(&p) => out.taylor = Some(p),
                Some(0) => out.taylor_off = true,
                _ => cx.error_at(
                    &arg.value,
                    "`taylor = p` takes an order p from 1 to 8 (the economic scheme's derivatives), or 0 for no Taylor code at all; `Method::Taylor` picks its own order, and `unroll = [p]` emits order p as code",
                ),
            }
        } else if arg.path.is_ident("unroll") && out.unroll.is_empty() {
            let orders: Option<Vec<usize>> = match &arg.value {
                syn::Expr::Array(a) if !a.elems.is_empty() => a
                    .elems
                    .iter()
                    .map(|e| integer(e).filter(|p| (2..=40).contains(p)))
                    .collect(),
                _ => None,
            };
            match orders {
                Some(mut orders) => {
                    if let syn::Expr::Array(a) = &arg.value {
                        out.odd_unrolled = a
                            .elems
                            .iter()
                            .filter_map(|e| Some((integer(e)?, syn::spanned::Spanned::span(e))))
                            .filter(|(p, _)| p % 2 == 1)
                            .collect();
                    }
                    orders.sort_unstable();
                    orders.dedup();
                    out.unroll = orders;
                }
                None => cx.error_at(
                    &arg.value,
                    "`unroll` takes a list of Taylor orders from 2 to 40, e.g. `unroll = [14, 18]` (Kepler at tolerances 1e-9 and 1e-12; `daegen::runtime::taylor_order::order_to_unroll` says which order a model uses)",
                ),
            }
        } else if arg.path.is_ident("bench") && out.bench.is_none() {
            out.bench = Some(arg.value.clone());
            continue;
        } else if arg.path.is_ident("scene") {
            match &arg.value {
                syn::Expr::Path(p) if p.path.is_ident("recursive") => out.recursive = true,
                syn::Expr::Path(p) if p.path.is_ident("global") => out.recursive = false,
                other => cx.error_at(other, "`scene` is `global` (each body free, joints as constraints; the default) or `recursive` (relative joint coordinates on a spanning tree)"),
            }
        } else {
            cx.error_at(arg, fix);
        }
        if !out.written.is_empty() {
            out.written.push_str(", ");
        }
        out.written
            .push_str(&quote::ToTokens::to_token_stream(arg).to_string());
    }
    out
}

/// `impl Benchmark` for a model declared with `bench = ...`: its name, its
/// source for timing the expansion, and the problem (the user's expression,
/// with the benchmark types and the methods in scope).
fn benchmark_impl(item: &syn::ItemFn, ir: &ir::ModelIr, attributes: &Attributes) -> TokenStream {
    let Some(bench) = &attributes.bench else {
        return TokenStream::new();
    };
    let ty = expand::type_name(ir);
    let name = item.sig.ident.to_string();
    let source = quote::ToTokens::to_token_stream(item).to_string();
    let written = &attributes.written;
    quote::quote! {
        impl ::daegen::runtime::bench::Benchmark for #ty {
            const NAME: &'static str = #name;
            const SOURCE: &'static str = #source;
            const ATTRIBUTES: &'static str = #written;
            fn bench() -> ::daegen::runtime::bench::Bench {
                #[allow(unused_imports)]
                use ::daegen::runtime::bench::{Bench, Reference};
                #[allow(unused_imports)]
                use ::daegen::runtime::Method::*;
                #bench
            }
        }
    }
}

/// The errors `expand_dae_model` would report, as messages: for tests of
/// diagnostics without compiling a macro.
pub fn diagnostics(item: TokenStream) -> Vec<String> {
    let mut cx = ctxt::Ctxt::default();
    let Ok(item) = syn::parse2::<syn::ItemFn>(item) else {
        return vec!["not a function".to_string()];
    };
    let mut ir = lower::lower(&mut cx, &item);
    if cx.is_ok() {
        if let Some(system) = reduce::reduce(&mut cx, &mut ir) {
            if let Err(e) = expand::expand(&mut ir, &system, &Attributes::default()) {
                cx.error_at(&item.sig.ident, e);
            }
        }
    }
    cx.messages()
}
