//! Numerical evaluation of expressions at a point, with the same semantics as
//! the emitted code (integer powers by `powi`, half-integer powers by `sqrt`).

use crate::expr::graph::Graph;
use crate::expr::node::{Id, Node, SymbolId, SymbolKind};
use crate::expr::number::pow_f64;

impl Graph {
    /// The values of `roots`, with each symbol's value given by `value`
    /// (intermediates are evaluated from their definitions).
    pub fn eval(&self, roots: &[Id], value: &dyn Fn(SymbolId) -> f64) -> Vec<f64> {
        let order = self.reachable(roots);
        let mut slot = vec![usize::MAX; self.len()];
        let mut values: Vec<f64> = Vec::with_capacity(order.len());
        for &id in &order {
            let v = |c: Id| values[slot[c.index()]];
            let x = match self.node(id) {
                Node::Number(n) => n.to_f64(),
                Node::Symbol(s) => match self.symbol(*s).kind {
                    SymbolKind::Intermediate { definition } => v(definition),
                    _ => value(*s),
                },
                Node::Add(terms) => terms.iter().map(|&t| v(t)).sum(),
                Node::Mul(factors) => factors.iter().map(|&f| v(f)).product(),
                Node::Pow([b, e]) => match self.as_number(*e) {
                    Some(n) => pow_f64(v(*b), n),
                    None => v(*b).powf(v(*e)),
                },
                Node::Call(f, a) => f.apply(v(*a)),
                Node::Atan2([y, x]) => v(*y).atan2(v(*x)),
            };
            slot[id.index()] = values.len();
            values.push(x);
        }
        roots.iter().map(|r| values[slot[r.index()]]).collect()
    }

    /// The value of one expression, with symbol values given by name; a
    /// symbol not listed reads as NaN, so a forgotten value shows in the result.
    pub fn eval_named(&self, id: Id, values: &[(&str, f64)]) -> f64 {
        let lookup = |s: SymbolId| {
            let name = &self.symbol(s).name;
            values.iter().find(|(n, _)| n == name).map_or(f64::NAN, |&(_, v)| v)
        };
        self.eval(&[id], &lookup)[0]
    }
}
