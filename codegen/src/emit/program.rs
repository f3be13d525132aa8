//! Emission of a scheduled [`Program`] as Rust tokens: the last step of every
//! pipeline. The output is deterministic, allocation-free, `unsafe`-free and
//! panic-free straight-line code over `f64`.
//!
//! Choices that matter for speed and accuracy: `x^2` and `x^3` are products,
//! larger integer powers `powi` (which LLVM expands into multiplications);
//! half-integer powers use `sqrt`, one per base (`r^(-3/2)` is
//! `1.0 / (r * s)` with `s = r.sqrt()`); negative powers become one division;
//! constants are exact literals, or `p / q` for rationals that have none.
//!
//! The code is written as text and lexed once: building thousands of small
//! token streams costs more than the rest of the pipeline.

use crate::expr::graph::{FxHashMap, Graph};
use crate::expr::node::{Func, Id, Node, SymbolId, SymbolKind};
use crate::expr::number::Number;
use crate::programs::schedule::Program;
use proc_macro2::{TokenStream, TokenTree};
use quote::quote;
use std::cell::{Cell, RefCell};
use std::fmt::Write;

/// Binding strength of an emitted piece, weakest first.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Prec {
    Sum,
    Product,
    Unary,
    /// Safe as the receiver of a method call.
    Postfix,
}

type Piece = (String, Prec);

/// Emits `program` as statements: one `let` per temporary, then
/// `assign(i, value)` for each output `i`.
///
/// `symbol` gives the tokens that read a symbol (`y[0]`, `p.m`, `t`); they
/// must be single expressions safe as method receivers.
pub fn emit_program(
    g: &Graph,
    program: &Program,
    symbol: &dyn Fn(SymbolId) -> TokenStream,
    assign: &dyn Fn(usize, TokenStream) -> TokenStream,
) -> TokenStream {
    let symbols = symbol_texts(g, program, symbol);
    let e = Emitter::new(g, program, symbols);
    let mut text = String::new();
    for t in &program.temps {
        let _ = writeln!(text, "let {} = {};", t.name, e.inline(t.node).0);
    }
    let mut out = lex(&text);
    for (i, &o) in program.outputs.iter().enumerate() {
        out.extend(assign(i, lex(&e.render(o).0)));
    }
    out
}

/// Outputs that differ only in which states they read, this many or more,
/// are written by one loop over a table of their indices.
const ROLLED_FROM: usize = 8;

/// An output's expression, inlined, above this many nodes or characters
/// stays straight-line code: inlining the temporaries it shares could grow
/// it without bound (a multibody model's accelerations).
const ROLLED_NODES_MAX: usize = 200;
/// See [`ROLLED_NODES_MAX`].
const ROLLED_TEXT_MAX: usize = 1000;

