//! Taylor coefficients by automatic differentiation: the right-hand side,
//! decomposed by the macro into a tape of elementary operations (one
//! "u-variable" each, shared subexpressions once), is propagated order by
//! order with the classical recurrences (Jorba & Zou 2005; heyoka's
//! `ad_notes`): products by Cauchy convolution, quotients, powers, exp, log,
//! sin/cos as a pair. This is the compact layout: one loop over the tape
//! per order, the same code for every model.

pub mod coefficient;

use coefficient::Coefficient;

/// `a·b + c`, fused (one rounding, one instruction) where the target has
/// FMA, as the straight-line recurrences emitted by `#[dae_model(unroll =
/// [..])]` are compiled with `-C target-cpu=native`; plain otherwise (a
/// software `fma` would be slower than both).
#[inline(always)]
pub fn mul_add(a: f64, b: f64, c: f64) -> f64 {
    if cfg!(target_feature = "fma") {
        a.mul_add(b, c)
    } else {
        a * b + c
    }
}

/// An operand of a tape operation; its constants are `C`s (`f64`, or
/// [`crate::lanes::Lanes`] for a batch's members side by side).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Operand<C = f64> {
    /// u-variable `i` (an earlier operation of the tape).
    Var(usize),
    /// State `i`.
    State(usize),
    /// The independent variable.
    Time,
    /// A constant (parameters are folded in by the generated code).
    Const(C),
}

/// One elementary operation; the result is the next u-variable.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TapeOp<C = f64> {
    /// `a + b`.
    Add(Operand<C>, Operand<C>),
    /// `a * b`.
    Mul(Operand<C>, Operand<C>),
    /// `a / b`.
    Div(Operand<C>, Operand<C>),
    /// `a^e` for a constant real `e` (`sqrt` is `e = 0.5`).
    Pow(Operand<C>, C),
    /// `exp(a)`.
    Exp(Operand<C>),
    /// `ln(a)`.
    Ln(Operand<C>),
    /// `sin(a)`; its `cos` is the next u-variable (`SinCos` pairs them).
    Sin(Operand<C>),
    /// The `cos` of the argument of the preceding `Sin`.
    CosOfPrevious,
    /// `sinh(a)`; its `cosh` is the next u-variable.
    Sinh(Operand<C>),
    /// The `cosh` of the argument of the preceding `Sinh`.
    CoshOfPrevious,
    /// `f(a)` for an inverse function f whose derivative is ±a'/d; `d` is
    /// √(1 − a²) for asin and acos, 1 + a² for atan (earlier u-variables).
    Inverse(Inverse, Operand<C>, Operand<C>),
    /// `atan2(y, x)` with `d = x² + y²`: u' = (x·y' − y·x')/d.
    Atan2(Operand<C>, Operand<C>, Operand<C>),
    /// `a` itself: gathers the entries of a linear system into consecutive
    /// u-variables for [`TapeOp::Solve`].
    Copy(Operand<C>),
    /// The first unknown of the `size × size` linear system E·z = g whose
    /// entries are the u-variables from `first` on (E row-major, then g):
    /// a mass matrix or a mechanism's constraint block solved at run time.
    /// Order by order, E^\[0\]·z^\[k\] = g^\[k\] − Σ_{j≥1} E^\[j\]·z^\[k−j\], with
    /// one LU of E^\[0\] a step. The other unknowns are the next `size − 1`
    /// u-variables ([`TapeOp::SolvedWithPrevious`]).
    Solve {
        /// The number of unknowns.
        size: usize,
        /// The u-variable of E's first entry.
        first: usize,
    },
    /// An unknown after the first of the preceding [`TapeOp::Solve`].
    SolvedWithPrevious,
}

/// A model's tape: its operations, and the operand that is each f_i.
pub type Tape<C = f64> = (Vec<TapeOp<C>>, Vec<Operand<C>>);

impl<C> Operand<C> {
    /// The same operand with its constant, if any, mapped by `f`.
    pub fn map_constant<D>(&self, f: impl FnOnce(&C) -> D) -> Operand<D> {
        match self {
            Operand::Var(i) => Operand::Var(*i),
            Operand::State(i) => Operand::State(*i),
            Operand::Time => Operand::Time,
            Operand::Const(c) => Operand::Const(f(c)),
        }
    }
}

