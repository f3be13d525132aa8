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

use proc_macro2::TokenStream;

/// Expands `#[dae_model(attr)] item`.
pub fn expand_dae_model(attr: TokenStream, item: TokenStream) -> TokenStream {
    let mut cx = ctxt::Ctxt::default();
    if !attr.is_empty() {
        cx.error_at(&attr, "`#[dae_model]` takes no arguments");
    }
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
        match expand::expand(&mut ir, system) {
            Ok(tokens) => return tokens,
            Err(e) => cx.error_at(&item.sig.ident, e),
        }
    }
    let mut out = cx.to_compile_errors();
    out.extend(expand::stub(&ir));
    out
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
            if let Err(e) = expand::expand(&mut ir, &system) {
                cx.error_at(&item.sig.ident, e);
            }
        }
    }
    cx.messages()
}
