//! The `#[dae_model]` front end as a plain library: attribute input in,
//! tokens out. The proc-macro crate only forwards to [`expand_dae_model`].
//!
//! The pipeline, one pass per module:
//! `parse (syn) → lower → reduce → expand`, each mistake collected in a
//! [`ctxt::Ctxt`] with the user's tokens; on error the expansion is the
//! errors plus a stub of the type, so the user sees one error per mistake.

pub mod ctxt;
pub mod expand;
pub mod ir;
pub mod lower;
pub mod names;
pub mod reduce;
pub mod taylor_tape;

use proc_macro2::TokenStream;

/// Expands `#[dae_model(attr)] item`.
pub fn expand_dae_model(attr: TokenStream, item: TokenStream) -> TokenStream {
    let mut cx = ctxt::Ctxt::default();
    let taylor = taylor_order(&mut cx, attr);
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
    let mut ir = lower::lower(&mut cx, &item);
    let system = if cx.is_ok() {
        reduce::reduce(&mut cx, &mut ir)
    } else {
        None
    };
    if let (Some(system), true) = (&system, cx.is_ok()) {
        match expand::expand(&mut ir, system, taylor) {
            Ok(tokens) => return tokens,
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

/// `#[dae_model]` or `#[dae_model(taylor = p)]`, 1 ≤ p ≤ 8: the order of the
/// economic Taylor derivatives to generate (none by default: only what is asked for).
fn taylor_order(cx: &mut ctxt::Ctxt, attr: TokenStream) -> Option<usize> {
    if attr.is_empty() {
        return None;
    }
    let fix = "`#[dae_model]` takes one optional argument: `taylor = p` with p from 1 to 8";
    let Ok(arg) = syn::parse2::<syn::MetaNameValue>(attr.clone()) else {
        cx.error_at(&attr, fix);
        return None;
    };
    let order = match &arg.value {
        syn::Expr::Lit(syn::ExprLit {
            lit: syn::Lit::Int(i),
            ..
        }) => i.base10_parse::<usize>().ok(),
        _ => None,
    };
    match order {
        Some(p) if arg.path.is_ident("taylor") && (1..=8).contains(&p) => Some(p),
        _ => {
            cx.error_at(&attr, fix);
            None
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
            if let Err(e) = expand::expand(&mut ir, &system, None) {
                cx.error_at(&item.sig.ident, e);
            }
        }
    }
    cx.messages()
}
