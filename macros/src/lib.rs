//! The `#[dae_model]` attribute. It parses nothing itself: the model language,
//! its diagnostics and the generated code all live in `daegen-codegen`
//! ([`daegen_codegen::expand_dae_model`]), a plain library that is tested
//! without compiling a macro.

#![warn(missing_docs)]

use proc_macro::TokenStream;

/// Turns a function written in the model language into a model type that
/// implements `daegen::Model`. See the `daegen` crate for the language.
#[proc_macro_attribute]
pub fn dae_model(attr: TokenStream, item: TokenStream) -> TokenStream {
    daegen_codegen::expand_dae_model(attr.into(), item.into()).into()
}
