//! Lane groups: rows of the unrolled Taylor recurrences that repeat one
//! computation on other operands, any number of them, computed for large
//! jets by one loop over their lanes instead of one copy each.
//!
//! Large jets keep their coefficients in memory and are one function per
//! order; written out row by row they are long (the outer solar system at
//! order 15: some 150 kB of instructions per jet, several times what the
//! processor's instruction cache holds), and the time goes as much into
//! fetching and decoding them as into the arithmetic. The interactions of an N-body model are one
//! computation repeated: a group of rows (the 15 interactions' powers, say)
//! with their coefficients interleaved (coefficient k of lane l at
//! `first + W·k + l`) is one loop over l whose body reads its operands'
//! lane l, which the compiler vectorises. Groups are found as lane pairs
//! are (`vector_rows`), with tuples in place of pairs: from a seed tuple
//! (every row of one shape), unify the operands position by position —
//! one operand read by every lane, a tuple that is itself a group in the
//! same lane order, or states (the group's rows are then written lane by
//! lane, reading each state where it is) — and give the seed up on any
//! conflict. Consecutive groups of one width share one loop (the sums of
//! squares, powers and products of the interactions: their common
//! operands are loaded once per lane). Values are never affected: a group
//! only changes where coefficients are stored and whether a lane's
//! statement is written out or run by the loop. On the outer solar system
//! (15 interactions, order 15) a step went from 5.7 µs with lane pairs to
//! 3.0 µs with a loop per group and 2.6 µs with fused loops.

use crate::taylor::folding::{Folding, Role};
use crate::taylor::tape::{Operand, Tape};
use crate::taylor::vector_rows::{schedule, shape, Node, Shape, VectorRows};
use std::collections::BTreeMap;

/// A seed class: the rows' shape and the kinds of their operands.
type Class = (Shape, Vec<u8>);

/// Finds the lane groups of the rows of `tape` under `folding`; `known[i]`
/// is constant i's value when it is a number (lanes reading different
/// constants of one value read them as one).
pub fn group_rows(tape: &Tape, folding: &Folding, known: &[Option<f64>]) -> VectorRows {
    let mut nodes: Vec<Node> = Vec::new();
    for &(v, _) in &tape.recurrences {
        if folding.roles[v] == Role::Row {
            nodes.push(Node::Var(v));
        }
    }
    for (v, role) in folding.roles.iter().enumerate() {
        if let Role::SumRow(_) = role {
            nodes.push(Node::Var(v));
        }
    }
    let shapes: BTreeMap<Node, (Shape, Vec<Operand>)> =
        nodes.iter().filter_map(|&x| Some((x, shape(x, tape, folding)?))).collect();
    let mut vectors = VectorRows::default();
    // Seeds: every nonlinear row of one shape whose operands are of the
    // same kinds (rows, states, constants), in tape order.
    let mut classes: Vec<(Class, Vec<Node>)> = Vec::new();
    for &(v, _) in &tape.recurrences {
        let n = Node::Var(v);
        let Some((s, ops)) = shapes.get(&n) else {
            continue;
        };
        if folding.roles[v] != Role::Row {
            continue;
        }
        let key = (s.clone(), ops.iter().map(operand_kind).collect::<Vec<u8>>());
        match classes.iter_mut().find(|(c, _)| *c == key) {
            Some((_, members)) => members.push(n),
            None => classes.push((key, vec![n])),
        }
    }
    for (_, members) in &classes {
        try_group(tape, folding, known, &shapes, &mut vectors, members.clone());
    }
    // Then rows whose operands are in groups, their lanes in the order of
    // their first grouped operand's lanes, until no group forms.
    loop {
        let mut formed = false;
        let mut buckets: BTreeMap<String, Vec<(usize, Node)>> = BTreeMap::new();
        for &n in &nodes {
            if vectors.group_of.contains_key(&n) {
                continue;
            }
            let Some((s, ops)) = shapes.get(&n) else {
                continue;
            };
            let mut key = format!("{s:?}");
            let mut lane = None;
            for o in ops {
                match Node::of(*o).and_then(|m| vectors.group_of.get(&m)) {
                    Some(&(g, l)) => {
                        key.push_str(&format!(" g{g}"));
                        lane.get_or_insert(l);
                    }
                    None => key.push_str(" -"),
                }
            }
            if let Some(lane) = lane {
                buckets.entry(key).or_default().push((lane, n));
            }
        }
        for (_, mut members) in buckets {
            members.sort();
            let tuple: Vec<Node> = members.into_iter().map(|(_, n)| n).collect();
            formed |= try_group(tape, folding, known, &shapes, &mut vectors, tuple);
        }
        if !formed {
            break;
        }
    }
    vectors
}

/// Adds the groups that `tuple` implies to `lanes` when they unify and the
/// rows can still be scheduled; true when they were added.
fn try_group(
    tape: &Tape,
    folding: &Folding,
    known: &[Option<f64>],
    shapes: &BTreeMap<Node, (Shape, Vec<Operand>)>,
    vectors: &mut VectorRows,
    tuple: Vec<Node>,
) -> bool {
    if tuple.len() < 2 {
        return false;
    }
    let Some(found) = unify(vectors, shapes, known, tuple) else {
        return false;
    };
    let mut trial = VectorRows {
        groups: vectors.groups.clone(),
        group_of: vectors.group_of.clone(),
        ..VectorRows::default()
    };
    for members in found {
        let g = trial.groups.len();
        for (lane, &m) in members.iter().enumerate() {
            trial.group_of.insert(m, (g, lane));
        }
        trial.groups.push(members);
    }
    if schedule(tape, folding, &trial).is_none() {
        return false;
    }
    *vectors = trial;
    true
}

