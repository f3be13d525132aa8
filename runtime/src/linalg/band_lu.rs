//! Banded LU for the Newton matrices of the implicit methods when the
//! Jacobian is sparse: the states are renumbered by reverse Cuthill–McKee
//! (Cuthill & McKee 1969; George & Liu, "Computer Solution of Large Sparse
//! Positive Definite Systems", 1981, §4.3) so that the non-zeros gather in a
//! narrow band, and the band is factored with partial pivoting as LAPACK's
//! `dgbtrf`/`dgbtrs` do: O(n·kl·(kl + ku)) per factorisation and
//! O(n·(2kl + ku)) per solve instead of O(n³) and O(n²). A chain of 100
//! masses (200 states) spent 92 % of RADAU5's time in dense LU.
//!
//! The complex systems of RADAU5, `((α + iβ)I − J) z = r`, are solved in
//! their real form with the real and imaginary part of each unknown side by
//! side, which keeps the band (twice as wide).

/// A renumbering of the states that narrows the band of a sparsity pattern.
#[derive(Clone, Debug)]
pub struct BandOrdering {
    /// `order[k]` is the state placed at position k.
    pub order: Vec<usize>,
    /// Lower bandwidth of the renumbered pattern.
    pub lower: usize,
    /// Upper bandwidth of the renumbered pattern.
    pub upper: usize,
}

impl BandOrdering {
    /// Reverse Cuthill–McKee on the symmetrised pattern of an n × n matrix
    /// with non-zeros at `pattern` (row, column); each connected component
    /// starts from a vertex of least degree.
    pub fn reverse_cuthill_mckee(n: usize, pattern: &[(usize, usize)]) -> BandOrdering {
        let mut neighbours: Vec<Vec<usize>> = vec![Vec::new(); n];
        for &(r, c) in pattern {
            if r != c && r < n && c < n {
                neighbours[r].push(c);
                neighbours[c].push(r);
            }
        }
        for list in &mut neighbours {
            list.sort_unstable();
            list.dedup();
        }
        let degree = |v: usize| neighbours[v].len();
        let mut placed = vec![false; n];
        let mut order = Vec::with_capacity(n);
        let mut by_degree: Vec<usize> = (0..n).collect();
        by_degree.sort_by_key(|&v| (degree(v), v));
        for &start in &by_degree {
            if placed[start] {
                continue;
            }
            placed[start] = true;
            let mut head = order.len();
            order.push(start);
            while head < order.len() {
                let v = order[head];
                head += 1;
                let mut next: Vec<usize> =
                    neighbours[v].iter().copied().filter(|&u| !placed[u]).collect();
                next.sort_by_key(|&u| (degree(u), u));
                for u in next {
                    placed[u] = true;
                    order.push(u);
                }
            }
        }
        order.reverse();
        let mut position = vec![0; n];
        for (k, &v) in order.iter().enumerate() {
            position[v] = k;
        }
        let (mut lower, mut upper) = (0, 0);
        for &(r, c) in pattern {
            if r < n && c < n {
                let (pr, pc) = (position[r], position[c]);
                lower = lower.max(pr.saturating_sub(pc));
                upper = upper.max(pc.saturating_sub(pr));
            }
        }
        BandOrdering { order, lower, upper }
    }

    /// Whether banded factorisation beats the dense one for n states: the
    /// band, with the fill of pivoting, is under a quarter of the matrix.
    pub fn pays(&self) -> bool {
        let n = self.order.len();
        4 * (2 * self.lower + self.upper + 1) < n
    }
}

/// `P A = L U` of an n × n band matrix with `kl` sub- and `ku`
/// super-diagonals; row i keeps columns i − kl ..= i + ku + kl (the extra
/// kl for the fill of row interchanges).
pub struct BandLu {
    n: usize,
    kl: usize,
    ku: usize,
    a: Vec<f64>,
    pivots: Vec<usize>,
}

