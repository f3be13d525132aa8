//! Which rows of the unrolled Taylor recurrences are computed side by side
//! as the two lanes of a vector.
//!
//! Gravity models repeat one computation per body or per attracting centre:
//! Arenstorf's two distances `((x + μ)² + y²)^(−3/2)` and
//! `((x − μ')² + y²)^(−3/2)`, Kepler's two components `−x·r⁻³` and
//! `−y·r⁻³`. Two rows whose recurrences have the same shape and whose
//! operands are themselves such pairs (or one operand read by both) make a
//! lane pair: the emission writes them one after the other with identical
//! sums, so that LLVM's SLP vectoriser turns the two scalar sums into one
//! on two lanes (about half the multiply-adds and half the loads). Pairs
//! are found as the vectoriser does (Rosen, Nuzman & Zaks 2007, "Loop-aware
//! SLP in GCC"): from a seed pair, unify the operands position by position,
//! and give the seed up if any position conflicts. Values are never
//! affected: a pairing only changes where coefficients are stored and the
//! order in which independent statements are written.
//!
//! Pairs whose operands pair all the way down cover an N-body model only in
//! part: pairing bodies 1 and 2 pairs the interactions (1, 3) and (2, 3),
//! which then cannot also pair with (1, 4) and (2, 4) for bodies 3 and 4
//! (the outer solar system: 64 of its 120 rows). A second pass therefore
//! lets the two lanes read states that are not a pair, which the
//! vectoriser loads as one vector from two places; every interaction can
//! then pair with any other (116 of the 120 rows; as one function its
//! order-12 coefficients took 588 instead of 808 cycles of llvm-mca's
//! throughput, the solve 15 % faster). Jets that large are now split per
//! order with lane groups instead (`groups`): pairs serve the small
//! ones. Kepler pairs its components (x with y, vx with vy), both lanes
//! reading its one power; Arenstorf pairs its two centres' rows, all but
//! y².

use crate::taylor::folding::{operands, Base, Folding, LinearTerm, Role};
use crate::taylor::tape::{Operand, Tape, TapeOp};
use std::cmp::Reverse;
use std::collections::{BTreeMap, BinaryHeap};

/// A row of coefficients: a state's or a u-variable's.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Node {
    /// State `i` (its coefficients follow from output `i`'s sum).
    State(usize),
    /// u-variable `v` with a row.
    Var(usize),
}

impl Node {
    /// The row an operand reads, if it has one.
    pub(super) fn of(o: Operand) -> Option<Node> {
        match o {
            Operand::State(i) => Some(Node::State(i)),
            Operand::Var(v) => Some(Node::Var(v)),
            Operand::Time | Operand::Const(_) => None,
        }
    }
}

/// The lane pairs of a model: each node with a partner, and its lane (0 or
/// 1); or, for jets computed in memory, its lane groups (`groups`):
/// rows of one shape, any number of them, computed by one loop over lanes.
#[derive(Debug, Default, PartialEq)]
pub struct VectorRows {
    pub(super) partner: BTreeMap<Node, (Node, u8)>,
    /// The groups, each its nodes in lane order.
    pub(super) groups: Vec<Vec<Node>>,
    /// Per node in a group: the group and the node's lane.
    pub(super) group_of: BTreeMap<Node, (usize, usize)>,
}

impl VectorRows {
    /// The partner of `n` and `n`'s lane, when it has one.
    pub fn of(&self, n: Node) -> Option<(Node, u8)> {
        self.partner.get(&n).copied()
    }

    /// The vector `n` is a lane of: its lane-0 node, `n`'s lane and the
    /// number of lanes (a pair's or a group's).
    pub fn vector_of(&self, n: Node) -> Option<(Node, usize, usize)> {
        if let Some(&(g, lane)) = self.group_of.get(&n) {
            let members = &self.groups[g];
            return Some((members[0], lane, members.len()));
        }
        let (partner, lane) = self.of(n)?;
        Some(if lane == 0 { (n, 0, 2) } else { (partner, 1, 2) })
    }

    /// The members of the group `n` is in, in lane order.
    pub fn group(&self, n: Node) -> Option<&[Node]> {
        let &(g, _) = self.group_of.get(&n)?;
        Some(&self.groups[g])
    }

