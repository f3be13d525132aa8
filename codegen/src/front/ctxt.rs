//! Collects the errors of one expansion, so the user sees every mistake at
//! once (serde_derive's `Ctxt`). Errors travel one way, into a `Ctxt`;
//! functions that meet one report it here and return `None` (or `false`)
//! to stop. A `Ctxt` must be consumed — its errors turned into
//! `compile_error!`s or messages, or abandoned where the expansion runs
//! again and finds them anew — and dropping one that holds errors is a
//! bug it panics on, as serde's does, so no mistake is lost silently.

use proc_macro2::{Span, TokenStream};
use quote::ToTokens;

/// Errors found so far.
#[derive(Default)]
pub struct Ctxt {
    errors: Vec<syn::Error>,
    /// Consumed: its errors were handed on (or deliberately left).
    consumed: bool,
}

impl Ctxt {
    /// Records an error on the tokens of `at`.
    pub fn error_at(&mut self, at: impl ToTokens, message: impl std::fmt::Display) {
        self.errors.push(syn::Error::new_spanned(at, message));
    }

    /// Records an error at a span.
    pub fn error_span(&mut self, span: Span, message: impl std::fmt::Display) {
        self.errors.push(syn::Error::new(span, message));
    }

    /// Records a finished error.
    pub fn push(&mut self, error: syn::Error) {
        self.errors.push(error);
    }

    /// `true` when nothing went wrong.
    pub fn is_ok(&self) -> bool {
        self.errors.is_empty()
    }

    /// The error messages so far, for tests.
    pub fn messages(&self) -> Vec<String> {
        self.errors.iter().map(|e| e.to_string()).collect()
    }

    /// The errors as `compile_error!` invocations.
    pub fn into_compile_errors(mut self) -> TokenStream {
        self.consumed = true;
        self.errors.iter().map(syn::Error::to_compile_error).collect()
    }

    /// The error messages.
    pub fn into_messages(mut self) -> Vec<String> {
        self.consumed = true;
        self.messages()
    }

    /// Leaves the errors unreported, where the expansion runs again (once
    /// the parts it lacks arrive) and finds them anew.
    pub fn abandon(mut self) {
        self.consumed = true;
    }
}

impl Drop for Ctxt {
    fn drop(&mut self) {
        if !self.consumed && !self.errors.is_empty() && !std::thread::panicking() {
            panic!("daegen lost the errors of an expansion: {:?}", self.messages());
        }
    }
}
