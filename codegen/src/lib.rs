//! `daegen-codegen`: daegen's symbolic engine, a plain library that the
//! `#[dae_model]` macro calls and that tests use directly.
//!
//! The pipeline is [`pipeline::analyse`], one function that runs every
//! stage in order and returns the analysed model; [`expand_dae_model`]
//! emits it (and [`diagnostics`] reports its errors):
//!
//! 1. attributes (`front/attributes`): what the model asks to generate;
//! 2. lower (`front/lower/`): the function read as the model language into
//!    the model IR ([`front::ir::ModelIr`]); scenes of bodies and joints
//!    through `mechanics/`;
//! 3. structure (`dae/structure`): each state's order, derivative-free
//!    combinations, index reduction;
//! 4. reduce (`dae/reduce`): the unknowns solved block by block into the
//!    first-order system ([`dae::system::FirstOrder`]);
//! 5. variational (`dae/variational`): forward sensitivities, a system of
//!    their own;
//! 6. mass form (`dae/mass_form`): `M w' = F(t, w)` for RADAU5;
//! 7. Taylor (`taylor/analysis`): the economic scheme, the AD tape, the
//!    unrolled jets;
//! 8. projection levels (`dae/constraints`);
//! 9. programs (`programs/`): each generated item's straight-line
//!    programs ([`Program`]), with the derivatives they need, common
//!    subexpressions shared;
//!
//! then `emit/` prints each item of the model as Rust tokens.
//!
//! Under all of them, `expr/`: [`Graph`], a hash-consed DAG of canonical
//! nodes with exact rational constants whose constructors simplify without
//! changing values, with forward-mode differentiation, substitution and
//! evaluation.
//!
//! ```
//! use daegen_codegen::{Graph, emit_program};
//! use proc_macro2::Literal;
//! use quote::quote;
//!
//! let mut g = Graph::new();
//! let x = g.time("x")?;
//! let y = g.state("y")?;
//! let f = g.parse("x*y + x")?;                 // y' = x y + x (course notes, Example 1.4)
//! let ys = g.as_symbol(y).unwrap();
//! let dfdy = g.partial(f, ys)?;
//! assert_eq!(g.show(dfdy).to_string(), "x");
//! let program = g.schedule(&[f, dfdy]);
//! let code = emit_program(&g, &program, &|s| if s == ys { quote!(y) } else { quote!(x) },
//!     &|i, v| { let i = Literal::usize_unsuffixed(i); quote!(out[#i] = #v;) });
//! assert_eq!(code.to_string(), "out [0] = x + x * y ; out [1] = x ;");
//! # let _ = x;
//! # Ok::<(), daegen_codegen::Error>(())
//! ```

// The symbolic kernels index several arrays by one position (y, f, scale, …):
// an index loop says so more plainly than zipped iterators.
#![allow(clippy::needless_range_loop)]
#![warn(missing_docs)]

pub mod analysis;
pub mod dae;
pub mod emit;
mod error;
pub mod expr;
pub mod front;
pub mod mechanics;
pub mod parts;
pub mod pipeline;
pub mod programs;
mod recorded;
pub mod taylor;
mod verify;

pub use emit::program::{emit_program, token_count};
pub use error::{Error, Result};
pub use expr::diff::VectorField;
pub use expr::display::Show;
pub use expr::graph::{FxHashMap, Graph};
pub use expr::jacobian::SparseJacobian;
pub use expr::node::{sign, Func, Id, Node, Symbol, SymbolId, SymbolKind};
pub use expr::number::{pow_f64, Number};
pub use expr::rational::Rational;
pub use programs::schedule::{Program, Temp, MAX_INLINE_DEPTH};
pub use taylor::economic::economic_taylor_derivatives;

use front::components::definitions::Definitions;
use front::ctxt::Ctxt;
use proc_macro2::TokenStream;

/// Expands `#[dae_model(attr)] item`: the pipeline's analysed model as
/// tokens, or on any error the errors plus a stub of the type, so the user
/// sees one error per mistake and the rest of their code still
/// type-checks.
pub fn expand_dae_model(attr: TokenStream, item: TokenStream) -> TokenStream {
    match expand_model_with(attr.clone(), item.clone(), Definitions::default()) {
        parts::Expansion::Done(tokens) => tokens,
        parts::Expansion::Fetch(missing) => match syn::parse2::<syn::ItemFn>(item) {
            Ok(item) => parts::fetch_for_model(attr, &item, &Definitions::default(), missing),
            Err(e) => e.to_compile_error(),
        },
    }
}