/// Emits `program` as statements writing output `i` to
/// `array[targets[i]]`, like [`emit_program`], except that outputs whose
/// expressions are the same up to the states they read (`state_slot` gives
/// a state symbol's index in the slice `states`) are written by one loop
/// over a table of the target's and the states' indices, where there are
/// eight or more of them. The temporaries such an output shares
/// with others are recomputed in the loop where they depend on the states,
/// read where they do not. A grid's right-hand side and Jacobian are
/// thousands of copies of a few expressions, and LLVM's optimisation time
/// grows faster than straight-line code's length: the 2-D Brusselator
/// (2048 states, 12 288 Jacobian entries) took 43 s of rustc written out.
/// A loop's body is the straight-line expression with its states renamed
/// (its temporaries written out): the same operations in the same order,
/// so the same values.
pub fn emit_rolled_program(
    g: &Graph,
    program: &Program,
    symbol: &dyn Fn(SymbolId) -> TokenStream,
    state_slot: &dyn Fn(SymbolId) -> Option<usize>,
    (array, targets): (&str, &[usize]),
    states: &str,
) -> TokenStream {
    let symbols = symbol_texts(g, program, symbol);
    // The temporaries that depend on the states: inlined in a loop's body.
    let varying = varying_temps(g, program, state_slot);
    let plain = Emitter::new(g, program, symbols.clone());
    let rolling = Emitter { inline_temps: varying.clone(), ..Emitter::new(g, program, symbols) };
    // Each output's expression with its states as placeholders `a0`, `a1`, …
    // and the states' indices, grouped by expression in order of first use.
    let mut groups: Vec<(String, Vec<Member>)> = Vec::new();
    let mut group_of: FxHashMap<String, usize> = FxHashMap::default();
    let mut rolled = vec![false; program.outputs.len()];
    let mut sizes: FxHashMap<Id, usize> = FxHashMap::default();
    for (i, &o) in program.outputs.iter().enumerate() {
        // Measured before it is written: a multibody model's shared
        // expressions, written out as trees, grow exponentially.
        if inlined_size(g, program, &varying, o, &mut sizes) > ROLLED_NODES_MAX {
            continue;
        }
        rolling.placeholders.borrow_mut().clear();
        let text = rolling.render_placeholders(o, state_slot);
        if text.len() > ROLLED_TEXT_MAX {
            continue;
        }
        let slots = rolling.placeholders.borrow().iter().map(|&(_, slot)| slot).collect();
        let k = *group_of.entry(text.clone()).or_insert_with(|| {
            groups.push((text, Vec::new()));
            groups.len() - 1
        });
        groups[k].1.push((i, slots));
    }
    for (_, members) in &groups {
        if members.len() >= ROLLED_FROM {
            members.iter().for_each(|&(i, _)| rolled[i] = true);
        }
    }
    // The temporaries the straight-line outputs still read, and those that
    // do not depend on the states (the loops read them).
    let needed = needed_temps(g, program, &rolled);
    let mut text = String::new();
    for (k, t) in program.temps.iter().enumerate() {
        if needed[k] || !varying[k] {
            let _ = writeln!(text, "let {} = {};", t.name, plain.inline(t.node).0);
        }
    }
    for (i, &o) in program.outputs.iter().enumerate() {
        if !rolled[i] {
            let _ = writeln!(text, "{array}[{}] = {};", targets[i], plain.render(o).0);
        }
    }
    for (body, members) in &groups {
        if members.len() < ROLLED_FROM {
            continue;
        }
        let arity = members[0].1.len();
        if arity == 0 && members.len() == program.outputs.len() {
            let _ = writeln!(text, "{array}.fill({body});");
            continue;
        }
        // `get` and `get_mut`: the table's indices are in bounds by
        // construction, and generated code has no panicking path.
        if arity == 0 {
            let rows: Vec<String> = members.iter().map(|(i, _)| targets[*i].to_string()).collect();
            let _ = writeln!(
                text,
                "for &k in &[{}usize] {{ if let Some(out) = {array}.get_mut(k) {{ *out = {body}; }} }}",
                rows.join(", ")
            );
            continue;
        }
        let names: Vec<String> = (0..arity).map(|j| format!("s{j}")).collect();
        let reads: Vec<String> = (0..arity).map(|j| format!("Some(&a{j})")).collect();
        let gets: Vec<String> = names.iter().map(|s| format!("{states}.get({s})")).collect();
        let rows: Vec<String> = members
            .iter()
            .enumerate()
            .map(|(r, (i, slots))| {
                let suffix = if r == 0 { "usize" } else { "" };
                let mut row = vec![format!("{}{suffix}", targets[*i])];
                row.extend(slots.iter().map(|s| format!("{s}{suffix}")));
                format!("({})", row.join(", "))
            })
            .collect();
        let _ = writeln!(
            text,
            "for &(k, {names}) in &[{rows}] {{ if let (Some(out), {reads}) = ({array}.get_mut(k), {gets}) {{ *out = {body}; }} }}",
            names = names.join(", "),
            rows = rows.join(", "),
            reads = reads.join(", "),
            gets = gets.join(", "),
        );
    }
    lex(&text)
}

