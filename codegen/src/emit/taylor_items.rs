//! The Taylor methods' items of a model: the economic scheme's
//! derivatives (`taylor = p`), the adaptive method's tape and unrolled
//! jets, or why there are none.

use crate::dae::system::{FirstOrder, SlotDerivative};
use crate::emit::layout::{index, program, Layout};
use crate::front::attributes::Attributes;
use crate::front::ir::ModelIr;
use crate::{Graph, Id, SymbolId, SymbolKind};
use proc_macro2::TokenStream;
use quote::quote;

/// The Taylor methods' items: the economic scheme and the tape when asked
/// for (`taylor = p`, `unroll = [..]`); otherwise the tape alone wherever
/// the model allows it (`taylor = 0`: nothing), and where it does not, the
/// reason, for the run-time refusal.
pub(crate) fn taylor_items(
    ir: &mut ModelIr,
    layout: &mut Layout,
    sys: &FirstOrder,
    taylor: Option<usize>,
    attributes: &Attributes,
) -> crate::Result<(TokenStream, Option<String>)> {
    Ok(match taylor {
        Some(order) => {
            let f = explicit_rhs(sys).map_err(|e| match (&e, attributes.taylor) {
                // `unroll` alone asked for the scheme.
                (crate::Error::Unsupported { message }, None) => crate::Error::Unsupported {
                    message: message
                        .replace("`taylor = p` needs", "`unroll = [..]` needs")
                        .replace("remove `taylor = p`", "remove `unroll`")
                        .replace(
                            "without it, solving",
                            "without it, on its interpreted tape, solving",
                        ),
                },
                _ => e,
            })?;
            let economic = economic_taylor(&mut ir.graph, layout, sys, ir.time, f.clone(), order)?;
            let tape =
                taylor_tape_items(&mut ir.graph, layout, sys, ir.time, &f, &attributes.unroll)?;
            (quote!(#tape #economic), None)
        }
        None if attributes.taylor_off => (
            TokenStream::new(),
            Some("it was expanded with `#[dae_model(taylor = 0)]`".to_string()),
        ),
        None => match tape_outputs(&mut ir.graph, sys)
            .and_then(|f| taylor_tape_items(&mut ir.graph, layout, sys, ir.time, &f, &[]))
        {
            Ok(tape) => (tape, None),
            Err(e) => (TokenStream::new(), Some(taylor_refusal(&e))),
        },
    })
}

/// The right-hand side of an explicit ODE, slot by slot: what the
/// economic scheme and the unrolled jets differentiate. `Err` for a model
/// that solves a system at run time.
pub(crate) fn explicit_rhs(sys: &FirstOrder) -> crate::Result<Vec<Id>> {
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
                    message: "`taylor = p` needs an explicit ODE; this model solves a linear system of more than three coupled unknowns at run time (its mass matrix, or the constraint block of a mechanism), so its derivatives have no closed form: remove `taylor = p` from `#[dae_model]` (`Method::Taylor` runs the model without it, solving the system order by order)".into(),
                })
            }
        })
        .collect()
}

/// What the tape differentiates: each slot's derivative, where a slot
/// solved at run time reads its linear system's unknown (solved order by
/// order by the tape's `Solve`). `Err` for a model that solves nonlinear
/// equations by Newton's method.
fn tape_outputs(g: &mut Graph, sys: &FirstOrder) -> crate::Result<Vec<Id>> {
    if sys.newton.is_some() {
        return explicit_rhs(sys);
    }
    sys.derivatives
        .iter()
        .map(|d| match d {
            SlotDerivative::Explicit(e) | SlotDerivative::AfterSolve(e) => Ok(*e),
            SlotDerivative::Block { block, row } => sys
                .block_unknowns
                .iter()
                .find(|&&(_, b, r)| b == *block && r == *row)
                .map(|&(s, _, _)| g.symbol_node(s))
                .ok_or_else(|| crate::Error::Unsupported {
                    message: "a slot solved at run time without its unknown".into(),
                }),
        })
        .collect()
}

/// Why the Taylor tape could not be made, as a clause after "because":
/// the compile-time error's own reason without its fix (which speaks of a
/// `taylor = p` the user did not write).
pub(crate) fn taylor_refusal(e: &crate::Error) -> String {
    let text = match e {
        crate::Error::Unsupported { message } => message.clone(),
        other => other.to_string(),
    };
    let reason = text.split(": remove").next().unwrap_or(&text);
    let reason = reason
        .split("; this model")
        .nth(1)
        .map_or(reason.to_string(), |r| format!("the model{}", r));
    reason.replace("`taylor = p` needs an explicit ODE", "the model is no explicit ODE")
}

