//! Which u-variables of the Taylor tape the unrolled layout gives a row of
//! coefficients, and which it folds into the sums that use them.
//!
//! The tape keeps one u-variable per elementary operation, so an N-body
//! model spends most of its u-variables on negations, scalings by masses
//! and two-term additions (the outer solar system: 345 of 450). Their
//! recurrences are linear: coefficient k of `Σ wᵢ aᵢ` is `Σ wᵢ aᵢ^[k]`.
//! Folding them into their users removes their rows and their loads and
//! stores (the outer solar system at order 15: 450 u-variable rows to 120,
//! its coefficient array from 66 kB, more than L1, to 21 kB); a square or
//! product used by one sum only (the `dx² + dy² + dz²` of gravity) is folded too, its
//! convolution becoming terms of that sum (heyoka's `sum_sq`). A linear
//! u-variable keeps a row when a nonlinear recurrence reads it, or when it
//! has several users and a convolution or many terms would be recomputed.

use crate::taylor::tape::{Constant, Operand, Tape, TapeOp};

/// Sums longer than this keep a row instead of being copied into users.
const MAX_FOLDED_TERMS: usize = 64;

/// A constant factor of a folded term: `literal · Π c[times] / Π c[over]`.
#[derive(Clone, Debug, PartialEq)]
pub struct Weight {
    /// The numeric part (integers and known constants multiplied out).
    pub literal: f64,
    /// Constants the term is multiplied by, sorted.
    pub times: Vec<usize>,
    /// Constants the term is divided by, sorted.
    pub over: Vec<usize>,
}

impl Weight {
    pub(super) fn one() -> Weight {
        Weight { literal: 1.0, times: Vec::new(), over: Vec::new() }
    }

    /// True when the weight is a number known at expansion time.
    pub fn is_literal(&self) -> bool {
        self.times.is_empty() && self.over.is_empty()
    }

    fn scaled(&self, c: usize, known: Option<f64>, divide: bool) -> Weight {
        let mut w = self.clone();
        match (known, divide) {
            (Some(x), false) => w.literal *= x,
            (Some(x), true) => w.literal /= x,
            (None, false) => {
                w.times.push(c);
                w.times.sort_unstable();
            }
            (None, true) => {
                w.over.push(c);
                w.over.sort_unstable();
            }
        }
        w
    }
}

/// What a folded term multiplies: an operand's coefficients, or a
/// convolution computed in place.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Base {
    /// The coefficients of an operand (a state, the time, a constant or a
    /// u-variable with a row).
    Operand(Operand),
    /// The coefficients of `a·a`.
    Square(Operand),
    /// The coefficients of `a·b`.
    Product(Operand, Operand),
    /// The first term of `a·b`'s convolution, `a^[0]·b^[k]` (see
    /// `taylor::factoring`).
    Head(Operand, Operand),
    /// The rest of `a·b`'s convolution, `Σ_{j=1..k} a^[j]·b^[k−j]`.
    Tail(Operand, Operand),
}

impl Base {
    fn is_convolution(&self) -> bool {
        matches!(self, Base::Square(_) | Base::Product(..) | Base::Tail(..))
    }

    /// 0 for an operand, 1 for a square, 2 for a product, 3 for a head and
    /// 4 for a tail.
    pub fn kind(&self) -> u8 {
        match self {
            Base::Operand(_) => 0,
            Base::Square(_) => 1,
            Base::Product(..) => 2,
            Base::Head(..) => 3,
            Base::Tail(..) => 4,
        }
    }
}

/// One term `weight · base` of a folded sum.
#[derive(Clone, Debug, PartialEq)]
pub struct LinearTerm {
    /// The constant factor.
    pub weight: Weight,
    /// What it multiplies.
    pub base: Base,
}

/// What the unrolled layout does with one u-variable.
#[derive(Clone, Debug, PartialEq)]
pub enum Role {
    /// Its own recurrence (or the second of a sin/cos pair) in a row.
    Row,
    /// A folded sum that keeps a row: computed once per order from its terms.
    SumRow(Vec<LinearTerm>),
    /// Folded into its users: no row, no code of its own.
    Folded,
}

