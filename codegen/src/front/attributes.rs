//! The arguments of `#[dae_model(...)]`: what to generate besides the
//! model (Taylor code, the scene formulation, a benchmark).

use crate::front::ctxt::Ctxt;
use proc_macro2::TokenStream;

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
    /// to emit as straight-line code (see `taylor::unrolled`).
    pub unroll: Vec<usize>,
    /// The odd orders of `unroll`, where they were written: `Method::Taylor`
    /// never picks them (see `warnings`).
    pub odd_unrolled: Vec<(usize, proc_macro2::Span)>,
    /// `scene = recursive`: a scene in relative joint coordinates (the
    /// default, `scene = global`, keeps each body's coordinates).
    pub recursive: bool,
    /// `scene = global` written out: body coordinates however much code
    /// they make (else a large scene in them is refused).
    pub global_written: bool,
    /// `bench = Bench::until(t1)...`: the model's benchmark problem; the
    /// model then implements `daegen::runtime::bench::Benchmark`.
    pub bench: Option<syn::Expr>,
    /// `batch = L`, 2 ≤ L ≤ 16: also the type `<Model>Batch` stepping L
    /// members together; where the argument was written.
    pub batch: Option<(usize, proc_macro2::Span)>,
    /// `sensitivities = [k, init(x)]`: the parameters and initial values
    /// to generate forward sensitivities for, as written.
    pub sensitivities: Vec<syn::Expr>,
    /// Set when expanding `<Model>Sensitivities` itself: its number of
    /// sensitivity columns (`Model::SENSITIVITY_COLUMNS`).
    pub sensitivity_columns: usize,
    /// The other arguments, as written (for re-expanding the model when the
    /// benchmark times its expansion).
    pub written: String,
}

/// Reads `#[dae_model]`, `#[dae_model(taylor = p)]`, `#[dae_model(unroll = [14, 18])]`
/// or both (only what is asked for is generated).
pub fn attributes(cx: &mut Ctxt, attr: TokenStream) -> Attributes {
    let mut out = Attributes::default();
    if attr.is_empty() {
        return out;
    }
    let fix = "`#[dae_model]` takes `taylor = p` (p from 0 to 8), `unroll = [p, ...]` (orders from 2 to 40), `scene = global` or `scene = recursive`, `batch = L` (members stepped together, 2 to 16), `sensitivities = [k, init(x)]`, and `bench = Bench::until(t1)...`";
    let parser =
        syn::punctuated::Punctuated::<syn::MetaNameValue, syn::Token![,]>::parse_terminated;
    let Ok(args) = syn::parse::Parser::parse2(parser, attr.clone()) else {
        cx.error_at(&attr, fix);
        return out;
    };
    let integer = |e: &syn::Expr| match e {
        syn::Expr::Lit(syn::ExprLit { lit: syn::Lit::Int(i), .. }) => {
            i.base10_parse::<usize>().ok()
        }
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
                syn::Expr::Array(a) if !a.elems.is_empty() => {
                    a.elems.iter().map(|e| integer(e).filter(|p| (2..=40).contains(p))).collect()
                }
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
        } else if arg.path.is_ident("batch") && out.batch.is_none() {
            match integer(&arg.value) {
                Some(l) if (2..=16).contains(&l) => {
                    out.batch = Some((l, syn::spanned::Spanned::span(&arg.value)))
                }
                _ => cx.error_at(
                    &arg.value,
                    "`batch = L` takes the number of members stepped together, from 2 to 16 (4 or 8 fill a SIMD register)",
                ),
            }
        } else if arg.path.is_ident("sensitivities") && out.sensitivities.is_empty() {
            match &arg.value {
                syn::Expr::Array(a) if !a.elems.is_empty() => {
                    out.sensitivities = a.elems.iter().cloned().collect();
                }
                other => cx.error_at(
                    other,
                    "`sensitivities` takes a list of parameters and initial values, e.g. `sensitivities = [k, init(x)]`",
                ),
            }
        } else if arg.path.is_ident("scene") {
            match &arg.value {
                syn::Expr::Path(p) if p.path.is_ident("recursive") => out.recursive = true,
                syn::Expr::Path(p) if p.path.is_ident("global") => {
                    out.recursive = false;
                    out.global_written = true;
                }
                other => cx.error_at(other, "`scene` is `global` (each body free, joints as constraints; the default) or `recursive` (relative joint coordinates on a spanning tree)"),
            }
        } else {
            cx.error_at(arg, fix);
        }
        if !out.written.is_empty() {
            out.written.push_str(", ");
        }
        out.written.push_str(&quote::ToTokens::to_token_stream(arg).to_string());
    }
    out
}
