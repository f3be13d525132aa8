//! Dense LU factorisations with partial pivoting, real and complex, whose
//! storage is allocated once and reused for every refactorisation: the
//! stiff solvers factor `γ/h·I − J` many times per run and must not allocate
//! in the step loop.

/// `P A = L U` of a real n × n matrix, in place.
pub struct RealLu {
    n: usize,
    a: Vec<f64>,
    pivots: Vec<usize>,
}

impl RealLu {
    /// Storage for n × n matrices.
    pub fn new(n: usize) -> RealLu {
        RealLu { n, a: vec![0.0; n * n], pivots: vec![0; n] }
    }

    /// Factors `shift·I − J` (J row-major). `false` when a pivot is zero.
    pub fn factor_shifted(&mut self, shift: f64, jacobian: &[f64]) -> bool {
        self.factor_shifted_mass(shift, &[], jacobian)
    }

    /// Factors `shift·M − J` for a mass matrix `M`: empty for I, n values
    /// for a diagonal, n × n (row-major) for a general one.
    pub fn factor_shifted_mass(&mut self, shift: f64, mass: &[f64], jacobian: &[f64]) -> bool {
        let n = self.n;
        for (dst, src) in self.a.iter_mut().zip(jacobian) {
            *dst = -src;
        }
        if mass.len() == n * n && n > 1 {
            for (dst, m) in self.a.iter_mut().zip(mass) {
                *dst += shift * m;
            }
        } else {
            for i in 0..n {
                self.a[i * n + i] += shift * mass.get(i).copied().unwrap_or(1.0);
            }
        }
        self.factor()
    }