impl<C> TapeOp<C> {
    /// The same operation with its constants mapped by `f`, in the order
    /// of its operands.
    pub fn map_constants<D>(&self, mut f: impl FnMut(&C) -> D) -> TapeOp<D> {
        let mut o = |a: &Operand<C>| a.map_constant(&mut f);
        match self {
            TapeOp::Add(a, b) => TapeOp::Add(o(a), o(b)),
            TapeOp::Mul(a, b) => TapeOp::Mul(o(a), o(b)),
            TapeOp::Div(a, b) => TapeOp::Div(o(a), o(b)),
            TapeOp::Pow(a, e) => {
                let a = o(a);
                TapeOp::Pow(a, f(e))
            }
            TapeOp::Exp(a) => TapeOp::Exp(o(a)),
            TapeOp::Ln(a) => TapeOp::Ln(o(a)),
            TapeOp::Sin(a) => TapeOp::Sin(o(a)),
            TapeOp::CosOfPrevious => TapeOp::CosOfPrevious,
            TapeOp::Sinh(a) => TapeOp::Sinh(o(a)),
            TapeOp::CoshOfPrevious => TapeOp::CoshOfPrevious,
            TapeOp::Inverse(g, a, d) => TapeOp::Inverse(*g, o(a), o(d)),
            TapeOp::Atan2(y, x, d) => TapeOp::Atan2(o(y), o(x), o(d)),
            TapeOp::Copy(a) => TapeOp::Copy(o(a)),
            TapeOp::Solve { size, first } => TapeOp::Solve { size: *size, first: *first },
            TapeOp::SolvedWithPrevious => TapeOp::SolvedWithPrevious,
        }
    }
}

/// The inverse functions of [`TapeOp::Inverse`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Inverse {
    /// u' = a'/√(1 − a²).
    Asin,
    /// u' = −a'/√(1 − a²).
    Acos,
    /// u' = a'/(1 + a²).
    Atan,
}

impl Inverse {
    fn value(self, a: f64) -> f64 {
        match self {
            Inverse::Asin => a.asin(),
            Inverse::Acos => a.acos(),
            Inverse::Atan => a.atan(),
        }
    }

    fn sign<T: Coefficient>(self) -> T {
        T::splat(match self {
            Inverse::Acos => -1.0,
            _ => 1.0,
        })
    }
}

/// An operation with its operands resolved to rows of the coefficient
/// buffer (row r holds coefficients 0..=order at r·w). The compact layout
/// interprets a list of these; the emitted layout calls [`advance`] with
/// literal ones, which the compiler specialises.
#[derive(Clone, Copy, Debug)]
pub enum Step<T = f64> {
    /// `a + b`.
    Add(usize, usize),
    /// Multiplication by a constant: one product per order, not a convolution.
    Scale(usize, T),
    /// Division by a constant.
    Quotient(usize, T),
    /// `a·b`, the Cauchy convolution.
    Mul(usize, usize),
    /// `(a·b)·c` for a constant c, where nothing else reads `a·b`: one
    /// step instead of a product and a scaling.
    ScaledMul(usize, usize, T),
    /// `a·a`: the symmetric convolution, half the products.
    Square(usize),
    /// `a/b`.
    Div(usize, usize),
    /// `a^e`, constant real e.
    Pow(usize, T),
    /// `exp(a)`.
    Exp(usize),
    /// `ln(a)`.
    Ln(usize),
    /// `sin(a)` into this row and `cos(a)` into the next, together.
    SinCos(usize),
    /// `sinh(a)` into this row and `cosh(a)` into the next.
    SinhCosh(usize),
    /// An inverse function `f(a)` with d·u' = ±a' (`d` the second row).
    Inverse(Inverse, usize, usize),
    /// `atan2(y, x)` with d = x² + y² (rows y, x, d).
    Atan2(usize, usize, usize),
    /// `a` itself.
    Copy(usize),
    /// Linear system `b` of [`TaylorWork`]'s, its unknowns in this row and
    /// the next ones: solved by [`TaylorWork::compute`], not by [`advance`].
    Solve(usize),
}

/// A linear system of the tape (a [`TapeOp::Solve`]) with its
/// factorisation, one per lane.
struct LinearSystem {
    size: usize,
    /// The row of E's first entry (then E row-major, then g).
    entries: usize,
    /// The row of the first unknown.
    unknowns: usize,
    /// The entries (i, c) of E that vary (not constants): only they enter
    /// Σ_{j≥1} E^\[j\]·z^\[k−j\] (a mechanism's KKT system is mostly its
    /// constant mass matrix and zeros).
    varying: Vec<(usize, usize)>,
    /// Per lane: E^\[0\] factored in place (L below the diagonal, U on and
    /// above), then its row permutation.
    lu: Vec<f64>,
    pivots: Vec<usize>,
    /// Per lane: the right-hand side being solved.
    rhs: Vec<f64>,
}

