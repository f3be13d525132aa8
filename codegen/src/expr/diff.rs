//! Symbolic differentiation in forward mode over the DAG: each node's
//! derivative is built once from its children's, so shared subexpressions
//! are differentiated once and the result shares them too (no swell).
//!
//! One propagation serves every derivative: a partial derivative seeds one
//! symbol with 1; a total time derivative along a vector field seeds each
//! symbol with its time derivative, `d/dt e = ∂e/∂t + Σ ∂e/∂y_i · f_i`
//! (course notes §1.3.1, the economic Taylor scheme; eq. 2.2 for hidden
//! constraints).

use crate::error::Result;
use crate::expr::graph::{FxHashMap, Graph};
use crate::expr::node::{Func, Id, Node, SymbolId, SymbolKind};
use std::collections::BTreeMap;

/// Time derivatives of symbols, and the derivatives already taken along them.
///
/// Symbols without an entry are constant along the field (parameters).
#[derive(Default)]
pub struct VectorField {
    derivative_of: BTreeMap<SymbolId, Id>,
    memo: FxHashMap<Id, Id>,
}

impl VectorField {
    /// A field where every symbol is constant.
    pub fn new() -> VectorField {
        VectorField::default()
    }

    /// Declares `d/dt symbol = derivative`. Derivatives taken before the
    /// change are forgotten.
    pub fn set(&mut self, symbol: SymbolId, derivative: Id) {
        self.derivative_of.insert(symbol, derivative);
        self.memo.clear();
    }

    /// The declared derivative of `symbol`, if any.
    pub fn get(&self, symbol: SymbolId) -> Option<Id> {
        self.derivative_of.get(&symbol).copied()
    }
}

impl Graph {
    /// `∂e/∂s`, memoised per (node, symbol) for the life of the graph.
    pub fn partial(&mut self, e: Id, s: SymbolId) -> Result<Id> {
        let mut known = self.partials.remove(&s).unwrap_or_default();
        let one = self.one();
        let result = self.propagate(&[e], &mut known, &|x| (x == s).then_some(one));
        self.partials.insert(s, known);
        result.map(|v| v[0])
    }

    /// `∂e/∂s` for each `s` in `wrt`.
    pub fn gradient(&mut self, e: Id, wrt: &[SymbolId]) -> Result<Vec<Id>> {
        wrt.iter().map(|&s| self.partial(e, s)).collect()
    }

    /// The `n`-th partial derivative `∂ⁿe/∂sⁿ` (`n = 0` is `e`).
    pub fn nth_partial(&mut self, e: Id, s: SymbolId, n: usize) -> Result<Id> {
        (0..n).try_fold(e, |acc, _| self.partial(acc, s))
    }

    /// `d/dt e` along `field`. Derivatives of nodes met before (in earlier
    /// calls with the same field) are reused.
    pub fn total_derivative(&mut self, e: Id, field: &mut VectorField) -> Result<Id> {
        let mut known = std::mem::take(&mut field.memo);
        let seeds = &field.derivative_of;
        let result = self.propagate(&[e], &mut known, &|x| seeds.get(&x).copied());
        field.memo = known;
        result.map(|v| v[0])
    }

    /// `[e, d/dt e, d²/dt² e, ..., dⁿ/dtⁿ e]` along `field`.
    pub fn total_derivatives(
        &mut self,
        e: Id,
        field: &mut VectorField,
        n: usize,
    ) -> Result<Vec<Id>> {
        let mut out = vec![e];
        for _ in 0..n {
            let last = out[out.len() - 1];
            out.push(self.total_derivative(last, field)?);
        }
        Ok(out)
    }

    /// Forward-mode propagation: extends `known` (node -> derivative) to every
    /// node reachable from `roots`, seeding symbol `s` with `seed(s)` (zero when
    /// `None`). Nodes are visited in ascending id order, children first.
    fn propagate(
        &mut self,
        roots: &[Id],
        known: &mut FxHashMap<Id, Id>,
        seed: &dyn Fn(SymbolId) -> Option<Id>,
    ) -> Result<Vec<Id>> {
        let order = self.reachable_until(roots, |id| known.contains_key(&id));
        let zero = self.zero();
        for id in order {
            let d = self.derivative_of_node(id, known, zero, seed)?;
            known.insert(id, d);
        }
        Ok(roots.iter().map(|r| known[r]).collect())
    }