/// The groups that making `tuple` one group implies, or None if a shape or
/// an existing group conflicts.
fn unify(
    vectors: &VectorRows,
    shapes: &BTreeMap<Node, (Shape, Vec<Operand>)>,
    known: &[Option<f64>],
    tuple: Vec<Node>,
) -> Option<Vec<Vec<Node>>> {
    let mut found: Vec<Vec<Node>> = Vec::new();
    let mut pending = vec![tuple];
    while let Some(t) = pending.pop() {
        if t.iter().all(|&n| n == t[0]) {
            continue;
        }
        let existing = |n: &Node| {
            vectors
                .group(*n)
                .map(<[Node]>::to_vec)
                .or_else(|| found.iter().find(|g| g.contains(n)).cloned())
        };
        match existing(&t[0]) {
            Some(g) if g == t => continue,
            Some(_) => return None,
            None if t.iter().any(|n| existing(n).is_some()) => return None,
            None => {}
        }
        let mut distinct = t.clone();
        distinct.sort();
        distinct.dedup();
        if distinct.len() != t.len() {
            return None;
        }
        let (s0, o0) = shapes.get(&t[0])?;
        for n in &t[1..] {
            let (s, o) = shapes.get(n)?;
            if s != s0 || o.len() != o0.len() {
                return None;
            }
        }
        for position in 0..o0.len() {
            let ops: Vec<Operand> = t.iter().map(|n| shapes[n].1[position]).collect();
            if same_operand(&ops, known) {
                continue;
            }
            let rows: Option<Vec<Node>> = ops.iter().map(|&o| Node::of(o)).collect();
            match rows {
                Some(rows) if rows.iter().all(|r| matches!(r, Node::Var(_))) => pending.push(rows),
                // States are read where they are, lane by lane.
                Some(rows) if rows.iter().all(|r| matches!(r, Node::State(_))) => {}
                _ => return None,
            }
        }
        found.push(t);
    }
    Some(found)
}

/// The kind of an operand: a row (0), a state (1), a constant (2) or the
/// time (3).
fn operand_kind(o: &Operand) -> u8 {
    match o {
        Operand::Var(_) => 0,
        Operand::State(_) => 1,
        Operand::Const(_) => 2,
        Operand::Time => 3,
    }
}

/// True when every lane reads the same operand: one operand, or constants
/// known to be one number.
pub(super) fn same_operand(ops: &[Operand], known: &[Option<f64>]) -> bool {
    let value = |o: &Operand| match o {
        Operand::Const(i) => known.get(*i).copied().flatten(),
        _ => None,
    };
    ops.iter().all(|o| *o == ops[0])
        || (value(&ops[0]).is_some() && ops.iter().all(|o| value(o) == value(&ops[0])))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::taylor::folding::fold_linear;
    use crate::taylor::tape::n_body_tape;

    /// Squares of three states and of a constant: the states' squares make
    /// one group (the constant's, of the same shape, is left out rather
    /// than spoiling it), and three quotients by different constants of
    /// one value make another, reading the constants as one.
    #[test]
    fn seeds_split_by_operand_kind_and_equal_constants_match() {
        use crate::taylor::tape::{test_tape, TapeOp};
        use Operand::{Const, State, Var};
        let t = test_tape(
            vec![
                TapeOp::Square(State(0)), // u0
                TapeOp::Square(State(1)), // u1
                TapeOp::Square(Const(0)), // u2
                TapeOp::Square(State(2)), // u3
                TapeOp::Div(Var(0), Const(1)),
                TapeOp::Div(Var(1), Const(2)),
                TapeOp::Div(Var(3), Const(3)),
                TapeOp::Add(Var(4), Var(2)),
            ],
            vec![Var(7), Var(5), Var(6)],
            4,
        );
        let known = [Some(1.5), Some(2.0), Some(2.0), Some(2.0)];
        let folding = fold_linear(&t, &known);
        let vectors = group_rows(&t, &folding, &known);
        let squares = [Node::Var(0), Node::Var(1), Node::Var(3)];
        let quotients = [Node::Var(4), Node::Var(5), Node::Var(6)];
        assert_eq!(vectors.group(Node::Var(0)), Some(&squares[..]));
        assert_eq!(vectors.group(Node::Var(4)), Some(&quotients[..]));
        assert_eq!(vectors.group(Node::Var(2)), None);
        // With the constants unknown, the quotients read different ones.
        let unknown = [None; 4];
        let vectors = group_rows(&t, &fold_linear(&t, &unknown), &unknown);
        assert_eq!(vectors.group(Node::Var(4)), None);
    }

    /// Six bodies: each of the 8 rows of an interaction (3 differences,
    /// the sum of squares, the power, 3 products) makes one group of the
    /// 15 interactions, all in the powers' lane order.
    #[test]
    fn n_body_rows_make_one_group_per_row_of_an_interaction() {
        let t = n_body_tape(6);
        let folding = fold_linear(&t, &vec![None; t.constants.len()]);
        let vectors = group_rows(&t, &folding, &vec![None; t.constants.len()]);
        assert_eq!(vectors.groups.len(), 8);
        assert!(vectors.groups.iter().all(|g| g.len() == 15));
        // Lane l of the powers reads lane l of the sums of squares.
        let powers = vectors
            .groups
            .iter()
            .find(|g| matches!(shape(g[0], &t, &folding), Some((Shape::TapeOp(..), ops)) if ops.len() == 1))
            .expect("the powers' group");
        for (lane, &p) in powers.iter().enumerate() {
            let (_, ops) = shape(p, &t, &folding).expect("a shape");
            let sum = Node::of(ops[0]).expect("a row");
            assert_eq!(vectors.group_of.get(&sum).map(|&(_, l)| l), Some(lane));
        }
        assert!(schedule(&t, &folding, &vectors).is_some());
    }
}