/// The tape compiled for one order, with its coefficient storage. Rows of
/// `order + 1` coefficients: states, time, constants, then u-variables;
/// each coefficient a `T` (`f64`, or a batch's lanes).
pub struct TaylorWork<T: Coefficient = f64> {
    order: usize,
    states: usize,
    time_row: usize,
    steps: Vec<(usize, Step<T>)>,
    outputs: Vec<usize>,
    rows: Vec<T>,
    systems: Vec<LinearSystem>,
}

impl<T: Coefficient> TaylorWork<T> {
    /// Compiles `tape` (with `outputs[i]` the operand that is f_i) for
    /// `states` states up to `order`. Allocates; call once per integration.
    pub fn new(
        tape: &[TapeOp<T>],
        outputs: &[Operand<T>],
        states: usize,
        order: usize,
    ) -> TaylorWork<T> {
        let w = order + 1;
        let time_row = states;
        let mut constants: Vec<T> = Vec::new();
        let constant_row = |c: T, constants: &mut Vec<T>| {
            let i = constants.iter().position(|d| d.same(&c)).unwrap_or_else(|| {
                constants.push(c);
                constants.len() - 1
            });
            time_row + 1 + i
        };
        // Constants are numbered in a first pass so that u-variable rows
        // follow them.
        let operands = tape
            .iter()
            .flat_map(|op| match *op {
                TapeOp::Add(a, b) | TapeOp::Mul(a, b) | TapeOp::Div(a, b) => vec![a, b],
                TapeOp::Pow(a, _)
                | TapeOp::Exp(a)
                | TapeOp::Ln(a)
                | TapeOp::Sin(a)
                | TapeOp::Sinh(a) => vec![a],
                TapeOp::Inverse(_, a, d) => vec![a, d],
                TapeOp::Atan2(y, x, d) => vec![y, x, d],
                TapeOp::Copy(a) => vec![a],
                TapeOp::CosOfPrevious
                | TapeOp::CoshOfPrevious
                | TapeOp::Solve { .. }
                | TapeOp::SolvedWithPrevious => vec![],
            })
            .chain(outputs.iter().copied());
        for o in operands {
            if let Operand::Const(c) = o {
                constant_row(c, &mut constants);
            }
        }
        let first_var = time_row + 1 + constants.len();
        let row = |o: Operand<T>, constants: &mut Vec<T>| match o {
            Operand::Var(i) => first_var + i,
            Operand::State(i) => i,
            Operand::Time => time_row,
            Operand::Const(c) => constant_row(c, constants),
        };
        let mut steps = Vec::with_capacity(tape.len());
        let mut systems = Vec::new();
        for (v, op) in tape.iter().enumerate() {
            let mut r = |o| row(o, &mut constants);
            let step = match *op {
                TapeOp::Add(a, b) => Step::Add(r(a), r(b)),
                TapeOp::Mul(a, Operand::Const(c)) | TapeOp::Mul(Operand::Const(c), a) => {
                    Step::Scale(r(a), c)
                }
                TapeOp::Div(a, Operand::Const(c)) => Step::Quotient(r(a), c),
                TapeOp::Mul(a, b) if a == b => Step::Square(r(a)),
                TapeOp::Mul(a, b) => Step::Mul(r(a), r(b)),
                TapeOp::Div(a, b) => Step::Div(r(a), r(b)),
                TapeOp::Pow(a, e) => Step::Pow(r(a), e),
                TapeOp::Exp(a) => Step::Exp(r(a)),
                TapeOp::Ln(a) => Step::Ln(r(a)),
                TapeOp::Sin(a) => Step::SinCos(r(a)),
                TapeOp::Sinh(a) => Step::SinhCosh(r(a)),
                TapeOp::Inverse(f, a, d) => Step::Inverse(f, r(a), r(d)),
                TapeOp::Atan2(y, x, d) => Step::Atan2(r(y), r(x), r(d)),
                TapeOp::Copy(a) => Step::Copy(r(a)),
                TapeOp::Solve { size, first } => {
                    let lanes = T::WIDTH;
                    let varying = (0..size * size)
                        .filter(|e| {
                            !matches!(tape.get(first + e), Some(TapeOp::Copy(Operand::Const(_))))
                        })
                        .map(|e| (e / size, e % size))
                        .collect();
                    systems.push(LinearSystem {
                        size,
                        entries: first_var + first,
                        unknowns: first_var + v,
                        varying,
                        lu: vec![0.0; lanes * size * size],
                        pivots: vec![0; lanes * size],
                        rhs: vec![0.0; lanes * size],
                    });
                    Step::Solve(systems.len() - 1)
                }
                // Computed together with its sine, or its system's first unknown.
                TapeOp::CosOfPrevious | TapeOp::CoshOfPrevious | TapeOp::SolvedWithPrevious => {
                    continue
                }
            };
            steps.push((first_var + v, step));
        }
        let outputs: Vec<usize> = outputs.iter().map(|&o| row(o, &mut constants)).collect();
        let steps = fuse_scaled_products(steps, &outputs);
        let mut rows = vec![T::splat(0.0); (first_var + tape.len()) * w];
        for (i, c) in constants.iter().enumerate() {
            rows[(time_row + 1 + i) * w] = *c;
        }
        if order > 0 {
            rows[time_row * w + 1] = T::splat(1.0);
        }
        TaylorWork { order, states, time_row, steps, outputs, rows, systems }
    }

