//! Decomposition of the right-hand side into the Taylor tape of
//! `daegen_runtime::taylor_tape`: one elementary operation per u-variable,
//! shared subexpressions once (Jorba & Zou's decomposition; heyoka's
//! u-variables). Subexpressions of parameters and numbers only are
//! constants, computed once when the tape is built.

use crate::{Func, FxHashMap, Graph, Id, Node, SymbolId, SymbolKind};
use proc_macro2::TokenStream;
use quote::quote;

/// An operand of a tape operation (the model's side of
/// `daegen::runtime::taylor_tape::Operand`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Operand {
    /// u-variable `i`.
    Var(usize),
    /// State `i`.
    State(usize),
    /// The independent variable.
    Time,
    /// Index into the constants computed at the top of the method.
    Const(usize),
}

impl Operand {
    fn tokens(&self) -> TokenStream {
        let path = quote!(O);
        let lit = |i: usize| proc_macro2::Literal::usize_unsuffixed(i);
        match self {
            Operand::Var(i) => {
                let i = lit(*i);
                quote!(#path::Var(#i))
            }
            Operand::State(i) => {
                let i = lit(*i);
                quote!(#path::State(#i))
            }
            Operand::Time => quote!(#path::Time),
            // The constants' slot: the tape is a table, its constants
            // computed beside it (`emit::taylor_items`).
            Operand::Const(i) => {
                let i = lit(*i);
                quote!(#path::Const(#i))
            }
        }
    }
}

/// A constant of the tape, computed once when the tape is built.
pub enum Constant {
    /// The value of a parameter expression.
    Expr(Id),
    /// An integer the decomposition needs (the 1 of `1 − a²`, ...).
    Integer(i64),
    /// The product of the constant factors of one product.
    Product(Vec<Id>),
    /// The sum of the constant terms of one sum.
    Sum(Vec<Id>),
    /// A real number of the decomposition (the exponent of a power).
    Value(f64),
}

// The runtime's `TapeOp` of the same name mirrors these variants: the
// macro crate cannot link the runtime, so each side has its own.
/// How a u-variable's Taylor coefficients follow from its operands' (the
/// recurrences of `daegen::runtime::taylor_tape::Step`, for the unrolled
/// layout). Constants are indices into [`Tape::constants`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TapeOp {
    /// `a + b`.
    Add(Operand, Operand),
    /// `a·c`, c a constant.
    Scale(Operand, usize),
    /// `a/c`, c a constant.
    Quotient(Operand, usize),
    /// `a·b`.
    Mul(Operand, Operand),
    /// `a·a`.
    Square(Operand),
    /// `a/b`.
    Div(Operand, Operand),
    /// `a^e`, e a real constant.
    Pow(Operand, f64),
    /// `exp(a)`.
    Exp(Operand),
    /// `ln(a)`.
    Ln(Operand),
    /// `sin(a)` and, in the next u-variable, `cos(a)`.
    SinCos(Operand),
    /// `sinh(a)` and, in the next u-variable, `cosh(a)`.
    SinhCosh(Operand),
    /// `asin`, `acos` or `atan` of `a`, with d·u' = ±a'.
    Inverse(InverseFunction, Operand, Operand),
    /// `atan2(y, x)` with `d = x² + y²`.
    Atan2(Operand, Operand, Operand),
}

/// The inverse functions of [`TapeOp::Inverse`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum InverseFunction {
    /// d = √(1 − a²), u' = a'/d.
    Asin,
    /// d = √(1 − a²), u' = −a'/d.
    Acos,
    /// d = 1 + a², u' = a'/d.
    Atan,
}

/// A tape of `recurrences` (u-variable i computed by recurrence i) and
/// `constants` constants, for the unit tests of the passes that read tapes.
#[cfg(test)]
pub(crate) fn test_tape(recurrences: Vec<TapeOp>, outputs: Vec<Operand>, constants: usize) -> Tape {
    Tape {
        constants: (0..constants).map(|_| Constant::Integer(0)).collect(),
        ops: vec![TokenStream::new(); recurrences.len()],
        outputs: vec![TokenStream::new(); outputs.len()],
        recurrences: recurrences.into_iter().enumerate().collect(),
        output_operands: outputs,
    }
}

/// The tape of `bodies` bodies attracting each other in space, as the
/// outer solar system writes it: per interaction (i, j), i < j, the
/// differences `x_j − x_i`, their squares' sum, its −3/2 power and the
/// three products, added with ±G·m into both bodies' accelerations.
#[cfg(test)]
pub(crate) fn n_body_tape(bodies: usize) -> Tape {
    use Operand::{State, Var};
    // States: positions 3i + c, velocities 3(bodies + i) + c. Constants:
    // c0 = −1, then G·m_j, then −G·m_i.
    let position = |i: usize, c: usize| State(3 * i + c);
    let mut ops: Vec<TapeOp> = Vec::new();
    let push = |ops: &mut Vec<TapeOp>, r| {
        ops.push(r);
        Var(ops.len() - 1)
    };
    let mut acceleration: Vec<Option<Operand>> = vec![None; 3 * bodies];
    for i in 0..bodies {
        for j in i + 1..bodies {
            let mut d = Vec::new();
            let mut squares = Vec::new();
            for c in 0..3 {
                let minus = push(&mut ops, TapeOp::Scale(position(i, c), 0));
                let dc = push(&mut ops, TapeOp::Add(position(j, c), minus));
                squares.push(push(&mut ops, TapeOp::Square(dc)));
                d.push(dc);
            }
            let partial = push(&mut ops, TapeOp::Add(squares[0], squares[1]));
            let r2 = push(&mut ops, TapeOp::Add(partial, squares[2]));
            let r3 = push(&mut ops, TapeOp::Pow(r2, -1.5));
            for (c, &dc) in d.iter().enumerate() {
                let product = push(&mut ops, TapeOp::Mul(dc, r3));
                for (body, weight) in [(i, 1 + j), (j, 1 + bodies + i)] {
                    let term = push(&mut ops, TapeOp::Scale(product, weight));
                    let sum = match acceleration[3 * body + c] {
                        Some(previous) => push(&mut ops, TapeOp::Add(previous, term)),
                        None => term,
                    };
                    acceleration[3 * body + c] = Some(sum);
                }
            }
        }
    }
    let outputs = (0..3 * bodies)
        .map(|i| State(3 * bodies + i))
        .chain(acceleration.into_iter().flatten())
        .collect();
    let mut tape = test_tape(ops, outputs, 1 + 2 * bodies);
    // Integers for the expansion to fold: G·m_j = j + 1.
    tape.constants = std::iter::once(-1)
        .chain((0..bodies as i64).map(|j| j + 1))
        .chain((0..bodies as i64).map(|i| -(i + 1)))
        .map(Constant::Integer)
        .collect();
    tape
}

/// The tape of `outputs`: (constant expressions, operations, output operands).
pub struct Tape {
    /// Constants, in order (`c0`, `c1`, ...).
    pub constants: Vec<Constant>,
    /// One `TapeOp` per u-variable, as tokens.
    pub ops: Vec<TokenStream>,
    /// The operand of each output, as tokens.
    pub outputs: Vec<TokenStream>,
    /// Per u-variable with a recurrence of its own (cos and cosh come with
    /// sin and sinh), its index and recurrence.
    pub recurrences: Vec<(usize, TapeOp)>,
    /// The operand of each output.
    pub output_operands: Vec<Operand>,
}

struct Builder<'g> {
    g: &'g Graph,
    slot_of: &'g FxHashMap<SymbolId, usize>,
    time: SymbolId,
    operand_of: FxHashMap<Id, Operand>,
    constants: Vec<Constant>,
    ops: Vec<TokenStream>,
    recurrences: Vec<(usize, TapeOp)>,
    /// ("Sin", a) → the u-variable of sin(a), paired with cos(a) after it
    /// (likewise "Sinh" and cosh), so the pair is made once per argument.
    pairs_of: FxHashMap<(&'static str, Id), usize>,
    /// Each sum, product and quotient of two operands once: products that
    /// differ only by their constant factors (m_j·dx·r³ and −m_i·dx·r³ of
    /// an N-body model) share the convolution dx·r³.
    binary_of: FxHashMap<(&'static str, Operand, Operand), Operand>,
    /// Sums whose negation is also a node (x_j − x_i and x_i − x_j).
    negation_of: &'g FxHashMap<Id, Id>,
    /// u-variables that are the negation of another operand.
    negative_of: FxHashMap<Operand, Operand>,
}

impl Builder<'_> {
    /// Appends a tape operation and, unless its value comes with the
    /// previous one (cos, cosh), its step for the emitted layout.
    fn push(&mut self, op: TokenStream, recurrence: Option<TapeOp>) -> Operand {
        if let Some(r) = recurrence {
            self.recurrences.push((self.ops.len(), r));
        }
        self.ops.push(op);
        Operand::Var(self.ops.len() - 1)
    }

    fn constant(&mut self, id: Id) -> Operand {
        self.constants.push(Constant::Expr(id));
        Operand::Const(self.constants.len() - 1)
    }

    fn integer(&mut self, n: i64) -> Operand {
        self.constants.push(Constant::Integer(n));
        Operand::Const(self.constants.len() - 1)
    }

    /// The slot of the real number `v`, as a literal of the table.
    fn value_slot(&mut self, v: f64) -> TokenStream {
        self.constants.push(Constant::Value(v));
        let slot = proc_macro2::Literal::usize_unsuffixed(self.constants.len() - 1);
        quote!(#slot)
    }

    /// The u-variable of `f(a)` with d·u' = ±a' (asin, acos, atan); `d` is
    /// built from products, sums and a square root of earlier u-variables.
    fn inverse(&mut self, f: &str, a: &Operand) -> Operand {
        let square = self.binary("Mul", a, a);
        let one = self.integer(1);
        let d = if f == "Atan" {
            self.binary("Add", &one, &square)
        } else {
            let minus_one = self.integer(-1);
            let negated = self.binary("Mul", &minus_one, &square);
            let difference = self.binary("Add", &one, &negated);
            let (b, half) = (difference.tokens(), self.value_slot(0.5));
            self.push(quote!(T::Pow(#b, #half)), Some(TapeOp::Pow(difference, 0.5)))
        };
        let function = match f {
            "Asin" => InverseFunction::Asin,
            "Acos" => InverseFunction::Acos,
            _ => InverseFunction::Atan,
        };
        let recurrence = TapeOp::Inverse(function, *a, d);
        let (a, d) = (a.tokens(), d.tokens());
        let f = quote::format_ident!("{}", f);
        self.push(
            quote!(T::Inverse(
                I::#f,
                #a,
                #d
            )),
            Some(recurrence),
        )
    }

    fn binary(&mut self, name: &'static str, a: &Operand, b: &Operand) -> Operand {
        // Sums and products commute: one key for both orders.
        let key = match name {
            "Div" => (name, *a, *b),
            _ => (name, *a.min(b), *a.max(b)),
        };
        if let Some(&done) = self.binary_of.get(&key) {
            return done;
        }
        let result = self.new_binary(name, a, b);
        self.binary_of.insert(key, result);
        result
    }

    fn new_binary(&mut self, name: &'static str, a: &Operand, b: &Operand) -> Operand {
        let constant = |o: &Operand| match o {
            Operand::Const(i) => Some(*i),
            _ => None,
        };
        let step = match (name, constant(a), constant(b)) {
            ("Mul", _, _) if a == b => TapeOp::Square(*a),
            ("Mul", Some(c), None) => TapeOp::Scale(*b, c),
            ("Mul", None, Some(c)) => TapeOp::Scale(*a, c),
            ("Mul", _, _) => TapeOp::Mul(*a, *b),
            ("Div", _, Some(c)) => TapeOp::Quotient(*a, c),
            ("Div", _, _) => TapeOp::Div(*a, *b),
            _ => TapeOp::Add(*a, *b),
        };
        let (a, b) = (a.tokens(), b.tokens());
        let op = quote::format_ident!("{}", name);
        self.push(quote!(T::#op(#a, #b)), Some(step))
    }

    fn unary(&mut self, name: &str, a: &Operand) -> Operand {
        let step = match name {
            "Sin" => TapeOp::SinCos(*a),
            "Sinh" => TapeOp::SinhCosh(*a),
            "Exp" => TapeOp::Exp(*a),
            _ => TapeOp::Ln(*a),
        };
        let a = a.tokens();
        let op = quote::format_ident!("{}", name);
        self.push(quote!(T::#op(#a)), Some(step))
    }

    /// `a^n` for an integer n ≥ 1 by binary powering (products only: safe
    /// at a zero base, where the general power recurrence divides by it).
    fn integer_power(&mut self, a: &Operand, n: u64) -> Operand {
        if n == 1 {
            return *a;
        }
        let half = self.integer_power(a, n / 2);
        let square = self.binary("Mul", &half, &half);
        if n % 2 == 1 {
            self.binary("Mul", &square, a)
        } else {
            square
        }
    }

    /// sin(a) and cos(a) (`first` = "Sin"), or sinh(a) and cosh(a)
    /// ("Sinh"): one recurrence for the pair, the second reading the
    /// first's variable + 1, made once per argument.
    fn pair(&mut self, first: &'static str, arg: Id, a: &Operand) -> (Operand, Operand) {
        if let Some(&v) = self.pairs_of.get(&(first, arg)) {
            return (Operand::Var(v), Operand::Var(v + 1));
        }
        let s = self.unary(first, a);
        let second =
            if first == "Sin" { quote!(T::CosOfPrevious) } else { quote!(T::CoshOfPrevious) };
        let c = self.push(second, None);
        if let Operand::Var(v) = s {
            self.pairs_of.insert((first, arg), v);
        }
        (s, c)
    }

    /// The operands of a sum or product of a time-dependent node, split
    /// into constants and the others (never empty: the node depends on time).
    /// `acc op c` for the constant operands of a sum or a product: one
    /// constant as it is, several folded into one tape constant by `fold`.
    fn with_constants(
        &mut self,
        op: &'static str,
        acc: Operand,
        constant: Vec<Id>,
        fold: fn(Vec<Id>) -> Constant,
    ) -> Operand {
        match constant.len() {
            0 => acc,
            1 => self.binary(op, &acc, &self.operand(constant[0])),
            _ => {
                self.constants.push(fold(constant));
                let c = Operand::Const(self.constants.len() - 1);
                self.binary(op, &acc, &c)
            }
        }
    }

    fn split_constants(&self, operands: &[Id]) -> (Vec<Id>, Vec<Id>) {
        let (constant, varying): (Vec<Id>, Vec<Id>) =
            operands.iter().partition(|&&o| matches!(self.operand(o), Operand::Const(_)));
        if varying.is_empty() {
            (Vec::new(), constant)
        } else {
            (constant, varying)
        }
    }

    fn operand(&self, id: Id) -> Operand {
        self.operand_of.get(&id).cloned().unwrap_or(Operand::Time)
    }

    /// The operand of `id`, its operands being done (ascending ids).
    fn node(&mut self, id: Id, time_dependent: bool) -> crate::Result<Operand> {
        // One match arm per node kind of the expression DAG, each its Taylor recurrence.
        if !time_dependent {
            return Ok(self.constant(id));
        }
        let g = self.g;
        Ok(match g.node(id) {
            Node::Number(_) => self.constant(id),
            Node::Symbol(s) => match g.symbol(*s).kind {
                _ if *s == self.time => Operand::Time,
                SymbolKind::Parameter => self.constant(id),
                // A named intermediate is its definition's coefficients.
                SymbolKind::Intermediate { definition } => self.operand(definition),
                _ => match self.slot_of.get(s) {
                    Some(&i) => Operand::State(i),
                                        None => {
                        return Err(crate::Error::Unsupported {
                            message: format!(
                                "`{}` has no place in the Taylor tape: remove `taylor = ...` from `#[dae_model]`",
                                g.symbol(*s).name
                            ),
                        })
                    }
                },
            },
                        // Constant terms and factors become one constant, so that the
            // tape holds no u-variable that is a constant (whose zero
            // higher coefficients would cost a full convolution in every
            // product it enters), and the constant enters last, as an O(1)
            // shift or scaling per order.
                        Node::Add(_) if self.negation_of.get(&id).is_some_and(|n| self.operand_of.contains_key(n)) => {
                // The negation of a sum already on the tape: one scaling.
                let positive = self.operand(self.negation_of[&id]);
                let minus_one = self.integer(-1);
                let negated = self.binary("Mul", &positive, &minus_one);
                self.negative_of.insert(negated, positive);
                negated
            }
            Node::Add(terms) => {
                let (constant, varying) = self.split_constants(terms);
                let mut acc = self.operand(varying[0]);
                for &t in &varying[1..] {
                    let next = self.operand(t);
                    acc = self.binary("Add", &acc, &next);
                }
                self.with_constants("Add", acc, constant, Constant::Sum)
            }
            Node::Mul(factors) => {
                let (constant, varying) = self.split_constants(factors);
                // A factor that is the negation of another operand enters
                // as that operand with a sign, so −dx·r³ and dx·r³ share
                // their convolution.
                let mut negative = false;
                let mut varying: Vec<Operand> = varying
                    .iter()
                    .map(|&f| {
                        let o = self.operand(f);
                        match self.negative_of.get(&o) {
                            Some(&positive) => {
                                negative = !negative;
                                positive
                            }
                            None => o,
                        }
                    })
                    .collect();
                varying.sort();
                let mut acc = varying[0];
                for next in &varying[1..] {
                    acc = self.binary("Mul", &acc, next);
                }
                if negative {
                    let minus_one = self.integer(-1);
                    acc = self.binary("Mul", &acc, &minus_one);
                }
                self.with_constants("Mul", acc, constant, Constant::Product)
            }
            Node::Pow([b, e]) => {
                let base = self.operand(*b);
                match g.as_number(*e) {
                    Some(n) if n.as_integer().is_some_and(|k| k > 0) => {
                        self.integer_power(&base, n.as_integer().unwrap_or(1).unsigned_abs())
                    }
                    Some(n) if n.as_integer().is_some() => {
                        let k = n.as_integer().unwrap_or(-1).unsigned_abs();
                        let p = self.integer_power(&base, k);
                        let one = self.integer(1);
                        self.binary("Div", &one, &p)
                    }
                    Some(n) => {
                        let value = n.to_f64();
                        let (b, e) = (base.tokens(), self.value_slot(value));
                        self.push(
                            quote!(T::Pow(#b, #e)),
                            Some(TapeOp::Pow(base, value)),
                        )
                    }
                    None => {
                        // b^e = exp(e ln b)
                        let exponent = self.operand(*e);
                        let ln = self.unary("Ln", &base);
                        let product = self.binary("Mul", &exponent, &ln);
                        self.unary("Exp", &product)
                    }
                }
            }
            Node::Call(f, a) => {
                let arg = self.operand(*a);
                match f {
                    Func::Exp => self.unary("Exp", &arg),
                    Func::Ln => self.unary("Ln", &arg),
                    Func::Sin => self.pair("Sin", *a, &arg).0,
                    Func::Cos => self.pair("Sin", *a, &arg).1,
                    Func::Tan => {
                        let (s, c) = self.pair("Sin", *a, &arg);
                        self.binary("Div", &s, &c)
                    }
                    Func::Sinh => self.pair("Sinh", *a, &arg).0,
                    Func::Cosh => self.pair("Sinh", *a, &arg).1,
                    Func::Tanh => {
                        let (s, c) = self.pair("Sinh", *a, &arg);
                        self.binary("Div", &s, &c)
                    }
                    Func::Asin => self.inverse("Asin", &arg),
                    Func::Acos => self.inverse("Acos", &arg),
                    Func::Atan => self.inverse("Atan", &arg),
                                        Func::Abs | Func::Sign => {
                        return Err(crate::Error::NotSmooth {
                            node: id,
                            function: f.name(),
                        })
                    }
                }
            }
            Node::Atan2([y, x]) => {
                let (y, x) = (self.operand(*y), self.operand(*x));
                let xx = self.binary("Mul", &x, &x);
                let yy = self.binary("Mul", &y, &y);
                let d = self.binary("Add", &xx, &yy);
                let step = TapeOp::Atan2(y, x, d);
                let (y, x, d) = (y.tokens(), x.tokens(), d.tokens());
                self.push(
                    quote!(T::Atan2(#y, #x, #d)),
                    Some(step),
                )
            }
        })
    }
}

/// The sums reachable from `outputs` whose term-by-term negation is also
/// reachable (x_j − x_i and x_i − x_j of an N-body model), both ways: the
/// symbolic core keeps them as two nodes.
pub fn negated_sums(g: &mut Graph, outputs: &[Id]) -> crate::Result<FxHashMap<Id, Id>> {
    let reachable = g.reachable(outputs);
    let known: std::collections::HashSet<Id> = reachable.iter().copied().collect();
    let mut pairs = FxHashMap::default();
    for id in reachable {
        if let Node::Add(_) = g.node(id) {
            let negation = g.negate_terms(id)?;
            if negation != id && known.contains(&negation) {
                pairs.insert(id, negation);
            }
        }
    }
    Ok(pairs)
}

/// A linear system E·z = g that the model solves at run time (a mass
/// matrix, a mechanism's constraint block): its unknowns' symbols, E
/// row-major and g, expressions of the states and of earlier systems'
/// unknowns.
pub struct LinearSystem<'a> {
    /// The unknowns z, as the outputs and later systems read them.
    pub unknowns: &'a [SymbolId],
    /// E, row-major.
    pub matrix: &'a [Id],
    /// g.
    pub rhs: &'a [Id],
}

/// Decomposes `outputs` (f of each slot) into a tape; `negations` from
/// [`negated_sums`]. Each of `systems` in turn becomes its entries' operations,
/// their copies side by side, and a `Solve` whose u-variables are its
/// unknowns (the runtime solves it order by order with one LU a step);
/// the outputs come last.
pub fn decompose(
    g: &Graph,
    outputs: &[Id],
    systems: &[LinearSystem<'_>],
    (slot_of, time): (&FxHashMap<SymbolId, usize>, SymbolId),
    negations: &FxHashMap<Id, Id>,
) -> crate::Result<Tape> {
    let entries: Vec<Id> =
        systems.iter().flat_map(|s| s.matrix.iter().chain(s.rhs).copied()).collect();
    let targets: Vec<Id> = entries.iter().chain(outputs).copied().collect();
    let order = g.reachable(&targets);
    let solved: FxHashMap<SymbolId, usize> =
        systems.iter().flat_map(|s| s.unknowns.iter()).enumerate().map(|(k, &s)| (s, k)).collect();
    // A node depends on time when it reaches a state, the time symbol or
    // a system's unknown.
    let mut time_dependent: FxHashMap<Id, bool> = FxHashMap::default();
    let mut unknown_nodes: FxHashMap<SymbolId, Id> = FxHashMap::default();
    for &id in &order {
        let own = match g.node(id) {
            Node::Symbol(s) if solved.contains_key(s) => {
                unknown_nodes.insert(*s, id);
                true
            }
            Node::Symbol(s) => *s == time || slot_of.contains_key(s),
            _ => false,
        };
        let dep =
            own || g.operands(id).iter().any(|c| time_dependent.get(c).copied().unwrap_or(false));
        time_dependent.insert(id, dep);
    }
    let mut b = Builder {
        g,
        slot_of,
        time,
        operand_of: FxHashMap::default(),
        constants: Vec::new(),
        ops: Vec::new(),
        recurrences: Vec::new(),
        pairs_of: FxHashMap::default(),
        binary_of: FxHashMap::default(),
        negation_of: negations,
        negative_of: FxHashMap::default(),
    };
    // Constant nodes get a slot only when a time-dependent node, an output
    // or a system's entry uses them; their own constant operands are
    // computed inside them.
    let mut needed: std::collections::HashSet<Id> = targets.iter().copied().collect();
    for &id in &order {
        if time_dependent[&id] {
            needed.insert(id);
            needed.extend(g.operands(id).iter().copied());
        }
    }
    let visit = |b: &mut Builder<'_>, targets: &[Id]| -> crate::Result<()> {
        for id in g.reachable(targets) {
            if b.operand_of.contains_key(&id) || !needed.contains(&id) {
                continue;
            }
            let operand = b.node(id, time_dependent[&id])?;
            b.operand_of.insert(id, operand);
        }
        Ok(())
    };
    for system in systems {
        let entries: Vec<Id> = system.matrix.iter().chain(system.rhs).copied().collect();
        visit(&mut b, &entries)?;
        let first = b.ops.len();
        for &e in &entries {
            let a = b.operand(e).tokens();
            b.push(quote!(T::Copy(#a)), None);
        }
        let (size, first_lit) = (
            proc_macro2::Literal::usize_unsuffixed(system.unknowns.len()),
            proc_macro2::Literal::usize_unsuffixed(first),
        );
        for (row, unknown) in system.unknowns.iter().enumerate() {
            let op = if row == 0 {
                quote!(T::Solve { size: #size, first: #first_lit })
            } else {
                quote!(T::SolvedWithPrevious)
            };
            let z = b.push(op, None);
            if let Some(&node) = unknown_nodes.get(unknown) {
                b.operand_of.insert(node, z);
            }
        }
    }
    visit(&mut b, outputs)?;
    let output_operands: Vec<Operand> = outputs.iter().map(|&o| b.operand(o)).collect();
    let outputs = output_operands.iter().map(Operand::tokens).collect();
    Ok(Tape {
        constants: b.constants,
        ops: b.ops,
        outputs,
        recurrences: b.recurrences,
        output_operands,
    })
}
