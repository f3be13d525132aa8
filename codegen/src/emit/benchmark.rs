//! `impl Benchmark` for a model registered with `bench = ...`.

use crate::front::attributes::Attributes;
use crate::front::ir::ModelIr;
use proc_macro2::TokenStream;

/// `impl Benchmark` for a model declared with `bench = ...`: its name, its
/// source for timing the expansion, and the problem (the user's expression,
/// with the benchmark types and the methods in scope).
pub fn benchmark_impl(item: &syn::ItemFn, ir: &ModelIr, attributes: &Attributes) -> TokenStream {
    let Some(bench) = &attributes.bench else {
        return TokenStream::new();
    };
    let ty = crate::emit::docs::type_name(&crate::emit::docs::Naming::of(ir));
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