    /// The pairs, lane 0 first, in the order of their lane-0 node.
    pub fn pairs(&self) -> impl Iterator<Item = (Node, Node)> + '_ {
        self.partner.iter().filter(|(_, (_, lane))| *lane == 0).map(|(a, (b, _))| (*a, *b))
    }

    /// True when `a` and `b` are lane 0 and lane 1 of one pair, or the
    /// same operand (read by both lanes).
    pub fn match_operands(&self, a: Operand, b: Operand) -> bool {
        a == b
            || match (Node::of(a), Node::of(b)) {
                (Some(x), Some(y)) => self.of(x) == Some((y, 0)),
                _ => matches!((a, b), (Operand::Const(_), Operand::Const(_))),
            }
    }

    /// True when the bases of two folded terms read lane-paired operands
    /// position by position and at least one pair of them (a shared
    /// operand alone gives nothing to vectorise).
    pub fn match_bases(&self, a: Base, b: Base) -> bool {
        let (x, y) = match (a, b) {
            (Base::Square(a), Base::Square(b)) => (vec![a], vec![b]),
            (Base::Product(a1, a2), Base::Product(b1, b2)) => (vec![a1, a2], vec![b1, b2]),
            _ => return false,
        };
        x.iter().zip(&y).all(|(a, b)| self.match_operands(*a, *b)) && x != y
    }
}

/// The shape of a node's computation, without its operands: two nodes of
/// one shape emit the same code up to which coefficients they read.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Shape {
    /// A nonlinear recurrence: its kind and its exponent, if any.
    TapeOp(std::mem::Discriminant<TapeOp>, u64),
    /// A sum: per term, its literal weight (None when it reads constants
    /// that are not numbers) and the kind of its base.
    Sum(Vec<(Option<u64>, u8)>),
}

fn sum_shape(terms: &[LinearTerm]) -> (Shape, Vec<Operand>) {
    let mut operands = Vec::new();
    let shape = terms
        .iter()
        .map(|t| {
            let weight = t.weight.is_literal().then(|| t.weight.literal.to_bits());
            match t.base {
                Base::Operand(o) | Base::Square(o) => operands.push(o),
                Base::Product(a, b) | Base::Head(a, b) | Base::Tail(a, b) => {
                    operands.extend([a, b])
                }
            }
            (weight, t.base.kind())
        })
        .collect();
    (Shape::Sum(shape), operands)
}

/// The shape and operands of node `n`, or None when it is never paired
/// (the sin/cos and sinh/cosh pairs, which fill two rows at once).
pub(super) fn shape(n: Node, tape: &Tape, folding: &Folding) -> Option<(Shape, Vec<Operand>)> {
    match n {
        Node::State(i) => Some(sum_shape(&folding.outputs[i])),
        Node::Var(v) => match &folding.roles[v] {
            Role::SumRow(terms) => Some(sum_shape(terms)),
            Role::Folded => None,
            Role::Row => {
                let (_, r) = tape.recurrences.iter().find(|(u, _)| *u == v)?;
                let exponent = match r {
                    TapeOp::SinCos(_) | TapeOp::SinhCosh(_) => return None,
                    TapeOp::Pow(_, e) => e.to_bits(),
                    TapeOp::Inverse(f, ..) => *f as u64,
                    _ => 0,
                };
                Some((Shape::TapeOp(std::mem::discriminant(r), exponent), operands(r)))
            }
        },
    }
}