/// A rolled output: its position among the outputs, and the slots of the
/// states its placeholders stand for.
type Member = (usize, Vec<usize>);

/// The nodes of `id` written as a tree with the temporaries that depend on
/// the states (`varying`) in place, the others by name; at most
/// [`ROLLED_NODES_MAX`] + 1.
fn inlined_size(
    g: &Graph,
    program: &Program,
    varying: &[bool],
    id: Id,
    sizes: &mut FxHashMap<Id, usize>,
) -> usize {
    if let Some(&size) = sizes.get(&id) {
        return size;
    }
    let named = program.temp_index(id).is_some_and(|k| !varying[k]);
    let size = if named {
        1
    } else {
        let mut size = 1usize;
        for &c in g.operands(id) {
            size = size.saturating_add(inlined_size(g, program, varying, c, sizes));
            if size > ROLLED_NODES_MAX {
                break;
            }
        }
        size.min(ROLLED_NODES_MAX + 1)
    };
    sizes.insert(id, size);
    size
}

/// Which temporaries depend on a state.
fn varying_temps(
    g: &Graph,
    program: &Program,
    state_slot: &dyn Fn(SymbolId) -> Option<usize>,
) -> Vec<bool> {
    let mut memo: FxHashMap<Id, bool> = FxHashMap::default();
    fn depends(
        g: &Graph,
        id: Id,
        state_slot: &dyn Fn(SymbolId) -> Option<usize>,
        memo: &mut FxHashMap<Id, bool>,
    ) -> bool {
        if let Some(&d) = memo.get(&id) {
            return d;
        }
        let d = match g.node(id) {
            Node::Symbol(s) if state_slot(*s).is_some() => true,
            _ => g.operands(id).iter().any(|&c| depends(g, c, state_slot, memo)),
        };
        memo.insert(id, d);
        d
    }
    program.temps.iter().map(|t| depends(g, t.node, state_slot, &mut memo)).collect()
}

/// The temporaries the outputs that are not `rolled` read, directly or
/// through others (and through the shared square roots of powers).
fn needed_temps(g: &Graph, program: &Program, rolled: &[bool]) -> Vec<bool> {
    let mut needed = vec![false; program.temps.len()];
    let mut seen: FxHashMap<Id, ()> = FxHashMap::default();
    let mut stack: Vec<Id> =
        program.outputs.iter().zip(rolled).filter(|(_, &r)| !r).map(|(&o, _)| o).collect();
    while let Some(id) = stack.pop() {
        if seen.insert(id, ()).is_some() {
            continue;
        }
        if let Some(k) = program.temp_index(id) {
            needed[k] = true;
        }
        if let Some(root) = program.shared_root(id) {
            stack.push(root);
        }
        match program.negation_of(id) {
            Some(positive) => stack.push(positive),
            None => stack.extend_from_slice(g.operands(id)),
        }
    }
    needed
}

/// How each symbol the program reads is written (`None`: not read).
fn symbol_texts(
    g: &Graph,
    program: &Program,
    symbol: &dyn Fn(SymbolId) -> TokenStream,
) -> Vec<Option<String>> {
    let mut symbols: Vec<Option<String>> = vec![None; g.symbols().count()];
    for id in g.reachable(&program.outputs) {
        if let Node::Symbol(s) = g.node(id) {
            symbols[s.index()] = Some(symbol(*s).to_string());
        }
    }
    symbols
}

