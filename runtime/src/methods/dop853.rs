//! Hairer's DOP853: an explicit Runge–Kutta method of order 8 with
//! embedded estimators of orders 5 and 3 and a continuous extension of
//! order 7 (Hairer, Nørsett, Wanner, *Solving ODEs I*, §II.10, code
//! `dop853.f`; coefficients of Dormand & Prince as published there).

// Published coefficients are kept digit for digit as printed.
#![allow(clippy::excessive_precision)]

use crate::error::Error;
use crate::methods::adaptive::{self, sums_of_squares, worst_lane, EmbeddedPair};
use crate::model::Model;
use crate::model::StateVector;
use crate::solution::Solution;
use crate::step::control::Controller;
use crate::step::Problem;

/// The DOP853 method.
pub struct Dop853;

/// Integrates `problem` with DOP853 alone (see [`crate::Method::Dop853`]).
pub(crate) fn integrate<M: Model>(
    problem: Problem<'_, M>,
    solution: Solution,
) -> Result<Solution, Error> {
    adaptive::integrate_alone::<M, Dop853>(problem, solution)
}

/// Nodes c of the 12 stages, the new point, and the 3 dense-output stages.
const C: [f64; 16] = [
    0.0,
    0.05260015195876773,
    0.0789002279381516,
    0.1183503419072274,
    0.2816496580927726,
    0.3333333333333333,
    0.25,
    0.3076923076923077,
    0.6512820512820513,
    0.6,
    0.8571428571428571,
    1.0,
    1.0,
    0.1,
    0.2,
    0.7777777777777778,
];
/// Stage coefficients: rows 1..=11 the stages, row 12 the weights b, rows 13..=15 the dense-output stages.
const A: [&[f64]; 16] = [
    &[],
    &[0.05260015195876773],
    &[0.0197250569845379, 0.0591751709536137],
    &[0.02958758547680685, 0.0, 0.08876275643042054],
    &[0.2413651341592667, 0.0, -0.8845494793282861, 0.924834003261792],
    &[0.037037037037037035, 0.0, 0.0, 0.17082860872947386, 0.12546768756682242],
    &[0.037109375, 0.0, 0.0, 0.17025221101954405, 0.06021653898045596, -0.017578125],
    &[
        0.03709200011850479,
        0.0,
        0.0,
        0.17038392571223998,
        0.10726203044637328,
        -0.015319437748624402,
        0.008273789163814023,
    ],
    &[
        0.6241109587160757,
        0.0,
        0.0,
        -3.3608926294469414,
        -0.868219346841726,
        27.59209969944671,
        20.154067550477894,
        -43.48988418106996,
    ],
    &[
        0.47766253643826434,
        0.0,
        0.0,
        -2.4881146199716677,
        -0.590290826836843,
        21.230051448181193,
        15.279233632882423,
        -33.28821096898486,
        -0.020331201708508627,
    ],
    &[
        -0.9371424300859873,
        0.0,
        0.0,
        5.186372428844064,
        1.0914373489967295,
        -8.149787010746927,
        -18.52006565999696,
        22.739487099350505,
        2.4936055526796523,
        -3.0467644718982196,
    ],
    &[
        2.273310147516538,
        0.0,
        0.0,
        -10.53449546673725,
        -2.0008720582248625,
        -17.9589318631188,
        27.94888452941996,
        -2.8589982771350235,
        -8.87285693353063,
        12.360567175794303,
        0.6433927460157636,
    ],
    &[
        0.054293734116568765,
        0.0,
        0.0,
        0.0,
        0.0,
        4.450312892752409,
        1.8915178993145003,
        -5.801203960010585,
        0.3111643669578199,
        -0.1521609496625161,
        0.20136540080403034,
        0.04471061572777259,
    ],
    &[
        0.056167502283047954,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.25350021021662483,
        -0.2462390374708025,
        -0.12419142326381637,
        0.15329179827876568,
        0.00820105229563469,
        0.007567897660545699,
        -0.008298,
    ],
    &[
        0.03183464816350214,
        0.0,
        0.0,
        0.0,
        0.0,
        0.028300909672366776,
        0.053541988307438566,
        -0.05492374857139099,
        0.0,
        0.0,
        -0.00010834732869724932,
        0.0003825710908356584,
        -0.00034046500868740456,
        0.1413124436746325,
    ],
    &[
        -0.42889630158379194,
        0.0,
        0.0,
        0.0,
        0.0,
        -4.697621415361164,
        7.683421196062599,
        4.06898981839711,
        0.3567271874552811,
        0.0,
        0.0,
        0.0,
        -0.0013990241651590145,
        2.9475147891527724,
        -9.15095847217987,
    ],
];
/// The 5th-order error estimator.
const E5: [f64; 12] = [
    0.01312004499419488,
    0.0,
    0.0,
    0.0,
    0.0,
    -1.2251564463762044,
    -0.4957589496572502,
    1.6643771824549864,
    -0.35032884874997366,
    0.3341791187130175,
    0.08192320648511571,
    -0.022355307863886294,
];
/// The stages with a non-zero weight in the 8th-order solution and in the
/// 5th-order error estimate.
const NONZERO_WEIGHTS: [usize; 8] = [0, 5, 6, 7, 8, 9, 10, 11];