/// `TAYLOR_ORDER` and `taylor_derivatives`: D_1 = f and D_{k+1} the total
/// time derivative of D_k (course notes §1.3.1), where the k-th derivative
/// of slot i is a fresh symbol read from `out` (`der` of a slot would alias
/// the other slots of a reduced higher-order state). One program per order,
/// each reading the lower orders already written.
pub(crate) fn economic_taylor(
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
pub(crate) fn taylor_tape_items(
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
    // The linear systems solved at run time, solved order by order on the
    // tape (only on the compact layout: `unroll` needs an explicit ODE).
    let unknowns: Vec<Vec<SymbolId>> = sys
        .blocks
        .iter()
        .enumerate()
        .map(|(b, block)| {
            (0..block.rhs.len())
                .filter_map(|r| {
                    sys.block_unknowns.iter().find(|&&(_, bb, rr)| bb == b && rr == r).map(|u| u.0)
                })
                .collect()
        })
        .collect();
    let systems: Vec<crate::taylor::tape::LinearSystem<'_>> = sys
        .blocks
        .iter()
        .zip(&unknowns)
        .map(|(block, unknowns)| crate::taylor::tape::LinearSystem {
            unknowns,
            matrix: &block.matrix,
            rhs: &block.rhs,
        })
        .collect();
    if !systems.is_empty() && !unroll.is_empty() {
        return Err(crate::Error::Unsupported {
            message: "`unroll = [..]` needs an explicit ODE; this model solves a linear system at run time (its mass matrix, or the constraint block of a mechanism), which only the compact tape solves order by order: remove `unroll` from `#[dae_model]`".into(),
        });
    }
    let mut targets = explicit.clone();
    targets.extend(systems.iter().flat_map(|s| s.matrix.iter().chain(s.rhs)));
    let negations = crate::taylor::tape::negated_sums(g, &targets)?;
    let tape =
        crate::taylor::tape::decompose(g, &explicit, &systems, (&slot_of, time), &negations)?;
    let consts: Vec<Id> = tape
        .constants
        .iter()
        .map(|c| match c {
            crate::taylor::tape::Constant::Expr(id) => Ok(*id),
            crate::taylor::tape::Constant::Integer(n) => Ok(g.int(*n)),
            crate::taylor::tape::Constant::Product(factors) => g.product(factors),
            crate::taylor::tape::Constant::Sum(terms) => g.sum(terms),
            crate::taylor::tape::Constant::Value(v) => g.float(*v),
        })
        .collect::<crate::Result<_>>()?;
    let const_code = program(g, layout, &consts, &|i, v| {
        let name = quote::format_ident!("c{}", i);
        quote!(let #name: f64 = #v;)
    });
    let (ops, outs) = (&tape.ops, &tape.outputs);
    let (n_ops, n_outs, n_consts) = (index(ops.len()), index(outs.len()), index(consts.len()));
    let const_names = (0..consts.len()).map(|i| quote::format_ident!("c{}", i));
    // The unrolled layout, for the orders the user asked for.
    let numbers: Vec<Option<f64>> =
        consts.iter().map(|&id| g.as_number(id).map(|x| x.to_f64())).collect();
    let jets: Vec<_> = unroll
        .iter()
        .map(|&order| (order, crate::taylor::unrolled::unrolled_jet(&tape, n, order, &numbers)))
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
    let by_coefficient: Vec<_> =
        jets.iter().filter(|(_, jet)| jet.by_coefficient).map(|(order, _)| index(*order)).collect();
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

        fn taylor_tape(&self) -> ::core::option::Option<(
            ::std::vec::Vec<::daegen::runtime::taylor_tape::TapeOp>,
            ::std::vec::Vec<::daegen::runtime::taylor_tape::Operand>,
        )> {
            // Short names: a large model's tape runs to thousands of operations.
            #[allow(unused_imports)]
            use ::daegen::runtime::taylor_tape::{Inverse as I, Operand as O, TapeOp as T};
            // The operations as a table with their constants by slot: code
            // that built them one by one would take rustc minutes for a
            // model of thousands of states.
            static OPS: [T<u32>; #n_ops] = [#(#ops),*];
            static OUTPUTS: [O<u32>; #n_outs] = [#(#outs),*];
            #const_code
            let constants: [f64; #n_consts] = [#(#const_names),*];
            let value = |k: &u32| constants.get(*k as usize).copied().unwrap_or(f64::NAN);
            ::core::option::Option::Some((
                OPS.iter().map(|op| op.map_constants(value)).collect(),
                OUTPUTS.iter().map(|o| o.map_constant(value)).collect(),
            ))
        }
    })
}
