//! Index reduction: constraints are differentiated along the dynamics
//! until they determine an unknown (course notes chapter 2, eq. 2.2).
//!
//! The unknowns of the reduced system at a point `(t, y)` are the highest
//! derivatives `z` of the states and the algebraic variables `λ`. An
//! equation that involves none of them (a constraint `Φ(t, y) = 0`) cannot
//! determine any: it is replaced by its total time derivative, where a
//! state's derivative below its highest order is the next state and its
//! highest derivative is the explicit definition `z_j = h_j(t, y)` when an
//! equation gives one (`der(x) == u`), else `z_j` itself. This repeats
//! until the derivative involves an unknown. For a mechanical system the
//! position constraint becomes the velocity constraint, then the
//! acceleration constraint, linear in the accelerations: the KKT system of
//! the index-1 form. The constraint and its derivatives below the last are
//! the invariants the runtime projects onto after each step. Derivatives
//! are taken by forward mode over the graph (a directional derivative, not
//! an expansion of second partials), so the acceleration level shares the
//! velocity level's subexpressions.
//!
//! The differentiation index is the largest number of differentiations,
//! plus one when algebraic variables are determined only by the last level
//! (they need one more differentiation to have an equation of their own).

use super::ctxt::Ctxt;
use crate::{FxHashMap, Graph, Id, SymbolId, VectorField};
use proc_macro2::TokenStream;

/// A constraint or one of its derivatives that must hold along solutions
/// but that the integrated system no longer enforces.
#[derive(Clone, Debug)]
pub struct Invariant {
    /// The user's equation it comes from.
    pub equation: usize,
    /// How often the equation was differentiated to get it (0: itself).
    pub level: usize,
    /// `Φ^(level)(t, y)`, zero on the solution.
    pub residual: Id,
}

/// The equations after index reduction.
pub struct IndexReduction {
    /// Each equation's residual as the reduced system uses it.
    pub residuals: Vec<Id>,
    /// How often each equation was differentiated.
    pub differentiations: Vec<usize>,
    /// The invariants, by equation then level.
    pub invariants: Vec<Invariant>,
    /// The differentiation index.
    pub index: usize,
}

/// What the pass needs to know about the unknowns.
pub struct Unknowns<'a> {
    /// The independent variable.
    pub time: SymbolId,
    /// Per state: its symbol and its order (highest derivative used).
    pub states: &'a [(SymbolId, u32)],
    /// `z_j`, the highest derivative of state `j`.
    pub z: &'a [SymbolId],
    /// The algebraic variables.
    pub algebraics: &'a [SymbolId],
}

/// Beyond this many differentiations a constraint is reported: mechanical
/// constraints need two, and no model here needs more than a handful.
const MAX_DIFFERENTIATIONS: usize = 8;

/// Differentiates each equation that involves no unknown until it does.
pub fn reduce_index(
    cx: &mut Ctxt,
    g: &mut Graph,
    unknowns: &Unknowns<'_>,
    residuals: &[Id],
    origins: &[TokenStream],
) -> Option<IndexReduction> {
    let is_unknown: FxHashMap<SymbolId, ()> = unknowns
        .z
        .iter()
        .chain(unknowns.algebraics)
        .map(|&s| (s, ()))
        .collect();
    let involves_unknown =
        |g: &Graph, r: Id| g.free_symbols(r).iter().any(|s| is_unknown.contains_key(s));
    let explicit = explicit_definitions(g, unknowns, residuals, &is_unknown)?;
    let mut field = VectorField::new();
    let one = g.one();
    field.set(unknowns.time, one);
    for (j, &(state, order)) in unknowns.states.iter().enumerate() {
        for k in 0..order {
            let slot = g.derivative(state, k).ok()?;
            let slot = g.as_symbol(slot)?;
            let next = if k + 1 < order {
                g.derivative(state, k + 1).ok()?
            } else {
                explicit[j].unwrap_or_else(|| g.symbol_node(unknowns.z[j]))
            };
            field.set(slot, next);
        }
    }
    let mut out = IndexReduction {
        residuals: Vec::with_capacity(residuals.len()),
        differentiations: Vec::with_capacity(residuals.len()),
        invariants: Vec::new(),
        index: 0,
    };
    let mut ok = true;
    for (e, (&r, origin)) in residuals.iter().zip(origins).enumerate() {
        let mut current = r;
        let mut level = 0;
        while !involves_unknown(g, current) {
            if let Some(c) = g.as_number(current) {
                let message = if level == 0 {
                    "this equation involves no variable: remove it".to_string()
                } else if c.is_zero() {
                    let which = if level == 1 {
                        "derivative".to_string()
                    } else {
                        format!("derivative of order {level}")
                    };
                    format!("this constraint determines nothing: its {which} along the other equations is identically zero, so the other equations decide whether it holds; remove it, or make a variable algebraic")
                } else {
                    format!("this constraint contradicts the other equations: its derivative of order {level} along them is the constant {}", c.to_f64())
                };
                cx.error_at(origin, message);
                ok = false;
                break;
            }
            if level == MAX_DIFFERENTIATIONS {
                cx.error_at(origin, format!("this constraint never involves an algebraic variable or a highest derivative, even after {MAX_DIFFERENTIATIONS} differentiations: no unknown is left for it to determine; remove it or make a variable algebraic"));
                ok = false;
                break;
            }
            out.invariants.push(Invariant {
                equation: e,
                level,
                residual: current,
            });
            current = match g.total_derivative(current, &mut field) {
                Ok(d) => d,
                Err(err) => {
                    cx.error_at(origin, err);
                    return None;
                }
            };
            level += 1;
        }
        out.residuals.push(current);
        out.differentiations.push(level);
    }
    let deepest = out.differentiations.iter().copied().max().unwrap_or(0);
    out.index = deepest + usize::from(!unknowns.algebraics.is_empty());
    ok.then_some(out)
}

/// `z_j = h_j(t, y)` for each highest derivative that an equation gives
/// explicitly (`der(x) == u`, `2 * der(x) == x`): the equation involves no
/// other unknown and `z_j` with a constant coefficient.
fn explicit_definitions(
    g: &mut Graph,
    unknowns: &Unknowns<'_>,
    residuals: &[Id],
    is_unknown: &FxHashMap<SymbolId, ()>,
) -> Option<Vec<Option<Id>>> {
    let mut explicit = vec![None; unknowns.z.len()];
    let zero = g.zero();
    for &r in residuals {
        let involved: Vec<SymbolId> = g
            .free_symbols(r)
            .into_iter()
            .filter(|s| is_unknown.contains_key(s))
            .collect();
        let [s] = involved[..] else { continue };
        let Some(j) = unknowns.z.iter().position(|&z| z == s) else {
            continue;
        };
        if explicit[j].is_some() {
            continue;
        }
        let c = g.partial(r, s).ok()?;
        let Some(c) = g.as_number(c).filter(|c| !c.is_zero()) else {
            continue;
        };
        let rest = g.substitute(r, &[(s, zero)].into_iter().collect()).ok()?;
        let minus_inverse = g.num(c.pow(crate::Number::MINUS_ONE)?.negated());
        explicit[j] = Some(g.mul(minus_inverse, rest).ok()?);
    }
    Some(explicit)
}