/// Finds the lane pairs of the rows of `tape` under `folding` (`n` states).
pub fn pair_rows(tape: &Tape, folding: &Folding, n: usize) -> VectorRows {
    let mut nodes: Vec<Node> = Vec::new();
    // Nonlinear recurrences first: they are the costly ones, and pairing
    // them pairs the sums they read.
    for &(v, _) in &tape.recurrences {
        if folding.roles[v] == Role::Row && shape(Node::Var(v), tape, folding).is_some() {
            nodes.push(Node::Var(v));
        }
    }
    for (v, role) in folding.roles.iter().enumerate() {
        if let Role::SumRow(_) = role {
            nodes.push(Node::Var(v));
        }
    }
    nodes.extend((0..n).map(Node::State));
    let shapes: BTreeMap<Node, (Shape, Vec<Operand>)> =
        nodes.iter().filter_map(|&x| Some((x, shape(x, tape, folding)?))).collect();
    let mut vectors = VectorRows::default();
    // First the pairs whose operands pair all the way down to the states;
    // then, among the rows left, those whose two lanes read states that
    // are not a pair (the vectoriser gathers those into one vector).
    for gather_states in [false, true] {
        for (i, &a) in nodes.iter().enumerate() {
            if vectors.of(a).is_some() || !shapes.contains_key(&a) {
                continue;
            }
            for &b in &nodes[i + 1..] {
                if vectors.of(b).is_some() {
                    continue;
                }
                if let Some(found) = unify(&vectors, &shapes, a, b, gather_states) {
                    let mut trial =
                        VectorRows { partner: vectors.partner.clone(), ..VectorRows::default() };
                    for (x, y) in found {
                        trial.partner.insert(x, (y, 0));
                        trial.partner.insert(y, (x, 1));
                    }
                    if schedule(tape, folding, &trial).is_some() {
                        vectors = trial;
                        break;
                    }
                }
            }
        }
    }
    vectors
}

/// The pairs that putting `a` and `b` in lanes 0 and 1 implies, or None if
/// a shape or an existing pair conflicts. With `gather_states`, two
/// different states read in one position pair nothing and conflict with
/// nothing (and no state row is itself paired).
fn unify(
    vectors: &VectorRows,
    shapes: &BTreeMap<Node, (Shape, Vec<Operand>)>,
    a: Node,
    b: Node,
    gather_states: bool,
) -> Option<Vec<(Node, Node)>> {
    if gather_states && matches!(a, Node::State(_)) {
        return None;
    }
    let mut found: BTreeMap<Node, (Node, u8)> = BTreeMap::new();
    let mut pending = vec![(a, b)];
    while let Some((x, y)) = pending.pop() {
        if x == y {
            continue;
        }
        let current = vectors.of(x).or_else(|| found.get(&x).copied());
        match current {
            Some(p) if p == (y, 0) => continue,
            Some(_) => return None,
            None if vectors.of(y).or_else(|| found.get(&y).copied()).is_some() => return None,
            None => {}
        }
        let ((sx, ox), (sy, oy)) = (shapes.get(&x)?, shapes.get(&y)?);
        if sx != sy || ox.len() != oy.len() {
            return None;
        }
        found.insert(x, (y, 0));
        found.insert(y, (x, 1));
        for (&p, &q) in ox.iter().zip(oy) {
            match (Node::of(p), Node::of(q)) {
                // A state's coefficient k is known when order k starts, a
                // u-variable's is computed in it: never one lane of each.
                (Some(Node::State(_)), Some(Node::State(_))) if gather_states => {}
                (Some(p @ Node::State(_)), Some(q @ Node::State(_)))
                | (Some(p @ Node::Var(_)), Some(q @ Node::Var(_))) => pending.push((p, q)),
                (None, None) if p == q => {}
                (None, None) if matches!((p, q), (Operand::Const(_), Operand::Const(_))) => {}
                _ => return None,
            }
        }
    }
    Some(found.into_iter().filter(|(_, (_, lane))| *lane == 0).map(|(x, (y, _))| (x, y)).collect())
}

