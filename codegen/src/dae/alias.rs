//! Alias elimination before matching: an equation `a == b`, `a == -b`,
//! `a + b == 0` or `a == c` (`c` a constant or an expression of the
//! parameters), with `a` an algebraic variable, removes `a` and the
//! equation; every other equation reads `±b` or `c` in its place. A
//! connected model writes hundreds of these (equal potentials, opposite
//! flows), and each would otherwise cost a block of the sorting and a
//! variable of the generated code. The variable stays readable: its value
//! is the alias's.

use crate::{FxHashMap, Graph, Id, Node, SymbolId, SymbolKind};

/// The alias equations found, the variables they removed, and the other
/// equations with those variables replaced.
pub struct Aliases {
    /// Each equation's residual with the removed variables replaced (an
    /// alias equation's is zero: it is gone).
    pub residuals: Vec<Id>,
    /// Which equations were aliases.
    pub alias_equations: Vec<bool>,
    /// Each removed variable with its value (`±b` or `c`, chains followed
    /// to their end), in the order removed.
    pub removed: Vec<(SymbolId, Id)>,
}

/// Finds the aliases among the equations (undifferentiated ones only:
/// `differentiations[e] == 0`), in the order written; of two algebraic
/// variables the one declared later is removed, so `v1 == v2` keeps `v1`.
pub fn eliminate_aliases(
    g: &mut Graph,
    residuals: &[Id],
    differentiations: &[usize],
    algebraics: &[SymbolId],
) -> crate::Result<Aliases> {
    let declared: FxHashMap<SymbolId, usize> =
        algebraics.iter().enumerate().map(|(k, &s)| (s, k)).collect();
    // Every value is kept resolved: it reads no removed variable.
    let mut value_of: FxHashMap<SymbolId, Id> = FxHashMap::default();
    // Removed variables whose value reads a symbol, to re-point when that
    // symbol is removed in turn.
    let mut readers: FxHashMap<SymbolId, Vec<SymbolId>> = FxHashMap::default();
    let mut removed = Vec::new();
    let mut alias_equations = vec![false; residuals.len()];
    for (e, &r) in residuals.iter().enumerate() {
        if differentiations[e] > 0 {
            continue;
        }
        let r = g.substitute(r, &value_of)?;
        let Some((a, value)) = alias(g, r, &declared)? else { continue };
        alias_equations[e] = true;
        let replace = FxHashMap::from_iter([(a, value)]);
        for x in readers.remove(&a).unwrap_or_default() {
            let v = g.substitute(value_of[&x], &replace)?;
            value_of.insert(x, v);
            if let Some(s) = read_symbol(g, v) {
                readers.entry(s).or_default().push(x);
            }
        }
        if let Some(s) = read_symbol(g, value) {
            readers.entry(s).or_default().push(a);
        }
        value_of.insert(a, value);
        removed.push(a);
    }
    let zero = g.zero();
    let mut out = Vec::with_capacity(residuals.len());
    for (e, &r) in residuals.iter().enumerate() {
        out.push(if alias_equations[e] { zero } else { g.substitute(r, &value_of)? });
    }
    let removed = removed.into_iter().map(|a| (a, value_of[&a])).collect();
    Ok(Aliases { residuals: out, alias_equations, removed })
}

/// `Some((a, value))` when `r = 0` says `a = value` with `a` an algebraic
/// variable (of `declared`) and `value` one of `b`, `-b` (b a variable,
/// a state or the time) or an expression of the parameters.
fn alias(
    g: &mut Graph,
    r: Id,
    declared: &FxHashMap<SymbolId, usize>,
) -> crate::Result<Option<(SymbolId, Id)>> {
    let symbols = g.free_symbols(r);
    let variables = symbols.iter().filter(|s| g.symbol(**s).kind != SymbolKind::Parameter).count();
    if variables > 2 {
        return Ok(None);
    }
    let mut candidates: Vec<(usize, SymbolId)> =
        symbols.iter().filter_map(|s| declared.get(s).map(|&k| (k, *s))).collect();
    // The later declared goes first.
    candidates.sort_unstable_by(|x, y| y.cmp(x));
    for (_, a) in candidates {
        let c = g.partial(r, a)?;
        let Some(c) = g.as_number(c) else { continue };
        let zero = g.zero();
        let rest = g.substitute(r, &FxHashMap::from_iter([(a, zero)]))?;
        // c a + rest = 0 with c = ±1: a = -rest / c.
        let value = if c.to_f64() == 1.0 {
            g.negate_terms(rest)?
        } else if c.to_f64() == -1.0 {
            rest
        } else {
            continue;
        };
        let parameters_only =
            g.free_symbols(value).iter().all(|&s| g.symbol(s).kind == SymbolKind::Parameter);
        if parameters_only || read_symbol(g, value).is_some() {
            return Ok(Some((a, value)));
        }
    }
    Ok(None)
}

