//! Smart constructors: the only way nodes are made. They fold constants,
//! flatten sums and products, collect like terms, merge powers of the same
//! base and keep children sorted, so that equal expressions get equal ids.
//!
//! Every rewrite preserves values: wherever the expression as written
//! evaluates to a finite number without passing through an infinity or NaN,
//! the built one evaluates to the same number (up to rounding). Identities such as `x - x = 0` or `x/x = 1` may remove a
//! point where the written form was undefined; none adds one. Folding that
//! would create NaN or an infinity (`1/0`, `ln(0)`) is an [`Error`].

use crate::error::{Error, Result};
use crate::expr::graph::Graph;
use crate::expr::node::{Func, Id, Node};
use crate::expr::number::Number;

fn overflow(expression: String) -> Error {
    Error::NotFinite { expression, reason: "the result overflows f64" }
}

impl Graph {
    /// `a + b`.
    pub fn add(&mut self, a: Id, b: Id) -> Result<Id> {
        self.sum(&[a, b])
    }

    /// `a - b`.
    pub fn sub(&mut self, a: Id, b: Id) -> Result<Id> {
        let nb = self.neg(b)?;
        self.sum(&[a, nb])
    }

    /// `-a`.
    pub fn neg(&mut self, a: Id) -> Result<Id> {
        let m1 = self.int(-1);
        self.product(&[m1, a])
    }

    /// `-a`, with a sum negated term by term (`-(x - y)` is `y - x`) where
    /// `neg` keeps `-1 * (x - y)` whole. For results read by people (the
    /// right-hand side solved from an equation) and for sign choices.
    pub fn negate_terms(&mut self, a: Id) -> Result<Id> {
        match self.node(a) {
            Node::Add(terms) => {
                let terms = terms.to_vec();
                let negated = terms.into_iter().map(|t| self.neg(t)).collect::<Result<Vec<_>>>()?;
                self.sum(&negated)
            }
            _ => self.neg(a),
        }
    }

    /// `a * b`.
    pub fn mul(&mut self, a: Id, b: Id) -> Result<Id> {
        self.product(&[a, b])
    }

    /// `a / b`, as `a * b^-1`.
    pub fn div(&mut self, a: Id, b: Id) -> Result<Id> {
        let m1 = self.int(-1);
        let inv = self.pow(b, m1)?;
        self.product(&[a, inv])
    }

    /// `a^n` for an integer `n`.
    pub fn powi(&mut self, a: Id, n: i64) -> Result<Id> {
        let e = self.int(n);
        self.pow(a, e)
    }

    /// `sqrt(a)`, as `a^(1/2)`.
    pub fn sqrt(&mut self, a: Id) -> Result<Id> {
        let half = self.rational(1, 2)?;
        self.pow(a, half)
    }

    /// The sum of `terms`: flattened, like terms collected, constants folded.
    pub fn sum(&mut self, terms: &[Id]) -> Result<Id> {
        let mut pending: Vec<Id> = Vec::with_capacity(terms.len());
        for &t in terms {
            match self.node(t) {
                Node::Add(children) => pending.extend_from_slice(children),
                _ => pending.push(t),
            }
        }
        // `e + 0` is `e` itself, even when `e` is a scaled sum like `2*(x + y)`.
        let mut non_numbers = pending.iter().filter(|&&t| self.as_number(t).is_none());
        if let (Some(&only), None) = (non_numbers.next(), non_numbers.next()) {
            if pending.iter().all(|&t| t == only || self.as_number(t).is_some_and(Number::is_zero))
            {
                return Ok(only);
            }
        }
        let mut constant = Number::ZERO;
        let mut collected: Vec<(Id, Number)> = Vec::with_capacity(pending.len());
        let mut work: Vec<(Number, Id)> = pending.into_iter().map(|t| (Number::ONE, t)).collect();
        while let Some((scale, t)) = work.pop() {
            if let Some(n) = self.as_number(t) {
                let n = scale.checked_mul(n).ok_or_else(|| overflow(format!("{scale} * {n}")))?;
                constant =
                    constant.checked_add(n).ok_or_else(|| overflow(format!("{constant} + {n}")))?;
                continue;
            }
            let (coefficient, rest) = self.split_coefficient(t);
            let c = scale
                .checked_mul(coefficient)
                .ok_or_else(|| overflow(format!("{scale} * {coefficient}")))?;
            match self.node(rest) {
                // A scaled sum inside a sum is spread into its terms, so that
                // `x + y - (x + y)` cancels; products keep `c*(x + y)` whole,
                // so that the sum stays shared.
                Node::Add(children) => work.extend(children.iter().map(|&child| (c, child))),
                _ => collected.push((rest, c)),
            }
        }
        collected.sort_by_key(|&(rest, _)| rest);
        let mut children: Vec<Id> = Vec::with_capacity(collected.len() + 1);
        let mut i = 0;
        while i < collected.len() {
            let (rest, mut coefficient) = collected[i];
            i += 1;
            while i < collected.len() && collected[i].0 == rest {
                let c = collected[i].1;
                coefficient = coefficient
                    .checked_add(c)
                    .ok_or_else(|| overflow(format!("{coefficient} + {c}")))?;
                i += 1;
            }
            if !coefficient.is_zero() {
                children.push(self.scale(coefficient, rest));
            }
        }
        if !constant.is_zero() {
            children.push(self.num(constant));
        }
        Ok(match children.len() {
            0 => self.zero(),
            1 => children[0],
            _ => {
                children.sort_unstable();
                self.intern(Node::Add(children.into_boxed_slice()))
            }
        })
    }

