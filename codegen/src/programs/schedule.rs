//! Common-subexpression elimination and scheduling: many outputs (a
//! right-hand side and its Jacobian, say) become one straight-line program in
//! which every shared node is computed once, into a named temporary.
//!
//! Hash-consing already made equal subexpressions one node; this pass decides
//! which nodes get a `let`: those used more than once, those that emission
//! would otherwise write twice (`x*x` for `x^2`), named intermediates, and
//! nodes whose inline form would nest deeper than [`MAX_INLINE_DEPTH`] (deep
//! nesting slows rustc and would recurse deeply in emission).

use crate::expr::graph::{FxHashMap, Graph};
use crate::expr::node::{Func, Id, Node, SymbolKind};
use std::collections::{BTreeMap, BTreeSet};

/// Deepest inline nesting before a node is put into a temporary.
pub const MAX_INLINE_DEPTH: u32 = 12;

/// A temporary of a [`Program`]: `let name = <node>;`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Temp {
    /// The node it holds.
    pub node: Id,
    /// Its name: `t0`, `t1`, ... or an intermediate's own name.
    pub name: String,
}

/// Straight-line code for a list of outputs.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Program {
    /// Temporaries in evaluation order (each only uses earlier ones).
    pub temps: Vec<Temp>,
    /// The outputs, in the order asked for.
    pub outputs: Vec<Id>,
    temp_of: FxHashMap<Id, usize>,
    /// For half-integer powers `b^(k/2)`: the shared `b^(1/2)` they are built from.
    root_of: BTreeMap<Id, Id>,
    /// For a product `-1 · f…` whose positive `f…` the outputs also read:
    /// that positive, which it is the negation of.
    negation_of: BTreeMap<Id, Id>,
}

impl Program {
    /// The temporary holding `id`, if it has one.
    pub fn temp(&self, id: Id) -> Option<&Temp> {
        self.temp_of.get(&id).map(|&i| &self.temps[i])
    }

    /// The position of `id`'s temporary in [`Program::temps`], if it has one.
    pub fn temp_index(&self, id: Id) -> Option<usize> {
        self.temp_of.get(&id).copied()
    }

    /// The shared square root `b^(1/2)` that emission builds `id = b^(k/2)` from.
    pub fn shared_root(&self, id: Id) -> Option<Id> {
        self.root_of.get(&id).copied()
    }

    /// The node `id` is the negation of, where emission writes `id` as
    /// `-that` (a current read with its sign by one node of a ladder and
    /// against it by the next is computed once).
    pub fn negation_of(&self, id: Id) -> Option<Id> {
        self.negation_of.get(&id).copied()
    }

    /// Evaluates the program as emitted code would: temporaries in order, each
    /// from earlier ones; outputs last. Fails if a temporary is read before it
    /// is written (a scheduling bug).
    pub fn evaluate(
        &self,
        g: &Graph,
        value: &dyn Fn(crate::SymbolId) -> f64,
    ) -> Result<Vec<f64>, String> {
        let mut done: BTreeMap<Id, f64> = BTreeMap::new();
        for t in &self.temps {
            let v = self.inline_value(g, t.node, true, &done, value)?;
            done.insert(t.node, v);
        }
        self.outputs.iter().map(|&o| self.inline_value(g, o, false, &done, value)).collect()
    }

    fn inline_value(
        &self,
        g: &Graph,
        id: Id,
        defining: bool,
        done: &BTreeMap<Id, f64>,
        value: &dyn Fn(crate::SymbolId) -> f64,
    ) -> Result<f64, String> {
        if !defining && self.temp_of.contains_key(&id) {
            return done
                .get(&id)
                .copied()
                .ok_or_else(|| format!("temporary for {id} read before it was written"));
        }
        let v = |c: Id| self.inline_value(g, c, false, done, value);
        Ok(match g.node(id) {
            Node::Number(n) => n.to_f64(),
            Node::Symbol(s) => match g.symbol(*s).kind {
                SymbolKind::Intermediate { definition } => v(definition)?,
                _ => value(*s),
            },
            Node::Add(t) => t.iter().map(|&c| v(c)).sum::<Result<f64, String>>()?,
            Node::Mul(f) => f.iter().map(|&c| v(c)).product::<Result<f64, String>>()?,
            Node::Pow([b, e]) => match g.as_number(*e) {
                Some(n) => crate::expr::number::pow_f64(v(*b)?, n),
                None => v(*b)?.powf(v(*e)?),
            },
            Node::Call(f, a) => f.apply(v(*a)?),
            Node::Atan2([y, x]) => v(*y)?.atan2(v(*x)?),
        })
    }
}

