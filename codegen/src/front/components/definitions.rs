//! The parts a model can instantiate: the standard library (`library.dae`,
//! read at each expansion) and the user's components, each a function in
//! the model language carrying the parts its own body instantiates.
//!
//! A user's component reaches a model as a bundle of tokens (its
//! function, then `parts { "path" => { bundle } ... }`), which the
//! component's `macro_rules!` hands back to the model's expansion;
//! [`Definition::parse_bundle`] reads one and [`Definition::bundle`]
//! writes one.

use proc_macro2::{Group, Span, TokenStream, TokenTree};
use quote::{quote, ToTokens};
use std::rc::Rc;
use syn::parse::ParseStream;

/// The standard library's source, in the model language.
pub const LIBRARY_SOURCE: &str = include_str!("library.dae");

/// One component: its function and the parts its body may instantiate.
pub struct Definition {
    /// `fn resistor() { ... }`.
    pub item: syn::ItemFn,
    /// The user's parts its body calls, by the path written there.
    pub parts: Rc<Definitions>,
    /// Part of the standard library (its tokens have no place in the
    /// user's code: errors point at the instance).
    pub library: bool,
}

impl Definition {
    /// The parameters, `let r = param(..);` at the top of the body, in the
    /// order a positional call gives them.
    pub fn params(&self) -> Vec<String> {
        self.item
            .block
            .stmts
            .iter()
            .filter_map(|s| match s {
                syn::Stmt::Local(l) => {
                    let syn::Pat::Ident(p) = &l.pat else { return None };
                    let init = l.init.as_ref()?;
                    let syn::Expr::Call(c) = &*init.expr else { return None };
                    let syn::Expr::Path(f) = &*c.func else { return None };
                    f.path.is_ident("param").then(|| p.ident.to_string())
                }
                _ => None,
            })
            .collect()
    }

    /// The function, with every token at `span` for a library part (so
    /// an error inside it points at the instance), as written otherwise.
    pub fn item_at(&self, span: Span) -> syn::ItemFn {
        if !self.library {
            return self.item.clone();
        }
        let tokens = respan(self.item.to_token_stream(), span);
        syn::parse2(tokens).unwrap_or_else(|_| self.item.clone())
    }

    /// Reads a bundle: a function, then `parts { "path" => { bundle } }`.
    pub fn parse_bundle(input: ParseStream) -> syn::Result<Definition> {
        let item: syn::ItemFn = input.parse()?;
        let keyword: syn::Ident = input.parse()?;
        if keyword != "parts" {
            return Err(syn::Error::new(keyword.span(), "expected `parts { .. }`"));
        }
        let content;
        syn::braced!(content in input);
        let mut parts = Definitions::default();
        while !content.is_empty() {
            let path: syn::LitStr = content.parse()?;
            content.parse::<syn::Token![=>]>()?;
            let inner;
            syn::braced!(inner in content);
            parts.insert(path.value(), Definition::parse_bundle(&inner)?);
        }
        Ok(Definition { item, parts: Rc::new(parts), library: false })
    }

    /// The bundle `parse_bundle` reads.
    pub fn bundle(&self) -> TokenStream {
        let item = &self.item;
        let parts = self.parts.by_path.iter().map(|(path, d)| {
            let inner = d.bundle();
            quote!(#path => { #inner })
        });
        quote!(#item parts { #(#parts)* })
    }
}

/// Parts by the path a body calls them by.
#[derive(Default)]
pub struct Definitions {
    by_path: Vec<(String, Rc<Definition>)>,
}

impl Definitions {
    /// The standard library, parsed from its source.
    pub fn standard_library() -> Definitions {
        let file: syn::File = match syn::parse_str(LIBRARY_SOURCE) {
            Ok(file) => file,
            // The library's own tests parse it: this cannot happen in a
            // release, and a broken library is then simply empty.
            Err(_) => return Definitions::default(),
        };
        let mut library = Definitions::default();
        for item in file.items {
            if let syn::Item::Fn(item) = item {
                let name = item.sig.ident.to_string();
                let parts = Rc::new(Definitions::default());
                library.insert(name, Definition { item, parts, library: true });
            }
        }
        library
    }

    /// Adds `definition` under `path` (spaces removed: `parts::motor`).
    pub fn insert(&mut self, path: String, definition: Definition) {
        let path: String = path.chars().filter(|c| !c.is_whitespace()).collect();
        self.by_path.retain(|(p, _)| *p != path);
        self.by_path.push((path, Rc::new(definition)));
    }

    /// The part called by `path`.
    pub fn get(&self, path: &str) -> Option<Rc<Definition>> {
        self.by_path.iter().find(|(p, _)| p == path).map(|(_, d)| d.clone())
    }

    /// The paths, in the order added.
    pub fn paths(&self) -> impl Iterator<Item = &str> {
        self.by_path.iter().map(|(p, _)| p.as_str())
    }
}

/// `tokens` with every span set to `span`.
fn respan(tokens: TokenStream, span: Span) -> TokenStream {
    tokens
        .into_iter()
        .map(|t| match t {
            TokenTree::Group(g) => {
                let mut out = Group::new(g.delimiter(), respan(g.stream(), span));
                out.set_span(span);
                TokenTree::Group(out)
            }
            mut other => {
                other.set_span(span);
                other
            }
        })
        .collect()
}

/// The path of a call's function as the lookup key: `resistor`,
/// `parts::motor`.
pub fn path_text(path: &syn::Path) -> String {
    path.to_token_stream().to_string().chars().filter(|c| !c.is_whitespace()).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_library_parses_and_every_part_checks() {
        let library = Definitions::standard_library();
        let written = LIBRARY_SOURCE.lines().filter(|l| l.starts_with("fn ")).count();
        assert_eq!(library.paths().count(), written);
        for path in library.paths() {
            let mut cx = crate::front::ctxt::Ctxt::default();
            let part = library.get(path).expect("listed");
            let missing =
                crate::front::lower::check_component::<crate::mechanics::Scene>(&mut cx, part);
            assert!(
                cx.is_ok() && missing.is_empty(),
                "{path}: {:?}, {} parts missing",
                cx.messages(),
                missing.len()
            );
        }
    }

    #[test]
    fn a_bundle_reads_back_as_written() {
        let item: syn::ItemFn = syn::parse_quote! {
            fn motor() { let r = param(1.0); let k = param(0.1); let p = pin(); }
        };
        let inner: syn::ItemFn = syn::parse_quote! { fn rotor() { let j = param(2.0); } };
        let mut parts = Definitions::default();
        parts.insert(
            "parts :: rotor".into(),
            Definition { item: inner, parts: Rc::default(), library: false },
        );
        let definition = Definition { item, parts: Rc::new(parts), library: false };
        let tokens = definition.bundle();
        let read = syn::parse::Parser::parse2(Definition::parse_bundle, tokens.clone()).unwrap();
        assert_eq!(read.bundle().to_string(), tokens.to_string());
        assert_eq!(read.params(), ["r", "k"]);
        assert!(read.parts.get("parts::rotor").is_some());
    }
}