    /// A term as `(numeric coefficient, the rest)`: `3*x*y` is `(3, x*y)`.
    fn split_coefficient(&mut self, t: Id) -> (Number, Id) {
        if let Node::Mul(factors) = self.node(t) {
            if let Some(pos) = factors.iter().position(|&f| self.as_number(f).is_some()) {
                let coefficient = self.as_number(factors[pos]).unwrap_or(Number::ONE);
                let rest: Vec<Id> = factors
                    .iter()
                    .enumerate()
                    .filter(|&(i, _)| i != pos)
                    .map(|(_, &f)| f)
                    .collect();
                let rest = if rest.len() == 1 {
                    rest[0]
                } else {
                    self.intern(Node::Mul(rest.into_boxed_slice()))
                };
                return (coefficient, rest);
            }
        }
        (Number::ONE, t)
    }

    /// `c * rest` where `rest` is a canonical term without coefficient.
    fn scale(&mut self, c: Number, rest: Id) -> Id {
        if c.is_one() {
            return rest;
        }
        let c = self.num(c);
        let mut factors: Vec<Id> = match self.node(rest) {
            Node::Mul(f) => f.to_vec(),
            _ => vec![rest],
        };
        factors.push(c);
        factors.sort_unstable();
        self.intern(Node::Mul(factors.into_boxed_slice()))
    }

    /// A factor as `(base, exponent)`: `x^3` is `(x, 3)`, `x` is `(x, 1)`.
    fn split_power(&mut self, f: Id) -> (Id, Id) {
        match self.node(f) {
            Node::Pow([b, e]) => (*b, *e),
            _ => (f, self.one()),
        }
    }

    /// The product of `factors`: flattened, constants folded, powers of the
    /// same base merged (`x * x^-1` is `1`). A coefficient is not distributed
    /// over a sum (`2*(x - y)` keeps `x - y` shared with other uses); `sum`
    /// spreads such terms where cancellation can use them.
    pub fn product(&mut self, factors: &[Id]) -> Result<Id> {
        let mut coefficient = Number::ONE;
        let mut powers: Vec<(Id, Id)> = Vec::with_capacity(factors.len());
        let mut pending: Vec<Id> = Vec::with_capacity(factors.len());
        for &f in factors {
            match self.node(f) {
                Node::Mul(children) => pending.extend_from_slice(children),
                _ => pending.push(f),
            }
        }
        for f in pending {
            if let Some(n) = self.as_number(f) {
                coefficient = coefficient
                    .checked_mul(n)
                    .ok_or_else(|| overflow(format!("{coefficient} * {n}")))?;
            } else {
                powers.push(self.split_power(f));
            }
        }
        if coefficient.is_zero() {
            return Ok(self.zero());
        }
        powers.sort_by_key(|&(base, _)| base);
        let mut out: Vec<Id> = Vec::with_capacity(powers.len());
        let mut needs_reflattening = false;
        let mut i = 0;
        while i < powers.len() {
            let (base, mut exponent) = powers[i];
            i += 1;
            while i < powers.len() && powers[i].0 == base {
                exponent = self.add(exponent, powers[i].1)?;
                i += 1;
            }
            let p = self.pow(base, exponent)?;
            match self.node(p) {
                Node::Number(n) => {
                    let n = *n;
                    coefficient = coefficient
                        .checked_mul(n)
                        .ok_or_else(|| overflow(format!("{coefficient} * {n}")))?;
                }
                Node::Mul(_) => {
                    needs_reflattening = true;
                    out.push(p);
                }
                _ => out.push(p),
            }
        }
        if coefficient.is_zero() {
            return Ok(self.zero());
        }
        if needs_reflattening {
            // A merged power turned back into a product, e.g. sqrt(x*y)^2 = x*y:
            // its factors may merge with the others.
            let c = self.num(coefficient);
            out.push(c);
            return self.product(&out);
        }
        Ok(match (out.len(), coefficient.is_one()) {
            (0, _) => self.num(coefficient),
            (1, true) => out[0],
            _ => {
                if !coefficient.is_one() {
                    out.push(self.num(coefficient));
                }
                out.sort_unstable();
                self.intern(Node::Mul(out.into_boxed_slice()))
            }
        })
    }

