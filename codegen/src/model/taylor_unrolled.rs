//! The unrolled layout of the Taylor recurrences: for an order fixed at
//! compile time, every coefficient of every u-variable is one local and every
//! recurrence one straight-line sum with literal weights (heyoka's default,
//! "non-compact" mode, without its JIT). The runtime's interpreter
//! (`daegen_runtime::taylor_tape`) spends as much time on dispatch, slicing
//! and loop control as on arithmetic for small models; here there is none,
//! and terms with a zero factor (constants and the time beyond their first
//! coefficients) are not emitted. Code size grows as (operations)·p², so
//! the orders are the user's choice (`#[dae_model(taylor = 1, unroll = [19])]`).
//!
//! The recurrences are those of the runtime's `advance` (Jorba & Zou 2005,
//! §3; heyoka's `ad_notes`), with 1/x₀ computed once per u-variable and the
//! j/k weights folded into literals, so the coefficients agree with the
//! interpreter's to rounding.

use super::taylor_tape::{InverseFunction, Operand, Recurrence, Tape};
use proc_macro2::{Literal, TokenStream};
use quote::{format_ident, quote};

/// Where the coefficients live: one array `r` of rows of `order + 1`
/// coefficients, states first, then u-variables, then one reciprocal 1/x₀
/// per u-variable; constants in `c`, the time in `t`.
struct Layout {
    order: usize,
    states: usize,
    vars: usize,
}

impl Layout {
    fn len(&self) -> usize {
        (self.states + self.vars) * (self.order + 1) + self.vars
    }

