//! What a model gives the Taylor methods: the economic scheme's
//! derivatives (`taylor = p`), the adaptive method's AD tape and its
//! unrolled jets, or why there is no tape.

use crate::dae::system::{FirstOrder, SlotDerivative};
use crate::front::attributes::Attributes;
use crate::taylor::tape::Tape;
use crate::taylor::unrolled::UnrolledJet;
use crate::{FxHashMap, Graph, Id, SymbolId, SymbolKind};

/// The Taylor methods' part of a model.
pub enum TaylorAnalysis {
    /// `taylor = p` (or `unroll` alone): the economic scheme's derivatives
    /// and the tape.
    Scheme {
        /// D_1 … D_p.
        economic: EconomicDerivatives,
        /// The tape and its unrolled jets.
        tape: TapeAnalysis,
    },
    /// The tape alone, which every model that allows one has.
    Tape(TapeAnalysis),
    /// No tape: why `Method::Taylor` refuses the model, as a clause.
    Refused(String),
}

/// The economic scheme's derivatives: D_1 = f and D_{k+1} the total time
/// derivative of D_k (course notes §1.3.1).
pub struct EconomicDerivatives {
    /// The order p.
    pub order: usize,
    /// Per slot, the symbols its 1st … p-th derivatives are read as (fresh
    /// symbols: `der` of a slot would alias the other slots of a reduced
    /// higher-order state).
    pub symbols: Vec<Vec<SymbolId>>,
    /// D_1 … D_p, slot by slot.
    pub levels: Vec<Vec<Id>>,
}

/// The adaptive method's tape: its operations, its constants as
/// expressions, and the straight-line jets of the orders in `unroll`.
pub struct TapeAnalysis {
    /// The operations and outputs.
    pub tape: Tape,
    /// The value of each constant `c_k` of the tape.
    pub constants: Vec<Id>,
    /// `(order, jet)` for each order in `unroll`.
    pub jets: Vec<(usize, UnrolledJet)>,
}

/// The Taylor items `attributes` ask for: the economic scheme and the tape
/// when asked for (`taylor = p`, `unroll = [..]`); otherwise the tape alone
/// wherever the model allows it (`taylor = 0`: nothing), and where it does
/// not, the reason, for the run-time refusal.
pub fn taylor_analysis(
    g: &mut Graph,
    sys: &FirstOrder,
    time: SymbolId,
    attributes: &Attributes,
) -> crate::Result<TaylorAnalysis> {
    if let Some(input) = input_read(g, sys) {
        let reason = format!("it reads the input `{input}`, a signal known only by its values at run time, whose Taylor coefficients are not");
        if attributes.taylor.is_some() || !attributes.unroll.is_empty() {
            return Err(crate::Error::Unsupported {
                message: format!("`taylor = p` needs the model's derivatives of every order, and {reason}: remove `taylor = p`"),
            });
        }
        return Ok(TaylorAnalysis::Refused(reason));
    }
    // `unroll` alone implies the Taylor tape (and the first-order scheme).
    let taylor = match (attributes.taylor, attributes.unroll.is_empty()) {
        (None, false) => Some(1),
        (t, _) => t,
    };
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
            let economic = economic_derivatives(g, sys, time, f.clone(), order)?;
            let tape = tape_analysis(g, sys, time, &f, &attributes.unroll)?;
            TaylorAnalysis::Scheme { economic, tape }
        }
        None if attributes.taylor_off => {
            TaylorAnalysis::Refused("it was expanded with `#[dae_model(taylor = 0)]`".to_string())
        }
        None => match tape_outputs(g, sys).and_then(|f| tape_analysis(g, sys, time, &f, &[])) {
            Ok(tape) => TaylorAnalysis::Tape(tape),
            Err(e) => TaylorAnalysis::Refused(taylor_refusal(&e)),
        },
    })
}

