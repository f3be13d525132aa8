//! Summing a Taylor series step: `y(t + h) ≈ y + h y' + h²/2! y'' + … +
//! hᵖ/p! y⁽ᵖ⁾` (course notes §1.3.1, the economic Taylor scheme).

/// Writes `y + Σ_{k=1..p} h^k/k! · derivatives[k-1]` into `out`, by Horner's
/// rule (`y + h(y' + h/2 (y'' + h/3 (y''' + …)))`), which needs no factorials
/// and loses less accuracy than summing powers of `h`.
///
/// `derivatives` holds `y'`, `y''`, … `y⁽ᵖ⁾` one after another, each as
/// long as `y` (the layout the generated `taylor_derivatives` writes).
///
/// ```
/// use daegen_runtime::taylor_series::taylor_step;
/// // y' = y, y(0) = 1: every derivative is 1; order 3 gives 1 + h + h²/2 + h³/6.
/// let mut out = [0.0];
/// taylor_step(&[1.0], &[1.0, 1.0, 1.0], 0.5, &mut out);
/// let expected = 1.0 + 0.5 + 0.5f64.powi(2) / 2.0 + 0.5f64.powi(3) / 6.0;
/// assert!((out[0] - expected).abs() < 1e-15);
/// ```
pub fn taylor_step(y: &[f64], derivatives: &[f64], h: f64, out: &mut [f64]) {
    let n = y.len();
    let p = derivatives.len().checked_div(n).unwrap_or(0);
    for (i, o) in out.iter_mut().enumerate().take(n) {
        let mut acc = 0.0;
        for k in (1..=p).rev() {
            acc = h / k as f64 * (derivatives[(k - 1) * n + i] + acc);
        }
        *o = y[i] + acc;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polynomials_of_degree_p_are_reproduced_exactly() {
        // y = 1 + 2t + 3t² + 4t³ at t = 0: y' = 2, y'' = 6, y''' = 24.
        let mut out = [0.0];
        let h = 0.75;
        taylor_step(&[1.0], &[2.0, 6.0, 24.0], h, &mut out);
        assert_eq!(out[0], 1.0 + 2.0 * h + 3.0 * h * h + 4.0 * h * h * h);
    }

    #[test]
    fn exponential_error_is_the_neglected_tail() {
        // y' = y, y(0) = 1: the step of order p misses exactly Σ_{k>p} h^k/k!.
        let h = 0.1;
        for p in 1..=6 {
            let ones = vec![1.0; p];
            let mut out = [0.0];
            taylor_step(&[1.0], &ones, h, &mut out);
            let tail: f64 = (p + 1..30)
                .map(|k| h.powi(k as i32) / (1..=k).map(|j| j as f64).product::<f64>())
                .sum();
            let error = h.exp() - out[0];
            assert!(
                (error - tail).abs() < 1e-15 + 1e-9 * tail,
                "p = {p}: error {error:e}, tail {tail:e}"
            );
        }
    }

    #[test]
    fn each_component_uses_its_own_derivatives() {
        let mut out = [0.0; 2];
        taylor_step(&[1.0, 2.0], &[1.0, -1.0], 0.5, &mut out);
        assert_eq!(out, [1.5, 1.5]);
    }
}
