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

/// Turns a function written in the model language into a component that
/// models instantiate by name (`let r1 = resistor(100.0);`): its
/// parameters, connectors, variables and equations. It expands to a
/// `macro_rules!` that carries the definition to the models that call it,
/// so a component is used like any item: by path, from another module or
/// another crate. See the guide's chapter on components.
#[proc_macro_attribute]
pub fn component(attr: TokenStream, item: TokenStream) -> TokenStream {
    daegen_codegen::expand_component(attr.into(), item.into()).into()
}

/// The callback a component's macro calls with its definition, on the
/// way to expanding the model that called it. Not for direct use.
#[doc(hidden)]
#[proc_macro]
pub fn __dae_model_parts(input: TokenStream) -> TokenStream {
    daegen_codegen::expand_parts(input.into()).into()
}

/// The callback a component's macro calls with its definition, on the
/// way to defining a component that uses it. Not for direct use.
#[doc(hidden)]
#[proc_macro]
pub fn __component_parts(input: TokenStream) -> TokenStream {
    daegen_codegen::expand_parts(input.into()).into()
}
