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
//! interpreter's to rounding. Rows that repeat one computation on other
//! operands are written side by side as lane pairs (`vector_rows`) in
//! small jets, and computed by one loop per lane group (`groups`)
//! in large ones; the compiler vectorises both. Products of one sum that
//! share a factor are one convolution (`taylor::factoring`).

use crate::taylor::factoring::factor_shared_operands;
use crate::taylor::folding::{
    fold_linear, known_constants, Base, Folding, LinearTerm, Role, Weight,
};
use crate::taylor::groups::{group_rows, same_operand};
use crate::taylor::jet_layout::float;
use crate::taylor::jet_layout::JetLayout;
use crate::taylor::sharing::{share, Piece};
use crate::taylor::tape::{InverseFunction, Operand, Tape, TapeOp};
use crate::taylor::vector_rows::{pair_rows, schedule, shape, Node, VectorRows};
use proc_macro2::{Literal, TokenStream};
use quote::{format_ident, quote, ToTokens};
use std::collections::BTreeSet;

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

/// One term `weight·a·b` of a sum (a missing factor is a zero one), `b`
/// the factor known last, and when it can be added (see [`Layout::fresh`]).
type Triple = (f64, Option<TokenStream>, Option<TokenStream>, u8);

/// `Σ weight·a·b` over the non-zero terms, or `0.0`.
fn sum(terms: Vec<Triple>) -> TokenStream {
    sum_with(terms, Vec::new(), None)
}

/// `scale · Σ weight·a·b` over the non-zero terms.
fn scaled_sum(terms: Vec<Triple>, scale: TokenStream) -> TokenStream {
    sum_with(terms, Vec::new(), Some(scale))
}

