//! Dormand–Prince 5(4) with Hairer's dense output of order 4 (Dormand &
//! Prince 1980; Hairer, Nørsett, Wanner, *Solving ODEs I*, §II.5 and §II.6,
//! code `dopri5.f`). Seven stages, the last one evaluated at the new point
//! and reused as the first of the next step (FSAL).

use crate::error::Error;
use crate::methods::adaptive::{self, sums_of_squares, worst_lane, EmbeddedPair};
use crate::model::Model;
use crate::model::StateVector;
use crate::solution::Solution;
use crate::step::control::Controller;
use crate::step::Problem;

/// The DOPRI5 pair.
pub struct Dopri5;

/// Integrates `problem` with DOPRI5 alone (see [`crate::Method::Dopri5`]).
pub(crate) fn integrate<M: Model>(
    problem: Problem<'_, M>,
    solution: Solution,
) -> Result<Solution, Error> {
    adaptive::integrate_alone::<M, Dopri5>(problem, solution)
}

const C: [f64; 7] = [0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0];
const A: [&[f64]; 7] = [
    &[],
    &[1.0 / 5.0],
    &[3.0 / 40.0, 9.0 / 40.0],
    &[44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0],
    &[19372.0 / 6561.0, -25360.0 / 2187.0, 64448.0 / 6561.0, -212.0 / 729.0],
    &[9017.0 / 3168.0, -355.0 / 33.0, 46732.0 / 5247.0, 49.0 / 176.0, -5103.0 / 18656.0],
    &[35.0 / 384.0, 0.0, 500.0 / 1113.0, 125.0 / 192.0, -2187.0 / 6784.0, 11.0 / 84.0],
];
/// b − b̂: the difference of the 5th- and 4th-order weights.
const E: [f64; 7] = [
    71.0 / 57600.0,
    0.0,
    -71.0 / 16695.0,
    71.0 / 1920.0,
    -17253.0 / 339200.0,
    22.0 / 525.0,
    -1.0 / 40.0,
];
/// Dense output weights (Shampine's 4th-order continuous extension, as in `dopri5.f`).
const D: [f64; 7] = [
    -12715105075.0 / 11282082432.0,
    0.0,
    87487479700.0 / 32700410799.0,
    -10690763975.0 / 1880347072.0,
    701980252875.0 / 199316789632.0,
    -1453857185.0 / 822651844.0,
    69997945.0 / 29380423.0,
];

impl EmbeddedPair for Dopri5 {
    const ORDER: usize = 5;
    const STAGES: usize = 7;
    const STIFFNESS_BOUND: f64 = 3.25;
    const DENSE_WIDTH: usize = 5;

    fn nodes() -> &'static [f64] {
        &C
    }

    fn coefficients() -> &'static [&'static [f64]] {
        &A
    }

    fn controller() -> Controller {
        Controller {
            exponent: 0.2 - 0.04 * 0.75,
            beta: 0.04,
            min_factor: 0.2,
            max_factor: 10.0,
            safety: 0.9,
        }
    }

    #[inline]
    fn error<S: StateVector>(h: f64, k: &[S], weights: &S, lanes: usize) -> f64 {
        // E[1] = 0: six terms.
        let w = weights.as_ref();
        let [k0, k2, k3, k4, k5, k6] = stages_but_the_second(k);
        let term = |i: usize| {
            let e = E[0] * k0[i]
                + E[2] * k2[i]
                + E[3] * k3[i]
                + E[4] * k4[i]
                + E[5] * k5[i]
                + E[6] * k6[i];
            e * w[i]
        };
        // |h| once, after the root: between the last stage and the next
        // step's size, no product per component waits.
        let norm = |sum: f64, n: usize| h.abs() * (sum * (1.0 / n.max(1) as f64)).sqrt();
        if lanes > 1 {
            return worst_lane(w.len(), lanes, |i| [term(i)], |[sum], n| norm(sum, n));
        }
        // The terms first, then their squares summed: with `term` inside
        // the sum's closure it was called, not inlined, per component.
        let mut terms = S::zeros();
        let terms = &mut terms.as_mut()[..w.len()];
        for (i, t) in terms.iter_mut().enumerate() {
            *t = term(i);
        }
        let [sum] = sums_of_squares(w.len(), |i| [terms[i]]);
        norm(sum, w.len())
    }

    fn dense_coefficients<S: StateVector>(h: f64, y: &S, y_new: &S, k: &[S], out: &mut [f64]) {
        let (y, y_new) = (y.as_ref(), y_new.as_ref());
        let n = y.len();
        let [k0, k2, k3, k4, k5, k6] = stages_but_the_second(k);
        for i in 0..n {
            let dy = y_new[i] - y[i];
            let bspl = h * k0[i] - dy;
            out[i] = y[i];
            out[n + i] = dy;
            out[2 * n + i] = bspl;
            out[3 * n + i] = dy - h * k6[i] - bspl;
            // D[1] = 0: six terms.
            out[4 * n + i] = h
                * (D[0] * k0[i]
                    + D[2] * k2[i]
                    + D[3] * k3[i]
                    + D[4] * k4[i]
                    + D[5] * k5[i]
                    + D[6] * k6[i]);
        }
    }

    fn interpolate(c: &[f64], n: usize, i: usize, s: f64) -> f64 {
        let s1 = 1.0 - s;
        c[i] + s * (c[n + i] + s1 * (c[2 * n + i] + s * (c[3 * n + i] + s1 * c[4 * n + i])))
    }
}

/// The stages the error estimate and the dense output combine: every one
/// but k₂, whose weight is zero in both.
#[inline(always)]
fn stages_but_the_second<S: StateVector>(k: &[S]) -> [&[f64]; 6] {
    [k[0].as_ref(), k[2].as_ref(), k[3].as_ref(), k[4].as_ref(), k[5].as_ref(), k[6].as_ref()]
}
