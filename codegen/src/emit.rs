//! Emission of a scheduled [`Program`] as Rust tokens: the last step of every
//! pipeline. The output is deterministic, allocation-free, `unsafe`-free and
//! panic-free straight-line code over `f64`.
//!
//! Choices that matter for speed and accuracy: `x^2` and `x^3` are products,
//! larger integer powers `powi` (which LLVM expands into multiplications);
//! half-integer powers use `sqrt` (`r^(-3/2)` is `1.0 / (r * r.sqrt())`,
//! the kernel of every gravity model); negative powers become one division;
//! constants are exact literals, or `p / q` for rationals that have none.

use crate::graph::Graph;
use crate::node::{Func, Id, Node, SymbolId};
use crate::number::Number;
use crate::schedule::Program;
use proc_macro2::{Literal, TokenStream, TokenTree};
use quote::{format_ident, quote};

/// Binding strength of an emitted piece, weakest first.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Prec {
    Sum,
    Product,
    Unary,
    /// Safe as the receiver of a method call.
    Postfix,
}

type Piece = (TokenStream, Prec);

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
    let e = Emitter { g, program, symbol };
    let mut out = TokenStream::new();
    for t in &program.temps {
        let name = format_ident!("{}", t.name);
        let value = e.inline(t.node).0;
        out.extend(quote! { let #name = #value; });
    }
    for (i, &o) in program.outputs.iter().enumerate() {
        out.extend(assign(i, e.render(o).0));
    }
    out
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

/// A non-negative finite `f64` as a literal that reads back exactly.
fn literal(v: f64) -> TokenStream {
    let text = format!("{v:?}");
    match text.parse::<Literal>() {
        Ok(lit) => quote! { #lit },
        Err(_) => {
            let lit = Literal::f64_unsuffixed(v);
            quote! { #lit }
        }
    }
}

/// A literal safe as a method receiver (`2f64`, not the ambiguous `2.0`).
fn typed_literal(v: f64) -> TokenStream {
    let lit = Literal::f64_suffixed(v);
    quote! { #lit }
}

fn integer_literal(n: i64) -> TokenStream {
    literal(n.unsigned_abs() as f64)
}

struct Emitter<'a> {
    g: &'a Graph,
    program: &'a Program,
    symbol: &'a dyn Fn(SymbolId) -> TokenStream,
}

impl Emitter<'_> {
    /// The value of `id`: its temporary's name if it has one.
    fn render(&self, id: Id) -> Piece {
        match self.program.temp(id) {
            Some(t) => {
                let name = format_ident!("{}", t.name);
                (quote! { #name }, Prec::Postfix)
            }
            None => self.inline(id),
        }
    }

    fn at(&self, id: Id, min: Prec) -> TokenStream {
        if min == Prec::Postfix {
            if let Some(n) = self.g.as_number(id) {
                if self.program.temp(id).is_none()
                    && !n.is_negative()
                    && n.as_rational().is_none_or(|r| r.is_exact_in_f64())
                {
                    return typed_literal(n.to_f64());
                }
            }
        }
        paren(self.render(id), min)
    }

    /// The expression of `id` itself, ignoring its own temporary.
    fn inline(&self, id: Id) -> Piece {
        match self.g.node(id) {
            Node::Number(n) => number(*n),
            Node::Symbol(s) => match self.g.symbol(*s).kind {
                crate::SymbolKind::Intermediate { definition } => self.render(definition),
                _ => ((self.symbol)(*s), Prec::Postfix),
            },
            Node::Add(terms) => self.sum(terms),
            Node::Mul(factors) => {
                let (negative, body, prec) = self.product(factors);
                if negative {
                    (quote! { -#body }, Prec::Product.min(prec))
                } else {
                    (body, prec)
                }
            }
            Node::Pow([b, e]) => match self.g.as_number(*e) {
                Some(n) if n.is_negative() => {
                    let den = paren(self.power(id, *b, n.neg()), Prec::Unary);
                    (quote! { 1.0 / #den }, Prec::Product)
                }
                Some(n) => self.power(id, *b, n),
                None => {
                    let base = self.at(*b, Prec::Postfix);
                    let exponent = self.render(*e).0;
                    (quote! { #base.powf(#exponent) }, Prec::Postfix)
                }
            },
            Node::Call(f, a) => self.call(*f, *a),
            Node::Atan2([y, x]) => {
                let y = self.at(*y, Prec::Postfix);
                let x = self.render(*x).0;
                (quote! { #y.atan2(#x) }, Prec::Postfix)
            }
        }
    }

    fn call(&self, f: Func, a: Id) -> Piece {
        if f == Func::Sign {
            let a = self.at(a, Prec::Postfix);
            // An `if` binds weakest of all: parenthesised wherever it is an operand.
            let piece = quote! { if #a > 0.0 { 1.0 } else if #a < 0.0 { -1.0 } else { 0.0 } };
            return (piece, Prec::Sum);
        }
        let a = self.at(a, Prec::Postfix);
        let method = format_ident!("{}", f.name());
        (quote! { #a.#method() }, Prec::Postfix)
    }

    /// `base ^ e` for a positive numeric exponent; `pow` is the node (whose
    /// exponent may be `-e`), for its shared square root.
    fn power(&self, pow: Id, base: Id, e: Number) -> Piece {
        let b = self.at(base, Prec::Postfix);
        if let Some(r) = e.as_rational() {
            let n = r.numer();
            if r.is_integer() {
                return match n {
                    2 => (quote! { #b * #b }, Prec::Product),
                    3 => (quote! { #b * #b * #b }, Prec::Product),
                    _ => {
                        let n = Literal::i32_unsuffixed(n as i32);
                        (quote! { #b.powi(#n) }, Prec::Postfix)
                    }
                };
            }
            if let (2, Some(root)) = (r.denom(), self.program.shared_root(pow)) {
                let s = self.render(root).0;
                return match (n - 1) / 2 {
                    0 => (s, Prec::Postfix),
                    1 => (quote! { #b * #s }, Prec::Product),
                    k => {
                        let k = Literal::i32_unsuffixed(k as i32);
                        (quote! { #b.powi(#k) * #s }, Prec::Product)
                    }
                };
            }
            if r.denom() == 2 {
                return match (n - 1) / 2 {
                    0 => (quote! { #b.sqrt() }, Prec::Postfix),
                    1 => (quote! { #b * #b.sqrt() }, Prec::Product),
                    k => {
                        let k = Literal::i32_unsuffixed(k as i32);
                        (quote! { #b.powi(#k) * #b.sqrt() }, Prec::Product)
                    }
                };
            }
        }
        let exponent = number(e).0;
        (quote! { #b.powf(#exponent) }, Prec::Postfix)
    }

    /// A term of a sum without its sign: `(is_negative, tokens of |term|, precedence)`.
    fn term(&self, id: Id) -> (bool, TokenStream, Prec) {
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

    /// A product without its sign: `(is_negative, tokens of |product|, precedence)`.
    fn product(&self, factors: &[Id]) -> (bool, TokenStream, Prec) {
        let mut coefficient = Number::ONE;
        let mut numerator: Vec<TokenStream> = Vec::new();
        let mut denominator: Vec<Piece> = Vec::new();
        for &f in factors.iter() {
            match self.g.node(f) {
                Node::Number(n) => coefficient = *n,
                Node::Pow([b, e])
                    if self.program.temp(f).is_none()
                        && self.g.as_number(*e).is_some_and(Number::is_negative) =>
                {
                    let e = self.g.as_number(*e).unwrap_or(Number::MINUS_ONE).neg();
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
                if r.numer() != 1 {
                    numerator.insert(0, integer_literal(r.numer()));
                }
                denominator.insert(0, (integer_literal(r.denom()), Prec::Postfix));
            }
            c if !c.is_one() => numerator.insert(0, number(c).0),
            _ => {}
        }
        let mut body = if numerator.is_empty() {
            quote! { 1.0 }
        } else {
            join(&numerator, quote! { * })
        };
        match denominator.len() {
            0 => {}
            1 => {
                let d = paren(denominator.remove(0), Prec::Unary);
                body = quote! { #body / #d };
            }
            _ => {
                let parts: Vec<TokenStream> = denominator
                    .into_iter()
                    .map(|p| paren(p, Prec::Product))
                    .collect();
                let d = join(&parts, quote! { * });
                body = quote! { #body / (#d) };
            }
        }
        (negative, body, Prec::Product)
    }

    fn sum(&self, terms: &[Id]) -> Piece {
        let rendered: Vec<(bool, TokenStream, Prec)> =
            terms.iter().map(|&t| self.term(t)).collect();
        let is_constant = |t: &Id| self.g.as_number(*t).is_some();
        let mut ordered = Vec::with_capacity(terms.len());
        for want_negative in [false, true] {
            for constants in [false, true] {
                for (t, r) in terms.iter().zip(&rendered) {
                    if is_constant(t) == constants && r.0 == want_negative {
                        ordered.push(r.clone());
                    }
                }
            }
        }
        let mut out = TokenStream::new();
        for (i, (negative, body, prec)) in ordered.into_iter().enumerate() {
            let body = paren((body, prec), Prec::Product);
            out.extend(match (i, negative) {
                (0, false) => body,
                (0, true) => quote! { -#body },
                (_, false) => quote! { + #body },
                (_, true) => quote! { - #body },
            });
        }
        (out, Prec::Sum)
    }
}

fn number(n: Number) -> Piece {
    let (body, prec) = match n.abs() {
        Number::Rational(r) if !r.is_exact_in_f64() => {
            let (p, q) = (integer_literal(r.numer()), integer_literal(r.denom()));
            (quote! { #p / #q }, Prec::Product)
        }
        a => (literal(a.to_f64()), Prec::Postfix),
    };
    if n.is_negative() {
        (quote! { -#body }, Prec::Unary.min(prec))
    } else {
        (body, prec)
    }
}

fn paren(piece: Piece, min: Prec) -> TokenStream {
    let (tokens, prec) = piece;
    if prec < min {
        quote! { (#tokens) }
    } else {
        tokens
    }
}

fn join(parts: &[TokenStream], sep: TokenStream) -> TokenStream {
    let mut out = TokenStream::new();
    for (i, p) in parts.iter().enumerate() {
        if i > 0 {
            out.extend(sep.clone());
        }
        out.extend(p.clone());
    }
    out
}
