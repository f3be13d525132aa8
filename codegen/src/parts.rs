//! Models and components that call the user's components. A proc-macro
//! sees only its own item, so a component carries its definition in a
//! `macro_rules!` that `#[component]` emits: called with a callback and
//! the caller's state, it calls the callback back with the state and its
//! definition appended (the tt-call pattern). A model whose body calls
//! parts nobody has defined expands to a call of the first one's macro;
//! the callback records the definition and calls the next, and the last
//! expands the model with every definition. A component fetches its own
//! parts the same way when it is defined, so the bundle its macro carries
//! is complete, and a crate of components works from any other crate.
//!
//! The state passed along: `model { attr } { item } resolved { "path" =>
//! { bundle } ... } pending [path, ...]` (or `component { .. }`), then the
//! callee appends `definition { bundle }`.

use crate::front::components::definitions::{path_text, Definition, Definitions};
use crate::front::ctxt::Ctxt;
use proc_macro2::TokenStream;
use quote::{format_ident, quote, ToTokens};
use std::rc::Rc;
use syn::parse::{Parse, ParseStream};

/// What the callback is completing.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Kind {
    Model,
    Component,
}

/// The state a fetch passes along.
struct Request {
    kind: Kind,
    attr: TokenStream,
    item: syn::ItemFn,
    resolved: Vec<(String, TokenStream)>,
    pending: Vec<syn::Path>,
    definition: Option<TokenStream>,
}

impl Parse for Request {
    fn parse(input: ParseStream) -> syn::Result<Request> {
        let kind: syn::Ident = input.parse()?;
        let kind = match kind.to_string().as_str() {
            "model" => Kind::Model,
            "component" => Kind::Component,
            _ => return Err(syn::Error::new(kind.span(), "expected `model` or `component`")),
        };
        let attr;
        syn::braced!(attr in input);
        let item;
        syn::braced!(item in input);
        let item: syn::ItemFn = item.parse()?;
        let keyword: syn::Ident = input.parse()?;
        if keyword != "resolved" {
            return Err(syn::Error::new(keyword.span(), "expected `resolved`"));
        }
        let resolved_tokens;
        syn::braced!(resolved_tokens in input);
        let mut resolved = Vec::new();
        while !resolved_tokens.is_empty() {
            let path: syn::LitStr = resolved_tokens.parse()?;
            resolved_tokens.parse::<syn::Token![=>]>()?;
            let bundle;
            syn::braced!(bundle in resolved_tokens);
            resolved.push((path.value(), bundle.parse()?));
        }
        let keyword: syn::Ident = input.parse()?;
        if keyword != "pending" {
            return Err(syn::Error::new(keyword.span(), "expected `pending`"));
        }
        let pending_tokens;
        syn::bracketed!(pending_tokens in input);
        let pending = pending_tokens
            .parse_terminated(syn::Path::parse_mod_style, syn::Token![,])?
            .into_iter()
            .collect();
        let definition = match input.is_empty() {
            true => None,
            false => {
                let keyword: syn::Ident = input.parse()?;
                if keyword != "definition" {
                    return Err(syn::Error::new(keyword.span(), "expected `definition`"));
                }
                let bundle;
                syn::braced!(bundle in input);
                Some(bundle.parse()?)
            }
        };
        Ok(Request { kind, attr: attr.parse()?, item, resolved, pending, definition })
    }
}

impl Request {
    /// The definitions resolved so far.
    fn definitions(&self) -> syn::Result<Definitions> {
        let mut out = Definitions::default();
        for (path, bundle) in &self.resolved {
            let definition = syn::parse::Parser::parse2(Definition::parse_bundle, bundle.clone())?;
            out.insert(path.clone(), definition);
        }
        Ok(out)
    }