/// The roles of all u-variables and the sum each output is computed from.
#[derive(Debug)]
pub struct Folding {
    /// One role per u-variable.
    pub roles: Vec<Role>,
    /// The terms of each output (one term of weight 1 when the output is a
    /// state or a u-variable with a row).
    pub outputs: Vec<Vec<LinearTerm>>,
}

fn is_linear(r: &TapeOp) -> bool {
    matches!(r, TapeOp::Add(..) | TapeOp::Scale(..) | TapeOp::Quotient(..))
}

/// The operands a recurrence reads, in order.
pub fn operands(r: &TapeOp) -> Vec<Operand> {
    match *r {
        TapeOp::Scale(a, _)
        | TapeOp::Quotient(a, _)
        | TapeOp::Square(a)
        | TapeOp::Pow(a, _)
        | TapeOp::Exp(a)
        | TapeOp::Ln(a)
        | TapeOp::SinCos(a)
        | TapeOp::SinhCosh(a) => vec![a],
        TapeOp::Add(a, b) | TapeOp::Mul(a, b) | TapeOp::Div(a, b) | TapeOp::Inverse(_, a, b) => {
            vec![a, b]
        }
        TapeOp::Atan2(y, x, d) => vec![y, x, d],
    }
}

/// The value of constant `i` when it is a number known at expansion time.
pub fn known_constants(tape: &Tape, numbers: &[Option<f64>]) -> Vec<Option<f64>> {
    tape.constants
        .iter()
        .zip(numbers)
        .map(|(c, &n)| match c {
            Constant::Integer(i) => Some(*i as f64),
            Constant::Value(v) => Some(*v),
            _ => n,
        })
        .collect()
}