/// `true` for nodes emitted as a plain token (a symbol or a literal).
fn is_leaf(g: &Graph, id: Id) -> bool {
    match g.node(id) {
        Node::Number(_) => true,
        Node::Symbol(s) => !matches!(g.symbol(*s).kind, SymbolKind::Intermediate { .. }),
        _ => false,
    }
}

/// `-x` for a leaf `x`: cheaper to repeat than to store (it folds into a subtraction).
fn is_negated_leaf(g: &Graph, id: Id) -> bool {
    match g.node(id) {
        Node::Mul(f) if f.len() == 2 => {
            let minus_one = |i: Id| g.as_number(i) == Some(crate::Number::MINUS_ONE);
            (minus_one(f[0]) && is_leaf(g, f[1])) || (minus_one(f[1]) && is_leaf(g, f[0]))
        }
        _ => false,
    }
}

/// Operands that emission writes more than once: the base of `x^2`, `x^3`,
/// `x^(3/2)` (`x * x.sqrt()`), the argument of `sign`.
fn duplicated_operand(g: &Graph, id: Id) -> Option<Id> {
    match g.node(id) {
        Node::Pow([b, e]) => {
            let r = g.as_number(*e)?.as_rational()?;
            let n = r.numer().unsigned_abs();
            let dup = (r.is_integer() && (n == 2 || n == 3)) || (r.denom() == 2 && n >= 3);
            dup.then_some(*b)
        }
        Node::Call(Func::Sign, a) => Some(*a),
        _ => None,
    }
}

impl Graph {
    /// Schedules `outputs` into a [`Program`]. Deterministic: the same graph and
    /// outputs give the same temporaries with the same names.
    pub fn schedule(&mut self, outputs: &[Id]) -> Program {
        let root_of = self.shared_square_roots(outputs);
        let negation_of = self.negated_products(outputs);
        let order = self.dependency_order(outputs, &root_of, &negation_of);
        let position: FxHashMap<Id, usize> =
            order.iter().enumerate().map(|(i, &id)| (id, i)).collect();
        let mut uses = vec![0u32; order.len()];
        for o in outputs {
            uses[position[o]] += 1;
        }
        for &id in &order {
            // A negation reads its positive, not its factors.
            match negation_of.get(&id) {
                Some(p) => uses[position[p]] += 1,
                None => {
                    for c in self.operands(id) {
                        uses[position[c]] += 1;
                    }
                }
            }
            if let Some(b) = duplicated_operand(self, id) {
                uses[position[&b]] += 1;
            }
            if let Some(r) = root_of.get(&id) {
                uses[position[r]] += 1;
            }
        }
        let mut is_temp = vec![false; order.len()];
        let mut depth = vec![0u32; order.len()];
        for (i, &id) in order.iter().enumerate() {
            if is_leaf(self, id) || is_negated_leaf(self, id) {
                continue;
            }
            let d = match negation_of.get(&id) {
                Some(p) => 1 + depth[position[p]],
                None => 1 + self.operands(id).iter().map(|c| depth[position[c]]).max().unwrap_or(0),
            };
            let named = matches!(self.node(id), Node::Symbol(_));
            if named || uses[i] > 1 || d > MAX_INLINE_DEPTH {
                is_temp[i] = true;
            } else {
                depth[i] = d;
            }
        }
        let temp_nodes: Vec<Id> =
            order.iter().zip(&is_temp).filter(|(_, &t)| t).map(|(&id, _)| id).collect();
        let taken: BTreeSet<&str> = temp_nodes
            .iter()
            .filter_map(|&id| self.as_symbol(id).map(|s| self.symbol(s).name.as_str()))
            .collect();
        let mut counter = 0usize;
        let mut temps = Vec::with_capacity(temp_nodes.len());
        let mut temp_of = FxHashMap::default();
        for &id in &temp_nodes {
            let name = match self.as_symbol(id) {
                Some(s) => self.symbol(s).name.clone(),
                None => loop {
                    let candidate = format!("t{counter}");
                    counter += 1;
                    if !taken.contains(candidate.as_str()) {
                        break candidate;
                    }
                },
            };
            temp_of.insert(id, temps.len());
            temps.push(Temp { node: id, name });
        }
        Program { temps, outputs: outputs.to_vec(), temp_of, root_of, negation_of }
    }