    /// The call of the first pending part's macro, this request its state.
    fn fetch(&self) -> TokenStream {
        let callback = match self.kind {
            Kind::Model => quote!(::daegen::__dae_model_parts),
            Kind::Component => quote!(::daegen::__component_parts),
        };
        let kind = match self.kind {
            Kind::Model => quote!(model),
            Kind::Component => quote!(component),
        };
        let (attr, item, pending) = (&self.attr, &self.item, &self.pending);
        let resolved = self.resolved.iter().map(|(p, b)| quote!(#p => { #b }));
        let first = &pending[0];
        quote! {
            #first! { [#callback] #kind { #attr } { #item } resolved { #(#resolved)* } pending [#(#pending),*] }
        }
    }
}

/// The callback of a fetch: records the definition the first pending part
/// sent, then fetches the next or expands.
pub fn expand_parts(input: TokenStream) -> TokenStream {
    let mut request: Request = match syn::parse2(input) {
        Ok(r) => r,
        Err(e) => return e.to_compile_error(),
    };
    if let Some(definition) = request.definition.take() {
        if !request.pending.is_empty() {
            let path = request.pending.remove(0);
            request.resolved.push((path_text(&path), definition));
        }
    }
    if !request.pending.is_empty() {
        return request.fetch();
    }
    let parts = match request.definitions() {
        Ok(parts) => parts,
        Err(e) => return e.to_compile_error(),
    };
    let (item, attr) = (request.item.to_token_stream(), request.attr.clone());
    let expanded = match request.kind {
        Kind::Model => crate::expand_model_with(attr, item, parts),
        Kind::Component => return expand_component_with(attr, item, parts),
    };
    match expanded {
        Expansion::Done(tokens) => tokens,
        Expansion::Fetch(missing) => {
            request.pending = missing;
            request.fetch()
        }
    }
}

/// What an expansion with some parts came to.
pub(crate) enum Expansion {
    /// The tokens.
    Done(TokenStream),
    /// Parts it calls that nobody has defined yet: fetch them first.
    Fetch(Vec<syn::Path>),
}

/// A fetch started by a model (`#[dae_model]`) for `missing`.
pub(crate) fn fetch_for_model(
    attr: TokenStream,
    item: &syn::ItemFn,
    parts: &Definitions,
    missing: Vec<syn::Path>,
) -> TokenStream {
    let resolved =
        parts.paths().filter_map(|p| parts.get(p).map(|d| (p.to_string(), d.bundle()))).collect();
    Request {
        kind: Kind::Model,
        attr,
        item: item.clone(),
        resolved,
        pending: missing,
        definition: None,
    }
    .fetch()
}

/// `#[component] fn resistor() { .. }`.
pub fn expand_component(attr: TokenStream, item: TokenStream) -> TokenStream {
    expand_component_with(attr, item, Definitions::default())
}

/// `#[component]` with the parts fetched so far: the component's macro,
/// its errors, or a fetch of the parts it still lacks.
fn expand_component_with(attr: TokenStream, item: TokenStream, parts: Definitions) -> TokenStream {
    let item: syn::ItemFn = match syn::parse2(item) {
        Ok(item) => item,
        Err(e) => {
            let message = "`#[component]` goes on a function: `fn resistor() { ... }`";
            return syn::Error::new(e.span(), message).to_compile_error();
        }
    };
    let mut cx = Ctxt::default();
    if !attr.is_empty() {
        cx.error_at(&attr, "`#[component]` takes no arguments");
    }
    if !item.sig.inputs.is_empty() {
        cx.error_at(&item.sig.inputs, "a component takes no arguments: declare its parameters with `let r = param(1.0);`, which a call sets in order or by name");
    }
    if let syn::ReturnType::Type(_, ty) = &item.sig.output {
        cx.error_at(
            ty,
            "a component returns nothing: its connectors and variables are what it offers",
        );
    }
    let definition =
        Rc::new(Definition { item: item.clone(), parts: Rc::new(parts), library: false });
    let missing = crate::front::lower::check_component::<crate::mechanics::Scene>(
        &mut cx,
        definition.clone(),
    );
    if !missing.is_empty() {
        // Its errors are found again once the parts arrive.
        cx.abandon();
        let resolved = definition
            .parts
            .paths()
            .filter_map(|p| definition.parts.get(p).map(|d| (p.to_string(), d.bundle())))
            .collect();
        let request = Request {
            kind: Kind::Component,
            attr,
            item,
            resolved,
            pending: missing,
            definition: None,
        };
        return request.fetch();
    }
    if !cx.is_ok() {
        return cx.into_compile_errors();
    }
    let mut out = cx.into_compile_errors();
    out.extend(component_macro(&definition));
    out
}

/// The `macro_rules!` that hands `definition` to a callback, under a name
/// unique to its source, and its re-export under the component's name.
fn component_macro(definition: &Definition) -> TokenStream {
    use std::hash::{Hash, Hasher};
    let item = &definition.item;
    let bundle = definition.bundle();
    let mut hasher = std::collections::hash_map::DefaultHasher::new();
    bundle.to_string().hash(&mut hasher);
    let name = &item.sig.ident;
    let hidden = format_ident!("__daegen_part_{}_{:016x}", name, hasher.finish());
    let vis = &item.vis;
    let doc = crate::front::lower::doc_comment(&item.attrs);
    let params = definition.params();
    let mut text = doc.clone();
    if !params.is_empty() {
        text.push_str(&format!("\n\nA component (`#[component]`): call it in a model with its parameters in order, or by name: `{name}({})`.", params.join(", ")));
    } else {
        text.push_str("\n\nA component (`#[component]`): instantiate it in a model with `let x = ");
        text.push_str(&format!("{name}();`."));
    }
    quote! {
        #[doc(hidden)]
        #[macro_export]
        macro_rules! #hidden {
            ([$($callback:tt)*] $($state:tt)*) => {
                $($callback)*! { $($state)* definition { #bundle } }
            };
        }
        #[doc = #text]
        #[allow(unused_imports)]
        #vis use #hidden as #name;
    }
}
