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

use super::taylor_folding::{
    fold_linear, known_constants, Base, Folding, LinearTerm, Role, Weight,
};
use super::taylor_tape::{InverseFunction, Operand, Recurrence, Tape};
use proc_macro2::{Literal, TokenStream};
use quote::{format_ident, quote, ToTokens};

/// Where the coefficients live: one array `r` of rows of `order + 1`
/// coefficients, states first, then the u-variables that have a row (see
/// [`Plan`]), then one reciprocal 1/x₀ per such row; constants and the
/// weights of the folded sums in `c`, the time in `t`.
struct Layout {
    order: usize,
    states: usize,
    /// The row of each u-variable among the u-variables' rows, if it has one.
    rows: Vec<Option<usize>>,
    row_count: usize,
}

impl Layout {
    fn len(&self) -> usize {
        (self.states + self.row_count) * (self.order + 1) + self.row_count
    }

    fn slot(&self, row: usize, k: usize) -> TokenStream {
        let at = Literal::usize_unsuffixed(row * (self.order + 1) + k);
        quote!(r[#at])
    }

    /// The row of u-variable `v` in `r`; only asked of u-variables that
    /// have one (the plan never refers to the others by row).
    fn var_row(&self, v: usize) -> usize {
        self.states + self.rows[v].unwrap_or(0)
    }

    /// Coefficient `k` of an operand: `None` when it is zero.
    fn coefficient(&self, o: Operand, k: usize) -> Option<TokenStream> {
        match o {
            Operand::State(i) => Some(self.slot(i, k)),
            Operand::Var(v) => Some(self.slot(self.var_row(v), k)),
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

    /// When coefficient `index` of `o` is known to order `k`'s sums: 0 from
    /// an earlier order, 1 at the start of order k (a state's coefficient
    /// k), 2 once computed in order k (a u-variable's coefficient k).
    fn fresh(&self, o: Operand, index: usize, k: usize) -> u8 {
        match o {
            _ if index != k => 0,
            Operand::Var(_) => 2,
            _ => 1,
        }
    }

    /// The slot of 1/x₀ for u-variable `v`'s recurrence.
    fn reciprocal(&self, v: usize) -> TokenStream {
        let row = self.rows[v].unwrap_or(0);
        let at = Literal::usize_unsuffixed((self.states + self.row_count) * (self.order + 1) + row);
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

/// One term `weight·a·b` of a sum (a missing factor is a zero one), and
/// when it can be added: 0 reads earlier coefficients only, 1 a state's
/// coefficient of the order being computed, 2 a u-variable's.
type Triple = (f64, Option<TokenStream>, Option<TokenStream>, u8);

/// `Σ weight·a·b` over the non-zero terms, or `0.0`.
fn sum(terms: Vec<Triple>) -> TokenStream {
    sum_with(terms, Vec::new())
}

/// A term as a product of its factors (weight first), or a single value.
fn term(weight: f64, a: TokenStream, b: TokenStream) -> Term {
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
    match factors.len() {
        0 => Term::Single(last),
        1 => Term::Product(factors.pop().unwrap_or_default(), last),
        _ => {
            let first = factors.remove(0);
            let product = factors.into_iter().fold(first, |acc, f| quote!(#acc * #f));
            Term::Product(quote!((#product)), last)
        }
    }
}

/// `Σ weight·a·b` over the non-zero terms plus the `extra` terms, or `0.0`.
///
/// The terms that read only earlier coefficients form a balanced tree,
/// which the processor computes while this order's u-variables are still
/// being produced. The terms that read a coefficient of this order come
/// after it, one fused multiply-add each: first those of the states (known
/// when the order starts), then those of u-variables computed in this order
/// (and the `extra` ones). The chain from one order's coefficient to the
/// next order's is then one operation per recurrence instead of
/// log₂(k) + 1, which is what bounds small jets (Kepler 25 % faster). The terms of this order are also the largest of a
/// convolution (they hold the coefficient 0 of the other factor), and adding
/// them last rather than in the tree keeps Kepler's error at tolerance
/// 1e-14 at 1.4e-11 (3.5e-10 with the states' terms in the tree), built
/// for a host with FMA as the benchmark is; it is a rounding floor, so it
/// moves with the target (about 1e-10 without FMA) and no test pins it.
fn sum_with(terms: Vec<Triple>, extra: Vec<Term>) -> TokenStream {
    let (mut old, mut fresh): (Vec<Term>, Vec<(u8, Term)>) = (Vec::new(), Vec::new());
    for (weight, a, b, rank) in terms {
        let (Some(a), Some(b)) = (a, b) else { continue };
        if weight == 0.0 {
            continue;
        }
        let t = term(weight, a, b);
        if rank == 0 {
            old.push(t);
        } else {
            fresh.push((rank, t));
        }
    }
    // States' coefficients of this order first, u-variables' last.
    fresh.sort_by_key(|(rank, _)| *rank);
    let mut fresh: Vec<Term> = fresh.into_iter().map(|(_, t)| t).collect();
    fresh.extend(extra);
    let mut acc = if old.is_empty() {
        None
    } else {
        Some(tree(old))
    };
    for t in fresh {
        acc = Some(match (acc, t) {
            (None, t) => t.tokens(),
            (Some(acc), Term::Product(a, b)) => {
                quote!(::daegen::runtime::taylor_tape::mul_add(#a, #b, #acc))
            }
            (Some(acc), Term::Single(v)) => quote!((#acc + #v)),
        });
    }
    acc.unwrap_or(quote!(0.0f64))
}

/// The sum of `out` as a balanced tree of fused pairs.
fn tree(out: Vec<Term>) -> TokenStream {
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

/// The terms `w(j)·x^[j]·y^[k−j]` for `j` in `range`, each with when it
/// can be added (see [`Layout::fresh`]).
fn convolution(
    l: &Layout,
    x: Operand,
    y: Operand,
    k: usize,
    range: impl Iterator<Item = usize>,
    w: impl Fn(usize) -> f64,
) -> Vec<Triple> {
    range
        .map(|j| {
            let rank = l.fresh(x, j, k).max(l.fresh(y, k - j, k));
            (w(j), l.coefficient(x, j), l.coefficient(y, k - j), rank)
        })
        .collect()
}

/// The terms of coefficient `k` of a base: the operand's coefficient, or
/// the Cauchy product (a square by its half-sum, each cross term twice).
fn base_terms(l: &Layout, base: Base, k: usize) -> Vec<Triple> {
    match base {
        Base::Operand(o) => vec![(
            1.0,
            l.coefficient(o, k),
            Some(quote!(1.0)),
            l.fresh(o, k, k),
        )],
        Base::Square(a) => convolution(l, a, a, k, (0..=k).filter(|&j| j <= k - j), |j| {
            if j < k - j {
                2.0
            } else {
                1.0
            }
        }),
        Base::Product(a, b) => convolution(l, a, b, k, 0..=k, |_| 1.0),
    }
}

/// `let` statements for coefficient `k` of u-variable `v` (and of `v + 1`
/// for the sin/cos and sinh/cosh pairs).
fn recurrence_at(l: &Layout, v: usize, r: Recurrence, k: usize) -> TokenStream {
    let c = |o: Operand, k: usize| l.coefficient(o, k);
    let name = l.slot(l.var_row(v), k);
    let kf = k as f64;
    if k == 0 {
        let zero = |o: Operand| c(o, 0).unwrap_or(quote!(0.0f64));
        let value = match r {
            // Linear recurrences are folded sums (`taylor_folding`), never
            // rows of their own.
            Recurrence::Add(..) | Recurrence::Scale(..) | Recurrence::Quotient(..) => {
                return TokenStream::new()
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
                let second = l.slot(l.var_row(v + 1), 0);
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
    let own = Operand::Var(v);
    let by_k = |j: usize| j as f64 / kf;
    let value = match r {
        Recurrence::Add(..) | Recurrence::Scale(..) | Recurrence::Quotient(..) => {
            return TokenStream::new()
        }
        Recurrence::Mul(a, b) => sum(base_terms(l, Base::Product(a, b), k)),
        Recurrence::Square(a) => sum(base_terms(l, Base::Square(a), k)),
        Recurrence::Div(a, d) => {
            // u = a/d: u^[k] = (a^[k] − Σ_{j<k} u^[j] d^[k−j]) / d^[0].
            let a = c(a, k).unwrap_or(quote!(0.0f64));
            let s = sum(convolution(l, own, d, k, 0..k, |_| 1.0));
            let inv = l.reciprocal(v);
            quote!((#a - (#s)) * #inv)
        }
        Recurrence::Pow(a, e) => {
            // u^[k] = Σ_{j<k} (k·e − j·(e+1)) u^[j] a^[k−j] / (k a^[0]).
            let w = |j: usize| (kf * e - j as f64 * (e + 1.0)) / kf;
            let s = sum(convolution(l, own, a, k, 0..k, w));
            let inv = l.reciprocal(v);
            quote!((#s) * #inv)
        }
        Recurrence::Exp(a) => sum(convolution(l, a, own, k, 1..=k, by_k)),
        Recurrence::Ln(a) => {
            let ak = c(a, k).unwrap_or(quote!(0.0f64));
            let s = sum(convolution(l, own, a, k, 1..k, by_k));
            let inv = l.reciprocal(v);
            quote!((#ak - (#s)) * #inv)
        }
        Recurrence::SinCos(a) | Recurrence::SinhCosh(a) => {
            let s = sum(convolution(l, a, Operand::Var(v + 1), k, 1..=k, by_k));
            let co = sum(convolution(l, a, own, k, 1..=k, by_k));
            let second = l.slot(l.var_row(v + 1), k);
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
            let s = sum(convolution(l, own, d, k, 1..k, by_k));
            let inv = l.reciprocal(v);
            quote!((#ak - (#s)) * #inv)
        }
        Recurrence::Atan2(y, x, d) => {
            // d·u' = x·y' − y·x'.
            let plus = sum(convolution(l, y, x, k, 1..=k, by_k));
            let minus = sum(convolution(l, x, y, k, 1..=k, by_k));
            let s = sum(convolution(l, own, d, k, 1..k, by_k));
            let inv = l.reciprocal(v);
            quote!(((#plus) - (#minus) - (#s)) * #inv)
        }
    };
    quote!(#name = #value;)
}

/// The weights of folded terms that are not numbers, as extra entries of
/// `c` after the tape's constants (computed once per call).
struct Weights {
    list: Vec<Weight>,
    first: usize,
}

impl Weights {
    fn collect(folding: &Folding, first: usize) -> Weights {
        let mut list: Vec<Weight> = Vec::new();
        let sums = folding.roles.iter().filter_map(|r| match r {
            Role::SumRow(terms) => Some(terms),
            _ => None,
        });
        for t in sums.chain(&folding.outputs).flatten() {
            if !t.weight.is_literal() && !list.contains(&t.weight) {
                list.push(t.weight.clone());
            }
        }
        Weights { list, first }
    }

    /// `c[i]` for a weight that is not a number.
    fn token(&self, w: &Weight) -> Option<TokenStream> {
        let i = self.list.iter().position(|x| x == w)?;
        let at = Literal::usize_unsuffixed(self.first + i);
        Some(quote!(c[#at]))
    }

    /// The expressions of the weights, from the constants `c0`, `c1`, ...
    fn values(&self) -> Vec<TokenStream> {
        let name = |i: &usize| format_ident!("c{}", i);
        self.list
            .iter()
            .map(|w| {
                let mut factors: Vec<TokenStream> = w
                    .times
                    .iter()
                    .map(|i| name(i).into_token_stream())
                    .collect();
                if w.literal.abs() != 1.0 || factors.is_empty() {
                    factors.insert(0, float(w.literal.abs()));
                }
                let sign = (w.literal < 0.0).then(|| quote!(-));
                let product = factors
                    .into_iter()
                    .reduce(|a, b| quote!(#a * #b))
                    .unwrap_or_default();
                let numerator = quote!(#sign (#product));
                if w.over.is_empty() {
                    numerator
                } else {
                    let over = w
                        .over
                        .iter()
                        .map(|i| name(i).into_token_stream())
                        .reduce(|a, b| quote!(#a * #b))
                        .unwrap_or_default();
                    quote!(#numerator / (#over))
                }
            })
            .collect()
    }
}

/// Coefficient `k` of a folded sum: terms with numeric weights (and the
/// convolutions of folded squares and products) flattened into one
/// pairwise sum, the others multiplied by their weight from `c`.
fn folded_sum(l: &Layout, weights: &Weights, terms: &[LinearTerm], k: usize) -> TokenStream {
    let mut flat = Vec::new();
    let mut extra = Vec::new();
    for t in terms {
        let products = base_terms(l, t.base, k);
        match weights.token(&t.weight) {
            None => flat.extend(
                products
                    .into_iter()
                    .map(|(w, a, b, fresh)| (w * t.weight.literal, a, b, fresh)),
            ),
            Some(weight) => {
                if products
                    .iter()
                    .any(|(_, a, b, _)| a.is_some() && b.is_some())
                {
                    let inner = sum(products);
                    extra.push(Term::Product(weight, quote!((#inner))));
                }
            }
        }
    }
    sum_with(flat, extra)
}

/// Up to this many (operations × order²), about the number of products, the
/// orders are inlined into one function (Kepler at order 19: 3,000).
const SINGLE_FUNCTION_TERMS: usize = 20_000;

/// The body of `taylor_jet_unrolled` for `order`: reads `t`, `y` (an array
/// of `n` states) and the constants `c0, c1, …` (`known[i]` is constant i's
/// value when it is a number) and writes state i's normalised coefficient k
/// to `out[i·(order+1) + k]` (an array). One function per order, not
/// inlined for large jets: rustc's time on one function of thousands of
/// live values grows much faster than linearly (the outer solar system at
/// three orders took over five minutes as one function, 1.5 minutes split,
/// for 12 % more run time).
pub fn unrolled_jet(tape: &Tape, n: usize, order: usize, known: &[Option<f64>]) -> TokenStream {
    let folding = fold_linear(tape, &known_constants(tape, known));
    let mut rows = vec![None; tape.ops.len()];
    let mut row_count = 0;
    for (v, role) in folding.roles.iter().enumerate() {
        if *role != Role::Folded {
            rows[v] = Some(row_count);
            row_count += 1;
        }
    }
    let l = Layout {
        order,
        states: n,
        rows,
        row_count,
    };
    let len = Literal::usize_unsuffixed(l.len());
    let weights = Weights::collect(&folding, tape.constants.len());
    // Small jets become one function, whose coefficient array the compiler
    // keeps in registers; large ones stay one function per order.
    let terms = row_count * order * order;
    let inline = if terms <= SINGLE_FUNCTION_TERMS {
        quote!(#[inline(always)])
    } else {
        quote!(#[inline(never)])
    };
    let constants: Vec<_> = (0..tape.constants.len())
        .map(|i| format_ident!("c{}", i))
        .collect();
    let weight_values = weights.values();
    let nc = Literal::usize_unsuffixed(constants.len() + weight_values.len());
    let mut code = TokenStream::new();
    code.extend(quote! {
        let c: [f64; #nc] = [#(#constants,)* #(#weight_values),*];
        let mut r = [0.0f64; #len];
    });
    for i in 0..n {
        let (slot, i) = (l.slot(i, 0), Literal::usize_unsuffixed(i));
        code.extend(quote!(#slot = y[#i];));
    }
    for k in 0..order {
        let mut step = TokenStream::new();
        for &(v, rec) in &tape.recurrences {
            match &folding.roles[v] {
                Role::Row => step.extend(recurrence_at(&l, v, rec, k)),
                Role::SumRow(terms) => {
                    let (name, value) =
                        (l.slot(l.var_row(v), k), folded_sum(&l, &weights, terms, k));
                    step.extend(quote!(#name = #value;));
                }
                Role::Folded => {}
            }
        }
        // x^[k+1] = f^[k] / (k + 1).
        let scale = float(1.0 / (k + 1) as f64);
        for (i, terms) in folding.outputs.iter().enumerate() {
            let slot = l.slot(i, k + 1);
            let single = match terms.as_slice() {
                [LinearTerm {
                    weight,
                    base: Base::Operand(o),
                }] if weight.is_literal() && weight.literal == 1.0 => Some(*o),
                _ => None,
            };
            let value = match single {
                Some(o) => l.coefficient(o, k),
                None => Some(folded_sum(&l, &weights, terms, k)),
            };
            let value = match value {
                Some(f) if k == 0 => f,
                Some(f) => quote!((#f) * #scale),
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