/// `#[dae_model]` with the user's components `parts` callable: the
/// model's tokens, or the parts it calls that `parts` lacks.
pub(crate) fn expand_model_with(
    attr: TokenStream,
    item: TokenStream,
    parts: Definitions,
) -> parts::Expansion {
    let mut cx = Ctxt::default();
    let item: syn::ItemFn = match syn::parse2(item) {
        Ok(item) => item,
        Err(e) => {
            return parts::Expansion::Done(
                syn::Error::new(
                    e.span(),
                    "`#[dae_model]` goes on a function: `fn pendulum() { ... }`",
                )
                .to_compile_error(),
            )
        }
    };
    match expand_or_report(&mut cx, attr.clone(), &item, parts) {
        Ok(tokens) => {
            // Nothing, unless a mistake was reported beside a model that
            // expanded (a warning's error).
            let mut out = cx.into_compile_errors();
            if out.is_empty() {
                recorded::record(&attr, &item, &tokens);
            }
            out.extend(tokens);
            parts::Expansion::Done(out)
        }
        Err(ir) if !ir.missing_parts.is_empty() => {
            // Found again once the parts arrive.
            cx.abandon();
            parts::Expansion::Fetch(ir.missing_parts)
        }
        Err(ir) => {
            let mut out = cx.into_compile_errors();
            out.extend(emit::model::stub(&ir));
            parts::Expansion::Done(out)
        }
    }
}

/// `#[component] fn part() { .. }`: a component of the model language,
/// checked, and the `macro_rules!` that hands it to the models that call
/// it (see [`parts`]).
pub fn expand_component(attr: TokenStream, item: TokenStream) -> TokenStream {
    parts::expand_component(attr, item)
}

/// The callback of a fetch of the user's components (see [`parts`]).
pub fn expand_parts(input: TokenStream) -> TokenStream {
    parts::expand_parts(input)
}

/// The errors `expand_dae_model` would report, as messages: for tests of
/// diagnostics without compiling a macro.
pub fn diagnostics(item: TokenStream) -> Vec<String> {
    let mut cx = Ctxt::default();
    let Ok(item) = syn::parse2::<syn::ItemFn>(item) else {
        return vec!["not a function".to_string()];
    };
    let _ = expand_or_report(&mut cx, TokenStream::new(), &item, Definitions::default());
    cx.into_messages()
}

/// The pipeline, then emission; every error reported to `cx` on the
/// user's tokens, with the IR as far as it got.
/// The most generated code (bytes of its text) a scene in body
/// coordinates may have unless `scene = global` is written out: a chain
/// of five revolute joints makes about 2 MB, and a UR5 arm made 5.8 MB
/// that rustc compiled for six minutes, where joint coordinates
/// makes 0.2 MB.
pub const BODY_COORDINATES_LIMIT: usize = 2_000_000;

/// The size in megabytes of `tokens` when it passes [`BODY_COORDINATES_LIMIT`].
fn too_large(tokens: &TokenStream) -> Option<f64> {
    let bytes = tokens.to_string().len();
    (bytes > BODY_COORDINATES_LIMIT).then_some(bytes as f64 / 1e6)
}

fn expand_or_report(
    cx: &mut Ctxt,
    attr: TokenStream,
    item: &syn::ItemFn,
    parts: Definitions,
) -> std::result::Result<TokenStream, Box<front::ir::ModelIr>> {
    let model = pipeline::analyse_with_parts(cx, attr, item, parts)?;
    let mut tokens = emit::model::expand(&model);
    if model.ir.body_coordinates && !model.attributes.global_written {
        if let Some(megabytes) = too_large(&tokens) {
            cx.error_at(&item.sig.ident, format!("in body coordinates this scene generates {megabytes:.1} MB of code, more than the {} MB rustc compiles in reasonable time: write `#[dae_model(scene = recursive)]` to use joint coordinates (or `scene = global` to keep body coordinates anyway)", BODY_COORDINATES_LIMIT / 1_000_000));
            return Err(Box::new(model.ir));
        }
    }
    let (ir, attributes) = (&model.ir, &model.attributes);
    tokens.extend(emit::benchmark::benchmark_impl(item, ir, attributes));
    tokens.extend(front::warnings::odd_unrolled_orders(&attributes.odd_unrolled));
    Ok(tokens)
}
