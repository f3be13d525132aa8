//! RADAU5's coefficients: the Radau IIA nodes, the transformation T that
//! block-diagonalises A⁻¹ and A⁻¹'s eigenvalues, the error estimate's
//! weights, the continuous output, and the controller's constants and
//! reuse rules (the values of `radau5.f`).

// Published coefficients are kept digit for digit as printed.
#![allow(clippy::excessive_precision)]

pub(super) const SQ6: f64 = 2.449_489_742_783_178;
pub(super) const C1: f64 = (4.0 - SQ6) / 10.0;
pub(super) const C2: f64 = (4.0 + SQ6) / 10.0;
pub(super) const C1M1: f64 = C1 - 1.0;
pub(super) const C2M1: f64 = C2 - 1.0;
pub(super) const C1MC2: f64 = C1 - C2;
pub(super) const DD1: f64 = -(13.0 + 7.0 * SQ6) / 3.0;
pub(super) const DD2: f64 = (-13.0 + 7.0 * SQ6) / 3.0;
pub(super) const DD3: f64 = -1.0 / 3.0;
/// T and T⁻¹: A⁻¹ = T diag(γ, [α −β; β α]) T⁻¹ (values of `radau5.f`).
pub(super) const T: [[f64; 3]; 3] = [
    [9.1232394870892942792e-02, -0.14125529502095420843, -3.0029194105147424492e-02],
    [0.24171793270710701896, 0.20412935229379993199, 0.38294211275726193779],
    [0.96604818261509293619, 1.0, 0.0],
];
pub(super) const TI: [[f64; 3]; 3] = [
    [4.3255798900631553510, 0.33919925181580986954, 0.54177053993587487119],
    [-4.1787185915519047273, -0.32768282076106238708, 0.47662355450055045196],
    [-0.50287263494578687595, 2.5719269498556054292, -0.59603920482822492497],
];

/// Eigenvalues of A⁻¹: the real γ and the complex pair α ± iβ.
pub(super) fn eigenvalues() -> (f64, f64, f64) {
    let (c81, c9) = (81f64.cbrt(), 9f64.cbrt());
    let u1 = (6.0 + c81 - c9) / 30.0;
    let alpha = (12.0 - c81 + c9) / 60.0;
    let beta = (c81 + c9) * 3f64.sqrt() / 60.0;
    let cno = alpha * alpha + beta * beta;
    (1.0 / u1, alpha / cno, beta / cno)
}

/// Controller constants of `radau5.f` (its defaults).
pub(super) const NIT: usize = 7;
pub(super) const SAFE: f64 = 0.9;
pub(super) const FACL: f64 = 5.0;
pub(super) const FACR: f64 = 1.0 / 8.0;

/// When RADAU5 keeps its Jacobian and its LU (`radau5.f`'s WORK(3),
/// WORK(5) and WORK(6)): the Jacobian while Newton's contraction θ stays
/// below `thet`, the LU too while h_new/h stays in `quot1..=quot2`.
#[derive(Clone, Copy)]
pub(super) struct Reuse {
    pub(super) thet: f64,
    pub(super) quot1: f64,
    pub(super) quot2: f64,
}

impl Reuse {
    /// Hairer's defaults for small systems (0.001, 1, 1.2) and, where one
    /// real factorisation takes over [`COSTLY_FACTORISATION`] operations,
    /// the values his documentation recommends for large ones (0.1 "when
    /// Jacobian evaluations are costly", as each one brings a
    /// factorisation; 0.99 and 2 "for large systems").
    pub(super) fn for_factorisation(operations: f64) -> Reuse {
        if operations > COSTLY_FACTORISATION {
            Reuse { thet: 0.1, quot1: 0.99, quot2: 2.0 }
        } else {
            Reuse { thet: 0.001, quot1: 1.0, quot2: 1.2 }
        }
    }
}

/// Operations of one real factorisation above which it outweighs the
/// extra Newton iterations of a kept LU (a dense system of some 110
/// states, a sparse 2-D grid of a thousand).
pub(super) const COSTLY_FACTORISATION: f64 = 1e6;

/// Component `i` of the collocation polynomial at `s = (t - t_old)/h`.
pub(crate) fn interpolate(c: &[f64], n: usize, i: usize, s: f64) -> f64 {
    // radau5's CONTR5 measures s from the new point: s - 1 ∈ [-1, 0].
    let s = s - 1.0;
    c[i] + s * (c[n + i] + (s - C2M1) * (c[2 * n + i] + (s - C1M1) * c[3 * n + i]))
}
