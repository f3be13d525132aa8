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

use crate::emit::schedule::Program;
use crate::expr::graph::Graph;
use crate::expr::node::{Func, Id, Node, SymbolId, SymbolKind};
use crate::expr::number::Number;
use proc_macro2::{TokenStream, TokenTree};
use quote::quote;
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
    let mut symbols: Vec<Option<String>> = vec![None; g.symbols().count()];
    for id in g.reachable(&program.outputs) {
        if let Node::Symbol(s) = g.node(id) {
            symbols[s.index()] = Some(symbol(*s).to_string());
        }
    }
    let e = Emitter { g, program, symbols };
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

/// Outputs that repeat one value this many times or more are written by
/// one loop over their indices: a grid's Jacobian holds its diffusion
/// coefficient thousands of times, and LLVM's optimisation time grows
/// faster than the straight-line code's length (the 2-D Brusselator's
/// 12 288 entries, 8192 of them one value: 43 s of rustc written out, 22 s
/// with the loop).
const REPEATS_AS_LOOP: usize = 8;

/// Emits `program` as statements writing output `i` to `array[i]`, like
/// [`emit_program`], except that a value written to
/// [`REPEATS_AS_LOOP`] or more entries is written by one loop over a table
/// of their indices after the others (or by `array.fill(v)` where it is
/// every entry).
pub fn emit_indexed_program(
    g: &Graph,
    program: &Program,
    symbol: &dyn Fn(SymbolId) -> TokenStream,
    array: &str,
) -> TokenStream {
    let mut symbols: Vec<Option<String>> = vec![None; g.symbols().count()];
    for id in g.reachable(&program.outputs) {
        if let Node::Symbol(s) = g.node(id) {
            symbols[s.index()] = Some(symbol(*s).to_string());
        }
    }
    let e = Emitter { g, program, symbols };
    let mut text = String::new();
    for t in &program.temps {
        let _ = writeln!(text, "let {} = {};", t.name, e.inline(t.node).0);
    }
    // Each value's entries, in the order of its first one.
    let mut entries: Vec<(Id, Vec<usize>)> = Vec::new();
    let mut group_of: std::collections::HashMap<Id, usize> = std::collections::HashMap::new();
    for (i, &o) in program.outputs.iter().enumerate() {
        let k = *group_of.entry(o).or_insert_with(|| {
            entries.push((o, Vec::new()));
            entries.len() - 1
        });
        entries[k].1.push(i);
    }
    let repeated = |k: usize| entries[k].1.len() >= REPEATS_AS_LOOP;
    for (i, o) in program.outputs.iter().enumerate() {
        if !repeated(group_of[o]) {
            let _ = writeln!(text, "{array}[{i}] = {};", e.render(*o).0);
        }
    }
    for (k, (o, indices)) in entries.iter().enumerate() {
        if !repeated(k) {
            continue;
        }
        let value = e.render(*o).0;
        if indices.len() == program.outputs.len() {
            let _ = writeln!(text, "{array}.fill({value});");
        } else {
            let list: Vec<String> = indices.iter().map(|i| i.to_string()).collect();
            // `get_mut`: the table's indices are in bounds by construction,
            // and generated code has no panicking path.
            let _ = writeln!(
                text,
                "for &k in &[{}usize] {{ if let Some(v) = {array}.get_mut(k) {{ *v = {value}; }} }}",
                list.join(", ")
            );
        }
    }
    lex(&text)
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
}

impl Emitter<'_> {
    /// The value of `id`: its temporary's name if it has one.
    fn render(&self, id: Id) -> Piece {
        match self.program.temp(id) {
            Some(t) => (t.name.clone(), Prec::Postfix),
            None => self.inline(id),
        }
    }

    fn at(&self, id: Id, min: Prec) -> String {
        if min == Prec::Postfix && self.program.temp(id).is_none() {
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
                _ => (self.symbols[s.index()].clone().unwrap_or_default(), Prec::Postfix),
            },
            Node::Add(terms) => self.sum(terms),
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
            Node::Mul(factors) if self.program.temp(id).is_none() => self.product(factors),
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
                    if self.program.temp(f).is_none()
                        && self.g.as_number(*e).is_some_and(Number::is_negative) =>
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