    /// All rows; state i's coefficients are row i.
    pub fn rows(&self) -> &[T] {
        &self.rows
    }

    /// The normalised coefficients x_i^\[k\] = x_i^(k)/k! of state `i`.
    #[inline]
    pub fn state(&self, i: usize) -> &[T] {
        let w = self.order + 1;
        &self.rows[i * w..(i + 1) * w]
    }

    /// Fills the normalised Taylor coefficients of the solution through
    /// (t, y): `self.state(i)[k]` for k = 0..=order.
    pub fn compute(&mut self, t: f64, y: &[T]) {
        let w = self.order + 1;
        let rows = &mut self.rows;
        for (i, &yi) in y.iter().enumerate().take(self.states) {
            rows[i * w] = yi;
        }
        rows[self.time_row * w] = T::splat(t);
        for k in 0..self.order {
            for &(v, step) in &self.steps {
                match step {
                    Step::Solve(s) => solve_order(&mut self.systems[s], rows, w, k),
                    _ => advance(rows, w, k, v, step),
                }
            }
            // x^[k+1] = f^[k] / (k + 1).
            let next = T::splat((k + 1) as f64);
            for (i, &out) in self.outputs.iter().enumerate() {
                rows[i * w + k + 1] = rows[out * w + k] / next;
            }
        }
    }
}

/// Each scaling `c·u` of a product `u = a·b` that nothing else reads
/// becomes one step: a product by a constant factor (m_j·dx·r³ of an
/// N-body model, −b·x·S of a sensitivity) costs the interpreter one
/// operation, not two.
fn fuse_scaled_products<T: Coefficient>(
    steps: Vec<(usize, Step<T>)>,
    outputs: &[usize],
) -> Vec<(usize, Step<T>)> {
    let mut reads: FxCounts = FxCounts::default();
    for &(_, step) in &steps {
        for r in step_operands(&step) {
            *reads.entry(r).or_insert(0) += 1;
        }
    }
    for &o in outputs {
        *reads.entry(o).or_insert(0) += 1;
    }
    let product_at: std::collections::HashMap<usize, (usize, usize)> = steps
        .iter()
        .filter_map(|&(v, step)| match step {
            Step::Mul(a, b) => Some((v, (a, b))),
            _ => None,
        })
        .collect();
    let mut fused_away = std::collections::HashSet::new();
    let mut out: Vec<(usize, Step<T>)> = steps
        .iter()
        .map(|&(v, step)| match step {
            Step::Scale(u, c) if reads.get(&u) == Some(&1) => match product_at.get(&u) {
                Some(&(a, b)) => {
                    fused_away.insert(u);
                    (v, Step::ScaledMul(a, b, c))
                }
                None => (v, step),
            },
            _ => (v, step),
        })
        .collect();
    out.retain(|(v, step)| !(matches!(step, Step::Mul(..)) && fused_away.contains(v)));
    out
}

type FxCounts = std::collections::HashMap<usize, usize>;

/// The rows a step reads.
fn step_operands<T>(step: &Step<T>) -> Vec<usize> {
    match *step {
        Step::Add(a, b) | Step::Mul(a, b) | Step::Div(a, b) | Step::ScaledMul(a, b, _) => {
            vec![a, b]
        }
        Step::Scale(a, _)
        | Step::Quotient(a, _)
        | Step::Square(a)
        | Step::Pow(a, _)
        | Step::Exp(a)
        | Step::Ln(a)
        | Step::SinCos(a)
        | Step::SinhCosh(a)
        | Step::Copy(a) => vec![a],
        Step::Inverse(_, a, d) => vec![a, d],
        Step::Atan2(y, x, d) => vec![y, x, d],
        // A linear system reads its entries' rows, which are copies that
        // no scaling fuses with.
        Step::Solve(_) => vec![],
    }
}

