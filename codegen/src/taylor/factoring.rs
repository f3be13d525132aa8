//! Products in one folded sum that share a factor, computed as one
//! convolution: `Σᵢ wᵢ·(aᵢ·bᵢ) = s·(Σᵢ wᵢ·bᵢ)` when every `aᵢ` is `s` or
//! `s` plus a constant.
//!
//! A product of two series costs k + 1 multiply-adds at order k and a
//! weighted sum one per term, so n products sharing a factor cost n(k + 1)
//! and their factored form k + 2n. The restricted three-body problem's
//! accelerations are the case in point: `−μ′(x + μ)/d₁³ − μ(x − μ′)/d₂³`
//! and `−μ′y/d₁³ − μy/d₂³` are four convolutions, factored two, on one new
//! row `E = −μ′/d₁³ − μ/d₂³` shared by both.
//!
//! The shared factor may be shifted by a constant: coefficient j ≥ 1 of
//! `s + c` is `s`'s own, so only the terms j = 0 of the products differ,
//!
//! ```text
//! Σᵢ wᵢ (aᵢ·bᵢ)^[k] = Σᵢ wᵢ aᵢ^[0] bᵢ^[k]  +  Σ_{j=1..k} s^[j] E^[k−j],   E = Σᵢ wᵢ bᵢ,
//! ```
//!
//! a head per product ([`Base::Head`]) and one tail ([`Base::Tail`]). The
//! heads keep `aᵢ^[0]` itself: writing `(s + c)·b` as `s·b + c·b` would
//! cancel where `s^[0] ≈ −c` (near a primary of the three-body problem,
//! where `b = 1/d³` is large). The tail only regroups the same products,
//! `Σᵢ wᵢ·s^[j]·bᵢ^[k−j] = s^[j]·Σᵢ wᵢ bᵢ^[k−j]`, with the same rounding
//! bound relative to `Σᵢ |wᵢ s^[j] bᵢ^[k−j]|`.

use crate::taylor::folding::{Base, Folding, LinearTerm, Role, Weight};
use crate::taylor::tape::{Constant, Operand, Tape};

/// Rewrites every sum of `folding` (rows and outputs) whose products share
/// a factor, adding one row per distinct `E` after the tape's u-variables.
pub fn factor_shared_operands(folding: &mut Folding, tape: &Tape) {
    let canonical = canonical_constants(&tape.constants);
    let vars = folding.roles.len();
    for v in 0..vars {
        if let Role::SumRow(terms) = &folding.roles[v] {
            let terms = terms.clone();
            if let Some(factored) = factor_sum(folding, &canonical, &terms) {
                folding.roles[v] = Role::SumRow(factored);
            }
        }
    }
    for i in 0..folding.outputs.len() {
        let terms = folding.outputs[i].clone();
        if let Some(factored) = factor_sum(folding, &canonical, &terms) {
            folding.outputs[i] = factored;
        }
    }
}

/// For each constant, the first constant equal to it: the tape writes the
/// −μ′ of two products as two constants, and their `E` rows should be one.
fn canonical_constants(constants: &[Constant]) -> Vec<usize> {
    (0..constants.len())
        .map(|i| (0..i).find(|&j| same_constant(&constants[j], &constants[i])).unwrap_or(i))
        .collect()
}

fn same_constant(a: &Constant, b: &Constant) -> bool {
    match (a, b) {
        (Constant::Expr(x), Constant::Expr(y)) => x == y,
        (Constant::Integer(x), Constant::Integer(y)) => x == y,
        (Constant::Value(x), Constant::Value(y)) => x.to_bits() == y.to_bits(),
        (Constant::Product(x), Constant::Product(y)) | (Constant::Sum(x), Constant::Sum(y)) => {
            x == y
        }
        _ => false,
    }
}

/// `w` with its constants replaced by their canonical ones.
fn canonical_weight(w: &Weight, canonical: &[usize]) -> Weight {
    let map = |list: &[usize]| {
        let mut mapped: Vec<usize> = list.iter().map(|&c| canonical[c]).collect();
        mapped.sort_unstable();
        mapped
    };
    Weight { literal: w.literal, times: map(&w.times), over: map(&w.over) }
}

/// The series `o` is a constant shift of, or `o` itself: u-variables whose
/// row is `s + c₁ + c₂ + …`, `s` a state or a u-variable.
fn root(folding: &Folding, o: Operand) -> Option<Operand> {
    let is_series = |o: Operand| matches!(o, Operand::State(_) | Operand::Var(_));
    if !is_series(o) {
        return None;
    }
    let Operand::Var(u) = o else { return Some(o) };
    let Role::SumRow(terms) = &folding.roles[u] else {
        return Some(o);
    };
    let mut series = terms.iter().filter(|t| !matches!(t.base, Base::Operand(Operand::Const(_))));
    match (series.next(), series.next()) {
        (Some(t), None) if t.weight.is_literal() && t.weight.literal == 1.0 => match t.base {
            Base::Operand(s) if is_series(s) => Some(s),
            _ => Some(o),
        },
        _ => Some(o),
    }
}

/// A product of a sum with the shared series as a factor: the term's
/// index, that factor (the series or a shift of it) and the other factor.
type Member = (usize, Operand, Operand);