/// Weights of the 3rd-order embedded solution (`bhh` of `dop853.f`), on stages 1, 9 and 12.
const BHH: [f64; 3] = [0.2440944881889764, 0.7338466882816118, 0.022058823529411766];
/// Floating-point operations per state of one step besides its twelve
/// right-hand sides: the least a DOP853 step does, for work models (the
/// benchmark's arithmetic per solve). Each of the eleven stages' and the
/// solution's y + h·Σ a_ij·k_j is a multiply-add per nonzero coefficient
/// and one more; the error estimates take one per nonzero weight (the
/// 5th-order one) and per `bhh` coefficient (the 3rd-order one, from the
/// solution's sum, as `dop853.f` forms it); the error norm four (two
/// products by the weights, two squares added) and the weight
/// 1 / (atol + rtol·max(|y|, |y₁|)) four.
pub fn operations_per_state() -> usize {
    let nonzero = |row: &[f64]| row.iter().filter(|&&a| a != 0.0).count();
    let sums: usize = A[1..=12].iter().map(|row| nonzero(row) + 1).sum();
    sums + nonzero(&E5) + BHH.len() + 4 + 4
}

/// Dense output: rows give r5..r8 as combinations of the 16 stages.
const D: [[f64; 16]; 4] = [
    [
        -8.428938276109013,
        0.0,
        0.0,
        0.0,
        0.0,
        0.5667149535193777,
        -3.0689499459498917,
        2.38466765651207,
        2.117034582445028,
        -0.871391583777973,
        2.2404374302607883,
        0.6315787787694688,
        -0.08899033645133331,
        18.148505520854727,
        -9.194632392478356,
        -4.436036387594894,
    ],
    [
        10.427508642579134,
        0.0,
        0.0,
        0.0,
        0.0,
        242.28349177525817,
        165.20045171727028,
        -374.5467547226902,
        -22.113666853125306,
        7.733432668472264,
        -30.674084731089398,
        -9.332130526430229,
        15.697238121770845,
        -31.139403219565178,
        -9.35292435884448,
        35.81684148639408,
    ],
    [
        19.985053242002433,
        0.0,
        0.0,
        0.0,
        0.0,
        -387.0373087493518,
        -189.17813819516758,
        527.8081592054236,
        -11.57390253995963,
        6.8812326946963,
        -1.0006050966910838,
        0.7777137798053443,
        -2.778205752353508,
        -60.19669523126412,
        84.32040550667716,
        11.99229113618279,
    ],
    [
        -25.69393346270375,
        0.0,
        0.0,
        0.0,
        0.0,
        -154.18974869023643,
        -231.5293791760455,
        357.6391179106141,
        93.40532418362432,
        -37.45832313645163,
        104.0996495089623,
        29.8402934266605,
        -43.53345659001114,
        96.32455395918828,
        -39.17726167561544,
        -149.72683625798564,
    ],
];

impl EmbeddedPair for Dop853 {
    const ORDER: usize = 8;
    /// Twelve stages and f at the new point.
    const STAGES: usize = 13;
    const STIFFNESS_BOUND: f64 = 6.1;
    const DENSE_WIDTH: usize = 8;
    const DENSE_STAGES: usize = 3;

