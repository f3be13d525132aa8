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

/// Coefficient `k` of an operand: `None` when it is zero.
fn coefficient(o: Operand, k: usize) -> Option<TokenStream> {
    match o {
        Operand::State(i) => {
            let name = format_ident!("s{}_{}", i, k);
            Some(quote!(#name))
        }
        Operand::Var(v) => {
            let name = format_ident!("u{}_{}", v, k);
            Some(quote!(#name))
        }
        Operand::Time => match k {
            0 => Some(quote!(t)),
            1 => Some(quote!(1.0)),
            _ => None,
        },
        Operand::Const(c) => (k == 0).then(|| {
            let name = format_ident!("c{}", c);
            quote!(#name)
        }),
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

/// `Σ weight·a·b` over the non-zero terms, or `0.0`.
fn sum(terms: Vec<(f64, Option<TokenStream>, Option<TokenStream>)>) -> TokenStream {
    let mut out: Vec<TokenStream> = Vec::new();
    for (weight, a, b) in terms {
        let (Some(a), Some(b)) = (a, b) else { continue };
        let term = match (a.to_string().as_str(), b.to_string().as_str()) {
            ("1.0", _) => b,
            (_, "1.0") => a,
            _ => quote!(#a * #b),
        };
        out.push(if weight == 1.0 {
            term
        } else if weight == -1.0 {
            quote!(-(#term))
        } else if weight < 0.0 {
            let w = float(-weight);
            quote!(-(#w * #term))
        } else {
            let w = float(weight);
            quote!(#w * #term)
        });
    }
    pairwise(out)
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

/// The local holding 1/x₀ for u-variable `v`'s recurrence.
fn reciprocal(v: usize) -> TokenStream {
    let name = format_ident!("inv{}", v);
    quote!(#name)
}

/// `let` statements for coefficient `k` of u-variable `v` (and of `v + 1`
/// for the sin/cos and sinh/cosh pairs).
fn recurrence_at(v: usize, r: Recurrence, k: usize) -> TokenStream {
    let u = |k: usize| coefficient(Operand::Var(v), k);
    let pair = |k: usize| coefficient(Operand::Var(v + 1), k);
    let c = coefficient;
    let name = format_ident!("u{}_{}", v, k);
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
                let inv = reciprocal(v);
                return quote!(let #inv = 1.0 / #d; let #name = #a * #inv;);
            }
            Recurrence::Pow(a, e) => {
                let a0 = zero(a);
                let inv = reciprocal(v);
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
                return quote!(let #inv = 1.0 / #a0; let #name = #value;);
            }
            Recurrence::Exp(a) => {
                let a = zero(a);
                quote!(#a.exp())
            }
            Recurrence::Ln(a) => {
                let a = zero(a);
                let inv = reciprocal(v);
                return quote!(let #inv = 1.0 / #a; let #name = #a.ln(););
            }
            Recurrence::SinCos(a) | Recurrence::SinhCosh(a) => {
                let a = zero(a);
                let second = format_ident!("u{}_0", v + 1);
                return if let Recurrence::SinCos(_) = r {
                    quote!(let (#name, #second) = #a.sin_cos();)
                } else {
                    quote!(let #name = #a.sinh(); let #second = #a.cosh();)
                };
            }
            Recurrence::Inverse(f, a, d) => {
                let (a, d) = (zero(a), zero(d));
                let inv = reciprocal(v);
                let value = match f {
                    InverseFunction::Asin => quote!(#a.asin()),
                    InverseFunction::Acos => quote!(#a.acos()),
                    InverseFunction::Atan => quote!(#a.atan()),
                };
                return quote!(let #inv = 1.0 / #d; let #name = #value;);
            }
            Recurrence::Atan2(y, x, d) => {
                let (y, x, d) = (zero(y), zero(x), zero(d));
                let inv = reciprocal(v);
                return quote!(let #inv = 1.0 / #d; let #name = #y.atan2(#x););
            }
        };
        return quote!(let #name = #value;);
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
            let inv = reciprocal(v);
            quote!((#a - (#s)) * #inv)
        }
        Recurrence::Pow(a, e) => {
            // u^[k] = Σ_{j<k} (k·e − j·(e+1)) u^[j] a^[k−j] / (k a^[0]).
            let s = sum((0..k)
                .map(|j| ((kf * e - j as f64 * (e + 1.0)) / kf, u(j), c(a, k - j)))
                .collect());
            let inv = reciprocal(v);
            quote!((#s) * #inv)
        }
        Recurrence::Exp(a) => sum((1..=k)
            .map(|j| (j as f64 / kf, c(a, j), u(k - j)))
            .collect()),
        Recurrence::Ln(a) => {
            let ak = c(a, k).unwrap_or(quote!(0.0f64));
            let s = sum((1..k).map(|j| (j as f64 / kf, u(j), c(a, k - j))).collect());
            let inv = reciprocal(v);
            quote!((#ak - (#s)) * #inv)
        }
        Recurrence::SinCos(a) | Recurrence::SinhCosh(a) => {
            let s = sum((1..=k)
                .map(|j| (j as f64 / kf, c(a, j), pair(k - j)))
                .collect());
            let co = sum((1..=k)
                .map(|j| (j as f64 / kf, c(a, j), u(k - j)))
                .collect());
            let second = format_ident!("u{}_{}", v + 1, k);
            return if let Recurrence::SinCos(_) = r {
                quote!(let #name = #s; let #second = -(#co);)
            } else {
                quote!(let #name = #s; let #second = #co;)
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
            let inv = reciprocal(v);
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
            let inv = reciprocal(v);
            quote!(((#plus) - (#minus) - (#s)) * #inv)
        }
    };
    quote!(let #name = #value;)
}

/// The body of `taylor_jet_unrolled` for `order`: reads `t`, `y` (an array
/// of `n` states), the constants `c0`, `c1`, … and writes state i's
/// normalised coefficient k to `out[i·(order+1) + k]` (an array).
pub fn unrolled_jet(tape: &Tape, n: usize, order: usize) -> TokenStream {
    let mut code = TokenStream::new();
    for i in 0..n {
        let (s, i) = (format_ident!("s{}_0", i), Literal::usize_unsuffixed(i));
        code.extend(quote!(let #s = y[#i];));
    }
    for k in 0..order {
        for &(v, r) in &tape.recurrences {
            code.extend(recurrence_at(v, r, k));
        }
        // x^[k+1] = f^[k] / (k + 1).
        let scale = float(1.0 / (k + 1) as f64);
        for (i, &o) in tape.output_operands.iter().enumerate() {
            let s = format_ident!("s{}_{}", i, k + 1);
            let value = match coefficient(o, k) {
                Some(f) if k == 0 => f,
                Some(f) => quote!(#f * #scale),
                None => quote!(0.0f64),
            };
            code.extend(quote!(let #s = #value;));
        }
    }
    for i in 0..n {
        for k in 0..=order {
            let s = format_ident!("s{}_{}", i, k);
            let at = Literal::usize_unsuffixed(i * (order + 1) + k);
            code.extend(quote!(out[#at] = #s;));
        }
    }
    code
}
