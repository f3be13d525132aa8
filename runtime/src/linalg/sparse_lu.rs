//! Sparse LU for the Newton matrices of the implicit methods when the
//! Jacobian is sparse but no renumbering gathers it in a narrow band (a
//! 2-D grid with periodic neighbours): the states are renumbered by
//! minimum degree on the symmetrised pattern (Tinney & Walker 1967; George
//! & Liu, "The evolution of the minimum degree ordering algorithm", SIAM
//! Review 31, 1989), whose elimination graph gives the fill once; each
//! factorisation is then Gaussian elimination row by row (the IKJ form)
//! inside that fixed pattern, on the diagonal pivots, as static-pivoting
//! sparse solvers do (SuperLU_DIST, Li & Demmel 2003). A pivot that is
//! zero, not finite or tiny beside its row makes the factorisation fail, so
//! that the caller falls back to a pivoting LU.
//!
//! RADAU5's complex system `((α + iβ)I − J) z = r` shares the pattern and
//! is factored in complex arithmetic.

use nalgebra::Complex;
use std::collections::BinaryHeap;
use std::ops::{Add, Div, Mul, Sub};
use std::sync::{Arc, Mutex};

/// The numbers a factorisation runs on: `f64` and `Complex<f64>`.
pub trait Scalar:
    Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> + Div<Output = Self>
{
    /// Zero.
    fn zero() -> Self;
    /// The real number `v`.
    fn from_real(v: f64) -> Self;
    /// |x|.
    fn magnitude(self) -> f64;
}

impl Scalar for f64 {
    fn zero() -> Self {
        0.0
    }
    fn from_real(v: f64) -> Self {
        v
    }
    fn magnitude(self) -> f64 {
        self.abs()
    }
}

impl Scalar for Complex<f64> {
    fn zero() -> Self {
        Complex::new(0.0, 0.0)
    }
    fn from_real(v: f64) -> Self {
        Complex::new(v, 0.0)
    }
    /// |re| + |im|: within √2 of the modulus, and no square root.
    fn magnitude(self) -> f64 {
        self.re.abs() + self.im.abs()
    }
}

/// A pivot below this fraction of its row's largest entry fails the
/// factorisation: without interchanges, growth would spoil the solve.
const PIVOT_THRESHOLD: f64 = 1e-10;

/// The fill pattern of `shift·I − J` under a minimum-degree renumbering:
/// rows of L and U together, compressed, in the new numbering.
#[derive(Clone, Debug)]
pub struct SparsePattern {
    /// `order[k]` is the state placed at position k.
    order: Vec<usize>,
    /// Row i's entries at `row_start[i]..row_start[i + 1]`.
    row_start: Vec<usize>,
    /// Their columns, ascending.
    columns: Vec<usize>,
    /// Where row i's diagonal is.
    diagonal: Vec<usize>,
    /// Where each entry of the Jacobian's pattern lands.
    slot_of_entry: Vec<usize>,
}

impl SparsePattern {
    /// [`SparsePattern::minimum_degree`] of a model's pattern, computed
    /// once per pattern and process: a run of a large model would otherwise
    /// spend a part of its time renumbering the same pattern again.
    pub fn of_model(n: usize, pattern: &'static [(usize, usize)]) -> Arc<SparsePattern> {
        // (states, the pattern's address and length) and its renumbering.
        type Found = Vec<((usize, usize, usize), Arc<SparsePattern>)>;
        static FOUND: Mutex<Found> = Mutex::new(Vec::new());
        let key = (n, pattern.as_ptr() as usize, pattern.len());
        let mut found = FOUND.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
        if let Some((_, p)) = found.iter().find(|(k, _)| *k == key) {
            return Arc::clone(p);
        }
        let p = Arc::new(SparsePattern::minimum_degree(n, pattern));
        found.push((key, Arc::clone(&p)));
        p
    }

