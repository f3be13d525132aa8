//! Where the unrolled Taylor recurrences keep their coefficients: one
//! array of rows, lane pairs interleaved, and which coefficients each order
//! may read early (`taylor::unrolled` emits the code that fills it).

use crate::taylor::tape::Operand;
use crate::taylor::vector_rows::{Node, VectorRows};
use proc_macro2::{Literal, TokenStream};
use quote::quote;
use std::cell::{Cell, RefCell};
use std::collections::BTreeSet;

/// Where the coefficients live: one array `r` of rows of `order + 1`
/// coefficients, states first, then the u-variables that have a row (see
/// `taylor::folding`), then one reciprocal 1/x₀ per such row; constants and the
/// weights of the folded sums in `c`, the time in `t`. The two rows of a
/// lane pair are interleaved (coefficient k of lane l at `2k + l` of their
/// block), so that their coefficients of one order are neighbours.
pub(super) struct JetLayout {
    states: usize,
    /// The row of each u-variable among the u-variables' rows, if it has one.
    rows: Vec<Option<usize>>,
    /// Per row (states first), its first slot and the distance between
    /// its coefficients.
    place: Vec<(usize, usize)>,
    /// Per u-variable row, the slot of its reciprocal.
    reciprocals: Vec<usize>,
    len: usize,
    /// While a lane group's loop is written: the rows read at lane `lane`
    /// of their group (the others are read at the slot itself).
    looped: RefCell<BTreeSet<usize>>,
    /// The slots of order 0 of the lanes that pad groups (see [`padded`]).
    padding: Vec<usize>,
    /// While a statement is written for any order (`taylor::sharing`): the
    /// order it is written at, whose coefficients k′ ≥ k are then read at
    /// `r[F + S * k]` with `k` a variable.
    any_order: Cell<Option<usize>>,
}

/// The lanes a group of `width` rows takes in `r`, and its loop runs over:
/// a whole number of 4-wide vectors (a pair keeps its two). With 15 lanes
/// the compiler masks every load and store of the loop (AVX-512); padded
/// to 16, the outer solar system's order-18 jet ran 0.83–0.88× the time
/// (three rounds alternated). Why is not settled: the state rows reading
/// the previous order's products instead of the ones just stored (no
/// store to forward from) changed nothing. The extra lanes compute on
/// their own slots only, from finite values (see [`Layout::padding`]).
pub(super) fn padded(width: usize) -> usize {
    if width > 2 {
        width.next_multiple_of(4)
    } else {
        width
    }
}

impl JetLayout {
    /// The layout for `order`, `states` states, the u-variables' `rows`
    /// (`None` for those folded away) and the pairs in `lanes`.
    /// With `by_coefficient`, the states' coefficients come first, order by
    /// order (state i's coefficient k at `k·states + i`), unless a state is
    /// a lane of a vector.
    pub(super) fn new(
        order: usize,
        states: usize,
        rows: Vec<Option<usize>>,
        vectors: &VectorRows,
        by_coefficient: bool,
    ) -> JetLayout {
        let row_count = rows.iter().flatten().count();
        let mut var_of_row = vec![0; row_count];
        for (v, row) in rows.iter().enumerate() {
            if let Some(row) = row {
                var_of_row[*row] = v;
            }
        }
        let node = |row: usize| {
            if row < states {
                Node::State(row)
            } else {
                Node::Var(var_of_row[row - states])
            }
        };
        let row_of = |n: Node| match n {
            Node::State(i) => i,
            Node::Var(v) => states + rows[v].unwrap_or(0),
        };
        let total = states + row_count;
        let (mut place, mut reciprocals) = (vec![(0, 1); total], vec![0; row_count]);
        // The rows of the vector whose lane 0 is `row`, in lane order.
        let vector = |row: usize| -> Option<Vec<usize>> {
            let n = node(row);
            match vectors.vector_of(n)? {
                (_, 0, _) => Some(match vectors.group(n) {
                    Some(members) => members.iter().map(|&m| row_of(m)).collect(),
                    None => vec![row, row_of(vectors.of(n)?.0)],
                }),
                _ => None,
            }
        };
        let (mut next, mut padding) = (0, Vec::new());
        let by_coefficient =
            by_coefficient && (0..states).all(|i| vectors.vector_of(Node::State(i)).is_none());
        if by_coefficient {
            for (i, place) in place.iter_mut().enumerate().take(states) {
                *place = (i, states);
            }
            next = states * (order + 1);
        }
        for row in (if by_coefficient { states } else { 0 })..total {
            match (vectors.vector_of(node(row)), vector(row)) {
                (_, Some(rows)) => {
                    let width = padded(rows.len());
                    padding.extend((rows.len()..width).map(|lane| next + lane));
                    for (lane, r) in rows.into_iter().enumerate() {
                        place[r] = (next + lane, width);
                    }
                    next += width * (order + 1);
                }
                (Some(_), None) => {}
                (None, None) => {
                    place[row] = (next, 1);
                    next += order + 1;
                }
            }
        }
        for row in states..total {
            match (vectors.vector_of(node(row)), vector(row)) {
                (_, Some(rows)) => {
                    for (lane, r) in rows.iter().enumerate() {
                        reciprocals[r - states] = next + lane;
                    }
                    padding.extend((rows.len()..padded(rows.len())).map(|lane| next + lane));
                    next += padded(rows.len());
                }
                (Some(_), None) => {}
                (None, None) => {
                    reciprocals[row - states] = next;
                    next += 1;
                }
            }
        }
        JetLayout {
            states,
            rows,
            place,
            reciprocals,
            len: next,
            looped: RefCell::new(BTreeSet::new()),
            padding,
            any_order: Cell::new(None),
        }
    }