    fn slot(&self, row: usize, k: usize) -> TokenStream {
        let at = Literal::usize_unsuffixed(row * (self.order + 1) + k);
        quote!(r[#at])
    }

    /// Coefficient `k` of an operand: `None` when it is zero.
    fn coefficient(&self, o: Operand, k: usize) -> Option<TokenStream> {
        match o {
            Operand::State(i) => Some(self.slot(i, k)),
            Operand::Var(v) => Some(self.slot(self.states + v, k)),
            Operand::Time => match k {
                0 => Some(quote!(t)),
                1 => Some(quote!(1.0)),
                _ => None,
            },
            Operand::Const(i) => (k == 0).then(|| {
                let i = Literal::usize_unsuffixed(i);
                quote!(c[#i])
            }),
        }
    }

    /// The slot of 1/x₀ for u-variable `v`'s recurrence.
    fn reciprocal(&self, v: usize) -> TokenStream {
        let at = Literal::usize_unsuffixed((self.states + self.vars) * (self.order + 1) + v);
        quote!(r[#at])
    }
}

/// A finite constant as tokens (a negative one as a negation: literals are unsigned).
fn float(x: f64) -> TokenStream {
    let magnitude = Literal::f64_suffixed(x.abs());
    if x.is_sign_negative() {
        quote!((-#magnitude))
    } else {
        quote!(#magnitude)
    }
}

/// One term of a sum: a product of two factors (a candidate for a fused
/// multiply-add) or a single value.
enum Term {
    Product(TokenStream, TokenStream),
    Single(TokenStream),
}

impl Term {
    fn tokens(&self) -> TokenStream {
        match self {
            Term::Product(a, b) => quote!(#a * #b),
            Term::Single(v) => v.clone(),
        }
    }
}

/// `Σ weight·a·b` over the non-zero terms, or `0.0`.
fn sum(terms: Vec<(f64, Option<TokenStream>, Option<TokenStream>)>) -> TokenStream {
    let mut out: Vec<Term> = Vec::new();
    for (weight, a, b) in terms {
        let (Some(a), Some(b)) = (a, b) else { continue };
        let mut factors: Vec<TokenStream> = [a, b]
            .into_iter()
            .filter(|f| f.to_string() != "1.0")
            .collect();
        if weight.abs() != 1.0 {
            factors.insert(0, float(weight.abs()));
        }
        if factors.is_empty() {
            factors.push(quote!(1.0f64));
        }
        if weight < 0.0 {
            let first = &factors[0];
            factors[0] = quote!((-#first));
        }
        let last = factors.pop().unwrap_or_default();
        out.push(match factors.len() {
            0 => Term::Single(last),
            1 => Term::Product(factors.pop().unwrap_or_default(), last),
            _ => {
                let first = factors.remove(0);
                let product = factors.into_iter().fold(first, |acc, f| quote!(#acc * #f));
                Term::Product(quote!((#product)), last)
            }
        });
    }
    // Leaves of the tree in pairs, a·b + c fused where the target has FMA.
    let mut leaves = Vec::with_capacity(out.len().div_ceil(2));
    let mut it = out.into_iter();
    while let Some(first) = it.next() {
        leaves.push(match (first, it.next()) {
            (Term::Product(a, b), Some(second)) => {
                let c = second.tokens();
                quote!(::daegen::runtime::taylor_tape::mul_add(#a, #b, #c))
            }
            (Term::Single(v), Some(Term::Product(a, b))) => {
                quote!(::daegen::runtime::taylor_tape::mul_add(#a, #b, #v))
            }
            (first, Some(second)) => {
                let (a, b) = (first.tokens(), second.tokens());
                quote!((#a + #b))
            }
            (only, None) => only.tokens(),
        });
    }
    pairwise(leaves)
}

/// The sum of `terms` as a balanced tree, `(a + b) + (c + d)`: its
/// dependency chain is log₂ n additions long instead of n (heyoka's
/// `pairwise_sum`), and its rounding error grows as log n.
fn pairwise(mut terms: Vec<TokenStream>) -> TokenStream {
    if terms.is_empty() {
        return quote!(0.0f64);
    }
    while terms.len() > 1 {
        let mut next = Vec::with_capacity(terms.len().div_ceil(2));
        let mut it = terms.into_iter();
        while let Some(a) = it.next() {
            next.push(match it.next() {
                Some(b) => quote!((#a + #b)),
                None => a,
            });
        }
        terms = next;
    }
    terms.pop().unwrap_or_default()
}

/// `let` statements for coefficient `k` of u-variable `v` (and of `v + 1`
/// for the sin/cos and sinh/cosh pairs).
fn recurrence_at(l: &Layout, v: usize, r: Recurrence, k: usize) -> TokenStream {
    let u = |k: usize| l.coefficient(Operand::Var(v), k);
    let pair = |k: usize| l.coefficient(Operand::Var(v + 1), k);
    let c = |o: Operand, k: usize| l.coefficient(o, k);
    let name = l.slot(l.states + v, k);
    let kf = k as f64;
    if k == 0 {
        let zero = |o: Operand| c(o, 0).unwrap_or(quote!(0.0f64));
        let value = match r {
            Recurrence::Add(a, b) => {
                let (a, b) = (zero(a), zero(b));
                quote!(#a + #b)
            }
            Recurrence::Scale(a, s) => {
                let (a, s) = (zero(a), zero(Operand::Const(s)));
                quote!(#a * #s)
            }
            Recurrence::Quotient(a, s) => {
                let (a, s) = (zero(a), zero(Operand::Const(s)));
                quote!(#a / #s)
            }
            Recurrence::Mul(a, b) => {
                let (a, b) = (zero(a), zero(b));
                quote!(#a * #b)
            }
            Recurrence::Square(a) => {
                let a = zero(a);
                quote!(#a * #a)
            }
            Recurrence::Div(b_over, d) => {
                let (a, d) = (zero(b_over), zero(d));
                let inv = l.reciprocal(v);
                return quote!(#inv = 1.0 / #d; #name = #a * #inv;);
            }
            Recurrence::Pow(a, e) => {
                let a0 = zero(a);
                let inv = l.reciprocal(v);
                // Half-integer powers (gravity's r^(-3/2)) by a square root.
                let value = if e == 0.5 {
                    quote!(#a0.sqrt())
                } else if e == -0.5 {
                    quote!(1.0 / #a0.sqrt())
                } else if e == 1.5 {
                    quote!(#a0 * #a0.sqrt())
                } else if e == -1.5 {
                    quote!(1.0 / (#a0 * #a0.sqrt()))
                } else {
                    let e = float(e);
                    quote!(#a0.powf(#e))
                };
                return quote!(#inv = 1.0 / #a0; #name = #value;);
            }
            Recurrence::Exp(a) => {
                let a = zero(a);
                quote!(#a.exp())
            }
            Recurrence::Ln(a) => {
                let a = zero(a);
                let inv = l.reciprocal(v);
                return quote!(#inv = 1.0 / #a; #name = #a.ln(););
            }
            Recurrence::SinCos(a) | Recurrence::SinhCosh(a) => {
                let a = zero(a);
                let second = l.slot(l.states + v + 1, 0);
                return if let Recurrence::SinCos(_) = r {
                    quote!(let (sin, cos) = #a.sin_cos(); #name = sin; #second = cos;)
                } else {
                    quote!(#name = #a.sinh(); #second = #a.cosh();)
                };
            }
            Recurrence::Inverse(f, a, d) => {
                let (a, d) = (zero(a), zero(d));
                let inv = l.reciprocal(v);
                let value = match f {
                    InverseFunction::Asin => quote!(#a.asin()),
                    InverseFunction::Acos => quote!(#a.acos()),
                    InverseFunction::Atan => quote!(#a.atan()),
                };
                return quote!(#inv = 1.0 / #d; #name = #value;);
            }
            Recurrence::Atan2(y, x, d) => {
                let (y, x, d) = (zero(y), zero(x), zero(d));
                let inv = l.reciprocal(v);
                return quote!(#inv = 1.0 / #d; #name = #y.atan2(#x););
            }
        };
        return quote!(#name = #value;);
    }
    let value = match r {
        Recurrence::Add(a, b) => sum(vec![
            (1.0, c(a, k), Some(quote!(1.0))),
            (1.0, c(b, k), Some(quote!(1.0))),
        ]),
        Recurrence::Scale(a, s) => sum(vec![(1.0, c(a, k), c(Operand::Const(s), 0))]),
        Recurrence::Quotient(a, s) => {
            let (a, s) = (c(a, k), c(Operand::Const(s), 0));
            match a {
                Some(a) => quote!(#a / #s),
                None => quote!(0.0f64),
            }
        }
        Recurrence::Mul(a, b) => sum((0..=k).map(|j| (1.0, c(a, j), c(b, k - j))).collect()),
        Recurrence::Square(a) => {
            let twice = sum((0..k)
                .filter(|&j| j < k - j)
                .map(|j| (2.0, c(a, j), c(a, k - j)))
                .collect());
            if k % 2 == 0 {
                let middle = c(a, k / 2);
                quote!(#twice + #middle * #middle)
            } else {
                twice
            }
        }
        Recurrence::Div(a, d) => {
            // u = a/d: u^[k] = (a^[k] − Σ_{j<k} u^[j] d^[k−j]) / d^[0].
            let a = c(a, k).unwrap_or(quote!(0.0f64));
            let s = sum((0..k).map(|j| (1.0, u(j), c(d, k - j))).collect());
            let inv = l.reciprocal(v);
            quote!((#a - (#s)) * #inv)
        }
        Recurrence::Pow(a, e) => {
            // u^[k] = Σ_{j<k} (k·e − j·(e+1)) u^[j] a^[k−j] / (k a^[0]).
            let s = sum((0..k)
                .map(|j| ((kf * e - j as f64 * (e + 1.0)) / kf, u(j), c(a, k - j)))
                .collect());
            let inv = l.reciprocal(v);
            quote!((#s) * #inv)
        }
        Recurrence::Exp(a) => sum((1..=k)
            .map(|j| (j as f64 / kf, c(a, j), u(k - j)))
            .collect()),
        Recurrence::Ln(a) => {
            let ak = c(a, k).unwrap_or(quote!(0.0f64));
            let s = sum((1..k).map(|j| (j as f64 / kf, u(j), c(a, k - j))).collect());
            let inv = l.reciprocal(v);
            quote!((#ak - (#s)) * #inv)
        }
        Recurrence::SinCos(a) | Recurrence::SinhCosh(a) => {
            let s = sum((1..=k)
                .map(|j| (j as f64 / kf, c(a, j), pair(k - j)))
                .collect());
            let co = sum((1..=k)
                .map(|j| (j as f64 / kf, c(a, j), u(k - j)))
                .collect());
            let second = l.slot(l.states + v + 1, k);
            return if let Recurrence::SinCos(_) = r {
                quote!(#name = #s; #second = -(#co);)
            } else {
                quote!(#name = #s; #second = #co;)
            };
        }
        Recurrence::Inverse(f, a, d) => {
            // d·u' = ±a': u^[k] = (±a^[k] − Σ_{0<j<k} (j/k) u^[j] d^[k−j]) / d^[0].
            let ak = c(a, k).unwrap_or(quote!(0.0f64));
            let ak = match f {
                InverseFunction::Acos => quote!(-(#ak)),
                _ => ak,
            };
            let s = sum((1..k).map(|j| (j as f64 / kf, u(j), c(d, k - j))).collect());
            let inv = l.reciprocal(v);
            quote!((#ak - (#s)) * #inv)
        }
        Recurrence::Atan2(y, x, d) => {
            // d·u' = x·y' − y·x'.
            let plus = sum((1..=k)
                .map(|j| (j as f64 / kf, c(y, j), c(x, k - j)))
                .collect());
            let minus = sum((1..=k)
                .map(|j| (j as f64 / kf, c(x, j), c(y, k - j)))
                .collect());
            let s = sum((1..k).map(|j| (j as f64 / kf, u(j), c(d, k - j))).collect());
            let inv = l.reciprocal(v);
            quote!(((#plus) - (#minus) - (#s)) * #inv)
        }
    };
    quote!(#name = #value;)
}

/// Up to this many (operations × order²), about the number of products, the
/// orders are inlined into one function (Kepler at order 19: 3,000).
const SINGLE_FUNCTION_TERMS: usize = 20_000;

/// The body of `taylor_jet_unrolled` for `order`: reads `t`, `y` (an array
/// of `n` states) and the constants `c` (an array) and writes state i's
/// normalised coefficient k to `out[i·(order+1) + k]` (an array). One
/// function per order, not inlined for large jets: rustc's time on one
/// function of thousands of live values grows much faster than linearly
/// (the outer solar system at three orders took over five minutes as one
/// function, 1.5 minutes split, for 12 % more run time).
pub fn unrolled_jet(tape: &Tape, n: usize, order: usize) -> TokenStream {
    let l = Layout {
        order,
        states: n,
        vars: tape.ops.len(),
    };
    let len = Literal::usize_unsuffixed(l.len());
    // Small jets become one function, whose coefficient array the compiler
    // keeps in registers; large ones stay one function per order.
    let terms = tape.ops.len() * order * order;
    let inline = if terms <= SINGLE_FUNCTION_TERMS {
        quote!(#[inline(always)])
    } else {
        quote!(#[inline(never)])
    };
    let constants: Vec<_> = (0..tape.constants.len())
        .map(|i| format_ident!("c{}", i))
        .collect();
    let nc = Literal::usize_unsuffixed(constants.len());
    let mut code = TokenStream::new();
    code.extend(quote! {
        let c: [f64; #nc] = [#(#constants),*];
        let mut r = [0.0f64; #len];
    });
    for i in 0..n {
        let (slot, i) = (l.slot(i, 0), Literal::usize_unsuffixed(i));
        code.extend(quote!(#slot = y[#i];));
    }
    for k in 0..order {
        let mut step = TokenStream::new();
        for &(v, rec) in &tape.recurrences {
            step.extend(recurrence_at(&l, v, rec, k));
        }
        // x^[k+1] = f^[k] / (k + 1).
        let scale = float(1.0 / (k + 1) as f64);
        for (i, &o) in tape.output_operands.iter().enumerate() {
            let slot = l.slot(i, k + 1);
            let value = match l.coefficient(o, k) {
                Some(f) if k == 0 => f,
                Some(f) => quote!(#f * #scale),
                None => quote!(0.0f64),
            };
            step.extend(quote!(#slot = #value;));
        }
        let name = format_ident!("order_{}", k);
        code.extend(quote! {
            #inline
            fn #name(r: &mut [f64; #len], t: f64, c: &[f64; #nc]) {
                #step
            }
            #name(&mut r, t, &c);
        });
    }
    for i in 0..n {
        for k in 0..=order {
            let slot = l.slot(i, k);
            let at = Literal::usize_unsuffixed(i * (order + 1) + k);
            code.extend(quote!(out[#at] = #slot;));
        }
    }
    code
}
