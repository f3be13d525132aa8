//! Expressions linear in a model's variables with coefficients that read
//! parameters only, `Σ c_k y_k + b`: the form in which connections tie
//! states (`tied_states`) and in which the equations that hide a tie are
//! eliminated (`hidden_ties`).

use crate::{FxHashMap, Graph, Id, SymbolId, SymbolKind};

/// `Σ c_k y_k + b` over states and derivatives, with `c_k` and `b`
/// reading parameters only.
pub(crate) struct Linear {
    /// Each term's symbol and its coefficient.
    pub(crate) terms: Vec<(SymbolId, Id)>,
    /// The part free of the terms' symbols.
    pub(crate) constant: Id,
}

impl Linear {
    /// `r` so; `None` when it is not linear so or reads another variable.
    pub(crate) fn of(g: &mut Graph, r: Id) -> crate::Result<Option<Linear>> {
        let variable = |g: &Graph, s: SymbolId| g.symbol(s).kind != SymbolKind::Parameter;
        Linear::in_terms(g, r, variable, |kind| {
            matches!(kind, SymbolKind::State | SymbolKind::Derivative { .. })
        })
    }

    /// `r` as `Σ c_k y_k + b` over the symbols `unknowns` alone, `b` any
    /// function of the rest (states, the time); `None` when it is not
    /// linear so.
    pub(crate) fn over_symbols(
        g: &mut Graph,
        r: Id,
        unknowns: &[SymbolId],
    ) -> crate::Result<Option<Linear>> {
        Linear::in_terms(g, r, |_, s| unknowns.contains(&s), |_| true)
    }

    /// `r` as `Σ c_k y_k + b(t)` over every variable it reads (states,
    /// derivatives, algebraic variables), `b` reading parameters and the
    /// time `time` only; `None` when it is not linear so.
    pub(crate) fn over_variables(
        g: &mut Graph,
        r: Id,
        time: SymbolId,
    ) -> crate::Result<Option<Linear>> {
        let variable =
            |g: &Graph, s: SymbolId| s != time && g.symbol(s).kind != SymbolKind::Parameter;
        Linear::in_terms(g, r, variable, |kind| {
            matches!(
                kind,
                SymbolKind::State | SymbolKind::Algebraic | SymbolKind::Derivative { .. }
            )
        })
    }

    /// `r` linear in every symbol it reads that `variable` selects, each
    /// of a kind `term` accepts, the rest left in `b`.
    fn in_terms(
        g: &mut Graph,
        r: Id,
        variable: impl Fn(&Graph, SymbolId) -> bool,
        term: impl Fn(SymbolKind) -> bool,
    ) -> crate::Result<Option<Linear>> {
        let variables: Vec<SymbolId> =
            g.free_symbols(r).into_iter().filter(|&s| variable(g, s)).collect();
        let mut terms = Vec::with_capacity(variables.len());
        let mut zeros = FxHashMap::default();
        for &y in &variables {
            if !term(g.symbol(y).kind) {
                return Ok(None);
            }
            let c = g.partial(r, y)?;
            if !is_constant(g, c) {
                return Ok(None);
            }
            terms.push((y, c));
            zeros.insert(y, g.zero());
        }
        let constant = g.substitute(r, &zeros)?;
        Ok(Some(Linear { terms, constant }))
    }

    /// `self − factor · other`, term by term, dropping the terms that cancel.
    pub(crate) fn minus_scaled(
        &self,
        factor: Id,
        other: &Linear,
        g: &mut Graph,
    ) -> crate::Result<Linear> {
        let mut terms = Vec::with_capacity(self.terms.len() + other.terms.len());
        for &(y, c) in &self.terms {
            let d = match other.coefficient(y) {
                Some(d) => g.mul(factor, d)?,
                None => g.zero(),
            };
            terms.push((y, g.sub(c, d)?));
        }
        for &(y, d) in &other.terms {
            if self.coefficient(y).is_none() {
                let scaled = g.mul(factor, d)?;
                terms.push((y, g.neg(scaled)?));
            }
        }
        terms.retain(|&(_, c)| !g.as_number(c).is_some_and(|n| n.is_zero()));
        let scaled = g.mul(factor, other.constant)?;
        let constant = g.sub(self.constant, scaled)?;
        Ok(Linear { terms, constant })
    }

    pub(crate) fn coefficient(&self, y: SymbolId) -> Option<Id> {
        self.terms.iter().find(|t| t.0 == y).map(|t| t.1)
    }

    /// `self / a − other / b`, term by term.
    pub(crate) fn difference(
        &self,
        a: Id,
        other: &Linear,
        b: Id,
        g: &mut Graph,
    ) -> crate::Result<Linear> {
        let mut symbols: Vec<SymbolId> = self.terms.iter().map(|t| t.0).collect();
        for &(y, _) in &other.terms {
            if !symbols.contains(&y) {
                symbols.push(y);
            }
        }
        let zero = g.zero();
        let scaled = |l: &Linear, y: Option<SymbolId>, by: Id, g: &mut Graph| {
            let c = match y {
                Some(y) => l.coefficient(y).unwrap_or(zero),
                None => l.constant,
            };
            g.div(c, by)
        };
        let mut terms = Vec::new();
        for y in symbols {
            let c = scaled(self, Some(y), a, g)?;
            let d = scaled(other, Some(y), b, g)?;
            let c = g.sub(c, d)?;
            if !g.as_number(c).is_some_and(|n| n.is_zero()) {
                terms.push((y, c));
            }
        }
        let c = scaled(self, None, a, g)?;
        let d = scaled(other, None, b, g)?;
        let constant = g.sub(c, d)?;
        Ok(Linear { terms, constant })
    }

    /// `Σ c_k y_k + b` as an expression.
    pub(crate) fn value(&self, g: &mut Graph) -> crate::Result<Id> {
        let mut sum = Vec::with_capacity(self.terms.len() + 1);
        for &(y, c) in &self.terms {
            let y = g.symbol_node(y);
            sum.push(g.mul(c, y)?);
        }
        sum.push(self.constant);
        g.sum(&sum)
    }
}

/// Whether `c` reads parameters only.
pub(crate) fn is_constant(g: &Graph, c: Id) -> bool {
    g.free_symbols(c).iter().all(|&s| g.symbol(s).kind == SymbolKind::Parameter)
}