    /// True when the states' rows come first, each its `order + 1`
    /// coefficients in a row, as the caller of the jet reads them.
    pub(super) fn states_first(&self, order: usize) -> bool {
        (0..self.states).all(|i| self.place[i] == (i * (order + 1), 1))
    }

    /// True when the states' coefficients come first order by order (see
    /// [`Layout::new`]).
    pub(super) fn states_by_coefficient(&self) -> bool {
        (0..self.states).all(|i| self.place[i] == (i, self.states))
    }

    /// The slots of order 0 that pad lane groups, set to 1 before the first
    /// order: a padding lane of a group written lane by lane (an N-body
    /// model's differences) is never written, and the loops that read it
    /// then compute 1, 1^(−3/2), … in their own padding lanes instead of
    /// whatever the buffer held (1/0 from the runtime's zeros). Its higher
    /// coefficients stay as the buffer has them, zero from the runtime.
    pub(super) fn padding(&self) -> &[usize] {
        &self.padding
    }

    /// The length of `r`.
    pub(super) fn len(&self) -> usize {
        self.len
    }

    /// Coefficient `k` of row `row` (states first) in `r`.
    pub(super) fn slot(&self, row: usize, k: usize) -> TokenStream {
        let (first, stride) = self.place[row];
        match self.any_order.get() {
            Some(at) if k >= at && !self.looped.borrow().contains(&row) => {
                let offset = Literal::usize_unsuffixed(first + stride * (k - at));
                match (first + stride * (k - at), stride) {
                    (0, 1) => quote!(r[k]),
                    (_, 1) => quote!(r[#offset + k]),
                    _ => {
                        let stride = Literal::usize_unsuffixed(stride);
                        quote!(r[#offset + #stride * k])
                    }
                }
            }
            _ => self.at(row, first + stride * k),
        }
    }

    /// `write` run as for order `k`, its slots of orders k′ ≥ k read as
    /// `r[F + S * k]` for any k (see `taylor::sharing`).
    pub(super) fn any_order<T>(&self, k: usize, write: impl FnOnce() -> T) -> T {
        self.any_order.set(Some(k));
        let written = write();
        self.any_order.set(None);
        written
    }

    /// `r[at]`, or `r[at + lane]` for a row read by a lane group's loop.
    fn at(&self, row: usize, at: usize) -> TokenStream {
        let at = Literal::usize_unsuffixed(at);
        if self.looped.borrow().contains(&row) {
            quote!(r[#at + lane])
        } else {
            quote!(r[#at])
        }
    }

    /// While `write` writes a lane group's statement for lane 0, `rows`
    /// (lane 0 of their groups) are read at lane `lane` of their group.
    pub(super) fn looping<T>(&self, rows: BTreeSet<usize>, write: impl FnOnce() -> T) -> T {
        *self.looped.borrow_mut() = rows;
        let written = write();
        self.looped.borrow_mut().clear();
        written
    }

    /// The row of a node.
    pub(super) fn row(&self, n: Node) -> usize {
        match n {
            Node::State(i) => i,
            Node::Var(v) => self.var_row(v),
        }
    }

    /// The row of u-variable `v` in `r`; only asked of u-variables that
    /// have one (the plan never refers to the others by row).
    pub(super) fn var_row(&self, v: usize) -> usize {
        self.states + self.rows[v].unwrap_or(0)
    }

    /// Coefficient `k` of an operand: `None` when it is zero.
    pub(super) fn coefficient(&self, o: Operand, k: usize) -> Option<TokenStream> {
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

    /// When coefficient `index` of `o` is known to order `k`'s sums: 0
    /// long before, 1 computed in order k − 1 (a u-variable's coefficient
    /// k − 1), 2 at the start of order k (a state's coefficient k), 3 once
    /// computed in order k (a u-variable's coefficient k).
    pub(super) fn fresh(&self, o: Operand, index: usize, k: usize) -> u8 {
        match o {
            Operand::Var(_) if index == k => 3,
            _ if index == k => 2,
            Operand::Var(_) if index + 1 == k => 1,
            _ => 0,
        }
    }

    /// The slot of 1/x₀ for u-variable `v`'s recurrence.
    pub(super) fn reciprocal(&self, v: usize) -> TokenStream {
        self.at(self.var_row(v), self.reciprocals[self.rows[v].unwrap_or(0)])
    }
}

/// A finite constant as tokens (a negative one as a negation: literals are unsigned).
pub(crate) fn float(x: f64) -> TokenStream {
    let magnitude = Literal::f64_suffixed(x.abs());
    if x.is_sign_negative() {
        quote!((-#magnitude))
    } else {
        quote!(#magnitude)
    }
}