    /// The minimum-degree renumbering of an n × n pattern (with the
    /// diagonal added) and its fill.
    pub fn minimum_degree(n: usize, pattern: &[(usize, usize)]) -> SparsePattern {
        // Adjacency lists of the symmetrised pattern, sorted.
        let mut graph: Vec<Vec<usize>> = vec![Vec::new(); n];
        for &(r, c) in pattern {
            if r != c && r < n && c < n {
                graph[r].push(c);
                graph[c].push(r);
            }
        }
        for list in &mut graph {
            list.sort_unstable();
            list.dedup();
        }
        // Eliminate the vertex of least degree (ties: the lowest index),
        // joining its neighbours into a clique; its neighbours then are its
        // row of U and its column of L.
        let mut heap: BinaryHeap<std::cmp::Reverse<(usize, usize)>> =
            (0..n).map(|v| std::cmp::Reverse((graph[v].len(), v))).collect();
        let mut eliminated = vec![false; n];
        let mut order = Vec::with_capacity(n);
        let mut upper: Vec<Vec<usize>> = Vec::with_capacity(n);
        let mut merged = Vec::new();
        while let Some(std::cmp::Reverse((degree, v))) = heap.pop() {
            if eliminated[v] || degree != graph[v].len() {
                continue;
            }
            eliminated[v] = true;
            order.push(v);
            let neighbours = std::mem::take(&mut graph[v]);
            for &u in &neighbours {
                // adj(u) ∪ neighbours, less u and v, by a merge of the two
                // sorted lists.
                merged.clear();
                let (mut a, mut b) = (graph[u].iter().peekable(), neighbours.iter().peekable());
                loop {
                    let next = match (a.peek(), b.peek()) {
                        (Some(&&x), Some(&&y)) if x < y => a.next(),
                        (Some(&&x), Some(&&y)) if x > y => b.next(),
                        (Some(_), Some(_)) => {
                            a.next();
                            b.next()
                        }
                        (Some(_), None) => a.next(),
                        (None, Some(_)) => b.next(),
                        (None, None) => break,
                    };
                    if let Some(&w) = next {
                        if w != u && w != v {
                            merged.push(w);
                        }
                    }
                }
                std::mem::swap(&mut graph[u], &mut merged);
                heap.push(std::cmp::Reverse((graph[u].len(), u)));
            }
            upper.push(neighbours);
        }
        let mut position = vec![0; n];
        for (k, &v) in order.iter().enumerate() {
            position[v] = k;
        }
        // Row i: the columns k < i whose U row holds i, the diagonal, and
        // its own U row.
        let mut rows: Vec<Vec<usize>> = vec![Vec::new(); n];
        for (k, neighbours) in upper.iter().enumerate() {
            for &v in neighbours {
                rows[position[v]].push(k);
            }
        }
        let mut row_start = Vec::with_capacity(n + 1);
        let (mut columns, mut diagonal) = (Vec::new(), Vec::with_capacity(n));
        for (i, lower) in rows.iter_mut().enumerate() {
            row_start.push(columns.len());
            lower.sort_unstable();
            columns.extend_from_slice(lower);
            diagonal.push(columns.len());
            columns.push(i);
            let mut own: Vec<usize> = upper[i].iter().map(|&v| position[v]).collect();
            own.sort_unstable();
            columns.extend(own);
        }
        row_start.push(columns.len());
        // Always found: an off-diagonal entry is an edge of the graph, and
        // eliminating the earlier of its ends puts it in the other's row.
        let slot = |r: usize, c: usize| -> usize {
            let (pr, pc) = (position[r], position[c]);
            let row = &columns[row_start[pr]..row_start[pr + 1]];
            row_start[pr] + row.binary_search(&pc).unwrap_or(0)
        };
        let slot_of_entry = pattern.iter().map(|&(r, c)| slot(r, c)).collect();
        SparsePattern { order, row_start, columns, diagonal, slot_of_entry }
    }

    /// The floating-point operations of one real factorisation.
    pub fn factor_operations(&self) -> f64 {
        let mut total = 0.0;
        for i in 0..self.order.len() {
            for &k in &self.columns[self.row_start[i]..self.diagonal[i]] {
                total += 2.0 * (self.row_start[k + 1] - self.diagonal[k]) as f64;
            }
        }
        total
    }

    /// The entries of L and U together.
    pub fn entries(&self) -> usize {
        self.columns.len()
    }
}

/// `shift·I − J` factored as L U within a [`SparsePattern`].
pub struct SparseLu<T> {
    lu: Vec<T>,
    /// Dense scratch row, indexed by column.
    work: Vec<T>,
    /// The right-hand side in the new numbering.
    x: Vec<T>,
}

impl<T: Scalar> SparseLu<T> {
    /// Storage for the matrices of `pattern`.
    pub fn new(pattern: &SparsePattern) -> SparseLu<T> {
        let n = pattern.order.len();
        SparseLu {
            lu: vec![T::zero(); pattern.entries()],
            work: vec![T::zero(); n],
            x: vec![T::zero(); n],
        }
    }