    /// The chain rule for one node, its operands' derivatives being in `known`.
    fn derivative_of_node(
        &mut self,
        id: Id,
        known: &FxHashMap<Id, Id>,
        zero: Id,
        seed: &dyn Fn(SymbolId) -> Option<Id>,
    ) -> Result<Id> {
        let d = |c: &Id| known[c];
        Ok(match self.node(id).clone() {
            Node::Number(_) => zero,
            Node::Symbol(s) => match self.symbol(s).kind {
                SymbolKind::Intermediate { definition } => known[&definition],
                _ => seed(s).unwrap_or(zero),
            },
            Node::Add(terms) => {
                let ds: Vec<Id> = terms.iter().map(d).filter(|&t| t != zero).collect();
                self.sum(&ds)?
            }
            Node::Mul(factors) => {
                // Leibniz: Σ_i (Π_{j≠i} f_j) f_i'.
                let mut terms = Vec::new();
                for (i, f) in factors.iter().enumerate() {
                    let df = d(f);
                    if df == zero {
                        continue;
                    }
                    let mut rest: Vec<Id> = factors
                        .iter()
                        .enumerate()
                        .filter(|&(j, _)| j != i)
                        .map(|(_, &g)| g)
                        .collect();
                    rest.push(df);
                    terms.push(self.product(&rest)?);
                }
                self.sum(&terms)?
            }
            Node::Pow([b, e]) => {
                let (db, de) = (d(&b), d(&e));
                let mut terms = Vec::new();
                if db != zero {
                    // e * b^(e-1) * b'
                    let m1 = self.int(-1);
                    let e_minus_1 = self.add(e, m1)?;
                    let p = self.pow(b, e_minus_1)?;
                    terms.push(self.product(&[e, p, db])?);
                }
                if de != zero {
                    if self.as_number(b).is_some_and(|n| n.is_negative() || n.is_zero()) {
                        return Err(crate::Error::NotFinite {
                            expression: self.show(id).to_string(),
                            reason:
                                "a power has a derivative by its exponent only for a positive base",
                        });
                    }
                    // b^e * ln(b) * e'
                    let ln_b = self.call(Func::Ln, b)?;
                    terms.push(self.product(&[id, ln_b, de])?);
                }
                self.sum(&terms)?
            }
            Node::Call(f, a) => {
                let da = d(&a);
                if da == zero {
                    return Ok(zero);
                }
                let outer = self.derivative_of_call(f, a, id)?;
                self.mul(outer, da)?
            }
            Node::Atan2([y, x]) => {
                let (dy, dx) = (d(&y), d(&x));
                if dy == zero && dx == zero {
                    return Ok(zero);
                }
                // (x y' - y x') / (x² + y²)
                let x_dy = self.mul(x, dy)?;
                let y_dx = self.mul(y, dx)?;
                let numerator = self.sub(x_dy, y_dx)?;
                let x2 = self.powi(x, 2)?;
                let y2 = self.powi(y, 2)?;
                let r2 = self.add(x2, y2)?;
                self.div(numerator, r2)?
            }
        })
    }

    /// `f'(a)`; `node` is `f(a)` itself, reused where the derivative contains it
    /// (exp, tan, tanh), which later lets Taylor recurrences share it.
    fn derivative_of_call(&mut self, f: Func, a: Id, node: Id) -> Result<Id> {
        let one = self.one();
        Ok(match f {
            Func::Sin => self.call(Func::Cos, a)?,
            Func::Cos => {
                let s = self.call(Func::Sin, a)?;
                self.neg(s)?
            }
            Func::Tan => {
                let t2 = self.powi(node, 2)?;
                self.add(one, t2)?
            }
            Func::Asin | Func::Acos => {
                let a2 = self.powi(a, 2)?;
                let one_minus = self.sub(one, a2)?;
                let m_half = self.rational(-1, 2)?;
                let r = self.pow(one_minus, m_half)?;
                if f == Func::Acos {
                    self.neg(r)?
                } else {
                    r
                }
            }
            Func::Atan => {
                let a2 = self.powi(a, 2)?;
                let s = self.add(one, a2)?;
                self.powi(s, -1)?
            }
            Func::Sinh => self.call(Func::Cosh, a)?,
            Func::Cosh => self.call(Func::Sinh, a)?,
            Func::Tanh => {
                let t2 = self.powi(node, 2)?;
                self.sub(one, t2)?
            }
            Func::Exp => node,
            Func::Ln => self.powi(a, -1)?,
            Func::Abs => self.call(Func::Sign, a)?,
            // The derivative of sign is zero wherever it exists.
            Func::Sign => self.zero(),
        })
    }
}
