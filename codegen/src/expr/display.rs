//! The text syntax of expressions: what tests compare against and what error
//! messages quote. [`crate::Graph::parse`] reads the same syntax back.
//!
//! Sums list positive terms first and constants last (`y + x*der(y) + 1`);
//! products put the coefficient first and negative powers under a slash
//! (`3*x/(2*y^2)`); exponents that are not plain integers are parenthesised
//! (`x^(1/2)`, `x^(-1)`).

use crate::expr::graph::Graph;
use crate::expr::node::{Id, Node};
use crate::expr::number::Number;
use std::fmt;

/// Binding strength of a rendered piece, weakest first.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Prec {
    Sum,
    Product,
    Unary,
    Power,
    Atom,
}

/// An expression ready to print; see [`Graph::show`].
pub struct Show<'g> {
    graph: &'g Graph,
    id: Id,
}

impl Graph {
    /// The expression `id` in the text syntax, through `Display`.
    pub fn show(&self, id: Id) -> Show<'_> {
        Show { graph: self, id }
    }
}

impl fmt::Display for Show<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&text(self.graph, self.id).0)
    }
}

fn wrap(piece: (String, Prec), at_least: Prec) -> String {
    if piece.1 < at_least {
        format!("({})", piece.0)
    } else {
        piece.0
    }
}

fn number_text(n: Number) -> (String, Prec) {
    let s = n.to_string();
    let prec = if n.is_negative() {
        Prec::Unary
    } else if n.as_rational().is_some_and(|r| !r.is_integer()) {
        Prec::Product
    } else {
        Prec::Atom
    };
    (s, prec)
}

fn text(g: &Graph, id: Id) -> (String, Prec) {
    match g.node(id) {
        Node::Number(n) => number_text(*n),
        Node::Symbol(s) => (g.symbol(*s).name.clone(), Prec::Atom),
        Node::Add(terms) => sum_text(g, terms),
        Node::Mul(_) => {
            let (negative, s, prec) = term_text(g, id);
            if negative {
                // `-2*x` reads as `(-2)*x`: the same product, so no parentheses.
                (format!("-{s}"), prec.min(Prec::Product))
            } else {
                (s, prec)
            }
        }
        Node::Pow([b, e]) => match g.as_number(*e) {
            Some(n) if n.is_negative() => (
                format!("1/{}", wrap(power_text(g, *b, &number_text(n.negated())), Prec::Unary)),
                Prec::Product,
            ),
            _ => power_text(g, *b, &text(g, *e)),
        },
        Node::Call(f, a) => (format!("{}({})", f.name(), text(g, *a).0), Prec::Atom),
        Node::Atan2([y, x]) => (format!("atan2({}, {})", text(g, *y).0, text(g, *x).0), Prec::Atom),
    }
}

fn power_text(g: &Graph, base: Id, exponent: &(String, Prec)) -> (String, Prec) {
    let b = wrap(text(g, base), Prec::Atom);
    let plain_integer = exponent.0.bytes().all(|c| c.is_ascii_digit());
    let e = if plain_integer || exponent.1 == Prec::Atom {
        exponent.0.clone()
    } else {
        format!("({})", exponent.0)
    };
    (format!("{b}^{e}"), Prec::Power)
}

/// A term without its sign: `(is_negative, text of |term|, precedence)`.
fn term_text(g: &Graph, id: Id) -> (bool, String, Prec) {
    match g.node(id) {
        Node::Number(n) => {
            let (s, p) = number_text(n.abs());
            (n.is_negative(), s, p)
        }
        Node::Mul(factors) => {
            let mut coefficient = Number::ONE;
            let mut numerator: Vec<(String, Prec)> = Vec::new();
            let mut denominator: Vec<(String, Prec)> = Vec::new();
            for &f in factors.iter() {
                match g.node(f) {
                    Node::Number(n) => coefficient = *n,
                    Node::Pow([b, e]) if g.as_number(*e).is_some_and(Number::is_negative) => {
                        let e = g.as_number(*e).unwrap_or(Number::ONE).negated();
                        denominator.push(if e.is_one() {
                            text(g, *b)
                        } else {
                            power_text(g, *b, &number_text(e))
                        });
                    }
                    _ => numerator.push(text(g, f)),
                }
            }
            let negative = coefficient.is_negative();
            let c = coefficient.abs();
            match c.as_rational() {
                Some(r) => {
                    if r.numer() != 1 {
                        numerator.insert(0, (r.numer().to_string(), Prec::Atom));
                    }
                    if r.denom() != 1 {
                        denominator.insert(0, (r.denom().to_string(), Prec::Atom));
                    }
                }
                None => numerator.insert(0, (c.to_string(), Prec::Atom)),
            }
            let numerator: Vec<String> =
                numerator.into_iter().map(|f| wrap(f, Prec::Unary)).collect();
            let mut s = if numerator.is_empty() { "1".to_string() } else { numerator.join("*") };
            match denominator.len() {
                0 => {}
                1 => {
                    s.push('/');
                    s.push_str(&wrap(denominator.remove(0), Prec::Unary));
                }
                _ => {
                    let d: Vec<String> =
                        denominator.into_iter().map(|p| wrap(p, Prec::Unary)).collect();
                    s.push_str(&format!("/({})", d.join("*")));
                }
            }
            (negative, s, Prec::Product)
        }
        _ => {
            let (s, p) = text(g, id);
            (false, s, p)
        }
    }
}

fn sum_text(g: &Graph, terms: &[Id]) -> (String, Prec) {
    let is_constant = |t: &Id| g.as_number(*t).is_some();
    let mut ordered: Vec<(bool, String, Prec)> = Vec::with_capacity(terms.len());
    for want_negative in [false, true] {
        for constants in [false, true] {
            for t in terms.iter().filter(|t| is_constant(t) == constants) {
                let term = term_text(g, *t);
                if term.0 == want_negative {
                    ordered.push(term);
                }
            }
        }
    }
    let mut s = String::new();
    for (i, (negative, body, prec)) in ordered.into_iter().enumerate() {
        let body = wrap((body, prec), Prec::Product);
        match (i, negative) {
            (0, false) => s.push_str(&body),
            (0, true) => s.push_str(&format!("-{body}")),
            (_, false) => s.push_str(&format!(" + {body}")),
            (_, true) => s.push_str(&format!(" - {body}")),
        }
    }
    (s, Prec::Sum)
}

/// A value whose expressions live in a graph, ready to print: the IRs'
/// printers (`dae::system`, `dae::structure`, `dae::mass_form`,
/// `taylor::analysis`) are `Display` for it. See [`Graph::with`].
pub struct WithGraph<'a, T: ?Sized> {
    /// The graph the value's ids point into.
    pub graph: &'a Graph,
    /// The value.
    pub value: &'a T,
}

impl Graph {
    /// `value`, whose ids point into this graph, ready to print.
    pub fn with<'a, T: ?Sized>(&'a self, value: &'a T) -> WithGraph<'a, T> {
        WithGraph { graph: self, value }
    }
}
