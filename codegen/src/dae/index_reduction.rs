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

use crate::dae::linear_pencil;
use crate::dae::system::Invariant;
use crate::front::ctxt::Ctxt;
use crate::{FxHashMap, Graph, Id, Number, SymbolId, VectorField};
use proc_macro2::TokenStream;

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
    /// Per state: its highest derivative is given explicitly by the states
    /// (`der(x) == u`), so its last slot is position-like; otherwise the
    /// dynamics determine it and the slot is velocity-like.
    pub explicit_highest: Vec<bool>,
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
    let is_unknown: FxHashMap<SymbolId, ()> =
        unknowns.z.iter().chain(unknowns.algebraics).map(|&s| (s, ())).collect();
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
    if singular_linear_pencil(cx, g, unknowns, residuals, origins) {
        return None;
    }
    let unknown_symbols: Vec<SymbolId> =
        unknowns.z.iter().chain(unknowns.algebraics).copied().collect();
    let m = residuals.len();
    let mut current = residuals.to_vec();
    let mut level = vec![0usize; m];
    let mut invariants = Vec::new();
    let mut combined = vec![false; m];
    // Differentiate what determines nothing; where the coefficients of the
    // unknowns are constant, combine the equations whose coefficient rows
    // are dependent into one that involves no unknown and differentiate
    // it too (Luenberger's shuffle); repeat until the coefficients are
    // regular or no longer constant.
    for _ in 0..=m + 1 {
        let mut ok = true;
        for e in 0..m {
            while !involves_unknown(g, current[e]) {
                if let Some(c) = g.as_number(current[e]) {
                    let message = if combined[e] {
                        format!("these equations are linearly dependent in their unknowns, and a combination of them reads 0 = {}: the DAE is inconsistent or under-determined (its pencil is singular, course notes Example 2.2)", c.to_f64())
                    } else if level[e] == 0 {
                        "this equation involves no variable: remove it".to_string()
                    } else if c.is_zero() {
                        let which = if level[e] == 1 {
                            "derivative".to_string()
                        } else {
                            format!("derivative of order {}", level[e])
                        };
                        format!("this constraint determines nothing: its {which} along the other equations is identically zero, so the other equations decide whether it holds; remove it, or make a variable algebraic")
                    } else {
                        format!("this constraint contradicts the other equations: its derivative of order {} along them is the constant {}", level[e], c.to_f64())
                    };
                    cx.error_at(&origins[e], message);
                    ok = false;
                    break;
                }
                if level[e] == MAX_DIFFERENTIATIONS {
                    cx.error_at(&origins[e], format!("this constraint never involves an algebraic variable or a highest derivative, even after {MAX_DIFFERENTIATIONS} differentiations: no unknown is left for it to determine; remove it or make a variable algebraic"));
                    ok = false;
                    break;
                }
                invariants.push(Invariant {
                    equation: e,
                    level: level[e],
                    residual: current[e],
                    text: crate::front::names::source_text(&origins[e]),
                });
                current[e] = match g.total_derivative(current[e], &mut field) {
                    Ok(d) => d,
                    Err(err) => {
                        cx.error_at(&origins[e], err);
                        return None;
                    }
                };
                level[e] += 1;
            }
        }
        if !ok {
            return None;
        }
        // Only a square system can be regular; the matching reports the others.
        if m != unknown_symbols.len() {
            break;
        }
        let Some(null) = constant_coefficients(g, &current, &unknown_symbols)
            .and_then(|c| linear_pencil::left_null_space(&c))
        else {
            break;
        };
        if null.is_empty() {
            break;
        }
        for (pivot, alpha) in null {
            let mut terms = Vec::new();
            let mut deepest = 0;
            for (i, a) in alpha.iter().enumerate() {
                if !a.is_zero() {
                    let a = g.num(*a);
                    terms.push(g.mul(a, current[i]).ok()?);
                    deepest = deepest.max(level[i]);
                }
            }
            current[pivot] = g.sum(&terms).ok()?;
            level[pivot] = deepest;
            combined[pivot] = true;
        }
    }
    let deepest = level.iter().copied().max().unwrap_or(0);
    Some(IndexReduction {
        residuals: current,
        differentiations: level,
        invariants,
        index: deepest + usize::from(!unknowns.algebraics.is_empty()),
        explicit_highest: explicit.iter().map(Option::is_some).collect(),
    })
}