/// Lexes emitted text. It is well-formed by construction; should it ever not
/// be, the user gets a compile error naming the bug, not a panic.
fn lex(text: &str) -> TokenStream {
    match text.parse::<TokenStream>() {
        Ok(tokens) => tokens,
        Err(err) => {
            let message =
                format!("daegen emitted code that does not lex ({err}); please report this model");
            quote! { compile_error!(#message); }
        }
    }
}

/// Number of tokens in a stream, counting inside groups: the size measure of
/// generated code.
pub fn token_count(tokens: &TokenStream) -> usize {
    tokens
        .clone()
        .into_iter()
        .map(|t| match t {
            TokenTree::Group(g) => 2 + token_count(&g.stream()),
            _ => 1,
        })
        .sum()
}

/// A non-negative finite `f64` as a literal that reads back exactly
/// (`Debug` is the shortest round-trip form: `0.1`, `2.0`, `1e-20`).
fn literal(v: f64) -> String {
    format!("{v:?}")
}

fn integer_literal(n: i64) -> String {
    literal(n.unsigned_abs() as f64)
}

struct Emitter<'a> {
    g: &'a Graph,
    program: &'a Program,
    symbols: Vec<Option<String>>,
    /// Temporaries written out in place (by position; empty: none), for
    /// the body of a rolled loop.
    inline_temps: Vec<bool>,
    /// The states a rolled expression has read so far, as (symbol, slot):
    /// the j-th reads as `a{j}`.
    placeholders: RefCell<Vec<(SymbolId, usize)>>,
    /// Whether states read as placeholders (while rendering a rolled body).
    by_placeholder: Cell<bool>,
    /// A state symbol's slot, while `by_placeholder`.
    slot_of: RefCell<FxHashMap<SymbolId, usize>>,
}

impl<'a> Emitter<'a> {
    fn new(g: &'a Graph, program: &'a Program, symbols: Vec<Option<String>>) -> Emitter<'a> {
        Emitter {
            g,
            program,
            symbols,
            inline_temps: Vec::new(),
            placeholders: RefCell::new(Vec::new()),
            by_placeholder: Cell::new(false),
            slot_of: RefCell::new(FxHashMap::default()),
        }
    }

    /// Whether `id` reads as its temporary's name.
    fn named(&self, id: Id) -> bool {
        self.program
            .temp_index(id)
            .is_some_and(|k| !self.inline_temps.get(k).copied().unwrap_or(false))
    }

    /// The value of `id`: its temporary's name if it has one (and is not
    /// written in place).
    fn render(&self, id: Id) -> Piece {
        match self.program.temp(id) {
            Some(t) if self.named(id) => (t.name.clone(), Prec::Postfix),
            _ => self.inline(id),
        }
    }

    /// `id` with its states as placeholders, recorded in `placeholders`.
    fn render_placeholders(
        &self,
        id: Id,
        state_slot: &dyn Fn(SymbolId) -> Option<usize>,
    ) -> String {
        {
            let mut slot_of = self.slot_of.borrow_mut();
            if slot_of.is_empty() {
                for (s, _) in self.g.symbols() {
                    if let Some(slot) = state_slot(s) {
                        slot_of.insert(s, slot);
                    }
                }
            }
        }
        self.by_placeholder.set(true);
        let text = self.render(id).0;
        self.by_placeholder.set(false);
        text
    }

    /// A symbol as the code reads it.
    fn symbol_text(&self, s: SymbolId) -> String {
        if self.by_placeholder.get() {
            if let Some(&slot) = self.slot_of.borrow().get(&s) {
                let mut seen = self.placeholders.borrow_mut();
                let j = match seen.iter().position(|&(t, _)| t == s) {
                    Some(j) => j,
                    None => {
                        seen.push((s, slot));
                        seen.len() - 1
                    }
                };
                return format!("a{j}");
            }
        }
        self.symbols[s.index()].clone().unwrap_or_default()
    }

    fn at(&self, id: Id, min: Prec) -> String {
        if min == Prec::Postfix && !self.named(id) {
            if let Some(n) = self.g.as_number(id) {
                // `2.0.powf(x)` is ambiguous to rustc; `2.0_f64.powf(x)` is
                // not, nor `(22.0_f64 / 31.0).sqrt()` or `(-0.5_f64).sin()`.
                let body = match n.abs() {
                    Number::Rational(r) if !r.is_exact_in_f64() => format!(
                        "{}_f64 / {}",
                        integer_literal(r.numer()),
                        integer_literal(r.denom())
                    ),
                    a => format!("{}_f64", literal(a.to_f64())),
                };
                return match (n.is_negative(), body.contains('/')) {
                    (false, false) => body,
                    (false, true) => format!("({body})"),
                    (true, _) => format!("(-{body})"),
                };
            }
        }
        paren(self.render(id), min)
    }

    /// The expression of `id` itself, ignoring its own temporary.
    fn inline(&self, id: Id) -> Piece {
        match self.g.node(id) {
            Node::Number(n) => number(*n),
            Node::Symbol(s) => match self.g.symbol(*s).kind {
                SymbolKind::Intermediate { definition } => self.render(definition),
                _ => (self.symbol_text(*s), Prec::Postfix),
            },
            Node::Add(terms) => self.sum(terms),
            Node::Mul(_) if self.program.negation_of(id).is_some() => {
                let positive = self.program.negation_of(id).unwrap_or(id);
                (format!("-{}", self.at(positive, Prec::Product)), Prec::Product)
            }
            Node::Mul(factors) => {
                let (negative, body, prec) = self.product(factors);
                if negative {
                    (format!("-{body}"), Prec::Product.min(prec))
                } else {
                    (body, prec)
                }
            }
            Node::Pow([b, e]) => match self.g.as_number(*e) {
                Some(n) if n.is_negative() => {
                    let den = paren(self.power(id, *b, n.negated()), Prec::Unary);
                    (format!("1.0 / {den}"), Prec::Product)
                }
                Some(n) => self.power(id, *b, n),
                None => {
                    let base = self.at(*b, Prec::Postfix);
                    let exponent = self.render(*e).0;
                    (format!("{base}.powf({exponent})"), Prec::Postfix)
                }
            },
            Node::Call(f, a) => self.call(*f, *a),
            Node::Atan2([y, x]) => {
                let y = self.at(*y, Prec::Postfix);
                let x = self.render(*x).0;
                (format!("{y}.atan2({x})"), Prec::Postfix)
            }
        }
    }

    fn call(&self, f: Func, a: Id) -> Piece {
        let a = self.at(a, Prec::Postfix);
        if f == Func::Sign {
            // An `if` binds weakest of all: parenthesised wherever it is an operand.
            return (
                format!("if {a} > 0.0 {{ 1.0 }} else if {a} < 0.0 {{ -1.0 }} else {{ 0.0 }}"),
                Prec::Sum,
            );
        }
        (format!("{a}.{}()", f.name()), Prec::Postfix)
    }

    /// `base ^ e` for a positive numeric exponent; `pow` is the node (whose
    /// exponent may be `-e`), for its shared square root.
    fn power(&self, pow: Id, base: Id, e: Number) -> Piece {
        let b = self.at(base, Prec::Postfix);
        if let Some(r) = e.as_rational() {
            let n = r.numer();
            if r.is_integer() {
                return match n {
                    // Only as the denominator of x^(-1).
                    1 => (b, Prec::Postfix),
                    2 => (format!("{b} * {b}"), Prec::Product),
                    3 => (format!("{b} * {b} * {b}"), Prec::Product),
                    _ => (format!("{b}.powi({n})"), Prec::Postfix),
                };
            }
            if r.denom() == 2 {
                let root = match self.program.shared_root(pow) {
                    Some(root) => self.render(root).0,
                    None => format!("{b}.sqrt()"),
                };
                return match (n - 1) / 2 {
                    0 => (root, Prec::Postfix),
                    1 => (format!("{b} * {root}"), Prec::Product),
                    k => (format!("{b}.powi({k}) * {root}"), Prec::Product),
                };
            }
        }
        (format!("{b}.powf({})", number(e).0), Prec::Postfix)
    }

    /// A term of a sum without its sign: `(is_negative, text of |term|, precedence)`.
    fn term(&self, id: Id) -> (bool, String, Prec) {
        match self.g.node(id) {
            Node::Mul(_) if !self.named(id) && self.program.negation_of(id).is_some() => {
                let positive = self.program.negation_of(id).unwrap_or(id);
                (true, self.at(positive, Prec::Product), Prec::Product)
            }
            Node::Mul(factors) if !self.named(id) => self.product(factors),
            Node::Number(n) => {
                let (t, p) = number(n.abs());
                (n.is_negative(), t, p)
            }
            _ => {
                let (t, p) = self.render(id);
                (false, t, p)
            }
        }
    }

    /// A product without its sign: `(is_negative, text of |product|, precedence)`.
    fn product(&self, factors: &[Id]) -> (bool, String, Prec) {
        let mut coefficient = Number::ONE;
        let mut numerator: Vec<String> = Vec::new();
        let mut denominator: Vec<Piece> = Vec::new();
        for &f in factors {
            match self.g.node(f) {
                Node::Number(n) => coefficient = *n,
                Node::Pow([b, e])
                    if !self.named(f) && self.g.as_number(*e).is_some_and(Number::is_negative) =>
                {
                    let e = self.g.as_number(*e).unwrap_or(Number::MINUS_ONE).negated();
                    denominator.push(if e.is_one() {
                        self.render(*b)
                    } else {
                        self.power(f, *b, e)
                    });
                }
                _ => numerator.push(self.at(f, Prec::Product)),
            }
        }
        let negative = coefficient.is_negative();
        match coefficient.abs() {
            Number::Rational(r) if !r.is_exact_in_f64() => {
                // x/3.0 rounds once; x * (1.0/3.0) would round twice.
                if r.numer() != 1 {
                    numerator.insert(0, integer_literal(r.numer()));
                }
                denominator.insert(0, (integer_literal(r.denom()), Prec::Postfix));
            }
            c if !c.is_one() => numerator.insert(0, number(c).0),
            _ => {}
        }
        let mut body = if numerator.is_empty() { "1.0".to_string() } else { numerator.join(" * ") };
        match denominator.len() {
            0 => {}
            1 => {
                let d = paren(denominator.remove(0), Prec::Unary);
                let _ = write!(body, " / {d}");
            }
            _ => {
                let parts: Vec<String> =
                    denominator.into_iter().map(|p| paren(p, Prec::Product)).collect();
                let _ = write!(body, " / ({})", parts.join(" * "));
            }
        }
        (negative, body, Prec::Product)
    }

    fn sum(&self, terms: &[Id]) -> Piece {
        let rendered: Vec<(bool, String, Prec)> = terms.iter().map(|&t| self.term(t)).collect();
        let is_constant = |t: &Id| self.g.as_number(*t).is_some();
        let mut out = String::new();
        let mut first = true;
        for want_negative in [false, true] {
            for constants in [false, true] {
                for (t, (negative, body, prec)) in terms.iter().zip(&rendered) {
                    if is_constant(t) != constants || *negative != want_negative {
                        continue;
                    }
                    let body = paren((body.clone(), *prec), Prec::Product);
                    match (first, negative) {
                        (true, false) => out.push_str(&body),
                        (true, true) => out.push_str(&format!("-{body}")),
                        (false, false) => out.push_str(&format!(" + {body}")),
                        (false, true) => out.push_str(&format!(" - {body}")),
                    }
                    first = false;
                }
            }
        }
        (out, Prec::Sum)
    }
}

fn number(n: Number) -> Piece {
    let (body, prec) = match n.abs() {
        Number::Rational(r) if !r.is_exact_in_f64() => (
            format!("{} / {}", integer_literal(r.numer()), integer_literal(r.denom())),
            Prec::Product,
        ),
        a => (literal(a.to_f64()), Prec::Postfix),
    };
    if n.is_negative() {
        (format!("-{body}"), Prec::Unary.min(prec))
    } else {
        (body, prec)
    }
}

fn paren(piece: Piece, min: Prec) -> String {
    let (text, prec) = piece;
    if prec < min {
        format!("({text})")
    } else {
        text
    }
}
