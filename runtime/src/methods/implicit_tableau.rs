//! Implicit Runge–Kutta tableaux as data: implicit Euler and the 3-stage
//! Radau IIA method behind RADAU5 (Hairer & Wanner, *Solving ODEs II*,
//! §IV.5, Table 5.6). Their orders are proved in the tests through
//! Butcher's simplifying assumptions B(p), C(η), D(ζ).

/// A full (implicit) Butcher tableau, row-major `a`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImplicitTableau {
    /// Name for messages.
    pub name: &'static str,
    /// Classical order.
    pub order: usize,
    /// Stage order (η in C(η)).
    pub stage_order: usize,
    /// Rows of A, each with s entries.
    pub a: &'static [&'static [f64]],
    /// Weights.
    pub b: &'static [f64],
    /// Nodes.
    pub c: &'static [f64],
}

/// Implicit (backward) Euler: y₁ = y₀ + h f(x₁, y₁).
pub const IMPLICIT_EULER: ImplicitTableau = ImplicitTableau {
    name: "implicit Euler",
    order: 1,
    stage_order: 1,
    a: &[&[1.0]],
    b: &[1.0],
    c: &[1.0],
};

const S6: f64 = 2.449_489_742_783_178;

/// Radau IIA, 3 stages, order 5, stage order 3.
pub const RADAU_IIA_3: ImplicitTableau = ImplicitTableau {
    name: "Radau IIA (3 stages)",
    order: 5,
    stage_order: 3,
    a: &[
        &[(88.0 - 7.0 * S6) / 360.0, (296.0 - 169.0 * S6) / 1800.0, (-2.0 + 3.0 * S6) / 225.0],
        &[(296.0 + 169.0 * S6) / 1800.0, (88.0 + 7.0 * S6) / 360.0, (-2.0 - 3.0 * S6) / 225.0],
        &[(16.0 - S6) / 36.0, (16.0 + S6) / 36.0, 1.0 / 9.0],
    ],
    b: &[(16.0 - S6) / 36.0, (16.0 + S6) / 36.0, 1.0 / 9.0],
    c: &[(4.0 - S6) / 10.0, (4.0 + S6) / 10.0, 1.0],
};

#[cfg(test)]
mod tests {
    use super::*;

    /// B(p): Σ b_i c_i^(k−1) = 1/k, k = 1..p.
    fn b_condition(t: &ImplicitTableau, p: usize) -> f64 {
        (1..=p)
            .map(|k| {
                (t.b.iter().zip(t.c).map(|(b, c)| b * c.powi(k as i32 - 1)).sum::<f64>()
                    - 1.0 / k as f64)
                    .abs()
            })
            .fold(0.0, f64::max)
    }

    /// C(η): Σ_j a_ij c_j^(k−1) = c_i^k / k, k = 1..η.
    fn c_condition(t: &ImplicitTableau, eta: usize) -> f64 {
        let mut worst = 0.0f64;
        for (row, ci) in t.a.iter().zip(t.c) {
            for k in 1..=eta {
                let lhs: f64 = row.iter().zip(t.c).map(|(a, c)| a * c.powi(k as i32 - 1)).sum();
                worst = worst.max((lhs - ci.powi(k as i32) / k as f64).abs());
            }
        }
        worst
    }

    /// D(ζ): Σ_i b_i c_i^(k−1) a_ij = b_j (1 − c_j^k) / k, k = 1..ζ.
    fn d_condition(t: &ImplicitTableau, zeta: usize) -> f64 {
        let s = t.b.len();
        let mut worst = 0.0f64;
        for j in 0..s {
            for k in 1..=zeta {
                let lhs: f64 = (0..s).map(|i| t.b[i] * t.c[i].powi(k as i32 - 1) * t.a[i][j]).sum();
                worst = worst.max((lhs - t.b[j] * (1.0 - t.c[j].powi(k as i32)) / k as f64).abs());
            }
        }
        worst
    }

    #[test]
    fn radau_iia_has_order_5_by_butchers_theorem() {
        // B(5), C(3), D(2) with 5 ≤ 3 + 2 + 1 and 5 ≤ 2·3 + 2 give order 5.
        let t = RADAU_IIA_3;
        assert!(b_condition(&t, 5) < 1e-15, "B(5) off by {}", b_condition(&t, 5));
        assert!(c_condition(&t, 3) < 1e-15, "C(3) off by {}", c_condition(&t, 3));
        assert!(d_condition(&t, 2) < 1e-15, "D(2) off by {}", d_condition(&t, 2));
        assert!(b_condition(&t, 6) > 1e-4, "and not order 6");
        // Stiffly accurate: the last row of A is b, so y₁ is the last stage.
        assert_eq!(t.a[2], t.b);
    }

    #[test]
    fn implicit_euler_has_order_1() {
        let t = IMPLICIT_EULER;
        assert!(b_condition(&t, 1) == 0.0 && c_condition(&t, 1) == 0.0);
        assert!(b_condition(&t, 2) > 0.4);
    }
}