    fn nodes() -> &'static [f64] {
        &C
    }

    fn coefficients() -> &'static [&'static [f64]] {
        &A
    }

    fn controller() -> Controller {
        Controller {
            exponent: 1.0 / 8.0,
            beta: 0.0,
            min_factor: 1.0 / 3.0,
            max_factor: 6.0,
            safety: 0.9,
        }
    }

    /// Hairer's combination of the 5th- and 3rd-order estimates: the 3rd
    /// guards against the 5th being accidentally small.
    fn error<S: StateVector>(h: f64, k: &[S], weights: &S, lanes: usize) -> f64 {
        let w = weights.as_ref();
        let n = w.len();
        // Stages 2–5 have zero weight in both sums (`dop853.f` leaves them
        // out too). The sums are accumulated stage by stage over whole
        // vectors, then weighted in one pass: each loop
        // vectorises (the outer solar system spent 16 % of its time here
        // component by component); per component the terms are added in
        // the same order as in `dop853.f`.
        let (mut e5, mut e3) = (S::zeros(), S::zeros());
        let (e5s, e3s) = (&mut e5.as_mut()[..n], &mut e3.as_mut()[..n]);
        let b_row = A[12];
        for j in NONZERO_WEIGHTS {
            let kj = &k[j].as_ref()[..n];
            for ((e, b), kv) in e5s.iter_mut().zip(e3s.iter_mut()).zip(kj) {
                *e += E5[j] * kv;
                *b += b_row[j] * kv;
            }
        }
        let (k0, k8, k11) = (&k[0].as_ref()[..n], &k[8].as_ref()[..n], &k[11].as_ref()[..n]);
        for i in 0..n {
            let e3 = e3s[i] - BHH[0] * k0[i] - BHH[1] * k8[i] - BHH[2] * k11[i];
            e5s[i] *= w[i];
            e3s[i] = e3 * w[i];
        }
        if lanes > 1 {
            return worst_lane(n, lanes, |i| [e5s[i], e3s[i]], |sums, n| combined(h, sums, n));
        }
        combined(h, sums_of_squares(n, |i| [e5s[i], e3s[i]]), n)
    }

    fn dense_coefficients<S: StateVector>(h: f64, y: &S, y_new: &S, k: &[S], out: &mut [f64]) {
        let (y, y_new) = (y.as_ref(), y_new.as_ref());
        let n = y.len();
        // All sixteen stages at a fixed length, so that each row's sums
        // unroll and its zero weights drop out at compile time.
        let Some(k) = k.first_chunk::<16>() else { return };
        for i in 0..n {
            let dy = y_new[i] - y[i];
            let bspl = h * k[0].as_ref()[i] - dy;
            out[i] = y[i];
            out[n + i] = dy;
            out[2 * n + i] = bspl;
            out[3 * n + i] = dy - h * k[12].as_ref()[i] - bspl;
            // Σ_j d_mj k_j in stage order, as in dop853.f, then times h.
            for (m, d) in D.iter().enumerate() {
                let mut sum = 0.0;
                for (dj, kj) in d.iter().zip(k) {
                    if *dj != 0.0 {
                        sum += dj * kj.as_ref()[i];
                    }
                }
                out[(4 + m) * n + i] = sum * h;
            }
        }
    }

    fn interpolate(c: &[f64], n: usize, i: usize, s: f64) -> f64 {
        let s1 = 1.0 - s;
        let r = |m: usize| c[m * n + i];
        let tail = r(4) + s * (r(5) + s1 * (r(6) + s * r(7)));
        r(0) + s * (r(1) + s1 * (r(2) + s * (r(3) + s1 * tail)))
    }
}

/// DOP853's error from the sums of squares of its fifth- and third-order
/// estimates over `n` components (`dop853.f`'s `err`).
#[inline(always)]
fn combined(h: f64, [err5, err3]: [f64; 2], n: usize) -> f64 {
    if err5 == 0.0 && err3 == 0.0 {
        return 0.0;
    }
    h.abs() * err5 / ((err5 + 0.01 * err3) * n as f64).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_skipped_stages_have_zero_weight() {
        for j in 0..12 {
            if !NONZERO_WEIGHTS.contains(&j) {
                assert_eq!(E5[j], 0.0, "E5[{j}]");
                assert_eq!(A[12][j], 0.0, "b[{j}]");
            }
        }
    }
}
