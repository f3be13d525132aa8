//! Expansion: the generated struct, its `Default`, and its `daegen::Model`
//! implementation. The last step; everything it needs was decided before.

use crate::dae::reduce::{FirstOrder, SlotDerivative};
use crate::front::ir::{EventDirection, ModelIr};
use crate::front::names::upper_camel_case;
use crate::{emit_program, Graph, Id, SymbolId, SymbolKind};
use proc_macro2::{Literal, TokenStream};
use quote::{format_ident, quote, quote_spanned};

/// How generated code reads each symbol: states from `y`, parameters from
/// `self`, time from `t`.
struct Layout {
    slot_of: crate::FxHashMap<SymbolId, usize>,
    /// Unknowns solved at run time, read after the solve: symbol -> (block, row).
    block_of: crate::FxHashMap<SymbolId, (usize, usize)>,
    /// Taylor coefficients read by higher orders: symbol -> index in `out`.
    taylor_of: crate::FxHashMap<SymbolId, usize>,
}

impl Layout {
    /// Component `i` of the state read as `y[i]`.
    fn of_components(components: &[SymbolId]) -> Layout {
        Layout {
            slot_of: components
                .iter()
                .enumerate()
                .map(|(i, &s)| (s, i))
                .collect(),
            block_of: Default::default(),
            taylor_of: Default::default(),
        }
    }