/// Decides the role of every u-variable of `tape`; `known[i]` is constant
/// i's value when it is a number.
pub fn fold_linear(tape: &Tape, known: &[Option<f64>]) -> Folding {
    let vars = tape.ops.len();
    // Uses of each u-variable: by linear recurrences, by the others, by outputs.
    let (mut linear_uses, mut other_uses, mut output_uses) =
        (vec![0usize; vars], vec![0usize; vars], vec![0usize; vars]);
    for (_, r) in &tape.recurrences {
        for o in operands(r) {
            if let Operand::Var(u) = o {
                if is_linear(r) {
                    linear_uses[u] += 1;
                } else {
                    other_uses[u] += 1;
                }
            }
        }
    }
    for o in &tape.output_operands {
        if let Operand::Var(u) = o {
            output_uses[*u] += 1;
        }
    }
    let mut roles = vec![Role::Row; vars];
    // The terms of each folded u-variable (a folded sum, square or product).
    let mut folded: Vec<Option<Vec<LinearTerm>>> = vec![None; vars];
    let terms_of = |o: Operand, folded: &[Option<Vec<LinearTerm>>]| -> Vec<LinearTerm> {
        match o {
            Operand::Var(u) => folded[u].clone().unwrap_or_else(|| {
                vec![LinearTerm { weight: Weight::one(), base: Base::Operand(o) }]
            }),
            _ => vec![LinearTerm { weight: Weight::one(), base: Base::Operand(o) }],
        }
    };
    for &(v, r) in &tape.recurrences {
        let uses = linear_uses[v] + other_uses[v] + output_uses[v];
        let terms = match r {
            TapeOp::Add(a, b) => {
                let mut t = terms_of(a, &folded);
                t.extend(terms_of(b, &folded));
                t
            }
            TapeOp::Scale(a, c) | TapeOp::Quotient(a, c) => {
                let divide = matches!(r, TapeOp::Quotient(..));
                terms_of(a, &folded)
                    .into_iter()
                    .map(|t| LinearTerm {
                        weight: t.weight.scaled(c, known[c], divide),
                        base: t.base,
                    })
                    .collect()
            }
            // A square or product read by one sum only becomes terms of it.
            TapeOp::Square(a) | TapeOp::Mul(a, _) if linear_uses[v] == 1 && uses == 1 => {
                let base = match r {
                    TapeOp::Mul(a, b) => Base::Product(a, b),
                    _ => Base::Square(a),
                };
                folded[v] = Some(vec![LinearTerm { weight: Weight::one(), base }]);
                roles[v] = Role::Folded;
                continue;
            }
            _ => continue,
        };
        // One order for the terms of every sum (operands, squares,
        // products), so that sums built alike from different operands are
        // written alike (`vector_rows` pairs them).
        let mut terms = terms;
        terms.sort_by_key(|t| t.base.kind());
        let convolutions = terms.iter().any(|t| t.base.is_convolution());
        let keeps_row = other_uses[v] > 0
            || terms.len() > MAX_FOLDED_TERMS
            || (uses > 1 && (convolutions || terms.len() > 4));
        if keeps_row {
            roles[v] = Role::SumRow(terms);
        } else {
            folded[v] = Some(terms);
            roles[v] = Role::Folded;
        }
    }
    let outputs = tape.output_operands.iter().map(|&o| terms_of(o, &folded)).collect();
    Folding { roles, outputs }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::taylor::tape::test_tape;

    fn term(literal: f64, times: &[usize], over: &[usize], base: Base) -> LinearTerm {
        LinearTerm { weight: Weight { literal, times: times.to_vec(), over: over.to_vec() }, base }
    }

    /// One gravitating pair in the plane, as the tape writes it: the
    /// differences, the sum of squares and the power keep rows, the
    /// negations and squares fold, the force term read by both bodies keeps
    /// its row, and the masses become weights of the outputs.
    #[test]
    fn a_gravitating_pair_folds_to_its_convolutions() {
        use Operand::{State, Var};
        // c0 = −1 (known), c1 = a mass (a parameter).
        let t = test_tape(
            vec![
                TapeOp::Scale(State(0), 0),
                TapeOp::Add(State(1), Var(0)),
                TapeOp::Scale(State(2), 0),
                TapeOp::Add(State(3), Var(2)),
                TapeOp::Square(Var(1)),
                TapeOp::Square(Var(3)),
                TapeOp::Add(Var(4), Var(5)),
                TapeOp::Pow(Var(6), -1.5),
                TapeOp::Mul(Var(1), Var(7)),
                TapeOp::Scale(Var(8), 1),
                TapeOp::Scale(Var(8), 0),
            ],
            vec![Var(9), Var(10)],
            2,
        );
        let f = fold_linear(&t, &[Some(-1.0), None]);
        let row = |terms| Role::SumRow(terms);
        assert_eq!(
            f.roles,
            vec![
                Role::Folded,
                row(vec![
                    term(1.0, &[], &[], Base::Operand(State(1))),
                    term(-1.0, &[], &[], Base::Operand(State(0))),
                ]),
                Role::Folded,
                row(vec![
                    term(1.0, &[], &[], Base::Operand(State(3))),
                    term(-1.0, &[], &[], Base::Operand(State(2))),
                ]),
                Role::Folded,
                Role::Folded,
                row(vec![
                    term(1.0, &[], &[], Base::Square(Var(1))),
                    term(1.0, &[], &[], Base::Square(Var(3))),
                ]),
                Role::Row,
                Role::Row,
                Role::Folded,
                Role::Folded,
            ]
        );
        assert_eq!(
            f.outputs,
            vec![
                vec![term(1.0, &[1], &[], Base::Operand(Var(8)))],
                vec![term(-1.0, &[], &[], Base::Operand(Var(8)))],
            ]
        );
    }

    /// A product read by one sum is folded into it; a sum read twice that
    /// holds a convolution keeps a row, so the convolution runs once; a
    /// quotient by a parameter divides the weight; operands come before
    /// convolutions in every sum.
    #[test]
    fn convolutions_are_never_computed_twice() {
        use Operand::{State, Var};
        let t = test_tape(
            vec![
                TapeOp::Mul(State(0), State(1)),
                TapeOp::Quotient(Var(0), 0),
                TapeOp::Add(Var(1), State(0)),
            ],
            vec![Var(2), Var(2)],
            1,
        );
        let f = fold_linear(&t, &[None]);
        assert_eq!(f.roles[0], Role::Folded);
        assert_eq!(f.roles[1], Role::Folded);
        assert_eq!(
            f.roles[2],
            Role::SumRow(vec![
                term(1.0, &[], &[], Base::Operand(State(0))),
                term(1.0, &[], &[0], Base::Product(State(0), State(1))),
            ])
        );
        assert_eq!(f.outputs[0], vec![term(1.0, &[], &[], Base::Operand(Var(2)))]);
    }
}