/// The u-variables with a row in the order their statements are written
/// within one order: the tape's order, except that the second lane of a
/// pair comes right after the first. None when pairs make the order
/// impossible (lane 1 of one pair reads lane 0 of a pair that reads it).
pub fn schedule(tape: &Tape, folding: &Folding, vectors: &VectorRows) -> Option<Vec<usize>> {
    let vars = folding.roles.len();
    let has_row = |v: usize| folding.roles[v] != Role::Folded;
    // Groups: a lane group, a pair or a single row, named by its first
    // u-variable.
    let leader = |v: usize| match vectors.vector_of(Node::Var(v)) {
        Some((Node::Var(w), _, _)) => w,
        _ => v,
    };
    let reads = |v: usize| -> Vec<usize> {
        let ops = match &folding.roles[v] {
            Role::SumRow(terms) => sum_shape(terms).1,
            Role::Row => tape
                .recurrences
                .iter()
                .find(|(u, _)| *u == v)
                .map(|(_, r)| operands(r))
                .unwrap_or_default(),
            Role::Folded => Vec::new(),
        };
        ops.into_iter()
            .filter_map(|o| match o {
                Operand::Var(u) => Some(u),
                _ => None,
            })
            .collect()
    };
    // The second of a sin/cos pair is written with the first.
    let mut written_with = vec![None; vars];
    for &(v, r) in &tape.recurrences {
        if matches!(r, TapeOp::SinCos(_) | TapeOp::SinhCosh(_)) {
            written_with[v + 1] = Some(v);
        }
    }
    let group_of = |v: usize| leader(written_with[v].unwrap_or(v));
    let mut members: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    for v in (0..vars).filter(|&v| has_row(v)) {
        members.entry(group_of(v)).or_default().push(v);
    }
    // In lane order.
    for list in members.values_mut() {
        list.sort_by_key(|&v| (vectors.vector_of(Node::Var(v)).map_or(0, |(_, lane, _)| lane), v));
    }
    let mut waits: BTreeMap<usize, usize> = members.keys().map(|&g| (g, 0)).collect();
    let mut users: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    for (&g, list) in &members {
        let mut deps: Vec<usize> = list
            .iter()
            .flat_map(|&v| reads(v))
            .filter(|&u| has_row(u))
            .map(group_of)
            .filter(|&d| d != g)
            .collect();
        deps.sort_unstable();
        deps.dedup();
        *waits.entry(g).or_default() = deps.len();
        for d in deps {
            users.entry(d).or_default().push(g);
        }
    }
    // Kahn's algorithm, the earliest group in the tape first.
    let mut ready: BinaryHeap<Reverse<usize>> =
        waits.iter().filter(|(_, &w)| w == 0).map(|(&g, _)| Reverse(g)).collect();
    let mut order = Vec::new();
    while let Some(Reverse(g)) = ready.pop() {
        order.extend(members[&g].iter().copied());
        for &u in users.get(&g).into_iter().flatten() {
            let w = waits.get_mut(&u)?;
            *w -= 1;
            if *w == 0 {
                ready.push(Reverse(u));
            }
        }
    }
    (order.len() == members.values().map(Vec::len).sum::<usize>()).then_some(order)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::taylor::folding::fold_linear;
    use crate::taylor::tape::{n_body_tape, test_tape};
    use Operand::{Const, State, Var};

    /// The lanes with every constant a parameter (no number known).
    fn vector_rows_of(t: &Tape, n: usize) -> (Folding, VectorRows) {
        let folding = fold_linear(t, &vec![None; t.constants.len()]);
        let vectors = pair_rows(t, &folding, n);
        (folding, vectors)
    }

    /// Kepler in the plane, as the tape writes it: x and y are one pair,
    /// and so are their velocities (each output is `−x·r⁻³`, `−y·r⁻³`);
    /// the single power is read by both lanes; the squares of `x² + y²`
    /// are a pair of convolutions inside one sum.
    #[test]
    fn kepler_pairs_the_components_and_shares_the_power() {
        // x, y, vx, vy; c0 = −1 (a parameter here).
        let t = test_tape(
            vec![
                TapeOp::Square(State(0)),
                TapeOp::Square(State(1)),
                TapeOp::Add(Var(0), Var(1)),
                TapeOp::Pow(Var(2), -1.5),
                TapeOp::Mul(State(0), Var(3)),
                TapeOp::Scale(Var(4), 0),
                TapeOp::Mul(State(1), Var(3)),
                TapeOp::Scale(Var(6), 0),
            ],
            vec![State(2), State(3), Var(5), Var(7)],
            1,
        );
        let (folding, vectors) = vector_rows_of(&t, 4);
        assert_eq!(
            vectors.pairs().collect::<Vec<_>>(),
            vec![(Node::State(0), Node::State(1)), (Node::State(2), Node::State(3))]
        );
        assert!(vectors.match_bases(Base::Square(State(0)), Base::Square(State(1))));
        assert!(!vectors.match_bases(Base::Square(State(1)), Base::Square(State(0))));
        // A product with the shared power pairs; the power alone does not.
        assert!(
            vectors.match_bases(Base::Product(State(0), Var(3)), Base::Product(State(1), Var(3)))
        );
        assert!(!vectors.match_bases(Base::Square(Var(3)), Base::Square(Var(3))));
        assert_eq!(schedule(&t, &folding, &vectors), Some(vec![2, 3]));
    }

    /// Arenstorf's two attracting centres: the shifted positions, the
    /// sums of squares and the powers pair up, each pair written side by
    /// side; `y²`, read by both sums, stays single.
    #[test]
    fn two_centres_pair_their_distances_and_powers() {
        // y1, y2, v1, v2; c0 = μ, c1 = μ − 1, c2 = −1 (parameters here).
        let t = test_tape(
            vec![
                TapeOp::Add(State(0), Const(0)), // u0 = y1 + μ
                TapeOp::Square(Var(0)),          // u1
                TapeOp::Square(State(1)),        // u2 = y2²
                TapeOp::Add(Var(1), Var(2)),     // u3
                TapeOp::Add(State(0), Const(1)), // u4 = y1 + μ − 1
                TapeOp::Square(Var(4)),          // u5
                TapeOp::Add(Var(2), Var(5)),     // u6 (the other order)
                TapeOp::Pow(Var(3), -1.5),       // u7
                TapeOp::Pow(Var(6), -1.5),       // u8
                TapeOp::Mul(Var(0), Var(7)),     // u9
                TapeOp::Mul(Var(4), Var(8)),     // u10
                TapeOp::Add(Var(9), Var(10)),    // u11
                TapeOp::Scale(Var(11), 2),       // u12
            ],
            vec![State(2), State(3), Var(12), Var(12)],
            3,
        );
        let (folding, vectors) = vector_rows_of(&t, 4);
        let pairs: Vec<_> = vectors.pairs().collect();
        for (a, b) in [(0, 4), (3, 6), (7, 8)] {
            assert!(pairs.contains(&(Node::Var(a), Node::Var(b))), "u{a} and u{b} in {pairs:?}");
        }
        assert_eq!(vectors.of(Node::Var(2)), None);
        let order = schedule(&t, &folding, &vectors).expect("a schedule");
        for (a, b) in [(0, 4), (3, 6), (7, 8)] {
            let at = |v| order.iter().position(|&u| u == v).unwrap();
            assert_eq!(at(b), at(a) + 1, "{order:?}");
        }
        // Every row after the rows it reads.
        let at = |v| order.iter().position(|&u| u == v).unwrap();
        assert!(at(2) < at(3) && at(3) < at(7) && at(6) < at(8));
    }

    /// With two lanes, pairs that must pair their states too cover the
    /// interactions of an N-body model only in part (bodies 1 and 2 paired
    /// for (1, 3) and (2, 3) cannot also pair for (1, 4) and (2, 4)); read
    /// as gathered vectors, the states leave every interaction free to pair
    /// with any other of its shape: 7 pairs of the 15 interactions' 8 rows
    /// (3 differences, the sum of squares, the power, 3 products) for six
    /// bodies, and in the interaction left over, as in Kepler, the x and y
    /// differences and their products with the one power.
    #[test]
    fn n_body_interactions_pair_by_gathering_states() {
        let t = n_body_tape(6);
        let (folding, vectors) = vector_rows_of(&t, 36);
        let rows: Vec<usize> =
            (0..t.ops.len()).filter(|&v| folding.roles[v] != Role::Folded).collect();
        assert_eq!(rows.len(), 15 * 8);
        let paired = rows.iter().filter(|&&v| vectors.of(Node::Var(v)).is_some()).count();
        assert_eq!(paired, 7 * 2 * 8 + 4, "{} of {} rows paired", paired, rows.len());
        assert!(schedule(&t, &folding, &vectors).is_some());
    }

    /// A row whose would-be partner reads it cannot share its lane pair:
    /// `exp(x)` and `exp(exp(x))` stay single.
    #[test]
    fn a_row_never_pairs_with_a_row_that_reads_it() {
        let t =
            test_tape(vec![TapeOp::Exp(State(0)), TapeOp::Exp(Var(0))], vec![Var(0), Var(1)], 0);
        let (folding, vectors) = vector_rows_of(&t, 2);
        assert_eq!(vectors.of(Node::Var(0)), None);
        assert_eq!(schedule(&t, &folding, &vectors), Some(vec![0, 1]));
    }
}