    fn tokens(&self, g: &Graph, s: SymbolId) -> TokenStream {
        if let Some(&i) = self.slot_of.get(&s) {
            let i = Literal::usize_unsuffixed(i);
            return quote!(y[#i]);
        }
        if let Some(&i) = self.taylor_of.get(&s) {
            let i = Literal::usize_unsuffixed(i);
            return quote!(out[#i]);
        }
        if let Some(&(b, row)) = self.block_of.get(&s) {
            let (gv, row) = (format_ident!("rhs{}", b), Literal::usize_unsuffixed(row));
            return quote!(#gv[#row]);
        }
        match g.symbol(s).kind {
            SymbolKind::Parameter => {
                let field = format_ident!("{}", g.symbol(s).name);
                quote!(self.#field)
            }
            SymbolKind::Time => quote!(t),
            // Reduction replaced every other symbol; NaN would surface at run time.
            _ => quote!(f64::NAN),
        }
    }
}

/// The right-hand side of an explicit ODE, slot by slot: what the Taylor
/// methods differentiate. `Err` for a model that solves a mass matrix at
/// run time.
fn explicit_rhs(sys: &FirstOrder) -> crate::Result<Vec<Id>> {
    if sys.newton.is_some() {
        return Err(crate::Error::Unsupported {
            message: "`taylor = p` needs an explicit ODE; this model solves nonlinear algebraic equations by Newton's method at each evaluation".into(),
        });
    }
    sys.derivatives
        .iter()
        .map(|d| match d {
            SlotDerivative::Explicit(e) => Ok(*e),
            SlotDerivative::Block { .. } | SlotDerivative::AfterSolve(_) => {
                Err(crate::Error::Unsupported {
                    message: "`taylor = p` needs an explicit ODE; this model solves a linear system of more than three coupled unknowns at run time (its mass matrix, or the constraint block of a mechanism), so its derivatives have no closed form".into(),
                })
            }
        })
        .collect()
}

/// Why the Taylor tape could not be made, as a clause after "because":
/// the compile-time error's own reason without its fix (which speaks of a
/// `taylor = p` the user did not write).
fn taylor_refusal(e: &crate::Error) -> String {
    let text = match e {
        crate::Error::Unsupported { message } => message.clone(),
        other => other.to_string(),
    };
    let reason = text.split(": remove").next().unwrap_or(&text);
    let reason = reason
        .split("; this model")
        .nth(1)
        .map_or(reason.to_string(), |r| format!("the model{}", r));
    reason.replace(
        "`taylor = p` needs an explicit ODE",
        "the model is no explicit ODE",
    )
}

/// `TAYLOR_ORDER` and `taylor_derivatives`: D_1 = f and D_{k+1} the total
/// time derivative of D_k (course notes §1.3.1), where the k-th derivative
/// of slot i is a fresh symbol read from `out` (`der` of a slot would alias
/// the other slots of a reduced higher-order state). One program per order,
/// each reading the lower orders already written.
fn economic_taylor(
    g: &mut Graph,
    layout: &mut Layout,
    sys: &FirstOrder,
    time: SymbolId,
    f: Vec<Id>,
    order: usize,
) -> crate::Result<TokenStream> {
    let n = sys.slots.len();
    let mut field = crate::VectorField::new();
    let one = g.one();
    field.set(time, one);
    let mut symbols: Vec<Vec<SymbolId>> = vec![Vec::with_capacity(order); n];
    for (i, slot) in sys.slots.iter().enumerate() {
        for j in 1..=order {
            let id = g.add_symbol(&format!("__taylor{j}_{i}"), SymbolKind::Algebraic)?;
            let s = g.as_symbol(id).unwrap_or(slot.symbol);
            symbols[i].push(s);
            layout.taylor_of.insert(s, (j - 1) * n + i);
        }
        let first = g.symbol_node(symbols[i][0]);
        field.set(slot.symbol, first);
        for j in 0..order.saturating_sub(1) {
            let next = g.symbol_node(symbols[i][j + 1]);
            field.set(symbols[i][j], next);
        }
    }
    let mut levels = vec![f];
    while levels.len() < order {
        let last = levels[levels.len() - 1].clone();
        let next = last
            .iter()
            .map(|&e| g.total_derivative(e, &mut field))
            .collect::<crate::Result<Vec<_>>>()?;
        levels.push(next);
    }
    let mut body = TokenStream::new();
    for (k, level) in levels.iter().enumerate() {
        let code = program(g, layout, level, &|i, v| {
            let at = index(k * n + i);
            quote!(out[#at] = #v;)
        });
        let k1 = index(k + 1);
        body.extend(quote!(if order >= #k1 { #code }));
    }
    let (nn, np, p) = (index(n), index(n * order), index(order));
    Ok(quote! {
        const TAYLOR_ORDER: usize = #p;

        #[inline]
        fn taylor_derivatives(&self, t: f64, y: &[f64], order: usize, out: &mut [f64]) -> ::core::result::Result<(), ::daegen::EvalError> {
            let (::core::result::Result::Ok(y), ::core::result::Result::Ok(out)) =
                (<&[f64; #nn]>::try_from(y), <&mut [f64; #np]>::try_from(out))
            else {
                return ::core::result::Result::Ok(());
            };
            #body
            ::core::result::Result::Ok(())
        }
    })
}

/// `taylor_tape`, the AD tape of the adaptive Taylor method (compact
/// layout, interpreted at run time), and the straight-line jets of the
/// orders in `unroll`.
fn taylor_tape_items(
    g: &mut Graph,
    layout: &Layout,
    sys: &FirstOrder,
    time: SymbolId,
    f: &[Id],
    unroll: &[usize],
) -> crate::Result<TokenStream> {
    let n = sys.slots.len();
    let nn = index(n);
    // The AD tape for the adaptive Taylor method (compact layout).
    let slot_of = layout.slot_of.clone();
    let explicit: Vec<Id> = f.to_vec();
    let negations = crate::taylor::tape::negated_sums(g, &explicit)?;
    let tape = crate::taylor::tape::decompose(g, &explicit, &slot_of, time, &negations)?;
    let consts: Vec<Id> = tape
        .constants
        .iter()
        .map(|c| match c {
            crate::taylor::tape::Constant::Expr(id) => Ok(*id),
            crate::taylor::tape::Constant::Integer(n) => Ok(g.int(*n)),
            crate::taylor::tape::Constant::Product(factors) => g.product(factors),
            crate::taylor::tape::Constant::Sum(terms) => g.sum(terms),
        })
        .collect::<crate::Result<_>>()?;
    let const_code = program(g, layout, &consts, &|i, v| {
        let name = quote::format_ident!("c{}", i);
        quote!(let #name: f64 = #v;)
    });
    let (ops, outs) = (&tape.ops, &tape.outputs);
    // The unrolled layout, for the orders the user asked for.
    let numbers: Vec<Option<f64>> = consts
        .iter()
        .map(|&id| g.as_number(id).map(|x| x.to_f64()))
        .collect();
    let jets: Vec<_> = unroll
        .iter()
        .map(|&order| {
            (
                order,
                crate::taylor::unrolled::unrolled_jet(&tape, n, order, &numbers),
            )
        })
        .collect();
    let jet_lengths = jets.iter().map(|(order, jet)| {
        let (order, buffer) = (index(*order), index(jet.buffer));
        quote!(#order => #buffer,)
    });
    let unrolled_arms = jets.iter().map(|(order, jet)| {
        let body = &jet.body;
        let (order_lit, len) = (index(*order), index(jet.buffer));
        quote! {
            #order_lit => {
                let ::core::option::Option::Some(out) = out.get_mut(..#len) else { return false };
                let (::core::result::Result::Ok(y), ::core::result::Result::Ok(out)) =
                    (<&[f64; #nn]>::try_from(y), <&mut [f64; #len]>::try_from(out)) else { return false };
                #const_code
                #body
                true
            }
        }
    });
    let unrolled_orders = unroll.iter().map(|&o| index(o));
    let by_coefficient: Vec<_> = jets
        .iter()
        .filter(|(_, jet)| jet.by_coefficient)
        .map(|(order, _)| index(*order))
        .collect();
    let by_coefficient = if by_coefficient.is_empty() {
        TokenStream::new()
    } else {
        quote! {
            fn taylor_jet_by_coefficient(&self, order: usize) -> bool {
                matches!(order, #(#by_coefficient)|*)
            }
        }
    };
    let unrolled = if unroll.is_empty() {
        TokenStream::new()
    } else {
        quote! {
            const TAYLOR_UNROLLED: &'static [usize] = &[#(#unrolled_orders),*];

            fn taylor_jet_len(&self, order: usize) -> usize {
                match order {
                    #(#jet_lengths)*
                    _ => #nn * (order + 1),
                }
            }

            #by_coefficient

            #[allow(clippy::all)]
            fn taylor_jet_unrolled(&self, t: f64, y: &[f64], order: usize, out: &mut [f64]) -> bool {
                match order {
                    #(#unrolled_arms)*
                    _ => false,
                }
            }
        }
    };
    Ok(quote! {
        #unrolled

        #[inline]
        fn taylor_tape(&self) -> ::core::option::Option<(
            ::std::vec::Vec<::daegen::runtime::taylor_tape::TapeOp>,
            ::std::vec::Vec<::daegen::runtime::taylor_tape::Operand>,
        )> {
            // Short names: a large model's tape runs to thousands of operations.
            #[allow(unused_imports)]
            use ::daegen::runtime::taylor_tape::{Inverse as I, Operand as O, TapeOp as T};
            #const_code
            ::core::option::Option::Some((::std::vec![#(#ops),*], ::std::vec![#(#outs),*]))
        }
    })
}

/// A doc comment as rustdoc writes `///` lines: each line after a space.
fn doc_attr(text: &str) -> String {
    text.lines()
        .map(|l| format!(" {l}"))
        .collect::<Vec<_>>()
        .join("\n")
}

/// The body of a method that reads `y` (`n` states) and writes the slice
/// `out` (`len` entries): both become arrays first, so every index in `code`
/// is checked at compile time and the method cannot panic. The runtime
/// always passes the right lengths; were it not to, nothing is written.
fn fixed_size_body(n: &Literal, out: &str, len: &Literal, code: TokenStream) -> TokenStream {
    let out = format_ident!("{}", out);
    quote! {
        let (::core::result::Result::Ok(y), ::core::result::Result::Ok(#out)) =
            (<&[f64; #n]>::try_from(y), <&mut [f64; #len]>::try_from(#out))
        else {
            return ::core::result::Result::Ok(());
        };
        #code
        ::core::result::Result::Ok(())
    }
}

fn index(i: usize) -> Literal {
    Literal::usize_unsuffixed(i)
}

/// Straight-line code computing `outputs` and handing each to `assign`.
fn program(
    g: &mut Graph,
    layout: &Layout,
    outputs: &[Id],
    assign: &dyn Fn(usize, TokenStream) -> TokenStream,
) -> TokenStream {
    let program = g.schedule(outputs);
    let g = &*g;
    emit_program(g, &program, &|s| layout.tokens(g, s), assign)
}

/// The Newton block (see `newton_block`): an inherent method that solves
/// its equations for its variables, warm-started from the last solution on
/// this thread (else from the guesses), and the statements that call it in
/// `rhs` (an error on failure) and in `output` (NaN). Empty for a model
/// without one.
fn newton_block_code(
    g: &mut Graph,
    layout: &Layout,
    sys: &FirstOrder,
    name: &syn::Ident,
) -> (TokenStream, TokenStream, TokenStream) {
    let Some(newton) = &sys.newton else {
        return (TokenStream::new(), TokenStream::new(), TokenStream::new());
    };
    let k = newton.unknowns.len();
    let (kk, n) = (index(k), index(sys.slots.len()));
    let array = format_ident!("rhs{}", sys.blocks.len());
    // Residuals and ∂g/∂z, sharing their subexpressions.
    let mut values = newton.residuals.clone();
    let mut targets: Vec<TokenStream> = (0..k)
        .map(|i| {
            let i = index(i);
            quote!(residual[#i])
        })
        .collect();
    for (i, &r) in newton.residuals.iter().enumerate() {
        for (j, &z) in newton.unknowns.iter().enumerate() {
            let Ok(d) = g.partial(r, z) else { continue };
            if g.as_number(d).is_some_and(|v| v.is_zero()) {
                continue;
            }
            values.push(d);
            let (i, j) = (index(i), index(j));
            targets.push(quote!(jacobian[#i][#j]));
        }
    }
    let body = program(g, layout, &values, &|i, v| {
        let target = &targets[i];
        quote!(#target = #v;)
    });
    let guesses = program(g, layout, &newton.guesses, &|i, v| {
        let i = index(i);
        quote!(guess[#i] = #v;)
    });
    let (texts, names) = (&newton.texts, &newton.names);
    let method = quote! {
        #[allow(unused_variables, clippy::all, clippy::pedantic)]
        impl #name {
            /// The model's nonlinear algebraic equations solved by Newton's
            /// method at `(t, y)` (generated by `#[dae_model]`).
            #[doc(hidden)]
            fn __daegen_algebraics(&self, t: f64, y: &[f64; #n]) -> ::core::result::Result<[f64; #kk], ::daegen::EvalError> {
                ::std::thread_local! {
                    static LAST: ::core::cell::Cell<::core::option::Option<[f64; #kk]>> =
                        const { ::core::cell::Cell::new(::core::option::Option::None) };
                }
                let eval = |#array: &[f64; #kk], residual: &mut [f64; #kk], jacobian: &mut [[f64; #kk]; #kk]| {
                    *jacobian = [[0.0f64; #kk]; #kk];
                    #body
                };
                let mut guess = [0.0f64; #kk];
                #guesses
                let solved = match LAST.with(|last| last.get()) {
                    ::core::option::Option::Some(last) => {
                        ::daegen::runtime::algebraic::newton(last, eval)
                            .or_else(|_| ::daegen::runtime::algebraic::newton(guess, eval))
                    }
                    ::core::option::Option::None => ::daegen::runtime::algebraic::newton(guess, eval),
                };
                match solved {
                    ::core::result::Result::Ok(z) => {
                        LAST.with(|last| last.set(::core::option::Option::Some(z)));
                        ::core::result::Result::Ok(z)
                    }
                    ::core::result::Result::Err(trouble) => ::core::result::Result::Err(::daegen::EvalError::NonlinearAlgebraic {
                        equations: ::std::vec![#(#texts),*],
                        unknowns: ::std::vec![#(#names),*],
                        singular: trouble == ::daegen::runtime::algebraic::AlgebraicTrouble::Singular,
                    }),
                }
            }
        }
    };
    let solve = quote!(let #array = self.__daegen_algebraics(t, y)?;);
    let for_outputs = quote! {
        let ::core::result::Result::Ok(#array) = self.__daegen_algebraics(t, y) else { return f64::NAN };
    };
    (method, solve, for_outputs)
}

/// Assembles and solves every run-time block into `rhs{b}` arrays, running
/// `on_singular` when one is singular.
fn block_solve_code(
    g: &mut Graph,
    layout: &Layout,
    sys: &FirstOrder,
    on_singular: TokenStream,
) -> TokenStream {
    let mut entries = Vec::new();
    let mut targets: Vec<TokenStream> = Vec::new();
    let mut setup = TokenStream::new();
    let mut solve = TokenStream::new();
    for (b, block) in sys.blocks.iter().enumerate() {
        let k = block.rhs.len();
        let (m, gv, kk) = (
            format_ident!("mass{}", b),
            format_ident!("rhs{}", b),
            index(k),
        );
        setup.extend(quote!(let mut #m = [[0.0f64; #kk]; #kk]; let mut #gv = [0.0f64; #kk];));
        for (r, &e) in block.rhs.iter().enumerate() {
            let rl = index(r);
            if !g.as_number(e).is_some_and(|v| v.is_zero()) {
                entries.push(e);
                targets.push(quote!(#gv[#rl]));
            }
            for c in 0..k {
                let entry = block.matrix[r * k + c];
                if g.as_number(entry).is_some_and(|v| v.is_zero()) {
                    continue;
                }
                entries.push(entry);
                let cl = index(c);
                targets.push(quote!(#m[#rl][#cl]));
            }
        }
        solve.extend(quote! {
            if !::daegen::runtime::linalg::solve_in_place(&mut #m, &mut #gv) {
                #on_singular;
            }
        });
    }
    let code = program(g, layout, &entries, &|i, v| {
        let target = &targets[i];
        quote!(#target = #v;)
    });
    quote!(#setup #code #solve)
}

/// What index reduction found, for the generated type's documentation:
/// the index, each differentiated equation and how often, the algebraic
/// variables. Empty for an ODE.
fn dae_analysis(ir: &ModelIr, sys: &FirstOrder) -> String {
    if sys.index == 0 && ir.algebraics.is_empty() {
        return String::new();
    }
    let mut lines = vec![format!(
        "DAE of differentiation index {} (found at compile time).",
        sys.index
    )];
    for (e, combines) in &sys.combined {
        let texts: Vec<String> = combines
            .iter()
            .map(|&i| {
                format!(
                    "`{}`",
                    crate::front::names::source_text(&ir.equations[i].origin)
                )
            })
            .collect();
        lines.push(format!(
            "- The highest derivatives cancel in a combination of {}: it stands in for `{}` as an equation without them.",
            texts.join(" and "),
            crate::front::names::source_text(&ir.equations[*e].origin)
        ));
    }
    for (e, &d) in sys.differentiations.iter().enumerate() {
        if d > 0 {
            let times = if d == 1 {
                "once".to_string()
            } else {
                format!("{d} times")
            };
            let what = if sys.combined.iter().any(|(c, _)| *c == e) {
                "The combination standing in for "
            } else {
                ""
            };
            lines.push(format!(
                "- {what}`{}` is differentiated {times}; it and its derivatives below the last are projected onto after each step.",
                crate::front::names::source_text(&ir.equations[e].origin)
            ));
        }
    }
    if !ir.algebraics.is_empty() {
        let names: Vec<String> = ir
            .algebraics
            .iter()
            .map(|a| format!("`{}`", a.name))
            .collect();
        lines.push(format!("- Algebraic variables: {}.", names.join(", ")));
    }
    if sys.mass_only {
        lines.push("- An algebraic equation is nonlinear in the algebraic variables: the model is integrated in its mass-matrix form by RADAU5.".into());
    }
    if let Some(newton) = &sys.newton {
        let names: Vec<String> = newton.names.iter().map(|n| format!("`{n}`")).collect();
        let (verb, pronoun) = if names.len() == 1 {
            ("enters its equation", "it")
        } else {
            ("enter their equations", "them")
        };
        lines.push(format!(
            "- {} {verb} nonlinearly: Newton's method solves for {pronoun} at each evaluation (with the generated Jacobian, from the last solution).",
            names.join(", ")
        ));
    }
    lines.join("\n")
}

/// The generated type's name.
pub fn type_name(ir: &ModelIr) -> syn::Ident {
    syn::Ident::new(
        &upper_camel_case(&ir.fn_name.to_string()),
        ir.fn_name.span(),
    )
}

/// The struct with one `pub f64` per parameter, and its `Default`.
fn struct_and_default(ir: &ModelIr, analysis: &str) -> TokenStream {
    let name = type_name(ir);
    let vis = &ir.vis;
    let mut doc = if ir.doc.is_empty() {
        format!("The model `{}`, generated by `#[dae_model]`.", ir.fn_name)
    } else {
        ir.doc.clone()
    };
    if !analysis.is_empty() {
        doc = format!("{doc}\n\n{analysis}");
    }
    let doc = doc_attr(&doc);
    let fields = ir.params.iter().map(|p| {
        let (ident, doc) = (&p.ident, &p.doc);
        let doc = doc_attr(&if doc.is_empty() {
            format!("Parameter `{ident}`.")
        } else {
            doc.clone()
        });
        quote!(#[doc = #doc] pub #ident: f64)
    });
    let defaults = ir.params.iter().map(|p| {
        let ident = &p.ident;
        let v = Literal::f64_unsuffixed(if p.default.is_finite() {
            p.default
        } else {
            0.0
        });
        quote!(#ident: #v)
    });
    quote! {
        #[doc = #doc]
        #[derive(Clone, Copy, Debug, PartialEq)]
        #vis struct #name { #(#fields,)* }

        impl ::core::default::Default for #name {
            fn default() -> Self {
                Self { #(#defaults,)* }
            }
        }
    }
}

/// The full expansion of a model that lowered and reduced without error.
pub fn expand(
    ir: &mut ModelIr,
    sys: &FirstOrder,
    attributes: &crate::front::attributes::Attributes,
) -> crate::Result<TokenStream> {
    // `unroll` alone implies the Taylor tape (and the first-order scheme).
    let taylor = match (attributes.taylor, attributes.unroll.is_empty()) {
        (None, false) => Some(1),
        (t, _) => t,
    };
    let name = type_name(ir);
    if sys.mass_only {
        return expand_mass_only(ir, sys);
    }
    let n = sys.slots.len();
    let slot_of = sys
        .slots
        .iter()
        .enumerate()
        .map(|(i, s)| (s.symbol, i))
        .collect();
    let mut layout = Layout {
        slot_of,
        block_of: Default::default(),
        taylor_of: Default::default(),
    };
    // The Newton block's variables are known throughout the right-hand
    // side, read from the array its solve returns.
    if let Some(newton) = &sys.newton {
        for (k, &s) in newton.unknowns.iter().enumerate() {
            layout.block_of.insert(s, (sys.blocks.len(), k));
        }
    }
    let (newton_method, newton_solve, newton_solve_for_outputs) =
        newton_block_code(&mut ir.graph, &layout, sys, &name);
    let g = &mut ir.graph;

    let inits: Vec<Id> = sys.slots.iter().map(|s| s.init).collect();
    let initial_state = program(g, &layout, &inits, &|i, v| {
        let i = index(i);
        quote!(y[#i] = #v;)
    });

    // Right-hand side: explicit entries, then each mass block's E and g.
    let mut outputs = Vec::new();
    let mut targets: Vec<TokenStream> = Vec::new();
    for (i, d) in sys.derivatives.iter().enumerate() {
        if let SlotDerivative::Explicit(e) = d {
            outputs.push(*e);
            let i = index(i);
            targets.push(quote!(dy[#i]));
        }
    }
    let mut block_setup = TokenStream::new();
    let mut block_solve = TokenStream::new();
    for (b, block) in sys.blocks.iter().enumerate() {
        let k = block.rhs.len();
        let (m, gv) = (format_ident!("mass{}", b), format_ident!("rhs{}", b));
        let kk = index(k);
        block_setup.extend(quote!(let mut #m = [[0.0f64; #kk]; #kk]; let mut #gv = [0.0f64; #kk];));
        // The arrays start at zero: zero entries are not written.
        let is_zero = |g: &Graph, e: Id| g.as_number(e).is_some_and(|v| v.is_zero());
        for (r, &e) in block.rhs.iter().enumerate() {
            let rl = index(r);
            if !is_zero(g, e) {
                outputs.push(e);
                targets.push(quote!(#gv[#rl]));
            }
            for c in 0..k {
                let entry = block.matrix[r * k + c];
                if is_zero(g, entry) {
                    continue;
                }
                outputs.push(entry);
                let cl = index(c);
                targets.push(quote!(#m[#rl][#cl]));
            }
        }
        let unknowns = &block.unknowns;
        block_solve.extend(quote! {
            if !::daegen::runtime::linalg::solve_in_place(&mut #m, &mut #gv) {
                return ::core::result::Result::Err(::daegen::EvalError::SingularMassMatrix {
                    unknowns: ::std::vec![#(#unknowns),*],
                });
            }
        });
    }
    for (i, d) in sys.derivatives.iter().enumerate() {
        if let SlotDerivative::Block { block, row } = d {
            let (i, gv, row) = (index(i), format_ident!("rhs{}", block), index(*row));
            block_solve.extend(quote!(dy[#i] = #gv[#row];));
        }
    }
    // Accelerations eliminated from a KKT block, from its multipliers.
    let after: Vec<(usize, Id)> = sys
        .derivatives
        .iter()
        .enumerate()
        .filter_map(|(i, d)| match d {
            SlotDerivative::AfterSolve(e) => Some((i, *e)),
            _ => None,
        })
        .collect();
    if !after.is_empty() {
        let after_layout = Layout {
            slot_of: layout.slot_of.clone(),
            block_of: sys
                .block_unknowns
                .iter()
                .map(|&(s, b, r)| (s, (b, r)))
                .collect(),
            taylor_of: Default::default(),
        };
        let ids: Vec<Id> = after.iter().map(|x| x.1).collect();
        block_solve.extend(program(g, &after_layout, &ids, &|k, v| {
            let i = index(after[k].0);
            quote!(dy[#i] = #v;)
        }));
    }
    let targets_for_rhs = targets.clone();
    let rhs_body = program(g, &layout, &outputs, &move |i, v| {
        let target = &targets_for_rhs[i];
        quote!(#target = #v;)
    });

    // Jacobian and ∂f/∂t: symbolic when every derivative is explicit in
    // the states (not through a Newton solve's variables).
    let explicit: Option<Vec<Id>> = sys
        .derivatives
        .iter()
        .map(|d| match d {
            SlotDerivative::Explicit(e) if sys.newton.is_none() => Some(*e),
            _ => None,
        })
        .collect();
    // The event functions' rates along the solution, dg/dt = ∂g/∂t + ∇g·f,
    // let the runtime find two crossings between neighbouring samples.
    let event_rates_method = match (&explicit, sys.events.is_empty()) {
        (Some(f), false) => {
            let mut field = crate::VectorField::new();
            let one = g.one();
            field.set(ir.time, one);
            for (slot, &fi) in sys.slots.iter().zip(f) {
                field.set(slot.symbol, fi);
            }
            let rates = sys
                .events
                .iter()
                .map(|&e| g.total_derivative(e, &mut field))
                .collect::<crate::error::Result<Vec<Id>>>()?;
            let (m, n_lit) = (index(rates.len()), index(n));
            let body = program(g, &layout, &rates, &|i, v| {
                let i = index(i);
                quote!(dg[#i] = #v;)
            });
            quote! {
                #[inline]
                fn event_rates(&self, t: f64, y: &[f64], dg: &mut [f64]) -> bool {
                    let (::core::result::Result::Ok(y), ::core::result::Result::Ok(dg)) =
                        (<&[f64; #n_lit]>::try_from(y), <&mut [f64; #m]>::try_from(dg)) else { return false };
                    #body
                    true
                }
            }
        }
        _ => TokenStream::new(),
    };
    let (pattern, jacobian_body, time_body) = match explicit {
        Some(f) => {
            let wrt: Vec<SymbolId> = sys.slots.iter().map(|s| s.symbol).collect();
            let j = g.jacobian(&f, &wrt)?;
            let nnz = index(j.entries.len());
            let nn = index(n);
            let pattern: Vec<TokenStream> = j
                .entries
                .iter()
                .map(|&(r, c, _)| {
                    let (r, c) = (index(r), index(c));
                    quote!((#r, #c))
                })
                .collect();
            let values = program(g, &layout, &j.expressions(), &|k, v| {
                let k = index(k);
                quote!(values[#k] = #v;)
            });
            let dfdt: Vec<Id> = f
                .iter()
                .map(|&e| g.partial(e, ir.time))
                .collect::<crate::Result<_>>()?;
            let time = program(g, &layout, &dfdt, &|i, v| {
                let i = index(i);
                quote!(dfdt[#i] = #v;)
            });
            (
                quote!(&[#(#pattern),*]),
                fixed_size_body(&nn, "values", &nnz, values),
                fixed_size_body(&nn, "dfdt", &nn, time),
            )
        }
        None => (
            quote!(&[]),
            quote!(::core::result::Result::Err(
                ::daegen::EvalError::JacobianUnavailable
            )),
            quote!(::core::result::Result::Err(
                ::daegen::EvalError::JacobianUnavailable
            )),
        ),
    };

    // Outputs, then the algebraic variables; a value that reads an unknown
    // solved at run time solves its blocks first.
    let mut observables = sys.outputs.clone();
    for a in &sys.algebraics {
        match a {
            SlotDerivative::Explicit(e) | SlotDerivative::AfterSolve(e) => observables.push(*e),
            SlotDerivative::Block { block, row } => {
                let (_, symbol) = sys
                    .block_unknowns
                    .iter()
                    .map(|&(s, b, r)| ((b, r), s))
                    .find(|&(at, _)| at == (*block, *row))
                    .ok_or_else(|| crate::Error::Unsupported {
                        message: "an algebraic variable lost its block".into(),
                    })?;
                observables.push(g.symbol_node(symbol));
            }
        }
    }
    let block_solve_for_outputs = {
        let linear = block_solve_code(g, &layout, sys, quote!(return f64::NAN));
        quote!(#newton_solve_for_outputs #linear)
    };
    layout.block_of = sys
        .block_unknowns
        .iter()
        .map(|&(s, b, r)| (s, (b, r)))
        .collect();
    let output_arms: Vec<TokenStream> = observables
        .iter()
        .enumerate()
        .map(|(k, &o)| {
            let reads_block = g
                .free_symbols(o)
                .iter()
                .any(|s| layout.block_of.contains_key(s));
            let solve = if reads_block {
                block_solve_for_outputs.clone()
            } else {
                TokenStream::new()
            };
            let body = program(g, &layout, &[o], &|_, v| v);
            let k = index(k);
            quote!(#k => { #solve #body })
        })
        .collect();
    layout.block_of.clear();
    let slot_symbols: Vec<SymbolId> = sys.slots.iter().map(|s| s.symbol).collect();
    let constraint_methods = crate::dae::constraints::constraint_methods(
        g,
        &|g, ids, assign| program(g, &layout, ids, assign),
        &layout.slot_of,
        &slot_symbols,
        sys,
    )?;

    // All event functions at once, sharing their subexpressions; nothing
    // is emitted for a model without events.
    let events_method = if sys.events.is_empty() {
        TokenStream::new()
    } else {
        let (m, n_lit) = (index(sys.events.len()), index(n));
        let body = program(g, &layout, &sys.events, &|i, v| {
            let i = index(i);
            quote!(g[#i] = #v;)
        });
        quote! {
            #[inline]
            fn events(&self, t: f64, y: &[f64], g: &mut [f64]) {
                let (::core::result::Result::Ok(y), ::core::result::Result::Ok(g)) =
                    (<&[f64; #n_lit]>::try_from(y), <&mut [f64; #m]>::try_from(g)) else { return };
                #body
            }
        }
    };

    let rhs_method_body = fixed_size_body(
        &index(n),
        "dy",
        &index(n),
        quote!(#newton_solve #block_setup #rhs_body #block_solve),
    );
    // Taylor: the economic scheme and the tape when asked for; otherwise
    // the tape alone wherever the model allows it (`taylor = 0`: nothing),
    // and where it does not, the reason, for the run-time refusal.
    let (taylor_tokens, taylor_unavailable) = match taylor {
        Some(order) => {
            let f = explicit_rhs(sys)?;
            let economic =
                economic_taylor(&mut ir.graph, &mut layout, sys, ir.time, f.clone(), order)?;
            let tape =
                taylor_tape_items(&mut ir.graph, &layout, sys, ir.time, &f, &attributes.unroll)?;
            (quote!(#tape #economic), None)
        }
        None if attributes.taylor_off => (
            TokenStream::new(),
            Some("it was expanded with `#[dae_model(taylor = 0)]`".to_string()),
        ),
        None => match explicit_rhs(sys)
            .and_then(|f| taylor_tape_items(&mut ir.graph, &layout, sys, ir.time, &f, &[]))
        {
            Ok(tape) => (tape, None),
            Err(e) => (TokenStream::new(), Some(taylor_refusal(&e))),
        },
    };
    let taylor_unavailable_const = match &taylor_unavailable {
        Some(reason) => quote!(const TAYLOR_UNAVAILABLE: &'static str = #reason;),
        None => TokenStream::new(),
    };
    // Last, so its partial derivatives cannot change the code above.
    let (mass_form_type, mass_form_method) =
        match crate::dae::mass_form::mass_form(&mut ir.graph, sys)? {
            Some(form) => {
                let form_layout = Layout::of_components(&form.components);
                let params: Vec<syn::Ident> = ir.params.iter().map(|p| p.ident.clone()).collect();
                crate::dae::mass_form::emit_mass_form(
                    &mut ir.graph,
                    &form,
                    &name,
                    &ir.vis,
                    &params,
                    &|g, ids, assign| program(g, &form_layout, ids, assign),
                )?
            }
            None => (TokenStream::new(), TokenStream::new()),
        };
    let info = info(ir, sys);
    let parameter = parameter_method(ir);
    let degenerate = degenerate_parameters_method(&mut ir.graph, &layout, sys);
    let model_index = index(sys.index);
    let mut analysis = dae_analysis(ir, sys);
    if let Some(reason) = &taylor_unavailable {
        let note = format!("`Method::Taylor` is not available: {reason}.");
        analysis = if analysis.is_empty() {
            note
        } else {
            format!("{analysis}\n\n{note}")
        };
    }
    let struct_and_default = struct_and_default(ir, &analysis);
    let n_lit = index(n);
    Ok(quote! {
        #struct_and_default

        #mass_form_type

        #newton_method

        #[allow(unused_variables, unused_mut, clippy::all, clippy::pedantic)]
        impl ::daegen::Model for #name {
            const STATES: usize = #n_lit;
            type State = [f64; #n_lit];
            const INDEX: usize = #model_index;
            const INFO: ::daegen::ModelInfo = #info;
            const JACOBIAN_PATTERN: &'static [(usize, usize)] = #pattern;

            #parameter
            #degenerate

            fn initial_state(&self, y: &mut [f64]) {
                let ::core::result::Result::Ok(y) = <&mut [f64; #n_lit]>::try_from(y) else { return };
                #initial_state
            }

                        fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) -> ::core::result::Result<(), ::daegen::EvalError> {
                #rhs_method_body
            }

            #[inline]
            fn jacobian(&self, t: f64, y: &[f64], values: &mut [f64]) -> ::core::result::Result<(), ::daegen::EvalError> {
                #jacobian_body
            }

            #[inline]
            fn time_derivative(&self, t: f64, y: &[f64], dfdt: &mut [f64]) -> ::core::result::Result<(), ::daegen::EvalError> {
                #time_body
            }

                        #taylor_tokens
            #taylor_unavailable_const

                        #events_method

            #event_rates_method

            #constraint_methods

            #mass_form_method

            #[inline]
            fn output(&self, index: usize, t: f64, y: &[f64]) -> f64 {
                let ::core::result::Result::Ok(y) = <&[f64; #n_lit]>::try_from(y) else { return f64::NAN };
                match index {
                    #(#output_arms)*
                    _ => f64::NAN,
                }
            }
        }
    })
}

/// A model whose algebraic equations are nonlinear in the algebraic
/// variables: its own `Model` implementation is the mass-matrix form,
/// integrated by RADAU5 (the algebraic variables are states).
fn expand_mass_only(ir: &mut ModelIr, sys: &FirstOrder) -> crate::Result<TokenStream> {
    let name = type_name(ir);
    let g = &mut ir.graph;
    let form = crate::dae::mass_form::mass_form(g, sys)?.ok_or_else(|| crate::Error::Unsupported {
        message: "an algebraic equation is nonlinear in the algebraic variables, and the differential equations do not solve symbolically for the highest derivatives: daegen cannot integrate this model yet".into(),
    })?;
    let layout = Layout::of_components(&form.components);
    let zero = g.zero();
    let mut inits: Vec<Id> = sys.slots.iter().map(|s| s.init).collect();
    inits.extend(ir.algebraics.iter().map(|a| a.init));
    inits.resize(form.components.len(), zero);
    let items =
        crate::dae::mass_form::primary_items(g, &form, &inits, &sys.outputs, &|g, ids, assign| {
            program(g, &layout, ids, assign)
        })?;
    let model_index = index(sys.index);
    let struct_and_default = struct_and_default(ir, &dae_analysis(ir, sys));
    // The algebraic variables are states here.
    let states: Vec<&str> = form.names.iter().map(String::as_str).collect();
    let info = info_with(ir, &states, &[]);
    let parameter = parameter_method(ir);
    let reason = "the model runs in mass-matrix form only (an algebraic equation is nonlinear in its variable)";
    Ok(quote! {
        #struct_and_default

        #[allow(unused_variables, unused_mut, clippy::all, clippy::pedantic)]
        impl ::daegen::Model for #name {
            const INDEX: usize = #model_index;
            const INFO: ::daegen::ModelInfo = #info;
            const TAYLOR_UNAVAILABLE: &'static str = #reason;
            #parameter
            #items
        }
    })
}

/// `Model::degenerate_parameters`: the first pivot of the elimination that
/// combined the model's equations (see `derivative_free`) that the run's
/// parameters make zero or not finite.
fn degenerate_parameters_method(g: &mut Graph, layout: &Layout, sys: &FirstOrder) -> TokenStream {
    if sys.rank_conditions.is_empty() {
        return TokenStream::new();
    }
    let pivots: Vec<Id> = sys.rank_conditions.iter().map(|c| c.pivot).collect();
    let k = index(pivots.len());
    let values = program(g, layout, &pivots, &|i, v| {
        let i = index(i);
        quote!(pivots[#i] = #v;)
    });
    let texts = sys.rank_conditions.iter().map(|c| c.text.as_str());
    quote! {
        fn degenerate_parameters(&self) -> ::core::option::Option<&'static str> {
            let t = 0.0f64;
            let mut pivots = [0.0f64; #k];
            #values
            const CONDITIONS: [&str; #k] = [#(#texts),*];
            pivots
                .iter()
                .position(|p| *p == 0.0 || !p.is_finite())
                .map(|i| CONDITIONS[i])
        }
    }
}

/// `Model::parameter`: each field by its index in `ModelInfo::parameters`
/// (nothing for a model without parameters, whose default is never asked).
fn parameter_method(ir: &ModelIr) -> TokenStream {
    if ir.params.is_empty() {
        return TokenStream::new();
    }
    let arms = ir.params.iter().enumerate().map(|(k, p)| {
        let (k, ident) = (index(k), &p.ident);
        quote!(#k => self.#ident,)
    });
    quote! {
        fn parameter(&self, index: usize) -> f64 {
            match index {
                #(#arms)*
                _ => f64::NAN,
            }
        }
    }
}

fn info(ir: &ModelIr, sys: &FirstOrder) -> TokenStream {
    let states: Vec<&str> = sys.slots.iter().map(|s| s.name.as_str()).collect();
    let algebraics: Vec<&str> = ir.algebraics.iter().map(|a| a.name.as_str()).collect();
    info_with(ir, &states, &algebraics)
}

/// `ModelInfo` with these state and algebraic-variable names.
fn info_with(ir: &ModelIr, states: &[&str], algebraics: &[&str]) -> TokenStream {
    let name = type_name(ir).to_string();
    let doc = &ir.doc;
    let params: Vec<String> = ir.params.iter().map(|p| p.ident.to_string()).collect();
    let param_docs: Vec<&str> = ir.params.iter().map(|p| p.doc.as_str()).collect();
    let outputs: Vec<&str> = ir.outputs.iter().map(|o| o.name.as_str()).collect();
    let output_docs: Vec<&str> = ir.outputs.iter().map(|o| o.doc.as_str()).collect();
    let state_docs: Vec<String> = states.iter().map(|s| value_doc(ir, s)).collect();
    let algebraic_docs: Vec<String> = algebraics.iter().map(|s| value_doc(ir, s)).collect();
    let equations = index(ir.equations.len());
    let events = ir.events.iter().map(|e| {
        let name = &e.name;
        let doc = &e.doc;
        let terminal = e.terminal;
        let direction = match e.direction {
            EventDirection::Any => quote!(Any),
            EventDirection::Rising => quote!(Rising),
            EventDirection::Falling => quote!(Falling),
        };
        quote! {
            ::daegen::EventInfo {
                name: #name,
                direction: ::daegen::EventDirection::#direction,
                terminal: #terminal,
                doc: #doc,
            }
        }
    });
    quote! {
        ::daegen::ModelInfo {
            name: #name,
            doc: #doc,
            states: &[#(#states),*],
            parameters: &[#(#params),*],
            parameter_docs: &[#(#param_docs),*],
            state_docs: &[#(#state_docs),*],
            outputs: &[#(#outputs),*],
            output_docs: &[#(#output_docs),*],
            equations: #equations,
            events: &[#(#events),*],
            algebraics: &[#(#algebraics),*],
            algebraic_docs: &[#(#algebraic_docs),*],
        }
    }
}

/// The doc comment of a state or algebraic variable; for `der(x)`, a
/// state reducing a higher derivative, what it is the derivative of.
fn value_doc(ir: &ModelIr, name: &str) -> String {
    let declared = ir
        .states
        .iter()
        .map(|s| (&s.name, &s.doc))
        .chain(ir.algebraics.iter().map(|a| (&a.name, &a.doc)))
        .find(|(n, _)| *n == name);
    if let Some((_, doc)) = declared {
        return doc.clone();
    }
    match name.strip_prefix("der(").and_then(|r| r.strip_suffix(')')) {
        Some(inner) => format!("rate of `{inner}`"),
        None if name.starts_with("mu[") => {
            "multiplier of the index-2 form, zero on the solution".to_string()
        }
        None => String::new(),
    }
}

/// What a model with errors expands to besides the errors: the struct and a
/// `Model` implementation that does nothing, so the user's other code still
/// type-checks and only the real mistakes are reported.
pub fn stub(ir: &ModelIr) -> TokenStream {
    let name = type_name(ir);
    let struct_and_default = struct_and_default(ir, "");
    let name_str = name.to_string();
    quote_spanned! {name.span()=>
        #struct_and_default

        #[allow(unused_variables)]
        impl ::daegen::Model for #name {
            const STATES: usize = 0;
            type State = [f64; 0];
            const INDEX: usize = 0;
            const INFO: ::daegen::ModelInfo = ::daegen::ModelInfo {
                name: #name_str, doc: "", states: &[], state_docs: &[], parameters: &[], parameter_docs: &[],
                outputs: &[], output_docs: &[], equations: 0, events: &[], algebraics: &[], algebraic_docs: &[],
            };
            const JACOBIAN_PATTERN: &'static [(usize, usize)] = &[];
            fn initial_state(&self, y: &mut [f64]) {}
            fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) -> ::core::result::Result<(), ::daegen::EvalError> {
                ::core::result::Result::Ok(())
            }
            fn jacobian(&self, t: f64, y: &[f64], values: &mut [f64]) -> ::core::result::Result<(), ::daegen::EvalError> {
                ::core::result::Result::Ok(())
            }
            fn time_derivative(&self, t: f64, y: &[f64], dfdt: &mut [f64]) -> ::core::result::Result<(), ::daegen::EvalError> {
                ::core::result::Result::Ok(())
            }
            fn output(&self, index: usize, t: f64, y: &[f64]) -> f64 {
                f64::NAN
            }
        }
    }
}