impl BandLu {
    /// Storage for n × n matrices with the given bandwidths.
    pub fn new(n: usize, kl: usize, ku: usize) -> BandLu {
        BandLu { n, kl, ku, a: vec![0.0; n * (2 * kl + ku + 1)], pivots: vec![0; n] }
    }

    fn width(&self) -> usize {
        2 * self.kl + self.ku + 1
    }

    fn at(&self, i: usize, j: usize) -> usize {
        i * self.width() + (j + self.kl - i)
    }

    /// Columns row i may hold after elimination.
    fn columns(&self, i: usize) -> std::ops::Range<usize> {
        i.saturating_sub(self.kl)..(i + self.ku + self.kl + 1).min(self.n)
    }

    /// Sets the matrix to `entry(i, j)` for the (i, j) inside the band
    /// (entries outside it must be zero) and factors it. `false` when a
    /// pivot is zero or not finite.
    pub fn factor(&mut self, entry: impl Fn(usize, usize) -> f64) -> bool {
        self.a.iter_mut().for_each(|v| *v = 0.0);
        for i in 0..self.n {
            let band = i.saturating_sub(self.kl)..(i + self.ku + 1).min(self.n);
            for j in band {
                let at = self.at(i, j);
                self.a[at] = entry(i, j);
            }
        }
        let n = self.n;
        for col in 0..n {
            let last = (col + self.kl).min(n - 1);
            let pivot = (col..=last)
                .max_by(|&x, &y| {
                    let (ax, ay) = (self.a[self.at(x, col)], self.a[self.at(y, col)]);
                    ax.abs().total_cmp(&ay.abs())
                })
                .unwrap_or(col);
            self.pivots[col] = pivot;
            let right = self.columns(col).end;
            if pivot != col {
                for j in col..right {
                    let (p, c) = (self.at(pivot, j), self.at(col, j));
                    self.a.swap(p, c);
                }
            }
            let p = self.a[self.at(col, col)];
            if p == 0.0 || !p.is_finite() {
                return false;
            }
            for row in col + 1..=last {
                let at = self.at(row, col);
                let factor = self.a[at] / p;
                self.a[at] = factor;
                if factor != 0.0 {
                    for j in col + 1..right {
                        let (r, c) = (self.at(row, j), self.at(col, j));
                        self.a[r] -= factor * self.a[c];
                    }
                }
            }
        }
        true
    }

    /// Solves `A x = b` in place with the last factorisation.
    pub fn solve(&self, b: &mut [f64]) {
        let n = self.n;
        for col in 0..n {
            b.swap(col, self.pivots[col]);
            let last = (col + self.kl).min(n - 1);
            let x = b[col];
            for row in col + 1..=last {
                b[row] -= self.a[self.at(row, col)] * x;
            }
        }
        for row in (0..n).rev() {
            let mut v = b[row];
            for j in row + 1..self.columns(row).end {
                v -= self.a[self.at(row, j)] * b[j];
            }
            b[row] = v / self.a[self.at(row, row)];
        }
    }
}

/// Entry (i, j) of a matrix stored by [`BandNewton::load`] (row i's
/// columns i − kl ..= i + ku), zero outside the band.
fn band_entry(band: &[f64], kl: usize, ku: usize) -> impl Fn(usize, usize) -> f64 + '_ {
    move |i, j| {
        if j + kl < i || j > i + ku {
            0.0
        } else {
            band[i * (kl + ku + 1) + j + kl - i]
        }
    }
}

/// The Newton matrices of the implicit methods in banded form: `γ·I − J`
/// and, for RADAU5, `(α + iβ)·I − J` in real form, both in the order of a
/// [`BandOrdering`].
pub struct BandNewton {
    ordering: BandOrdering,
    /// `position[state]`: where the ordering places it.
    position: Vec<usize>,
    /// J renumbered, row i's columns i − kl ..= i + ku.
    jacobian: Vec<f64>,
    real: BandLu,
    /// The complex matrix in real form, where the method has one.
    complex: Option<BandLu>,
    scratch: Vec<f64>,
}