/// Coefficient k of a linear system's unknowns, lane by lane: at k = 0
/// E^\[0\] is factored (LU with partial pivoting) and z^\[0\] solved; above,
/// z^\[k\] = (E^\[0\])⁻¹ (g^\[k\] − Σ_{j=1..k} E^\[j\] z^\[k−j\]), the
/// coefficients of E·z = g matched order by order. A singular E^\[0\]
/// gives NaN unknowns, which the step rule reports.
fn solve_order<T: Coefficient>(system: &mut LinearSystem, rows: &mut [T], w: usize, k: usize) {
    let n = system.size;
    let (entries, rhs_rows, unknowns) = (system.entries, system.entries + n * n, system.unknowns);
    for lane in 0..T::WIDTH {
        let lu = &mut system.lu[lane * n * n..(lane + 1) * n * n];
        let pivots = &mut system.pivots[lane * n..(lane + 1) * n];
        let b = &mut system.rhs[lane * n..(lane + 1) * n];
        let at = |r: usize, j: usize| rows[r * w + j].lane(lane);
        for (i, bi) in b.iter_mut().enumerate() {
            *bi = at(rhs_rows + i, k);
        }
        for &(i, c) in &system.varying {
            let (entry, unknown) = (entries + i * n + c, unknowns + c);
            let mut sum = 0.0;
            for j in 1..=k {
                sum += at(entry, j) * at(unknown, k - j);
            }
            b[i] -= sum;
        }
        let regular = if k == 0 {
            for (e, slot) in lu.iter_mut().enumerate() {
                *slot = at(entries + e, 0);
            }
            crate::linalg::lu_factor(lu, n, pivots)
        } else {
            true
        };
        if regular {
            crate::linalg::lu_solve(lu, n, pivots, b);
        } else {
            b.fill(f64::NAN);
        }
        for (i, &v) in b.iter().enumerate() {
            let cell = &mut rows[(unknowns + i) * w + k];
            *cell = cell.with_lane(lane, v);
        }
    }
}

/// Computes coefficient k of row `v` (and of row v + 1 for the sin/cos and
/// sinh/cosh pairs) by the recurrence of `step`, from coefficients 0..k of
/// its operands and 0..k−1 of its own row(s). `rows` holds rows of `w`
/// coefficients; rows of constants are zero beyond coefficient 0, the time
/// row is (t, 1, 0, …).
#[inline]
pub fn advance<T: Coefficient>(rows: &mut [T], w: usize, k: usize, v: usize, step: Step<T>) {
    let at = |r: usize, j: usize| rows[r * w + j];
    let row = |r: usize| &rows[r * w..r * w + k + 1];
    let own = &rows[v * w..v * w + k];
    let kf = T::splat(k as f64);
    let zero = T::splat(0.0);
    let (value, second) = match step {
        Step::Add(a, b) => (at(a, k) + at(b, k), zero),
        Step::Scale(a, c) => (at(a, k) * c, zero),
        Step::Quotient(a, c) => (at(a, k) / c, zero),
        Step::Mul(a, b) => (convolution(row(a), row(b)), zero),
        Step::ScaledMul(a, b, c) => (convolution(row(a), row(b)) * c, zero),
        Step::Square(a) => {
            // Σ_j a_j a_{k−j} = 2 Σ_{j<k−j} a_j a_{k−j} + a_{k/2}² (k even).
            let a = row(a);
            let half = k.div_ceil(2);
            let twice = T::splat(2.0) * convolution(&a[..half], &a[k + 1 - half..]);
            let middle = if k % 2 == 0 { a[k / 2] * a[k / 2] } else { zero };
            (twice + middle, zero)
        }
        Step::Div(a, b) => {
            // u = a/b: u^[k] = (a^[k] − Σ_{j<k} u^[j] b^[k−j]) / b^[0].
            let s = convolution(own, &row(b)[1..]);
            ((at(a, k) - s) / at(b, 0), zero)
        }
        Step::Pow(a, e) if k == 0 => (at(a, 0).zip(e, power), zero),
        Step::Pow(a, e) => {
            // Σ_{j<k} (k·e − j·(e+1)) a^[k−j] u^[j].
            let a = row(a);
            let (plain, weighted) = convolutions(own, &a[1..]);
            ((kf * e * plain - (e + T::splat(1.0)) * weighted) / (kf * a[0]), zero)
        }
        Step::Exp(a) if k == 0 => (at(a, 0).map(f64::exp), zero),
        Step::Exp(a) => (weighted_convolution(row(a), own) / kf, zero),
        Step::Ln(a) if k == 0 => (at(a, 0).map(f64::ln), zero),
        Step::Ln(a) => {
            // Σ_{0<j<k} j u^[j] a^[k−j].
            let a = row(a);
            let (_, s) = convolutions(own, &a[1..]);
            ((kf * a[k] - s) / (kf * a[0]), zero)
        }
        Step::SinhCosh(a) if k == 0 => (at(a, 0).map(f64::sinh), at(a, 0).map(f64::cosh)),
        Step::SinhCosh(a) => {
            // s' = a' c and c' = a' s.
            let a = row(a);
            let s = &rows[v * w..v * w + k];
            let c = &rows[(v + 1) * w..(v + 1) * w + k];
            (weighted_convolution(a, c) / kf, weighted_convolution(a, s) / kf)
        }
        Step::Inverse(f, a, _) if k == 0 => (at(a, 0).map(|x| f.value(x)), zero),
        Step::Inverse(f, a, d) => {
            // d·u' = ±a': k u^[k] d^[0] = ±k a^[k] − Σ_{0<j<k} j u^[j] d^[k−j].
            let d = row(d);
            let (_, s) = convolutions(own, &d[1..]);
            ((f.sign::<T>() * at(a, k) - s / kf) / d[0], zero)
        }
        Step::Atan2(y, x, _) if k == 0 => (at(y, 0).zip(at(x, 0), f64::atan2), zero),
        Step::Atan2(y, x, d) => {
            // d·u' = x·y' − y·x'.
            let (y, x, d) = (row(y), row(x), row(d));
            let numerator = weighted_convolution(y, &x[..k]) - weighted_convolution(x, &y[..k]);
            let (_, s) = convolutions(own, &d[1..]);
            ((numerator - s) / (kf * d[0]), zero)
        }
        Step::Copy(a) => (at(a, k), zero),
        // Solved by `TaylorWork::compute`, which holds the factorisation.
        Step::Solve(_) => return,
        Step::SinCos(a) if k == 0 => at(a, 0).sin_cos(),
        Step::SinCos(a) => {
            // s' = a' c and c' = −a' s, both from the previous orders.
            let a = row(a);
            let s = &rows[v * w..v * w + k];
            let c = &rows[(v + 1) * w..(v + 1) * w + k];
            (weighted_convolution(a, c) / kf, -weighted_convolution(a, s) / kf)
        }
    };
    rows[v * w + k] = value;
    if let Step::SinCos(_) | Step::SinhCosh(_) = step {
        rows[(v + 1) * w + k] = second;
    }
}