/// The variable `v` reads when `v` is `b` or `-b`, `b` an algebraic
/// variable, a state or the time. Not a derivative: an equation that
/// determines a derivative stays one, or `z == der(y)` would carry `der(y)`
/// into the equation that determines `z`, perhaps nonlinearly.
fn read_symbol(g: &Graph, v: Id) -> Option<SymbolId> {
    let plain = |id: Id| {
        g.as_symbol(id).filter(|&s| {
            matches!(g.symbol(s).kind, SymbolKind::Algebraic | SymbolKind::State | SymbolKind::Time)
        })
    };
    if let Some(s) = plain(v) {
        return Some(s);
    }
    match g.node(v) {
        Node::Mul(factors) if factors.len() == 2 => {
            let minus_one = |id: Id| g.as_number(id).is_some_and(|n| n.to_f64() == -1.0);
            match (minus_one(factors[0]), minus_one(factors[1])) {
                (true, _) => plain(factors[1]),
                (_, true) => plain(factors[0]),
                _ => None,
            }
        }
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chains_of_aliases_end_at_the_variable_kept() {
        let mut g = Graph::new();
        let x = g.state("x").unwrap();
        let a = g.algebraic("a").unwrap();
        let b = g.algebraic("b").unwrap();
        let c = g.algebraic("c").unwrap();
        let k = g.parameter("k").unwrap();
        let symbols: Vec<SymbolId> = [a, b, c].iter().map(|&n| g.as_symbol(n).unwrap()).collect();
        // b == a, c + b == 0, a == x, and x * c == k (not an alias).
        let residuals = vec![g.sub(b, a).unwrap(), g.add(c, b).unwrap(), g.sub(a, x).unwrap(), {
            let xc = g.mul(x, c).unwrap();
            g.sub(xc, k).unwrap()
        }];
        let found = eliminate_aliases(&mut g, &residuals, &[0; 4], &symbols).unwrap();
        assert_eq!(found.alias_equations, [true, true, true, false]);
        let value =
            |s: SymbolId| found.removed.iter().find(|r| r.0 == s).map(|r| g.show(r.1).to_string());
        assert_eq!(value(symbols[1]), Some("x".into()));
        assert_eq!(value(symbols[2]), Some("-x".into()));
        assert_eq!(value(symbols[0]), Some("x".into()));
        // The last equation reads x in place of c.
        let xs = g.as_symbol(x).unwrap();
        let ks = g.as_symbol(k).unwrap();
        assert_eq!(g.free_symbols(found.residuals[3]), [xs, ks]);
    }

    #[test]
    fn a_scaled_or_nonlinear_equation_is_no_alias() {
        let mut g = Graph::new();
        let a = g.algebraic("a").unwrap();
        let b = g.algebraic("b").unwrap();
        let symbols: Vec<SymbolId> = [a, b].iter().map(|&n| g.as_symbol(n).unwrap()).collect();
        let two = g.int(2);
        let two_b = g.mul(two, b).unwrap();
        let ab = g.mul(a, b).unwrap();
        let residuals = vec![g.sub(two_b, a).unwrap(), g.sub(ab, two).unwrap()];
        let found = eliminate_aliases(&mut g, &residuals, &[0; 2], &symbols).unwrap();
        // 2b − a = 0 does alias a to 2b? No: only ±b or a parameter value.
        assert_eq!(found.alias_equations, [false, false]);
    }
}