/// The first input the right-hand side reads, by name.
fn input_read(g: &Graph, sys: &FirstOrder) -> Option<String> {
    let mut roots: Vec<Id> = sys
        .derivatives
        .iter()
        .filter_map(|d| match d {
            SlotDerivative::Explicit(e) | SlotDerivative::AfterSolve(e) => Some(*e),
            SlotDerivative::Block { .. } => None,
        })
        .collect();
    roots.extend(sys.blocks.iter().flat_map(|b| b.rhs.iter().chain(&b.matrix).copied()));
    roots.into_iter().flat_map(|r| g.free_symbols(r)).find_map(|s| {
        matches!(g.symbol(s).kind, crate::SymbolKind::Input { .. })
            .then(|| g.symbol(s).name.clone())
    })
}

/// The right-hand side of an explicit ODE, slot by slot: what the
/// economic scheme and the unrolled jets differentiate. `Err` for a model
/// that solves a system at run time.
pub fn explicit_rhs(sys: &FirstOrder) -> crate::Result<Vec<Id>> {
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
pub fn taylor_refusal(e: &crate::Error) -> String {
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

/// D_1 … D_order of the explicit right-hand side `f`, the k-th derivative
/// of slot i a fresh symbol.
fn economic_derivatives(
    g: &mut Graph,
    sys: &FirstOrder,
    time: SymbolId,
    f: Vec<Id>,
    order: usize,
) -> crate::Result<EconomicDerivatives> {
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
    Ok(EconomicDerivatives { order, symbols, levels })
}

/// The AD tape of the adaptive Taylor method (compact layout, interpreted
/// at run time), its constants, and the straight-line jets of the orders
/// in `unroll`.
fn tape_analysis(
    g: &mut Graph,
    sys: &FirstOrder,
    time: SymbolId,
    f: &[Id],
    unroll: &[usize],
) -> crate::Result<TapeAnalysis> {
    let n = sys.slots.len();
    let slot_of: FxHashMap<SymbolId, usize> =
        sys.slots.iter().enumerate().map(|(i, s)| (s.symbol, i)).collect();
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
    let mut targets = f.to_vec();
    targets.extend(systems.iter().flat_map(|s| s.matrix.iter().chain(s.rhs)));
    let negations = crate::taylor::tape::negated_sums(g, &targets)?;
    let tape = crate::taylor::tape::decompose(g, f, &systems, (&slot_of, time), &negations)?;
    let constants: Vec<Id> = tape
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
    // The unrolled layout, for the orders the user asked for.
    let numbers: Vec<Option<f64>> =
        constants.iter().map(|&id| g.as_number(id).map(|x| x.to_f64())).collect();
    let jets = unroll
        .iter()
        .map(|&order| (order, crate::taylor::unrolled::unrolled_jet(&tape, n, order, &numbers)))
        .collect();
    Ok(TapeAnalysis { tape, constants, jets })
}

/// The tape as its tests read it: the constants, one operation a line,
/// then the outputs.
impl std::fmt::Display for crate::expr::display::WithGraph<'_, TapeAnalysis> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (g, a) = (self.graph, self.value);
        for (k, &c) in a.constants.iter().enumerate() {
            writeln!(f, "c{k} = {}", g.show(c))?;
        }
        // Tokens print spaced (`T :: Sin (O :: State (0))`); read as written.
        let tight = |t: &proc_macro2::TokenStream| {
            t.to_string().replace(" :: ", "::").replace(" (", "(").replace(" , ", ", ")
        };
        for (k, op) in a.tape.ops.iter().enumerate() {
            writeln!(f, "u{k} = {}", tight(op))?;
        }
        for (i, out) in a.tape.outputs.iter().enumerate() {
            writeln!(f, "out{i} = {}", tight(out))?;
        }
        for (order, jet) in &a.jets {
            writeln!(f, "unrolled order {order}: buffer {}", jet.buffer)?;
        }
        Ok(())
    }
}

/// The economic scheme's derivatives as their tests read them.
impl std::fmt::Display for crate::expr::display::WithGraph<'_, EconomicDerivatives> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (g, e) = (self.graph, self.value);
        for (k, level) in e.levels.iter().enumerate() {
            for (i, &d) in level.iter().enumerate() {
                writeln!(f, "D{}[{i}] = {}", k + 1, g.show(d))?;
            }
        }
        Ok(())
    }
}