    /// `base ^ exponent`. Integer exponents distribute over products and
    /// compose with inner powers (`(x^(1/2))^2 = x`); fractional exponents do
    /// neither, since `((-1)^2)^(1/2)` is 1, not -1.
    pub fn pow(&mut self, base: Id, exponent: Id) -> Result<Id> {
        let e = self.as_number(exponent);
        if let Some(e) = e {
            if e.is_zero() {
                return Ok(self.one());
            }
            if e.is_one() {
                return Ok(base);
            }
        }
        if let Some(b) = self.as_number(base) {
            if b.is_one() {
                return Ok(base);
            }
            if let Some(e) = e {
                if let (Some(rb), Some(re)) = (b.as_rational(), e.as_rational()) {
                    // An irrational root of a rational stays symbolic, so that
                    // 2^(1/2) * 2^(1/2) is exactly 2.
                    if !re.is_integer()
                        && !rb.is_negative()
                        && !rb.is_zero()
                        && rb.exact_root(re.denom()).is_none()
                    {
                        return Ok(self.intern(Node::Pow([base, exponent])));
                    }
                }
                return match b.pow(e) {
                    Some(v) => Ok(self.num(v)),
                    None => Err(Error::NotFinite {
                        expression: if e
                            .as_rational()
                            .is_some_and(|r| r.numer() == 1 && r.denom() == 2)
                        {
                            format!("sqrt({b})")
                        } else {
                            format!("{}^{}", paren_if_negative(b), paren_if_fraction(e))
                        },
                        reason: if b.is_zero() { "division by zero" } else { "not a real number" },
                    }),
                };
            }
        }
        if let Some(n) = e.and_then(Number::as_integer) {
            // (a - b)^2 = (b - a)^2 exactly: of a sum and its negation, even
            // powers take the one with the smaller id (a symmetric choice, so
            // (i, j) and (j, i) pair distances become one node).
            if n % 2 == 0 && matches!(self.node(base), Node::Add(_)) {
                let flipped = self.negate_terms(base)?;
                if flipped < base {
                    return Ok(self.intern(Node::Pow([flipped, exponent])));
                }
            }
            match self.node(base).clone() {
                Node::Pow([inner_base, inner_exp]) => {
                    let composed = self.mul(inner_exp, exponent)?;
                    return self.pow(inner_base, composed);
                }
                Node::Mul(factors) => {
                    let powered = factors
                        .iter()
                        .map(|&f| self.pow(f, exponent))
                        .collect::<Result<Vec<_>>>()?;
                    return self.product(&powered);
                }
                _ => {}
            }
        }
        Ok(self.intern(Node::Pow([base, exponent])))
    }

    /// `f(a)`, folded when `a` is a constant.
    pub fn call(&mut self, f: Func, a: Id) -> Result<Id> {
        if let Some(x) = self.as_number(a) {
            return self.fold_call(f, x).map(|n| self.num(n));
        }
        if let (Func::Abs | Func::Sign, Node::Call(inner, _)) = (f, self.node(a)) {
            if *inner == f {
                return Ok(a); // abs(abs(x)) = abs(x), sign(sign(x)) = sign(x)
            }
        }
        Ok(self.intern(Node::Call(f, a)))
    }

    fn fold_call(&self, f: Func, x: Number) -> Result<Number> {
        let not_finite =
            |reason| Error::NotFinite { expression: format!("{}({x})", f.name()), reason };
        let exact = match f {
            Func::Sin | Func::Tan | Func::Asin | Func::Atan | Func::Sinh | Func::Tanh
                if x.is_zero() =>
            {
                Some(Number::ZERO)
            }
            Func::Cos | Func::Cosh | Func::Exp if x.is_zero() => Some(Number::ONE),
            Func::Ln | Func::Acos if x.is_one() => Some(Number::ZERO),
            Func::Abs => Some(x.abs()),
            Func::Sign => Some(Number::integer(crate::expr::node::sign(x.to_f64()) as i64)),
            _ => None,
        };
        if let Some(v) = exact {
            return Ok(v);
        }
        let v = x.to_f64();
        match f {
            Func::Ln if v <= 0.0 => {
                return Err(not_finite("the logarithm needs a positive argument"))
            }
            Func::Asin | Func::Acos if v.abs() > 1.0 => {
                return Err(not_finite("the argument must lie in [-1, 1]"))
            }
            _ => {}
        }
        Number::from_f64(f.apply(v)).ok_or_else(|| not_finite("the result overflows f64"))
    }

    /// `atan2(y, x)`, folded when both are constants.
    pub fn atan2(&mut self, y: Id, x: Id) -> Result<Id> {
        if let (Some(a), Some(b)) = (self.as_number(y), self.as_number(x)) {
            return self.float(a.to_f64().atan2(b.to_f64()));
        }
        Ok(self.intern(Node::Atan2([y, x])))
    }
}

fn paren_if_negative(n: Number) -> String {
    if n.is_negative() {
        format!("({n})")
    } else {
        n.to_string()
    }
}

fn paren_if_fraction(n: Number) -> String {
    match n.as_rational() {
        Some(r) if r.is_integer() && !r.is_negative() => n.to_string(),
        _ => format!("({n})"),
    }
}