/// A term as a product of its factors (weight first), or a single value.
fn term(weight: f64, a: TokenStream, b: TokenStream) -> Term {
    let mut factors: Vec<TokenStream> =
        [a, b].into_iter().filter(|f| f.to_string() != "1.0").collect();
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

/// `Σ weight·a·b` over the non-zero terms plus the `extra` terms, times
/// `scale` if given, or `0.0`.
///
/// The terms that read only coefficients computed before order k − 1 form
/// a balanced tree, which the processor computes while the recent ones are
/// still being produced. The others come after it, one fused multiply-add
/// each, in the order their newest factor is known: a u-variable's
/// coefficient k − 1, a state's coefficient k (known when the order
/// starts), a u-variable's coefficient k (computed in this order), then
/// the `extra` ones. The chain from one order's coefficient to the next
/// order's is then one or two operations per recurrence instead of
/// log₂(k) + 1, which is what bounds small jets. A scale (the 1/x₀ of a
/// power, the 1/(k + 1) of an output) is distributed over the chain,
/// `(acc + a·b)·s = (a·s)·b + acc·s`, with `a·s` computed before `b` is
/// known, so that it adds no operation to the chain. With the lane pairs,
/// this took the order-16 jets from 621 to 462 cycles (Kepler) and from
/// 991 to 798 (Arenstorf) in llvm-mca's model of the benchmark's CPU
/// (Ice Lake server), and the solves 14–17 % faster.
///
/// The order of summation changes where the random walk of rounding errors
/// in long runs ends (Kepler e = 0.9 over ten orbits at tolerances 3e-14 to
/// 1e-15: anywhere from 1e-11 to 5e-10 from the exact solution with the
/// orders tried, before the state update carried its rounding errors), so
/// no test pins that floor.
fn sum_with(terms: Vec<Triple>, extra: Vec<Term>, scale: Option<TokenStream>) -> TokenStream {
    let mut fresh: Vec<(u8, Term)> = Vec::new();
    // The old terms by weight, in order of first appearance.
    let mut by_weight: Vec<(f64, Vec<(TokenStream, TokenStream)>)> = Vec::new();
    for (weight, a, b, rank) in terms {
        let (Some(a), Some(b)) = (a, b) else { continue };
        if weight == 0.0 {
            continue;
        }
        if rank == 0 {
            match by_weight.iter_mut().find(|(w, _)| *w == weight) {
                Some((_, class)) => class.push((a, b)),
                None => by_weight.push((weight, vec![(a, b)])),
            }
        } else {
            fresh.push((rank, term(weight, a, b)));
        }
    }
    // A weight shared by several old terms (the 2 of a square's cross
    // terms) multiplies their sum once instead of each term.
    let mut old: Vec<Term> = Vec::new();
    for (weight, class) in by_weight {
        if class.len() > 1 && weight.abs() != 1.0 {
            let inner = tree(class.into_iter().map(|(a, b)| term(1.0, a, b)).collect());
            old.push(Term::Product(float(weight), quote!((#inner))));
        } else {
            old.extend(class.into_iter().map(|(a, b)| term(weight, a, b)));
        }
    }
    fresh.sort_by_key(|(rank, _)| *rank);
    let mut fresh: Vec<Term> = fresh.into_iter().map(|(_, t)| t).collect();
    fresh.extend(extra);
    let mut acc = if old.is_empty() {
        None
    } else {
        let tree = tree(old);
        Some(match &scale {
            Some(s) => quote!((#tree) * #s),
            None => tree,
        })
    };
    for t in fresh {
        let t = match (&scale, t) {
            (None, t) => t,
            (Some(s), Term::Product(a, b)) => Term::Product(quote!((#a * #s)), b),
            (Some(s), Term::Single(v)) => Term::Product(v, s.clone()),
        };
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
    l: &JetLayout,
    x: Operand,
    y: Operand,
    k: usize,
    range: impl Iterator<Item = usize>,
    w: impl Fn(usize) -> f64,
) -> Vec<Triple> {
    range
        .map(|j| {
            let (fx, fy) = (l.fresh(x, j, k), l.fresh(y, k - j, k));
            let (a, b) = (l.coefficient(x, j), l.coefficient(y, k - j));
            // The weight multiplies the factor known first, before the
            // other is computed.
            let (a, b) = if fx > fy { (b, a) } else { (a, b) };
            (w(j), a, b, fx.max(fy))
        })
        .collect()
}

/// The terms of coefficient `k` of a base: the operand's coefficient, or
/// the Cauchy product (a square by its half-sum, each cross term twice).
fn base_terms(l: &JetLayout, base: Base, k: usize) -> Vec<Triple> {
    match base {
        Base::Operand(o) => vec![(1.0, l.coefficient(o, k), Some(quote!(1.0)), l.fresh(o, k, k))],
        Base::Square(a) => convolution(l, a, a, k, (0..=k).filter(|&j| j <= k - j), |j| {
            if j < k - j {
                2.0
            } else {
                1.0
            }
        }),
        Base::Product(a, b) => convolution(l, a, b, k, 0..=k, |_| 1.0),
        Base::Head(a, b) => convolution(l, a, b, k, 0..=0, |_| 1.0),
        Base::Tail(a, b) => convolution(l, a, b, k, 1..=k, |_| 1.0),
    }
}

/// `let` statements for coefficient `k` of u-variable `v` (and of `v + 1`
/// for the sin/cos and sinh/cosh pairs).
fn recurrence_at(l: &JetLayout, v: usize, r: TapeOp, k: usize) -> TokenStream {
    let c = |o: Operand, k: usize| l.coefficient(o, k);
    let name = l.slot(l.var_row(v), k);
    let kf = k as f64;
    if k == 0 {
        let zero = |o: Operand| c(o, 0).unwrap_or(quote!(0.0f64));
        let value = match r {
            // Linear recurrences are folded sums (`taylor::folding`), never
            // rows of their own.
            TapeOp::Add(..) | TapeOp::Scale(..) | TapeOp::Quotient(..) => {
                return TokenStream::new()
            }
            TapeOp::Mul(a, b) => {
                let (a, b) = (zero(a), zero(b));
                quote!(#a * #b)
            }
            TapeOp::Square(a) => {
                let a = zero(a);
                quote!(#a * #a)
            }
            TapeOp::Div(b_over, d) => {
                let (a, d) = (zero(b_over), zero(d));
                let inv = l.reciprocal(v);
                return quote!(#inv = 1.0 / #d; #name = #a * #inv;);
            }
            TapeOp::Pow(a, e) => {
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
            TapeOp::Exp(a) => {
                let a = zero(a);
                quote!(#a.exp())
            }
            TapeOp::Ln(a) => {
                let a = zero(a);
                let inv = l.reciprocal(v);
                return quote!(#inv = 1.0 / #a; #name = #a.ln(););
            }
            TapeOp::SinCos(a) | TapeOp::SinhCosh(a) => {
                let a = zero(a);
                let second = l.slot(l.var_row(v + 1), 0);
                return if let TapeOp::SinCos(_) = r {
                    quote!(let (sin, cos) = #a.sin_cos(); #name = sin; #second = cos;)
                } else {
                    quote!(#name = #a.sinh(); #second = #a.cosh();)
                };
            }
            TapeOp::Inverse(f, a, d) => {
                let (a, d) = (zero(a), zero(d));
                let inv = l.reciprocal(v);
                let value = match f {
                    InverseFunction::Asin => quote!(#a.asin()),
                    InverseFunction::Acos => quote!(#a.acos()),
                    InverseFunction::Atan => quote!(#a.atan()),
                };
                return quote!(#inv = 1.0 / #d; #name = #value;);
            }
            TapeOp::Atan2(y, x, d) => {
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
        TapeOp::Add(..) | TapeOp::Scale(..) | TapeOp::Quotient(..) => return TokenStream::new(),
        TapeOp::Mul(a, b) => sum(base_terms(l, Base::Product(a, b), k)),
        TapeOp::Square(a) => sum(base_terms(l, Base::Square(a), k)),
        TapeOp::Div(a, d) => {
            // u = a/d: u^[k] = (a^[k] − Σ_{j<k} u^[j] d^[k−j]) / d^[0].
            let a = c(a, k).unwrap_or(quote!(0.0f64));
            let s = sum(convolution(l, own, d, k, 0..k, |_| 1.0));
            let inv = l.reciprocal(v);
            quote!((#a - (#s)) * #inv)
        }
        TapeOp::Pow(a, e) => {
            // u^[k] = Σ_{j<k} (k·e − j·(e+1)) u^[j] a^[k−j] / (k a^[0]).
            let w = |j: usize| (kf * e - j as f64 * (e + 1.0)) / kf;
            scaled_sum(convolution(l, own, a, k, 0..k, w), l.reciprocal(v))
        }
        TapeOp::Exp(a) => sum(convolution(l, a, own, k, 1..=k, by_k)),
        TapeOp::Ln(a) => {
            let ak = c(a, k).unwrap_or(quote!(0.0f64));
            let s = sum(convolution(l, own, a, k, 1..k, by_k));
            let inv = l.reciprocal(v);
            quote!((#ak - (#s)) * #inv)
        }
        TapeOp::SinCos(a) | TapeOp::SinhCosh(a) => {
            let s = sum(convolution(l, a, Operand::Var(v + 1), k, 1..=k, by_k));
            let co = sum(convolution(l, a, own, k, 1..=k, by_k));
            let second = l.slot(l.var_row(v + 1), k);
            return if let TapeOp::SinCos(_) = r {
                quote!(#name = #s; #second = -(#co);)
            } else {
                quote!(#name = #s; #second = #co;)
            };
        }
        TapeOp::Inverse(f, a, d) => {
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
        TapeOp::Atan2(y, x, d) => {
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
                let mut factors: Vec<TokenStream> =
                    w.times.iter().map(|i| name(i).into_token_stream()).collect();
                if w.literal.abs() != 1.0 || factors.is_empty() {
                    factors.insert(0, float(w.literal.abs()));
                }
                let sign = (w.literal < 0.0).then(|| quote!(-));
                let product =
                    factors.into_iter().reduce(|a, b| quote!(#a * #b)).unwrap_or_default();
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

/// Where the lane pairs of the jet are copied for the vectoriser (see
/// [`unrolled_jet`]): the next free slot of `seeds`.
struct Seeds<'a> {
    vectors: &'a VectorRows,
    next: usize,
}

impl Seeds<'_> {
    /// `seeds[i] = a; seeds[i + 1] = b;` at the next two slots.
    fn store(&mut self, a: &TokenStream, b: &TokenStream) -> TokenStream {
        let (i, j) =
            (Literal::usize_unsuffixed(self.next), Literal::usize_unsuffixed(self.next + 1));
        self.next += 2;
        quote!(seeds[#i] = #a; seeds[#j] = #b;)
    }
}

/// `weight · value` as a term of a sum.
fn weighted(weights: &Weights, w: &LinearTerm, value: TokenStream) -> Term {
    match weights.token(&w.weight) {
        Some(c) => Term::Product(c, value),
        None if w.weight.literal == 1.0 => Term::Single(value),
        None => Term::Product(float(w.weight.literal), value),
    }
}

/// Coefficient `k` of a folded sum, with the statements to write before
/// it: terms with numeric weights (and the convolutions of folded squares
/// and products) flattened into one pairwise sum, the others multiplied by
/// their weight from `c`. Two convolutions of lane-paired operands (the
/// `x²` and `y²` of `x² + y²`) are summed apart, side by side, and copied to
/// `seeds`, so that they are vectorised as one.
fn folded_sum(
    l: &JetLayout,
    weights: &Weights,
    seeds: &mut Seeds,
    terms: &[LinearTerm],
    k: usize,
    pair_convolutions: bool,
    scale: Option<TokenStream>,
) -> (TokenStream, TokenStream) {
    // partner[i] = j: terms i and j are lanes 0 and 1 of one pair.
    let mut partner: Vec<Option<usize>> = vec![None; terms.len()];
    let mut second = vec![false; terms.len()];
    for i in (0..terms.len()).filter(|_| pair_convolutions) {
        for j in i + 1..terms.len() {
            if second[i] || partner[i].is_some() {
                break;
            }
            if second[j] || partner[j].is_some() {
                continue;
            }
            let (a, b) = (terms[i].base, terms[j].base);
            if seeds.vectors.match_bases(a, b) {
                (partner[i], second[j]) = (Some(j), true);
            } else if seeds.vectors.match_bases(b, a) {
                (partner[j], second[i]) = (Some(i), true);
            }
        }
    }
    let mut prelude = TokenStream::new();
    let mut flat = Vec::new();
    let mut extra = Vec::new();
    for (i, t) in terms.iter().enumerate() {
        if second[i] {
            continue;
        }
        if let Some(j) = partner[i] {
            let first = seeds.next;
            let (a, b) = (format_ident!("lane_{}", first), format_ident!("lane_{}", first + 1));
            let (sa, sb) = (sum(base_terms(l, t.base, k)), sum(base_terms(l, terms[j].base, k)));
            prelude.extend(quote!(let #a = #sa; let #b = #sb;));
            prelude.extend(seeds.store(&a.to_token_stream(), &b.to_token_stream()));
            extra.push(weighted(weights, t, a.to_token_stream()));
            extra.push(weighted(weights, &terms[j], b.to_token_stream()));
            continue;
        }
        let products = base_terms(l, t.base, k);
        match weights.token(&t.weight) {
            None => flat.extend(
                products.into_iter().map(|(w, a, b, fresh)| (w * t.weight.literal, a, b, fresh)),
            ),
            Some(weight) => {
                if products.iter().any(|(_, a, b, _)| a.is_some() && b.is_some()) {
                    let inner = sum(products);
                    extra.push(Term::Product(weight, quote!((#inner))));
                }
            }
        }
    }
    (prelude, sum_with(flat, extra, scale))
}

/// How a lane group is computed by a loop over its lanes.
struct Loop {
    /// The rows read at lane `lane` (lane 0 of the group itself and of
    /// each operand that is a group in the same lane order).
    looped: BTreeSet<usize>,
    /// The rows every lane reads at one place.
    shared: BTreeSet<usize>,
    /// The rows of all the group's lanes.
    written: BTreeSet<usize>,
}

/// The loop of a lane group, or None when its lanes cannot be one loop: an
/// operand read lane by lane from states, sums whose weights differ
/// between lanes, or a row read both at the lane and as the one operand of
/// every lane.
fn group_loop(
    l: &JetLayout,
    tape: &Tape,
    folding: &Folding,
    known: &[Option<f64>],
    vectors: &VectorRows,
    members: &[Node],
) -> Option<Loop> {
    let operands: Vec<Vec<Operand>> =
        members.iter().map(|&m| Some(shape(m, tape, folding)?.1)).collect::<Option<_>>()?;
    if let Node::Var(first) = members[0] {
        if let Role::SumRow(terms) = &folding.roles[first] {
            for m in &members[1..] {
                let Node::Var(v) = m else { return None };
                let Role::SumRow(other) = &folding.roles[*v] else {
                    return None;
                };
                if other.len() != terms.len()
                    || other.iter().zip(terms).any(|(a, b)| a.weight != b.weight)
                {
                    return None;
                }
            }
        }
    }
    let mut looped = BTreeSet::from([l.row(members[0])]);
    let mut shared = BTreeSet::new();
    for position in 0..operands[0].len() {
        let ops: Vec<Operand> = operands.iter().map(|o| o[position]).collect();
        if same_operand(&ops, known) {
            if let Some(n) = Node::of(ops[0]) {
                shared.insert(l.row(n));
            }
            continue;
        }
        let nodes: Vec<Node> = ops.iter().map(|&o| Node::of(o)).collect::<Option<_>>()?;
        if vectors.group(nodes[0]) != Some(nodes.as_slice()) {
            return None;
        }
        looped.insert(l.row(nodes[0]));
    }
    let written = members.iter().map(|&m| l.row(m)).collect();
    looped.is_disjoint(&shared).then_some(Loop { looped, shared, written })
}

/// Consecutive lane groups of one width written as one loop, so that the
/// operands they share (an N-body model's differences, read by the sum of
/// squares and by the products) are loaded once per lane.
struct FusedLoop {
    width: usize,
    written: BTreeSet<usize>,
    shared: BTreeSet<usize>,
    body: TokenStream,
}

impl FusedLoop {
    /// Whether `g` can join: same width, and no lane reads at one place a
    /// row that another statement of the loop writes lane by lane.
    fn admits(&self, width: usize, g: &Loop) -> bool {
        self.width == width
            && self.written.is_disjoint(&g.shared)
            && self.shared.is_disjoint(&g.written)
    }

    /// Adds a group's statement `body` to the open loop if it can join it;
    /// else opens a new loop with it and returns the one it closed.
    fn push(
        open: &mut Option<FusedLoop>,
        width: usize,
        g: &Loop,
        body: TokenStream,
    ) -> Option<TokenStream> {
        if let Some(f) = open.as_mut().filter(|f| f.admits(width, g)) {
            f.body.extend(body);
            f.written.extend(&g.written);
            f.shared.extend(&g.shared);
            return None;
        }
        let closed = open.take().map(FusedLoop::tokens);
        *open =
            Some(FusedLoop { width, written: g.written.clone(), shared: g.shared.clone(), body });
        closed
    }

    /// The loop's tokens.
    fn tokens(self) -> TokenStream {
        let (width, body) = (Literal::usize_unsuffixed(self.width), self.body);
        quote!(for lane in 0..#width { #body })
    }
}

/// Up to this many rows × order², the orders are inlined into one function
/// (Kepler's 2 rows at order 19: 722; Arenstorf's 7: 2,527), whose code
/// still fits the processor's instruction cache. Beyond, one function per
/// order with lane groups is faster: the outer solar system's 120 rows at
/// order 12 (17,280) take 2.5 µs per step so against 5.5 µs as one
/// function with lane pairs; Kepler and Arenstorf, split, 1.5× slower.
const SINGLE_FUNCTION_TERMS: usize = 5_000;

/// The body of `taylor_jet_unrolled` for `order`: reads `t`, `y` (an array
/// of `n` states) and the constants `c0, c1, …` (`known[i]` is constant i's
/// value when it is a number) and writes state i's normalised coefficient k
/// to `out[i·(order+1) + k]` (an array). One function per order, not
/// inlined, for large jets (see `SINGLE_FUNCTION_TERMS`): they run
/// faster so, and rustc's time on one function of thousands of live
/// values grows much faster than linearly (the outer solar system at three
/// orders took over five minutes as one function, 1.5 minutes split).
pub fn unrolled_jet(tape: &Tape, n: usize, order: usize, known: &[Option<f64>]) -> UnrolledJet {
    jet_in(tape, n, order, known, SINGLE_FUNCTION_TERMS)
}

/// The code of one unrolled order and the length of the buffer `out` it
/// writes: `n·(order + 1)`, or for a jet split per order all of its
/// coefficients, the states' first (see [`unrolled_jet`]).
pub struct UnrolledJet {
    /// Statements reading `t`, `y`, the constants and writing `out`.
    pub body: TokenStream,
    /// The length of `out`, an array.
    pub buffer: usize,
    /// Whether `out` holds the states' coefficients order by order (state
    /// i's coefficient k at `k·n + i`) rather than state by state.
    pub by_coefficient: bool,
}

/// [`unrolled_jet`], one function when rows × order² is at most
/// `single_function_terms`.
fn jet_in(
    tape: &Tape,
    n: usize,
    order: usize,
    known: &[Option<f64>],
    single_function_terms: usize,
) -> UnrolledJet {
    // The pass manager of an unrolled jet: each pass is a call below, in the order that fixes
    // the emitted code; the length is the order of the passes, written out.
    let known = known_constants(tape, known);
    let mut folding = fold_linear(tape, &known);
    factor_shared_operands(&mut folding, tape);
    let mut rows = vec![None; folding.roles.len()];
    let mut row_count = 0;
    for (v, role) in folding.roles.iter().enumerate() {
        if *role != Role::Folded {
            rows[v] = Some(row_count);
            row_count += 1;
        }
    }
    // Small jets become one function, whose coefficient array the compiler
    // keeps in registers, with lane pairs; large ones stay one function per
    // order, with lane groups, each computed by one loop.
    let single_function = row_count * order * order <= single_function_terms;
    let vectors = if single_function {
        pair_rows(tape, &folding, n)
    } else {
        group_rows(tape, &folding, &known)
    };
    let l = JetLayout::new(order, n, rows, &vectors, !single_function);
    let loops: Vec<Option<Loop>> = vectors
        .groups
        .iter()
        .map(|members| group_loop(&l, tape, &folding, &known, &vectors, members))
        .collect();
    let len = Literal::usize_unsuffixed(l.len());
    let weights = Weights::collect(&folding, tape.constants.len());
    let inline = if single_function { quote!(#[inline(always)]) } else { quote!(#[inline(never)]) };
    let constants: Vec<_> = (0..tape.constants.len()).map(|i| format_ident!("c{}", i)).collect();
    let weight_values = weights.values();
    let nc = Literal::usize_unsuffixed(constants.len() + weight_values.len());
    // The u-variables in the order they are written (lane pairs together).
    // (The rows `taylor::factoring` adds come after the tape's.)
    let written = schedule(tape, &folding, &vectors).unwrap_or_else(|| {
        let added = tape.ops.len()..folding.roles.len();
        tape.recurrences.iter().map(|(v, _)| *v).chain(added).collect()
    });
    let recurrence: std::collections::BTreeMap<usize, TapeOp> =
        tape.recurrences.iter().copied().collect();
    // The states in the order their next coefficients are written.
    let mut state_order = Vec::with_capacity(n);
    for i in 0..n {
        match vectors.of(Node::State(i)) {
            Some((_, 1)) => {}
            Some((Node::State(j), _)) => state_order.extend([i, j]),
            _ => state_order.push(i),
        }
    }
    // In one function the compiler keeps the coefficients in registers and
    // never stores them: a copy of each lane pair's two new coefficients to
    // neighbouring slots of `seeds` (kept by `black_box`) gives the SLP
    // vectoriser the adjacent stores it starts from. Split into functions,
    // the coefficients are stored in `r`, where lanes are neighbours.
    let seed_rows = single_function;
    let mut seeds = Seeds { vectors: &vectors, next: 0 };
    let row_slot = |node: Node, k: usize| match node {
        Node::State(i) => l.slot(i, k),
        Node::Var(v) => l.slot(l.var_row(v), k),
    };
    // Split per order, the jet works in `out` itself, where the states'
    // rows come first as the caller reads them: no array to clear and no
    // copy at the end (stale values are never read: every slot is written
    // before it is read).
    let by_coefficient = !single_function && l.states_by_coefficient();
    let in_out = !single_function && (by_coefficient || l.states_first(order));
    let mut code = TokenStream::new();
    code.extend(quote!(let c: [f64; #nc] = [#(#constants,)* #(#weight_values),*];));
    if in_out {
        code.extend(quote!(let r = out;));
    } else {
        code.extend(quote!(let mut r = [0.0f64; #len];));
    }
    let r_arg = if in_out { quote!(&mut *r) } else { quote!(&mut r) };
    for i in 0..n {
        let (slot, i) = (l.slot(i, 0), Literal::usize_unsuffixed(i));
        code.extend(quote!(#slot = y[#i];));
    }
    for &slot in l.padding() {
        let slot = Literal::usize_unsuffixed(slot);
        code.extend(quote!(r[#slot] = 1.0;));
    }
    // Split per order, statements written alike at every order are shared
    // between the orders' functions (`taylor::sharing`).
    let split = !single_function;
    let mut orders: Vec<Vec<Piece>> = Vec::with_capacity(order);
    for k in 0..order {
        let mut pieces = Vec::new();
        let mut fused: Option<FusedLoop> = None;
        for &v in &written {
            // The rows `taylor::factoring` adds are read only by tails, which
            // read coefficients below k: the last order needs none of theirs.
            if v >= tape.ops.len() && k + 1 == order {
                continue;
            }
            let write = |seeds: &mut Seeds| match (&folding.roles[v], recurrence.get(&v)) {
                (Role::Row, Some(&rec)) => recurrence_at(&l, v, rec, k),
                (Role::SumRow(terms), _) => {
                    let name = l.slot(l.var_row(v), k);
                    let (prelude, value) = folded_sum(&l, &weights, seeds, terms, k, true, None);
                    quote!(#prelude #name = #value;)
                }
                _ => TokenStream::new(),
            };
            // A looped group's lane 0 writes its statement into the loop;
            // its other lanes are in it.
            let group = vectors.group_of.get(&Node::Var(v)).copied();
            match group.and_then(|(g, lane)| Some((loops[g].as_ref()?, lane, g))) {
                Some((_, lane, _)) if lane > 0 => {}
                Some((group_loop, _, g)) => {
                    let width = crate::taylor::jet_layout::padded(vectors.groups[g].len());
                    let body = l.looping(group_loop.looped.clone(), || write(&mut seeds));
                    pieces.extend(
                        FusedLoop::push(&mut fused, width, group_loop, body).map(Piece::Own),
                    );
                }
                None => {
                    pieces.extend(fused.take().map(|f| Piece::Own(f.tokens())));
                    let literal = write(&mut seeds);
                    if !literal.is_empty() {
                        let any_order =
                            (split && k > 0).then(|| l.any_order(k, || write(&mut seeds)));
                        pieces.push(Piece::Statement { literal, any_order });
                    }
                }
            }
            if let (true, Some((first, 1))) = (seed_rows, vectors.of(Node::Var(v))) {
                let (a, b) = (row_slot(first, k), row_slot(Node::Var(v), k));
                pieces.push(Piece::Own(seeds.store(&a, &b)));
            }
        }
        pieces.extend(fused.take().map(|f| Piece::Own(f.tokens())));
        // x^[k+1] = f^[k] / (k + 1).
        let scale = float(1.0 / (k + 1) as f64);
        for &i in &state_order {
            let terms = &folding.outputs[i];
            let single = match terms.as_slice() {
                [LinearTerm { weight, base: Base::Operand(o) }]
                    if weight.is_literal() && weight.literal == 1.0 =>
                {
                    Some(*o)
                }
                _ => None,
            };
            let state_row = |scale: &TokenStream, seeds: &mut Seeds| {
                let slot = l.slot(i, k + 1);
                let (prelude, value) = match (single, k) {
                    (Some(o), 0) => {
                        (TokenStream::new(), l.coefficient(o, k).unwrap_or(quote!(0.0f64)))
                    }
                    (Some(o), _) => (
                        TokenStream::new(),
                        match l.coefficient(o, k) {
                            Some(f) => quote!(#f * #scale),
                            None => quote!(0.0f64),
                        },
                    ),
                    // One function: the scale distributed over the sum's
                    // chain, off the path from one order to the next.
                    (None, _) if !split => {
                        let scale = (k > 0).then(|| scale.clone());
                        folded_sum(&l, &weights, seeds, terms, k, false, scale)
                    }
                    // Split, the jet is bound by its operations: the sum
                    // scaled once, a product per term fewer (the outer
                    // solar system's 18 velocity rows of five terms).
                    (None, 0) => folded_sum(&l, &weights, seeds, terms, k, false, None),
                    (None, _) => {
                        let (prelude, value) =
                            folded_sum(&l, &weights, seeds, terms, k, false, None);
                        (prelude, quote!((#value) * #scale))
                    }
                };
                quote!(#prelude #slot = #value;)
            };
            let literal = state_row(&scale, &mut seeds);
            let any_order =
                (split && k > 0).then(|| l.any_order(k, || state_row(&quote!(s), &mut seeds)));
            pieces.push(Piece::Statement { literal, any_order });
            if let (true, Some((first, 1))) = (seed_rows, vectors.of(Node::State(i))) {
                let (a, b) = (row_slot(first, k + 1), row_slot(Node::State(i), k + 1));
                pieces.push(Piece::Own(seeds.store(&a, &b)));
            }
        }
        orders.push(pieces);
    }
    let (shared, steps) = if split {
        share(orders, l.len(), constants.len() + weight_values.len())
    } else {
        let whole = |pieces: Vec<Piece>| -> TokenStream {
            pieces
                .into_iter()
                .map(|piece| match piece {
                    Piece::Own(tokens) | Piece::Statement { literal: tokens, .. } => tokens,
                })
                .collect()
        };
        (TokenStream::new(), orders.into_iter().map(whole).collect())
    };
    code.extend(shared);
    let seeded = seeds.next > 0;
    let seed_count = Literal::usize_unsuffixed(seeds.next);
    let (seeds_param, seeds_arg) = if seeded {
        code.extend(quote!(let mut seeds = [0.0f64; #seed_count];));
        (quote!(seeds: &mut [f64; #seed_count],), quote!(&mut seeds,))
    } else {
        (TokenStream::new(), TokenStream::new())
    };
    for (k, step) in steps.into_iter().enumerate() {
        let name = format_ident!("order_{}", k);
        code.extend(quote! {
            #inline
            fn #name(r: &mut [f64; #len], #seeds_param t: f64, c: &[f64; #nc]) {
                #step
            }
            #name(#r_arg, #seeds_arg t, &c);
        });
    }
    if !in_out {
        for i in 0..n {
            for k in 0..=order {
                let slot = l.slot(i, k);
                let at = Literal::usize_unsuffixed(i * (order + 1) + k);
                code.extend(quote!(out[#at] = #slot;));
            }
        }
    }
    if seeded {
        code.extend(quote!(::core::hint::black_box(&seeds);));
    }
    UnrolledJet {
        body: code,
        buffer: if in_out { l.len() } else { n * (order + 1) },
        by_coefficient,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::taylor::tape::n_body_tape;

    /// Three bodies in space at order 3, one function per order: the three
    /// interactions' rows are lane groups, interleaved in `r` three by
    /// three; the differences are written lane by lane (they read states),
    /// the sums of squares, the powers and the products each by one loop.
    /// Orders 1 and 2 call one function for their differences and one for
    /// their state rows (`taylor::sharing`); order 0, with its constants,
    /// writes its own.
    #[test]
    fn three_bodies_in_lane_groups_at_order_3() {
        let tape = n_body_tape(3);
        let known = vec![Some(1.0); tape.constants.len()];
        let jet = jet_in(&tape, 18, 3, &known, 0);
        let (body, buffer) = (jet.body, Literal::usize_unsuffixed(jet.buffer));
        let tokens = quote! {
            fn jet(t: f64, y: &[f64; 18], out: &mut [f64; #buffer], c0: f64, c1: f64, c2: f64, c3: f64, c4: f64, c5: f64, c6: f64) {
                #body
            }
        };
        let file: syn::File = syn::parse2(tokens).expect("the jet parses");
        // One snapshot per function of the jet, each short enough to read:
        // the functions it defines, then what is left of it.
        let syn::Item::Fn(mut jet) = file.items[0].clone() else { panic!("the jet is a function") };
        let mut pieces = Vec::new();
        jet.block.stmts.retain(|stmt| match stmt {
            syn::Stmt::Item(syn::Item::Fn(f)) => {
                pieces.push((f.sig.ident.to_string(), syn::Item::Fn(f.clone())));
                false
            }
            _ => true,
        });
        pieces.push(("driver".to_string(), syn::Item::Fn(jet)));
        for (name, item) in pieces {
            let text = prettyplease::unparse(&syn::File {
                shebang: None,
                attrs: Vec::new(),
                items: vec![item],
            });
            assert!(text.lines().count() <= 80, "{name}: {} lines", text.lines().count());
            insta::assert_snapshot!(
                format!("three_bodies_in_lane_groups_at_order_3__{name}"),
                text
            );
        }
    }
}