impl BandNewton {
    /// Storage for the matrices of `ordering`, the complex one only if
    /// `complex`.
    pub fn new(ordering: BandOrdering, complex: bool) -> BandNewton {
        let n = ordering.order.len();
        let (kl, ku) = (ordering.lower, ordering.upper);
        let mut position = vec![0; n];
        for (k, &v) in ordering.order.iter().enumerate() {
            position[v] = k;
        }
        BandNewton {
            real: BandLu::new(n, kl, ku),
            complex: complex.then(|| BandLu::new(2 * n, 2 * kl + 1, 2 * ku + 1)),
            scratch: vec![0.0; 2 * n],
            jacobian: vec![0.0; n * (kl + ku + 1)],
            position,
            ordering,
        }
    }

    /// Renumbers J, given as `values` at `pattern` (the generated
    /// Jacobian's non-zeros), into the band.
    fn load(&mut self, pattern: &[(usize, usize)], values: &[f64]) {
        let (kl, ku) = (self.ordering.lower, self.ordering.upper);
        self.jacobian.fill(0.0);
        for (&(r, c), &v) in pattern.iter().zip(values) {
            let (i, j) = (self.position[r], self.position[c]);
            self.jacobian[i * (kl + ku + 1) + j + kl - i] += v;
        }
    }

    /// Factors `γ·I − J`, J given as `values` at `pattern`. `false` if
    /// singular.
    pub fn factor_real(&mut self, gamma: f64, pattern: &[(usize, usize)], values: &[f64]) -> bool {
        self.load(pattern, values);
        let entry = band_entry(&self.jacobian, self.ordering.lower, self.ordering.upper);
        self.real.factor(|i, j| if i == j { gamma } else { 0.0 } - entry(i, j))
    }

    /// Whether the complex matrix is kept.
    pub fn has_complex(&self) -> bool {
        self.complex.is_some()
    }

    /// Factors `(α + iβ)·I − J` for the J of the last
    /// [`BandNewton::factor_real`]. `false` if singular or not kept.
    pub fn factor_complex(&mut self, alpha: f64, beta: f64) -> bool {
        let entry = band_entry(&self.jacobian, self.ordering.lower, self.ordering.upper);
        let Some(complex) = &mut self.complex else { return false };
        // Unknown k's real part at 2k, its imaginary part at 2k + 1:
        // [[αI − J, −βI], [βI, αI − J]] interleaved.
        complex.factor(|i, j| {
            let (k, l) = (i / 2, j / 2);
            let a = if k == l { alpha } else { 0.0 } - entry(k, l);
            let b = if k == l { beta } else { 0.0 };
            match (i % 2, j % 2) {
                (0, 0) | (1, 1) => a,
                (0, _) => -b,
                _ => b,
            }
        })
    }

    /// Solves `(γI − J) x = b` in place.
    pub fn solve_real(&mut self, b: &mut [f64]) {
        let order = &self.ordering.order;
        let x = &mut self.scratch[..order.len()];
        for (xk, &v) in x.iter_mut().zip(order) {
            *xk = b[v];
        }
        self.real.solve(x);
        for (xk, &v) in x.iter().zip(order) {
            b[v] = *xk;
        }
    }