/// `∂r_i/∂w_j` for every equation and unknown, if all are numbers and the
/// matrix is not trivially regular (one unknown per row, each once: an
/// explicit ODE, which needs no elimination).
fn constant_coefficients(
    g: &mut Graph,
    residuals: &[Id],
    unknowns: &[SymbolId],
) -> Option<Vec<Vec<Number>>> {
    if unknowns.len() > 200 {
        return None;
    }
    // Structurally one distinct unknown per equation: regular, and no
    // partial derivative needs to be built.
    let mut owner = vec![false; unknowns.len()];
    let one_each = residuals.len() == unknowns.len()
        && residuals.iter().all(|&r| {
            let involved: Vec<usize> = g
                .free_symbols(r)
                .iter()
                .filter_map(|s| unknowns.iter().position(|u| u == s))
                .collect();
            match involved[..] {
                [j] if !owner[j] => {
                    owner[j] = true;
                    true
                }
                _ => false,
            }
        });
    if one_each {
        return None;
    }
    let mut rows = Vec::with_capacity(residuals.len());
    let mut seen = vec![0usize; unknowns.len()];
    let mut trivially_regular = residuals.len() == unknowns.len();
    for &r in residuals {
        let row = unknowns
            .iter()
            .map(|&s| g.partial(r, s).ok().and_then(|d| g.as_number(d)))
            .collect::<Option<Vec<Number>>>()?;
        let nonzero: Vec<usize> = (0..row.len()).filter(|&j| !row[j].is_zero()).collect();
        match nonzero[..] {
            [j] => seen[j] += 1,
            _ => trivially_regular = false,
        }
        rows.push(row);
    }
    if trivially_regular && seen.iter().all(|&k| k == 1) {
        return None;
    }
    Some(rows)
}

/// A linear DAE with constant coefficients `E y' + A y = c(t)` whose pencil
/// is singular (det(E·s + A) ≡ 0) is inconsistent or under-determined
/// (course notes §2.1, Example 2.2): reported on its equations.
fn singular_linear_pencil(
    cx: &mut Ctxt,
    g: &mut Graph,
    unknowns: &Unknowns<'_>,
    residuals: &[Id],
    origins: &[TokenStream],
) -> bool {
    let n = unknowns.states.len() + unknowns.algebraics.len();
    if residuals.len() != n || n > 60 || unknowns.states.iter().any(|&(_, order)| order != 1) {
        return false;
    }
    // On a copy: most models are not linear, and the partial derivatives
    // tried here must not change the graph the emitted code comes from.
    let g = &mut g.clone();
    let mut e = Vec::with_capacity(n);
    let mut a = Vec::with_capacity(n);
    for &r in residuals {
        let mut coefficient = |s: SymbolId| g.partial(r, s).ok().and_then(|d| g.as_number(d));
        let mut e_row = Vec::with_capacity(n);
        let mut a_row = Vec::with_capacity(n);
        for (&(y, _), &z) in unknowns.states.iter().zip(unknowns.z) {
            let (Some(ez), Some(ay)) = (coefficient(z), coefficient(y)) else {
                return false;
            };
            e_row.push(ez);
            a_row.push(ay);
        }
        for &l in unknowns.algebraics {
            let Some(al) = coefficient(l) else {
                return false;
            };
            e_row.push(Number::ZERO);
            a_row.push(al);
        }
        e.push(e_row);
        a.push(a_row);
    }
    if linear_pencil::pencil_is_singular(&e, &a) != Some(true) {
        return false;
    }
    let listed: Vec<String> =
        origins.iter().map(|o| format!("`{}`", crate::front::names::source_text(o))).collect();
    cx.error_at(&origins[0], format!("this linear DAE is inconsistent or under-determined: det(E·s + A) is identically zero, a singular pencil (course notes §2.1, Example 2.2); its equations {} do not determine the variables: change one of them", listed.join(", ")));
    true
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
        let involved: Vec<SymbolId> =
            g.free_symbols(r).into_iter().filter(|s| is_unknown.contains_key(s)).collect();
        let [s] = involved[..] else { continue };
        let Some(j) = unknowns.z.iter().position(|&z| z == s) else {
            continue;
        };
        if explicit[j].is_some() {
            continue;
        }
        // A coefficient of numbers and parameters (`m * der(x) == p`).
        let c = g.partial(r, s).ok()?;
        let constant = g
            .free_symbols(c)
            .iter()
            .all(|&p| matches!(g.symbol(p).kind, crate::SymbolKind::Parameter));
        if !constant || g.as_number(c).is_some_and(|v| v.is_zero()) {
            continue;
        }
        let rest = g.substitute(r, &[(s, zero)].into_iter().collect()).ok()?;
        let minus_rest = g.negate_terms(rest).ok()?;
        explicit[j] = Some(g.div(minus_rest, c).ok()?);
    }
    Some(explicit)
}