    /// Factors `shift·I − J`, with `jacobian(k)` the k-th entry of the
    /// Jacobian's pattern. `false` when a pivot fails.
    pub fn factor(
        &mut self,
        pattern: &SparsePattern,
        shift: T,
        jacobian: impl Fn(usize) -> f64,
    ) -> bool {
        let SparsePattern { row_start, columns, diagonal, slot_of_entry, .. } = pattern;
        self.lu.fill(T::zero());
        for (k, &slot) in slot_of_entry.iter().enumerate() {
            self.lu[slot] = self.lu[slot] - T::from_real(jacobian(k));
        }
        for &d in diagonal {
            self.lu[d] = self.lu[d] + shift;
        }
        let work = &mut self.work;
        for i in 0..diagonal.len() {
            let row = row_start[i]..row_start[i + 1];
            let mut largest = 0.0f64;
            for idx in row.clone() {
                work[columns[idx]] = self.lu[idx];
                largest = largest.max(self.lu[idx].magnitude());
            }
            for &k in &columns[row_start[i]..diagonal[i]] {
                let l = work[k] / self.lu[diagonal[k]];
                work[k] = l;
                let row_of_u = diagonal[k] + 1..row_start[k + 1];
                for (&j, &u) in columns[row_of_u.clone()].iter().zip(&self.lu[row_of_u]) {
                    work[j] = work[j] - l * u;
                }
            }
            let pivot = work[i].magnitude();
            if !pivot.is_finite() || pivot == 0.0 || pivot < PIVOT_THRESHOLD * largest {
                return false;
            }
            for idx in row {
                self.lu[idx] = work[columns[idx]];
            }
        }
        true
    }

    /// Solves `(shift·I − J) x = b` in place; `b` in the states' numbering.
    pub fn solve(&mut self, pattern: &SparsePattern, b: &mut [T]) {
        let SparsePattern { order, row_start, columns, diagonal, .. } = pattern;
        let x = &mut self.x;
        for (xk, &v) in x.iter_mut().zip(order) {
            *xk = b[v];
        }
        for i in 0..order.len() {
            let mut v = x[i];
            for idx in row_start[i]..diagonal[i] {
                v = v - self.lu[idx] * x[columns[idx]];
            }
            x[i] = v;
        }
        for i in (0..order.len()).rev() {
            let mut v = x[i];
            for idx in diagonal[i] + 1..row_start[i + 1] {
                v = v - self.lu[idx] * x[columns[idx]];
            }
            x[i] = v / self.lu[diagonal[i]];
        }
        for (xk, &v) in x.iter().zip(order) {
            b[v] = *xk;
        }
    }
}

/// The complex factorisation and its scratch right-hand side.
type ComplexPart = (SparseLu<Complex<f64>>, Vec<Complex<f64>>);

/// The Newton matrices of the implicit methods in sparse form: `γ·I − J`
/// and, for RADAU5, `(α + iβ)·I − J`, in one [`SparsePattern`].
pub struct SparseNewton {
    pattern: Arc<SparsePattern>,
    real: SparseLu<f64>,
    /// The complex matrix and its scratch, where the method has one.
    complex: Option<ComplexPart>,
}

impl SparseNewton {
    /// Storage for the matrices of `pattern`, the complex one only if
    /// `complex`.
    pub fn new(pattern: Arc<SparsePattern>, complex: bool) -> SparseNewton {
        let n = pattern.order.len();
        SparseNewton {
            real: SparseLu::new(&pattern),
            complex: complex.then(|| (SparseLu::new(&pattern), vec![Complex::new(0.0, 0.0); n])),
            pattern,
        }
    }

    /// The number of states.
    pub fn states(&self) -> usize {
        self.pattern.order.len()
    }

    /// Whether the complex matrix is kept.
    pub fn has_complex(&self) -> bool {
        self.complex.is_some()
    }

    /// Factors the matrices, `jacobian(k)` the k-th entry of the pattern
    /// (`alpha`, `beta` unused without the complex one). `false` when a
    /// pivot fails.
    pub fn factor(
        &mut self,
        gamma: f64,
        alpha: f64,
        beta: f64,
        jacobian: impl Fn(usize) -> f64,
    ) -> bool {
        self.real.factor(&self.pattern, gamma, &jacobian)
            && self.complex.as_mut().is_none_or(|(complex, _)| {
                complex.factor(&self.pattern, Complex::new(alpha, beta), &jacobian)
            })
    }

    /// Solves `(γI − J) x = b` in place.
    pub fn solve_real(&mut self, b: &mut [f64]) {
        self.real.solve(&self.pattern, b);
    }