    fn factor(&mut self) -> bool {
        let n = self.n;
        for col in 0..n {
            let pivot = (col..n)
                .max_by(|&x, &y| self.a[x * n + col].abs().total_cmp(&self.a[y * n + col].abs()))
                .unwrap_or(col);
            self.pivots[col] = pivot;
            if pivot != col {
                for k in 0..n {
                    self.a.swap(col * n + k, pivot * n + k);
                }
            }
            let p = self.a[col * n + col];
            if p == 0.0 || !p.is_finite() {
                return false;
            }
            for row in col + 1..n {
                let factor = self.a[row * n + col] / p;
                self.a[row * n + col] = factor;
                if factor != 0.0 {
                    for k in col + 1..n {
                        self.a[row * n + k] -= factor * self.a[col * n + k];
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
        }
        for row in 0..n {
            let l = &self.a[row * n..row * n + row];
            b[row] -= l.iter().zip(&b[..row]).map(|(l, x)| l * x).sum::<f64>();
        }
        for row in (0..n).rev() {
            let u = &self.a[row * n + row + 1..(row + 1) * n];
            let v = b[row] - u.iter().zip(&b[row + 1..]).map(|(u, x)| u * x).sum::<f64>();
            b[row] = v / self.a[row * n + row];
        }
    }
}

/// `P A = L U` of a complex n × n matrix, real and imaginary parts stored apart.
pub struct ComplexLu {
    n: usize,
    re: Vec<f64>,
    im: Vec<f64>,
    pivots: Vec<usize>,
}

impl ComplexLu {
    /// Storage for n × n matrices.
    pub fn new(n: usize) -> ComplexLu {
        ComplexLu { n, re: vec![0.0; n * n], im: vec![0.0; n * n], pivots: vec![0; n] }
    }

    /// Factors `(α + iβ)·I − J`. `false` when a pivot is zero.
    pub fn factor_shifted(&mut self, alpha: f64, beta: f64, jacobian: &[f64]) -> bool {
        self.factor_shifted_mass(alpha, beta, &[], jacobian)
    }

    /// Factors `(α + iβ)·M − J` for a mass matrix `M` as
    /// [`RealLu::factor_shifted_mass`] takes it.
    pub fn factor_shifted_mass(
        &mut self,
        alpha: f64,
        beta: f64,
        mass: &[f64],
        jacobian: &[f64],
    ) -> bool {
        let n = self.n;
        for (dst, src) in self.re.iter_mut().zip(jacobian) {
            *dst = -src;
        }
        self.im.iter_mut().for_each(|v| *v = 0.0);
        if mass.len() == n * n && n > 1 {
            for (k, &m) in mass.iter().enumerate() {
                self.re[k] += alpha * m;
                self.im[k] = beta * m;
            }
        } else {
            for i in 0..n {
                let m = mass.get(i).copied().unwrap_or(1.0);
                self.re[i * n + i] += alpha * m;
                self.im[i * n + i] = beta * m;
            }
        }
        for col in 0..n {
            let magnitude = |k: usize| self.re[k * n + col].hypot(self.im[k * n + col]);
            let pivot =
                (col..n).max_by(|&x, &y| magnitude(x).total_cmp(&magnitude(y))).unwrap_or(col);
            self.pivots[col] = pivot;
            if pivot != col {
                for k in 0..n {
                    self.re.swap(col * n + k, pivot * n + k);
                    self.im.swap(col * n + k, pivot * n + k);
                }
            }
            let (pr, pi) = (self.re[col * n + col], self.im[col * n + col]);
            let d = pr * pr + pi * pi;
            if d == 0.0 || !d.is_finite() {
                return false;
            }
            for row in col + 1..n {
                let (ar, ai) = (self.re[row * n + col], self.im[row * n + col]);
                // factor = a / p
                let (fr, fi) = ((ar * pr + ai * pi) / d, (ai * pr - ar * pi) / d);
                self.re[row * n + col] = fr;
                self.im[row * n + col] = fi;
                if fr != 0.0 || fi != 0.0 {
                    for k in col + 1..n {
                        let (cr, ci) = (self.re[col * n + k], self.im[col * n + k]);
                        self.re[row * n + k] -= fr * cr - fi * ci;
                        self.im[row * n + k] -= fr * ci + fi * cr;
                    }
                }
            }
        }
        true
    }

    /// Solves `A (x + iy) = b_re + i b_im` in place.
    pub fn solve(&self, b_re: &mut [f64], b_im: &mut [f64]) {
        let n = self.n;
        for col in 0..n {
            b_re.swap(col, self.pivots[col]);
            b_im.swap(col, self.pivots[col]);
        }
        for row in 0..n {
            let (mut vr, mut vi) = (b_re[row], b_im[row]);
            for k in 0..row {
                let (lr, li) = (self.re[row * n + k], self.im[row * n + k]);
                vr -= lr * b_re[k] - li * b_im[k];
                vi -= lr * b_im[k] + li * b_re[k];
            }
            b_re[row] = vr;
            b_im[row] = vi;
        }
        for row in (0..n).rev() {
            let (mut vr, mut vi) = (b_re[row], b_im[row]);
            for k in row + 1..n {
                let (ur, ui) = (self.re[row * n + k], self.im[row * n + k]);
                vr -= ur * b_re[k] - ui * b_im[k];
                vi -= ur * b_im[k] + ui * b_re[k];
            }
            let (pr, pi) = (self.re[row * n + row], self.im[row * n + row]);
            let d = pr * pr + pi * pi;
            b_re[row] = (vr * pr + vi * pi) / d;
            b_im[row] = (vi * pr - vr * pi) / d;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn real_solve_with_pivoting() {
        // (3I - J) x = b with J chosen so that the first pivot is small.
        let j = [3.0, 1.0, 2.0, 1.0, 2.0, 1.0, 0.0, 4.0, 3.0];
        let mut lu = RealLu::new(3);
        assert!(lu.factor_shifted(3.0, &j));
        // A = 3I - J = [[0,-1,-2],[-1,1,-1],[0,-4,0]]; x = (1, 2, 3) → b = A x.
        let mut b = [-8.0, -2.0, -8.0];
        lu.solve(&mut b);
        for (x, want) in b.iter().zip([1.0, 2.0, 3.0]) {
            assert!((x - want).abs() < 1e-14, "{b:?}");
        }
        assert!(!lu.factor_shifted(0.0, &[0.0; 9]));
    }

    #[test]
    fn complex_solve_matches_the_real_block_form() {
        // ((α + iβ) I − J) z = r checked through the real 2n × 2n block
        // [[αI − J, −βI], [βI, αI − J]] acting on (Re z, Im z).
        let j = [1.0, -2.0, 0.5, 3.0];
        let (alpha, beta) = (2.0, 1.5);
        let mut lu = ComplexLu::new(2);
        assert!(lu.factor_shifted(alpha, beta, &j));
        let (mut re, mut im) = ([1.0, -1.0], [0.5, 2.0]);
        let (r0, i0) = (re, im);
        lu.solve(&mut re, &mut im);
        for row in 0..2 {
            let mut out_re = -beta * im[row];
            let mut out_im = beta * re[row];
            for k in 0..2 {
                let a = if row == k { alpha } else { 0.0 } - j[row * 2 + k];
                out_re += a * re[k];
                out_im += a * im[k];
            }
            assert!((out_re - r0[row]).abs() < 1e-14 && (out_im - i0[row]).abs() < 1e-14);
        }
    }
}