/// `a^e`, by a square root for the half-integer powers of gravity models
/// (r^(−3/2)): several times cheaper than `powf`, and correctly rounded
/// up to the final product.
#[inline]
pub fn power(a: f64, e: f64) -> f64 {
    if e == 0.5 {
        a.sqrt()
    } else if e == -0.5 {
        1.0 / a.sqrt()
    } else if e == 1.5 {
        a * a.sqrt()
    } else if e == -1.5 {
        1.0 / (a * a.sqrt())
    } else {
        a.powf(e)
    }
}

/// Σ_i a[i]·b[n−1−i] over the common length n: the Cauchy product term.
/// Four partial sums: a single running sum is bound by the latency of one
/// addition per term, which dominated the whole method; the result differs
/// from the sequential sum only by rounding.
#[inline]
fn convolution<T: Coefficient>(a: &[T], b: &[T]) -> T {
    let n = a.len().min(b.len());
    let (a, b) = (&a[..n], &b[..n]);
    let mut acc = [T::splat(0.0); 4];
    let (a4, b4) = (a.chunks_exact(4), b.rchunks_exact(4));
    let (a_tail, b_head) = (a4.remainder(), b4.remainder());
    for (x, y) in a4.zip(b4) {
        acc[0] = acc[0] + x[0] * y[3];
        acc[1] = acc[1] + x[1] * y[2];
        acc[2] = acc[2] + x[2] * y[1];
        acc[3] = acc[3] + x[3] * y[0];
    }
    // a's last elements meet b's first ones, in reverse.
    for (x, y) in a_tail.iter().zip(b_head.iter().rev()) {
        acc[0] = acc[0] + *x * *y;
    }
    (acc[0] + acc[1]) + (acc[2] + acc[3])
}

/// (Σ_i a[i]·b[n−1−i], Σ_i i·a[i]·b[n−1−i]) over the common length n, in
/// one pass, with four partial sums each (see [`convolution`]).
#[inline]
fn convolutions<T: Coefficient>(a: &[T], b: &[T]) -> (T, T) {
    let n = a.len().min(b.len());
    let (a, b) = (&a[..n], &b[..n]);
    let (mut plain, mut weighted) = ([T::splat(0.0); 4], [T::splat(0.0); 4]);
    let mut index = [0.0, 1.0, 2.0, 3.0];
    let (a4, b4) = (a.chunks_exact(4), b.rchunks_exact(4));
    let (a_tail, b_head) = (a4.remainder(), b4.remainder());
    for (x, y) in a4.zip(b4) {
        for l in 0..4 {
            let term = x[l] * y[3 - l];
            plain[l] = plain[l] + term;
            weighted[l] = weighted[l] + T::splat(index[l]) * term;
            index[l] += 4.0;
        }
    }
    let mut i = index[0];
    for (x, y) in a_tail.iter().zip(b_head.iter().rev()) {
        let term = *x * *y;
        plain[0] = plain[0] + term;
        weighted[0] = weighted[0] + T::splat(i) * term;
        i += 1.0;
    }
    (
        (plain[0] + plain[1]) + (plain[2] + plain[3]),
        (weighted[0] + weighted[1]) + (weighted[2] + weighted[3]),
    )
}