    /// Solves `((α + iβ)I − J)(x + iy) = b_re + i·b_im` in place (nothing
    /// without the complex matrix).
    pub fn solve_complex(&mut self, b_re: &mut [f64], b_im: &mut [f64]) {
        let Some(complex) = &self.complex else { return };
        let order = &self.ordering.order;
        for (k, &v) in order.iter().enumerate() {
            self.scratch[2 * k] = b_re[v];
            self.scratch[2 * k + 1] = b_im[v];
        }
        complex.solve(&mut self.scratch);
        for (k, &v) in order.iter().enumerate() {
            b_re[v] = self.scratch[2 * k];
            b_im[v] = self.scratch[2 * k + 1];
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

    /// The Jacobian pattern of a chain of masses in (q, q') order: q_i' =
    /// v_i, v_i' depends on q_{i−1}, q_i, q_{i+1} and v_i. Dense bandwidth
    /// m; after RCM a handful.
    fn chain(m: usize) -> (usize, Vec<(usize, usize)>) {
        let mut pattern = Vec::new();
        for i in 0..m {
            pattern.push((i, m + i));
            for j in i.saturating_sub(1)..(i + 2).min(m) {
                pattern.push((m + i, j));
            }
            pattern.push((m + i, m + i));
        }
        (2 * m, pattern)
    }

    #[test]
    fn reverse_cuthill_mckee_narrows_a_chain_to_a_few_diagonals() {
        let (n, pattern) = chain(100);
        let ordering = BandOrdering::reverse_cuthill_mckee(n, &pattern);
        let mut sorted = ordering.order.clone();
        sorted.sort_unstable();
        assert_eq!(sorted, (0..n).collect::<Vec<_>>(), "a permutation");
        assert!(ordering.lower <= 3 && ordering.upper <= 3, "{ordering:?}");
        assert!(ordering.pays());
        // A dense pattern does not pay.
        let full: Vec<_> = (0..6).flat_map(|i| (0..6).map(move |j| (i, j))).collect();
        assert!(!BandOrdering::reverse_cuthill_mckee(6, &full).pays());
    }

    #[test]
    fn banded_solves_agree_with_dense_lu_on_random_sparse_jacobians() {
        let (n, pattern) = chain(30);
        let ordering = BandOrdering::reverse_cuthill_mckee(n, &pattern);
        let mut newton = BandNewton::new(ordering, true);
        let (mut dense_real, mut dense_complex) = (RealLu::new(n), ComplexLu::new(n));
        let mut seed = 11;
        for _ in 0..20 {
            let values: Vec<f64> = pattern.iter().map(|_| 10.0 * uniform(&mut seed)).collect();
            let mut jacobian = vec![0.0; n * n];
            for (&(r, c), &v) in pattern.iter().zip(&values) {
                jacobian[r * n + c] = v;
            }
            // Small shifts: pivoting is needed.
            let (gamma, alpha, beta) = (0.3, 0.2, 0.4);
            assert!(newton.factor_real(gamma, &pattern, &values));
            assert!(dense_real.factor_shifted(gamma, &jacobian));
            assert!(newton.factor_complex(alpha, beta));
            assert!(dense_complex.factor_shifted(alpha, beta, &jacobian));
            let b: Vec<f64> = (0..n).map(|_| uniform(&mut seed)).collect();
            let (mut x_band, mut x_dense) = (b.clone(), b.clone());
            newton.solve_real(&mut x_band);
            dense_real.solve(&mut x_dense);
            let scale = x_dense.iter().fold(1.0f64, |m, v| m.max(v.abs()));
            for (u, v) in x_band.iter().zip(&x_dense) {
                assert!((u - v).abs() <= 1e-10 * scale, "real: {u} vs {v}");
            }
            let c: Vec<f64> = (0..n).map(|_| uniform(&mut seed)).collect();
            let (mut re_band, mut im_band) = (b.clone(), c.clone());
            let (mut re_dense, mut im_dense) = (b.clone(), c.clone());
            newton.solve_complex(&mut re_band, &mut im_band);
            dense_complex.solve(&mut re_dense, &mut im_dense);
            let scale = re_dense.iter().chain(&im_dense).fold(1.0f64, |m, v| m.max(v.abs()));
            for (u, v) in re_band.iter().chain(&im_band).zip(re_dense.iter().chain(&im_dense)) {
                assert!((u - v).abs() <= 1e-10 * scale, "complex: {u} vs {v}");
            }
        }
    }

    #[test]
    fn a_singular_band_matrix_is_refused() {
        let mut lu = BandLu::new(3, 1, 1);
        assert!(!lu.factor(|i, j| if i == 2 || j == 2 { 0.0 } else { 1.0 }));
    }
}