/// `terms` with each group of two or more products sharing a (shifted)
/// factor replaced by its heads and tail, or None when there is none.
fn factor_sum(
    folding: &mut Folding,
    canonical: &[usize],
    terms: &[LinearTerm],
) -> Option<Vec<LinearTerm>> {
    let mut terms = terms.to_vec();
    let mut changed = false;
    loop {
        // Per shared series, the products that have it as a (shifted) factor.
        let mut groups: Vec<(Operand, Vec<Member>)> = Vec::new();
        for (i, t) in terms.iter().enumerate() {
            let Base::Product(p, q) = t.base else {
                continue;
            };
            for (a, b) in [(p, q), (q, p)] {
                let Some(s) = root(folding, a) else { continue };
                let index = groups.iter().position(|(r, _)| *r == s).unwrap_or_else(|| {
                    groups.push((s, Vec::new()));
                    groups.len() - 1
                });
                let group = &mut groups[index].1;
                if group.last().map(|(j, ..)| *j) != Some(i) {
                    group.push((i, a, b));
                }
            }
        }
        // The largest group first; among equals, the first found.
        let mut best: Option<&(Operand, Vec<Member>)> = None;
        for g in &groups {
            if g.1.len() >= 2 && best.is_none_or(|b| g.1.len() > b.1.len()) {
                best = Some(g);
            }
        }
        let Some((s, members)) = best.cloned() else {
            break;
        };
        let e_terms: Vec<LinearTerm> = members
            .iter()
            .map(|&(i, _, b)| LinearTerm {
                weight: canonical_weight(&terms[i].weight, canonical),
                base: Base::Operand(b),
            })
            .collect();
        let e = shared_row(folding, e_terms);
        let mut next: Vec<LinearTerm> = Vec::with_capacity(terms.len() + 1);
        for (i, t) in terms.iter().enumerate() {
            match members.iter().find(|(j, ..)| *j == i) {
                Some(&(_, a, b)) => {
                    next.push(LinearTerm { weight: t.weight.clone(), base: Base::Head(a, b) })
                }
                None => next.push(t.clone()),
            }
        }
        next.push(LinearTerm { weight: Weight::one(), base: Base::Tail(s, Operand::Var(e)) });
        terms = next;
        changed = true;
    }
    terms.sort_by_key(|t| t.base.kind());
    changed.then_some(terms)
}

/// The u-variable whose row is the sum `terms`: an earlier one with the
/// same terms, or a new one after all others.
fn shared_row(folding: &mut Folding, terms: Vec<LinearTerm>) -> usize {
    let existing = folding.roles.iter().position(|r| matches!(r, Role::SumRow(t) if *t == terms));
    existing.unwrap_or_else(|| {
        folding.roles.push(Role::SumRow(terms));
        folding.roles.len() - 1
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::taylor::folding::fold_linear;
    use crate::taylor::tape::{test_tape, TapeOp};

    fn term(times: &[usize], base: Base) -> LinearTerm {
        LinearTerm {
            weight: Weight { literal: 1.0, times: times.to_vec(), over: Vec::new() },
            base,
        }
    }

    /// The restricted three-body problem's accelerations as the tape
    /// writes them: `c₂(x + c₀)·d₁ + c₃(x + c₁)·d₂` and `c₄ y·d₁ + c₅ y·d₂`
    /// with c₄ = c₂ and c₅ = c₃ (equal constants the tape keeps apart).
    /// Both become heads and one tail on the same new row c₂d₁ + c₃d₂.
    #[test]
    fn products_sharing_a_shifted_factor_share_one_row() {
        use Operand::{Const, State, Var};
        let mut tape = test_tape(
            vec![
                TapeOp::Add(State(0), Const(0)),
                TapeOp::Add(State(0), Const(1)),
                TapeOp::Pow(State(1), -1.5),
                TapeOp::Pow(State(2), -1.5),
                TapeOp::Mul(Var(0), Var(2)),
                TapeOp::Scale(Var(4), 2),
                TapeOp::Mul(Var(1), Var(3)),
                TapeOp::Scale(Var(6), 3),
                TapeOp::Add(Var(5), Var(7)),
                TapeOp::Mul(Var(2), State(1)),
                TapeOp::Scale(Var(9), 4),
                TapeOp::Mul(Var(3), State(1)),
                TapeOp::Scale(Var(11), 5),
                TapeOp::Add(Var(10), Var(12)),
            ],
            vec![Var(8), Var(13)],
            6,
        );
        tape.constants = [1, 2, 3, 4, 3, 4].map(Constant::Integer).into();
        let mut folding = fold_linear(&tape, &[None; 6]);
        factor_shared_operands(&mut folding, &tape);
        assert_eq!(folding.roles.len(), 15);
        assert_eq!(
            folding.roles[14],
            Role::SumRow(vec![
                term(&[2], Base::Operand(Var(2))),
                term(&[3], Base::Operand(Var(3))),
            ])
        );
        assert_eq!(
            folding.outputs,
            vec![
                vec![
                    term(&[2], Base::Head(Var(0), Var(2))),
                    term(&[3], Base::Head(Var(1), Var(3))),
                    term(&[], Base::Tail(State(0), Var(14))),
                ],
                vec![
                    term(&[4], Base::Head(State(1), Var(2))),
                    term(&[5], Base::Head(State(1), Var(3))),
                    term(&[], Base::Tail(State(1), Var(14))),
                ],
            ]
        );
    }

    /// A single product, and products whose shared operand is a constant
    /// or the time, stay as they are.
    #[test]
    fn products_without_a_shared_series_are_left_alone() {
        use Operand::{Const, State, Time, Var};
        let tape = test_tape(
            vec![
                TapeOp::Mul(State(0), State(1)),
                TapeOp::Mul(Time, State(0)),
                TapeOp::Mul(Time, State(1)),
                TapeOp::Add(Var(1), Var(2)),
                TapeOp::Add(Var(0), Const(0)),
            ],
            vec![Var(3), Var(4)],
            1,
        );
        let mut folding = fold_linear(&tape, &[None]);
        factor_shared_operands(&mut folding, &tape);
        assert_eq!(folding.roles.len(), 5);
        assert!(folding.outputs.iter().flatten().all(|t| t.base.kind() <= 2));
    }
}