/// Σ_{j=1..k} j·a[j]·b[k−j] for `a` of length k+1 and `b` of length k: the
/// term of the derivative recurrences u' = a'·g.
#[inline]
fn weighted_convolution<T: Coefficient>(a: &[T], b: &[T]) -> T {
    let (plain, weighted) = convolutions(&a[1..], b);
    plain + weighted
}

#[cfg(test)]
mod tests {
    use super::*;

    /// y' = y², y(0) = y0: y = y0/(1 − y0 t), coefficients y0^(k+1) tᵏ... at t = 0: y0^(k+1).
    #[test]
    fn half_integer_powers_by_square_roots_agree_with_powf() {
        for a in [1e-8, 0.3, 1.0, 2.0, 7.5e5] {
            for e in [0.5, -0.5, 1.5, -1.5, 2.5, -0.3] {
                let (got, want) = (power(a, e), a.powf(e));
                assert!((got - want).abs() <= 4.0 * f64::EPSILON * want, "{a}^{e}");
            }
        }
    }

    #[test]
    fn products_give_the_geometric_series() {
        let tape = [TapeOp::Mul(Operand::State(0), Operand::State(0))];
        let mut work = TaylorWork::new(&tape, &[Operand::Var(0)], 1, 10);
        work.compute(0.0, &[0.5]);
        for (k, c) in work.state(0).iter().enumerate() {
            assert!((c - 0.5f64.powi(k as i32 + 1)).abs() < 1e-15);
        }
    }

    /// y′ = 2·y·z, z′ = −z with the product read once (fused with its
    /// scaling into one step) or twice (kept): y = y0·exp(2·z0·(1 −
    /// e^(−t))), the same coefficients either way.
    #[test]
    fn a_product_scaled_once_is_one_step_with_the_same_coefficients() {
        use Operand::{Const, State, Var};
        let fused = [
            TapeOp::Mul(State(0), State(1)),
            TapeOp::Mul(Var(0), Const(2.0)),
            TapeOp::Mul(State(1), Const(-1.0)),
        ];
        // The same, with an operation that reads the product again.
        let kept = [fused[0], fused[1], fused[2], TapeOp::Add(Var(0), Var(2))];
        let order = 14;
        let mut a = TaylorWork::new(&fused, &[Var(1), Var(2)], 2, order);
        assert_eq!(a.steps.len(), 2, "the product and its scaling are one step");
        let mut b = TaylorWork::new(&kept, &[Var(1), Var(2)], 2, order);
        assert_eq!(b.steps.len(), 4, "a product read twice stays a step of its own");
        let (y0, z0) = (0.7, 0.4);
        a.compute(0.0, &[y0, z0]);
        b.compute(0.0, &[y0, z0]);
        assert_eq!(a.state(0), b.state(0));
        let h = 0.1;
        let sum: f64 = a.state(0).iter().rev().fold(0.0, |acc, c| acc * h + c);
        let exact = y0 * (2.0 * z0 * (1.0 - (-h).exp())).exp();
        assert!((sum - exact).abs() <= 1e-15, "{sum} against {exact}");
    }

    /// y' = cos(t) y: y = exp(sin t); with sin/cos pairs, exp via the tape of
    /// y' = y·cos(t), compared with the series of exp(sin t) at t = 0.3
    /// computed through y' = y cos t by a different path (the exact value).
    #[test]
    fn sin_cos_pairs_and_time_agree_with_the_exact_solution() {
        let tape = [
            TapeOp::Sin(Operand::Time),
            TapeOp::CosOfPrevious,
            TapeOp::Mul(Operand::State(0), Operand::Var(1)),
        ];
        let order = 20;
        let mut work = TaylorWork::new(&tape, &[Operand::Var(2)], 1, order);
        let t0 = 0.3;
        work.compute(t0, &[t0.sin().exp()]);
        let h = 0.1;
        let sum: f64 = work.state(0).iter().rev().fold(0.0, |acc, c| acc * h + c);
        assert!((sum - (t0 + h).sin().exp()).abs() < 1e-15);
    }