    /// Solves `((α + iβ)I − J)(x + iy) = b_re + i·b_im` in place (nothing
    /// without the complex matrix).
    pub fn solve_complex(&mut self, b_re: &mut [f64], b_im: &mut [f64]) {
        let Some((complex, scratch)) = &mut self.complex else { return };
        for ((s, re), im) in scratch.iter_mut().zip(b_re.iter()).zip(b_im.iter()) {
            *s = Complex::new(*re, *im);
        }
        complex.solve(&self.pattern, scratch);
        for ((s, re), im) in scratch.iter().zip(b_re.iter_mut()).zip(b_im.iter_mut()) {
            (*re, *im) = (s.re, s.im);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linalg::dense_lu::{ComplexLu, RealLu};

    /// A deterministic pseudo-random number in [-1, 1).
    fn uniform(seed: &mut u64) -> f64 {
        *seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        2.0 * ((*seed >> 11) as f64 / (1u64 << 53) as f64) - 1.0
    }

    /// The five-point Laplacian's pattern on an m × m periodic grid, two
    /// species a cell, each coupled to the other in its cell.
    fn periodic_grid(m: usize) -> (usize, Vec<(usize, usize)>) {
        let cells = m * m;
        let mut pattern = Vec::new();
        for i in 0..m {
            for j in 0..m {
                let k = i * m + j;
                let around = [
                    k,
                    ((i + 1) % m) * m + j,
                    ((i + m - 1) % m) * m + j,
                    i * m + (j + 1) % m,
                    i * m + (j + m - 1) % m,
                ];
                for s in 0..2 {
                    for &a in &around {
                        pattern.push((s * cells + k, s * cells + a));
                    }
                    pattern.push((s * cells + k, (1 - s) * cells + k));
                }
            }
        }
        (2 * cells, pattern)
    }

    #[test]
    fn factors_a_periodic_grid_as_dense_lu_does() {
        let (n, pattern) = periodic_grid(6);
        let mut seed = 7;
        let values: Vec<f64> = pattern.iter().map(|_| uniform(&mut seed)).collect();
        let mut dense = vec![0.0; n * n];
        for (&(r, c), &v) in pattern.iter().zip(&values) {
            dense[r * n + c] += v;
        }
        let sparse = SparsePattern::minimum_degree(n, &pattern);
        let mut newton = SparseNewton::new(Arc::new(sparse), true);
        let (gamma, alpha, beta) = (8.0, 6.0, 3.0);
        assert!(newton.factor(gamma, alpha, beta, |k| values[k]));
        let mut real = RealLu::new(n);
        let mut complex = ComplexLu::new(n);
        assert!(real.factor_shifted_mass(gamma, &[], &dense));
        assert!(complex.factor_shifted_mass(alpha, beta, &[], &dense));
        let b: Vec<f64> = (0..n).map(|_| uniform(&mut seed)).collect();
        let c: Vec<f64> = (0..n).map(|_| uniform(&mut seed)).collect();
        let (mut x, mut y) = (b.clone(), b.clone());
        newton.solve_real(&mut x);
        real.solve(&mut y);
        let (mut xr, mut xi, mut yr, mut yi) = (b.clone(), c.clone(), b.clone(), c.clone());
        newton.solve_complex(&mut xr, &mut xi);
        complex.solve(&mut yr, &mut yi);
        for k in 0..n {
            assert!((x[k] - y[k]).abs() <= 1e-13, "real, {k}: {} against {}", x[k], y[k]);
            assert!(
                (xr[k] - yr[k]).abs() <= 1e-13 && (xi[k] - yi[k]).abs() <= 1e-13,
                "complex, {k}"
            );
        }
    }

    #[test]
    fn minimum_degree_fills_less_than_the_band_of_a_periodic_grid() {
        let (n, pattern) = periodic_grid(16);
        let sparse = SparsePattern::minimum_degree(n, &pattern);
        let band = crate::linalg::band_lu::BandOrdering::reverse_cuthill_mckee(n, &pattern);
        let band_entries = n * (2 * band.lower + band.upper + 1);
        assert!(sparse.entries() * 4 < band_entries, "{} against {band_entries}", sparse.entries());
    }

    #[test]
    fn a_zero_pivot_fails_instead_of_dividing_by_it() {
        // [[0, 1], [1, 0]] needs an interchange.
        let pattern = [(0, 1), (1, 0)];
        let sparse = SparsePattern::minimum_degree(2, &pattern);
        let mut lu = SparseLu::<f64>::new(&sparse);
        assert!(!lu.factor(&sparse, 0.0, |_| -1.0));
    }
}