    /// Every node the outputs need, dependencies first: operands, and for a
    /// half-integer power its shared root (which may have a larger id than the
    /// power, so id order is not enough). Deterministic: a depth-first
    /// post-order visiting operands in ascending id order.
    fn dependency_order(
        &self,
        outputs: &[Id],
        root_of: &BTreeMap<Id, Id>,
        negation_of: &BTreeMap<Id, Id>,
    ) -> Vec<Id> {
        let mut visited = vec![false; self.len()];
        let mut order = Vec::new();
        let mut starts: Vec<Id> = outputs.to_vec();
        starts.sort_unstable();
        let mut stack: Vec<(Id, bool)> = starts.into_iter().rev().map(|id| (id, false)).collect();
        while let Some((id, expanded)) = stack.pop() {
            if expanded {
                order.push(id);
                continue;
            }
            if visited[id.index()] {
                continue;
            }
            visited[id.index()] = true;
            stack.push((id, true));
            let mut deps: Vec<Id> = self.operands(id).to_vec();
            deps.extend(root_of.get(&id));
            deps.extend(negation_of.get(&id));
            deps.sort_unstable();
            stack
                .extend(deps.into_iter().rev().filter(|d| !visited[d.index()]).map(|d| (d, false)));
        }
        order
    }

    /// Half-integer powers of one base (`r^(-3/2)` and `r^(-5/2)` in gravity
    /// Jacobians, `u^(1/2)` and `u^(-1/2)` in `sqrt(u)` and its derivative)
    /// share one square root: maps each such power to the node `b^(1/2)`,
    /// created if needed.
    fn shared_square_roots(&mut self, outputs: &[Id]) -> BTreeMap<Id, Id> {
        let mut family: BTreeMap<Id, Vec<Id>> = BTreeMap::new();
        for id in self.reachable(outputs) {
            if let Node::Pow([b, e]) = self.node(id) {
                if self
                    .as_number(*e)
                    .and_then(crate::Number::as_rational)
                    .is_some_and(|r| r.denom() == 2)
                {
                    family.entry(*b).or_default().push(id);
                }
            }
        }
        let half = self.num(crate::Number::Rational(
            crate::Rational::new(1, 2).unwrap_or(crate::Rational::ONE),
        ));
        let mut root_of = BTreeMap::new();
        for (base, powers) in family {
            if powers.len() < 2 {
                continue;
            }
            let root = self.intern(Node::Pow([base, half]));
            for p in powers.into_iter().filter(|&p| p != root) {
                root_of.insert(p, root);
            }
        }
        root_of
    }

    /// Products `-1 · f…` whose positive (`f…`, or the single `f`) the
    /// outputs also read, each mapped to that positive: hash-consing folds
    /// the sign into the product, so `x·y` and `-x·y` are two nodes that
    /// would be computed twice.
    fn negated_products(&self, outputs: &[Id]) -> BTreeMap<Id, Id> {
        let reachable = self.reachable(outputs);
        // How often each node is read: by the outputs and by other nodes.
        let mut reads: FxHashMap<Id, u32> = FxHashMap::default();
        for &id in outputs.iter().chain(reachable.iter().flat_map(|&id| self.operands(id))) {
            *reads.entry(id).or_default() += 1;
        }
        let mut negation_of = BTreeMap::new();
        for &id in &reachable {
            let Node::Mul(factors) = self.node(id) else { continue };
            let Some(k) =
                factors.iter().position(|&f| self.as_number(f) == Some(crate::Number::MINUS_ONE))
            else {
                continue;
            };
            let rest: Vec<Id> =
                factors.iter().enumerate().filter(|&(i, _)| i != k).map(|(_, &f)| f).collect();
            // The positive must be read elsewhere too (the single factor
            // of `-1 · f` is read by this product itself).
            let (positive, elsewhere) = match rest[..] {
                [single] => (Some(single), 2),
                _ => (self.lookup(&Node::Mul(rest.into())), 1),
            };
            // A leaf's negation is cheaper to repeat than to share.
            let shared =
                |p: &Id| reads.get(p).is_some_and(|&n| n >= elsewhere) && !is_leaf(self, *p);
            if let Some(p) = positive.filter(shared) {
                negation_of.insert(id, p);
            }
        }
        negation_of
    }

    /// Number of distinct nodes reachable from `roots`: the size of the DAG
    /// they form, the measure of expression swell.
    pub fn dag_size(&self, roots: &[Id]) -> usize {
        self.reachable(roots).len()
    }
}
