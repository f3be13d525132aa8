//! Substitution: rebuild an expression with some symbols replaced, through
//! the smart constructors so the result is simplified again.

use crate::error::Result;
use crate::expr::graph::{FxHashMap, Graph};
use crate::expr::node::{Id, Node, SymbolId};

impl Graph {
    /// `e` with each symbol `s` in `replace` replaced by `replace[s]`.
    /// Shared subexpressions are rebuilt once.
    pub fn substitute(&mut self, e: Id, replace: &FxHashMap<SymbolId, Id>) -> Result<Id> {
        Ok(self.substitute_all(&[e], replace)?[0])
    }

    /// [`Graph::substitute`] for several expressions at once, sharing the work.
    pub fn substitute_all(
        &mut self,
        roots: &[Id],
        replace: &FxHashMap<SymbolId, Id>,
    ) -> Result<Vec<Id>> {
        let mut done: FxHashMap<Id, Id> = FxHashMap::default();
        for id in self.reachable(roots) {
            let new = match self.node(id).clone() {
                Node::Number(_) => id,
                Node::Symbol(s) => match replace.get(&s) {
                    Some(&r) => r,
                    None => match self.symbol(s).kind {
                        // An intermediate's definition may mention replaced symbols.
                        crate::SymbolKind::Intermediate { definition }
                            if done[&definition] != definition =>
                        {
                            done[&definition]
                        }
                        _ => id,
                    },
                },
                Node::Add(terms) => {
                    let t: Vec<Id> = terms.iter().map(|t| done[t]).collect();
                    if t[..] == terms[..] {
                        id
                    } else {
                        self.sum(&t)?
                    }
                }
                Node::Mul(factors) => {
                    let f: Vec<Id> = factors.iter().map(|f| done[f]).collect();
                    if f[..] == factors[..] {
                        id
                    } else {
                        self.product(&f)?
                    }
                }
                Node::Pow([b, e]) => {
                    let (nb, ne) = (done[&b], done[&e]);
                    if (nb, ne) == (b, e) {
                        id
                    } else {
                        self.pow(nb, ne)?
                    }
                }
                Node::Call(f, a) => {
                    let na = done[&a];
                    if na == a {
                        id
                    } else {
                        self.call(f, na)?
                    }
                }
                Node::Atan2([y, x]) => {
                    let (ny, nx) = (done[&y], done[&x]);
                    if (ny, nx) == (y, x) {
                        id
                    } else {
                        self.atan2(ny, nx)?
                    }
                }
            };
            done.insert(id, new);
        }
        Ok(roots.iter().map(|r| done[r]).collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn replaces_and_resimplifies() {
        let mut g = Graph::new();
        let x = g.state("x").unwrap();
        g.state("y").unwrap();
        let e = g.parse("x*y + sin(x) - y").unwrap();
        let y = g.symbol_named("y").unwrap();
        let mut map = FxHashMap::default();
        map.insert(y, x);
        let r = g.substitute(e, &map).unwrap();
        assert_eq!(r, g.parse("x^2 + sin(x) - x").unwrap());
        let zero = g.zero();
        map.insert(y, zero);
        let r = g.substitute(e, &map).unwrap();
        assert_eq!(r, g.parse("sin(x)").unwrap());
        let _ = x;
    }
}