    /// x′ = z0, y′ = z1 with [[1 + x², x], [x, 2]]·z = (−y, x): the linear
    /// system solved order by order against its closed form by Cramer's
    /// rule (det = 2 + x²), written with quotients.
    #[test]
    fn a_linear_system_solved_order_by_order_matches_its_closed_form() {
        use Operand::{Const, State, Var};
        let solved = [
            TapeOp::Mul(State(0), State(0)),
            TapeOp::Add(Var(0), Const(1.0)),
            TapeOp::Mul(State(1), Const(-1.0)),
            TapeOp::Copy(Var(1)),
            TapeOp::Copy(State(0)),
            TapeOp::Copy(State(0)),
            TapeOp::Copy(Const(2.0)),
            TapeOp::Copy(Var(2)),
            TapeOp::Copy(State(0)),
            TapeOp::Solve { size: 2, first: 3 },
            TapeOp::SolvedWithPrevious,
        ];
        let closed = [
            TapeOp::Mul(State(0), State(0)),
            TapeOp::Add(Var(0), Const(2.0)),
            TapeOp::Mul(State(1), Const(-2.0)),
            TapeOp::Mul(Var(0), Const(-1.0)),
            TapeOp::Add(Var(2), Var(3)),
            TapeOp::Div(Var(4), Var(1)),
            TapeOp::Mul(State(0), State(1)),
            TapeOp::Mul(Var(0), State(0)),
            TapeOp::Add(Var(7), State(0)),
            TapeOp::Add(Var(8), Var(6)),
            TapeOp::Div(Var(9), Var(1)),
        ];
        let order = 12;
        let mut a = TaylorWork::new(&solved, &[Var(9), Var(10)], 2, order);
        let mut b = TaylorWork::new(&closed, &[Var(5), Var(10)], 2, order);
        for _ in 0..2 {
            a.compute(0.0, &[0.3, -0.7]);
            b.compute(0.0, &[0.3, -0.7]);
            for i in 0..2 {
                for (k, (x, y)) in a.state(i).iter().zip(b.state(i)).enumerate() {
                    assert!(
                        (x - y).abs() <= 1e-14 * y.abs().max(1e-3),
                        "state {i}, order {k}: {x} {y}"
                    );
                }
            }
        }
        // A singular E^[0] (all zero at x = 0 once 1 and 2 are taken out)
        // gives NaN, for the step rule to report.
        let mut degenerate = solved;
        degenerate[6] = TapeOp::Copy(Const(0.0));
        degenerate[3] = TapeOp::Copy(Const(0.0));
        let mut zero = TaylorWork::new(&degenerate, &[Var(9), Var(10)], 2, order);
        zero.compute(0.0, &[0.0, 1.0]);
        assert!(zero.state(0)[1].is_nan());
    }

    #[test]
    fn quotient_power_exp_and_log_recurrences() {
        // y' = exp(ln(y) * 0.5) / y = y^(-1/2) written three ways must agree:
        // pow, exp∘ln, and 1/sqrt.
        let a = [TapeOp::Pow(Operand::State(0), -0.5)];
        let b = [
            TapeOp::Ln(Operand::State(0)),
            TapeOp::Mul(Operand::Var(0), Operand::Const(-0.5)),
            TapeOp::Exp(Operand::Var(1)),
        ];
        let c = [
            TapeOp::Pow(Operand::State(0), 0.5),
            TapeOp::Div(Operand::Const(1.0), Operand::Var(0)),
        ];
        let run = |tape: &[TapeOp], out: Operand| {
            let mut work = TaylorWork::new(tape, &[out], 1, 12);
            work.compute(0.0, &[2.0]);
            work.state(0).to_vec()
        };
        let (ca, cb, cc) =
            (run(&a, Operand::Var(0)), run(&b, Operand::Var(2)), run(&c, Operand::Var(1)));
        // Exact: y = (y0^(3/2) + 3t/2)^(2/3); check the first coefficients and mutual agreement.
        assert!((ca[1] - 2f64.powf(-0.5)).abs() < 1e-15);
        for k in 0..=12 {
            assert!((ca[k] - cb[k]).abs() < 1e-13 * ca[k].abs().max(1e-300) + 1e-16);
            assert!((ca[k] - cc[k]).abs() < 1e-13 * ca[k].abs().max(1e-300) + 1e-16);
        }
        let h = 0.2;
        let sum: f64 = ca.iter().rev().fold(0.0, |acc, c| acc * h + c);
        let exact = (2f64.powf(1.5) + 1.5 * h).powf(2.0 / 3.0);
        assert!((sum - exact).abs() < 1e-12, "{sum} vs {exact}");
    }
}
