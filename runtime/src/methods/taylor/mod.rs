//! The adaptive Taylor method (Jorba & Zou 2005, as in heyoka's
//! `taylor_determine_h`): coefficients from the model's AD tape
//! (`taylor_tape`) or the macro's straight-line recurrences, the order
//! of least work per unit time for the tolerance (`order.rs`;
//! Jorba & Zou's p₀ = ⌈−ln(tol)/2 + 1⌉ when the convolutions dominate),
//! step h = min(ρ_{p−1}, ρ_p)·[`step_factor`] with
//! ρ_k = (N/‖x^\[k\]‖∞)^(1/k), N = max(1, ‖x‖∞) (absolute below 1, relative
//! above); at p = p₀ the factor is their e⁻²·e^(−0.7/(p−1)). An order the
//! method picks takes a shorter step ([`chosen_order_step_factor`]), so
//! that its error is not above theirs. No step is rejected. Time is summed with compensation, and each step's polynomial
//! is the dense output.

pub(crate) mod fixed;
pub(crate) mod lanes;
pub mod order;
pub mod series;

// The tape lies below the model, which hands it over; the method reads it here.
pub use crate::taylor_tape as tape;
pub use crate::taylor_tape::coefficient;

use crate::error::Error;
use crate::methods::taylor::order::{choose_order, chosen_order_step_factor, step_factor, JetCost};
use crate::model::Model;
use crate::solution::Solution;
use crate::step::driver::{Counts, DenseOutput, Driver};
use crate::step::Problem;
use crate::taylor_tape::{mul_add, TaylorWork};

/// Sub-intervals of each step on which event functions are checked for a
/// sign change.
const EVENT_SAMPLES: usize = 8;

/// The position of the first NaN or infinity in `c`, if any. The common
/// case, all finite, is one pass of four independent sums of `0·x` (zero
/// for finite x, NaN otherwise).
fn first_non_finite(c: &[f64]) -> Option<usize> {
    let mut lanes = [0.0f64; 4];
    let chunks = c.chunks_exact(4);
    let tail = chunks.remainder();
    for x in chunks {
        for l in 0..4 {
            lanes[l] += 0.0 * x[l];
        }
    }
    let total = tail.iter().fold(lanes.iter().sum::<f64>(), |s, x| s + 0.0 * x);
    if total == 0.0 {
        return None;
    }
    c.iter().position(|x| !x.is_finite())
}

/// The largest |c[i·w + k]| over the rows of `c` (NaNs ignored, as
/// `f64::max` does). Four running maxima, so that the chain is a quarter
/// of the rows long: with one, the outer solar system's three norms were
/// chains of 36 NaN-aware maxima, some 5 % of its step.
#[inline]
fn column_max(c: &[f64], w: usize, k: usize) -> f64 {
    let mut lanes = [0.0f64; 4];
    let mut column = c.iter().skip(k).step_by(w).map(|x| x.abs());
    'rows: loop {
        for lane in &mut lanes {
            let Some(x) = column.next() else { break 'rows };
            // False for a NaN x: the maximum keeps its value.
            if x > *lane {
                *lane = x;
            }
        }
    }
    let pair = |a: f64, b: f64| if a > b { a } else { b };
    pair(pair(lanes[0], lanes[1]), pair(lanes[2], lanes[3]))
}

/// Leading coefficients of each series summed by Horner's rule, one fused
/// multiply-add each, as heyoka's state update does.
const LEADING: usize = 4;

/// Advances each state by its series (rows of `w` coefficients, the first
/// being the state) at `h`, four states at a time so that their chains
/// overlap; `carried` holds each state's rounding error from the steps
/// before.
///
/// The increment `h(c₁ + h(c₂ + h(c₃ + h·T)))` by Horner's rule with `h`
/// itself for the leading terms, which hold nearly all of it, and Estrin's
/// split `E(h²) + h·O(h²)` for the tail `T = Σ_{k≥4} c_k h^{k−4}` (some
/// 1e-4 of the step's change), two independent chains of half the length.
/// The increment is then added to the state by compensated summation
/// (Kahan; Hairer, Lubich & Wanner, GNI §VIII.5): the sum's rounding
/// error, and the product's (exact with FMA), are carried into the next
/// step instead of lost, as in heyoka's high-accuracy mode. Over 24
/// Kepler e = 0.9 starts one ulp apart (ten orbits, host build with FMA)
/// the energy error's RMS at tolerances 1e-14 and 1e-15 is 2.6–2.9e-15,
/// against 1.1e-14 added plainly (heyoka's default: 1.1–1.2e-14) and
/// 1.5–1.8e-14 with Estrin's split over the whole series; from the usual
/// start the final error falls from 9.9e-11 to 3.8e-12 at 1e-14 (heyoka
/// 3.1e-11), for 1–2 % more time per solve.
fn horner(rows: &[f64], w: usize, h: f64, y: &mut [f64], carried: &mut [f64]) {
    let h2 = h * h;
    // Σ_k c[k]·hᵏ for the tail of one row, by even and odd halves.
    let tail = |c: &[f64]| {
        let pairs = c.chunks_exact(2);
        let (mut even, mut odd) = (pairs.remainder().first().copied().unwrap_or(0.0), 0.0f64);
        for pair in pairs.rev() {
            even = mul_add(even, h2, pair[0]);
            odd = mul_add(odd, h2, pair[1]);
        }
        mul_add(h, odd, even)
    };
    // c₁ + h(c₂ + h(c₃ + h·T)), then the increment h·(…) added to the state
    // with its rounding error carried to the next step.
    let leading = |c: &[f64], acc: f64| c.iter().rev().fold(acc, |acc, &ck| mul_add(acc, h, ck));
    let update = |y: &mut f64, carried: &mut f64, p: f64| add_increment(y, carried, p, h);
    for ((ys, cs), block) in y.chunks_mut(4).zip(carried.chunks_mut(4)).zip(rows.chunks(4 * w)) {
        if let ([y0, y1, y2, y3], [e0, e1, e2, e3], true) =
            (&mut *ys, &mut *cs, block.len() == 4 * w && w > LEADING)
        {
            let (r0, rest) = block.split_at(w);
            let (r1, rest) = rest.split_at(w);
            let (r2, r3) = rest.split_at(w);
            let (t0, t1, t2, t3) = (
                tail(&r0[LEADING..]),
                tail(&r1[LEADING..]),
                tail(&r2[LEADING..]),
                tail(&r3[LEADING..]),
            );
            update(y0, e0, leading(&r0[1..LEADING], t0));
            update(y1, e1, leading(&r1[1..LEADING], t1));
            update(y2, e2, leading(&r2[1..LEADING], t2));
            update(y3, e3, leading(&r3[1..LEADING], t3));
        } else {
            for ((yi, ei), row) in ys.iter_mut().zip(cs.iter_mut()).zip(block.chunks_exact(w)) {
                let split = row.len().min(LEADING);
                let t = if row.len() > LEADING { tail(&row[LEADING..]) } else { 0.0 };
                let p = if split > 1 { leading(&row[1..split], t) } else { 0.0 };
                update(yi, ei, p);
            }
        }
    }
}

/// Floating-point operations per state of one step of order `order`
/// besides the jet, for work models (the benchmark's arithmetic per
/// solve): the series summed by `horner` (a multiply-add per
/// coefficient after the first, one more to join Estrin's halves), the
/// compensated addition of `add_increment` (ten) and the three norms
/// that set the step (an absolute value and a comparison each).
pub fn update_operations_per_state(order: usize) -> usize {
    order + 1 + 10 + 3 * 2
}

/// `y += p·h`, the increment's rounding error and the sum's carried in
/// `carried` to the next step (see [`horner`]).
#[inline(always)]
fn add_increment(y: &mut f64, carried: &mut f64, p: f64, h: f64) {
    let increment = p * h;
    // The product's own rounding error (zero without FMA).
    let product_error = mul_add(p, h, -increment);
    let t = increment + (*carried + product_error);
    let s = *y + t;
    let b = s - *y;
    *carried = (*y - (s - b)) + (t - b);
    *y = s;
}

/// [`horner`] for coefficients stored order by order (state i's
/// coefficient k at `c[k·n + i]`, as large unrolled jets write them): the
/// same operations on each state, in the same order, so the same result
/// to the bit, but on eight (then four, then one) neighbouring states at
/// once, which the compiler keeps in vector registers (stored state by
/// state, the rows are `w` apart and each state's sums go alone).
fn horner_by_coefficient(c: &[f64], w: usize, h: f64, y: &mut [f64], carried: &mut [f64]) {
    let n = y.len();
    let mut lo = 0;
    while lo < n {
        let (ys, cs) = (&mut y[lo..], &mut carried[lo..]);
        lo += match ys.len() {
            8.. => horner_states::<8>(c, n, lo, w, h, ys, cs),
            4.. => horner_states::<4>(c, n, lo, w, h, ys, cs),
            _ => horner_states::<1>(c, n, lo, w, h, ys, cs),
        };
    }
}

/// [`horner_by_coefficient`] for the `B` states from `lo`; returns `B`.
#[inline(always)]
fn horner_states<const B: usize>(
    c: &[f64],
    n: usize,
    lo: usize,
    w: usize,
    h: f64,
    y: &mut [f64],
    carried: &mut [f64],
) -> usize {
    let at = |k: usize| {
        let mut v = [0.0f64; B];
        if let Some(s) = c.get(k * n + lo..k * n + lo + B) {
            v.copy_from_slice(s);
        }
        v
    };
    let h2 = h * h;
    // The tail Σ_{k≥4} c_k h^(k−4) by even and odd halves, as `horner`'s.
    let tail = w.saturating_sub(LEADING);
    let mut sum = if tail % 2 == 1 { at(w - 1) } else { [0.0; B] };
    let mut odd = [0.0f64; B];
    for pair in (0..tail / 2).rev() {
        let (a, b) = (at(LEADING + 2 * pair), at(LEADING + 2 * pair + 1));
        for l in 0..B {
            sum[l] = mul_add(sum[l], h2, a[l]);
            odd[l] = mul_add(odd[l], h2, b[l]);
        }
    }
    if tail > 0 {
        for l in 0..B {
            sum[l] = mul_add(h, odd[l], sum[l]);
        }
    }
    // The leading terms c₁ + h(c₂ + h(c₃ + h·T)).
    let split = w.min(LEADING);
    if split > 1 {
        for k in (1..split).rev() {
            let ck = at(k);
            for l in 0..B {
                sum[l] = mul_add(sum[l], h, ck[l]);
            }
        }
    } else {
        sum = [0.0; B];
    }
    // The update lane by lane on arrays, so that it is vectorised too.
    let (Some(y), Some(carried)) = (y.get_mut(..B), carried.get_mut(..B)) else {
        return B;
    };
    let (mut ys, mut es) = ([0.0f64; B], [0.0f64; B]);
    ys.copy_from_slice(y);
    es.copy_from_slice(carried);
    for l in 0..B {
        add_increment(&mut ys[l], &mut es[l], sum[l], h);
    }
    y.copy_from_slice(&ys);
    carried.copy_from_slice(&es);
    B
}

/// Component `i` of the step polynomial at `s = (t − t_old)/h`; the
/// coefficients are stored state by state, already multiplied by hᵏ.
pub(crate) fn interpolate(c: &[f64], n: usize, i: usize, s: f64) -> f64 {
    let w = c.len() / n;
    c[i * w..(i + 1) * w].iter().rev().fold(0.0, |acc, ck| acc * s + ck)
}

/// Integrates `model` from `t0` to `t1` with the adaptive Taylor method.
pub(crate) fn integrate<M: Model>(
    problem: Problem<'_, M>,
    mut solution: Solution,
) -> Result<Solution, Error> {
    if M::LANES > 1 {
        return lanes::integrate(problem, solution);
    }
    let Problem { model, t0, y0, options, .. } = problem;
    let Some((tape, outputs)) = model.taylor_tape() else {
        // A model with its reason is refused before the run; this one
        // hands over no tape and gives none.
        let message = crate::methods::taylor_refusal::<M>("it has no Taylor tape");
        return Err(Error::InvalidOptions { message });
    };
    let n = M::STATES;
    let tol = if options.rtol > 0.0 { options.rtol } else { options.atol };
    let unrolled_orders = if options.taylor_compact { &[][..] } else { M::TAYLOR_UNROLLED };
    // The straight-line recurrences when the macro emitted the order, else
    // the interpreted tape.
    let (p, unrolled) = match options.taylor_order {
        Some(p) => (p, unrolled_orders.contains(&p)),
        None => choose_order(tol, &JetCost::of_tape(&tape, n), unrolled_orders),
    };
    solution.stats_mut().taylor_order = p;
    solution.stats_mut().taylor_unrolled = unrolled;
    // Taylor steps are long (a good part of an orbit): the event functions
    // are sampled inside them, so two crossings in one step are both found.
    let dense_output = DenseOutput { width: p + 1, interpolate };
    let mut run = Driver::new(&problem, solution, Some(dense_output), EVENT_SAMPLES);
    let mut work = (!unrolled).then(|| TaylorWork::new(&tape, &outputs, n, p));
    let mut jet = vec![0.0; if unrolled { model.taylor_jet_len(p) } else { 0 }];
    // Large jets write their coefficients order by order.
    let by_coefficient = unrolled && model.taylor_jet_by_coefficient(p);
    let mut y = y0.to_vec();
    let mut carried = vec![0.0; n];
    let mut dense = vec![0.0; (p + 1) * n];
    let mut powers = vec![0.0; p + 1];
    // An order given keeps Jorba & Zou's step; one picked here drops less.
    let safety = match options.taylor_order {
        Some(_) => step_factor(tol, p),
        None => chosen_order_step_factor(tol, p),
    };
    let radius = Radius::new(p, crate::methods::error_states::<M>(options), by_coefficient);
    let (mut t, mut compensation) = (t0, 0.0f64);
    let mut counts = Counts::default();
    while (run.t1 - t) * run.direction > 0.0 {
        run.check_steps(t, &counts)?;
        let coefficients: &[f64] = match work.as_mut() {
            Some(work) => {
                work.compute(t, &y);
                work.rows()
            }
            None => {
                model.taylor_jet_unrolled(t, &y, p, &mut jet);
                &jet[..n * (p + 1)]
            }
        };
        let w = p + 1;
        counts.evals += 1;
        let remaining = (run.t1 - t).abs();
        // A polynomial solution has an infinite radius: the step is then
        // limited by the interval and max_step only.
        let mut h = (radius.of(coefficients, n) * safety).min(run.hmax);
        // A NaN step ends the run here too, and is caught just below.
        // Within 1 % of the end the step reaches it (as Hairer's codes do),
        // rather than leave a remainder that may be below the time's ulp.
        let last = 1.01 * h >= remaining || h.is_nan();
        if last {
            h = remaining;
        }
        if h <= t.abs().max(1e-300) * f64::EPSILON || h.is_nan() {
            // Non-finite coefficients make the step collapse: say which.
            if let Some(at) = first_non_finite(&coefficients[..n * w]) {
                let state = if by_coefficient { at % n } else { at / w };
                return Err(run.non_finite(t, state, &counts));
            }
            return Err(run.fail(&counts, |partial| Error::StepSizeUnderflow { t, h, partial }));
        }
        let h = run.direction * h;
        if run.keep_dense() {
            scale_by_powers(&coefficients[..n * w], (h, by_coefficient), &mut powers, &mut dense);
        }
        // A non-finite coefficient makes its state non-finite (h is finite
        // and non-zero), which the check after the step reports.
        if by_coefficient {
            horner_by_coefficient(&coefficients[..n * w], w, h, &mut y, &mut carried);
        } else {
            horner(&coefficients[..n * w], w, h, &mut y, &mut carried);
        }
        let step = h - compensation;
        let t_next = t + step;
        compensation = (t_next - t) - step;
        t = if last { run.t1 } else { t_next };
        run.check_finite(t, &y, &counts)?;
        if run.project(t, &mut y, &counts)? {
            // The carried rounding errors belong to the state before it moved.
            carried.fill(0.0);
        }
        if run.record(t, &y, &dense, &counts)? {
            break;
        }
    }
    Ok(run.finish(&counts))
}

/// The radius of convergence a step is a fraction of, from a point's
/// coefficients: ρ = min(ρ_{p−1}, ρ_p), ρ_k = (N/‖x^\[k\]‖)^(1/k).
struct Radius {
    p: usize,
    /// 1/(p − 1) and 1/p.
    inverse_orders: (f64, f64),
    /// The states the error test measures (the model's own, where
    /// sensitivities are left out of it).
    measured: usize,
    /// Whether the coefficients lie order by order (else state by state).
    by_coefficient: bool,
}

impl Radius {
    fn new(p: usize, measured: usize, by_coefficient: bool) -> Radius {
        let inverse_orders = (1.0 / (p - 1) as f64, 1.0 / p as f64);
        Radius { p, inverse_orders, measured, by_coefficient }
    }

    /// ρ from the `n` states' coefficients.
    #[inline(always)]
    fn of(&self, coefficients: &[f64], n: usize) -> f64 {
        let (p, w, measured) = (self.p, self.p + 1, self.measured);
        let norm = |k: usize| match self.by_coefficient {
            true => column_max(coefficients.get(k * n..k * n + measured).unwrap_or(&[]), 1, 0),
            false => column_max(&coefficients[..measured * w], w, k),
        };
        // Of ρ_{p−1} and ρ_p the smaller, compared through logarithms so
        // that only one power is taken. The step waits for ρ: ln N −
        // ln ‖x^[k]‖ times 1/k keeps two divisions off that path.
        let log_n = norm(0).max(1.0).ln();
        let (norm_pm1, norm_p) = (norm(p - 1), norm(p));
        let log_rho = |nk: f64, inv_k: f64| {
            if nk == 0.0 {
                f64::INFINITY
            } else {
                (log_n - nk.ln()) * inv_k
            }
        };
        let (inv_pm1, inv_p) = self.inverse_orders;
        let rho = log_rho(norm_pm1, inv_pm1).min(log_rho(norm_p, inv_p)).exp();
        if norm_pm1 == 0.0 && norm_p == 0.0 {
            return radius_from_lower_orders(&norm, log_n, p);
        }
        rho
    }
}

/// The step's dense output: the coefficients scaled by hᵏ (the powers as
/// four interleaved chains of h⁴ products), laid out state by state.
#[inline(always)]
fn scale_by_powers(
    coefficients: &[f64],
    (h, by_coefficient): (f64, bool),
    powers: &mut [f64],
    dense: &mut [f64],
) {
    let (w, p) = (powers.len(), powers.len() - 1);
    let n = coefficients.len() / w;
    let (h2, h3) = (h * h, h * h * h);
    let h4 = h2 * h2;
    for (k, power) in powers.iter_mut().enumerate().take(4) {
        *power = [1.0, h, h2, h3][k];
    }
    for k in 4..=p {
        powers[k] = powers[k - 4] * h4;
    }
    if by_coefficient {
        for (k, (c, power)) in coefficients.chunks_exact(n).zip(&*powers).enumerate() {
            for (d, c) in dense.iter_mut().skip(k).step_by(w).zip(c) {
                *d = c * power;
            }
        }
    } else {
        for (d, c) in dense.chunks_exact_mut(w).zip(coefficients.chunks_exact(w)) {
            for ((d, c), power) in d.iter_mut().zip(c).zip(&*powers) {
                *d = c * power;
            }
        }
    }
}

/// ρ when the last two coefficients vanish at this point but the solution
/// is no polynomial of low degree: the least ρ_k = (N/‖x^\[k\]‖)^(1/k)
/// over the upper half of the orders whose coefficients do not vanish
/// (a chain released from rest in a symmetric pose has x^\[k\] = 0 for
/// k ≡ 3, 0 mod 4 at its start, and the last two orders alone would read
/// as an infinite radius); infinite when they all vanish (a polynomial of
/// degree below p/2, whose radius is).
pub(crate) fn radius_from_lower_orders(norm: &dyn Fn(usize) -> f64, log_n: f64, p: usize) -> f64 {
    (p / 2..p.saturating_sub(1))
        .filter(|&k| k > 0)
        .map(|k| (k, norm(k)))
        .filter(|&(_, nk)| nk > 0.0)
        .map(|(k, nk)| ((log_n - nk.ln()) / k as f64).exp())
        .fold(f64::INFINITY, f64::min)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn non_finite_coefficients_are_found_wherever_they_are() {
        let mut c = vec![1.0; 23];
        assert_eq!(first_non_finite(&c), None);
        for (at, bad) in [(0, f64::NAN), (5, f64::INFINITY), (22, f64::NEG_INFINITY)] {
            c[at] = bad;
            assert_eq!(first_non_finite(&c), Some(at));
            c[at] = 1.0;
        }
    }

    #[test]
    fn column_max_finds_the_largest_magnitude_in_any_row_and_ignores_nan() {
        // Seven rows of three: column k of row i is −(i + 1)·(k + 1) except
        // where set below.
        let (n, w) = (7, 3);
        let mut c: Vec<f64> =
            (0..n * w).map(|x| -(((x / w) + 1) as f64) * ((x % w) + 1) as f64).collect();
        assert_eq!(column_max(&c, w, 0), 7.0);
        assert_eq!(column_max(&c, w, 2), 21.0);
        for row in 0..n {
            let at = row * w + 1;
            let old = c[at];
            c[at] = 100.0;
            assert_eq!(column_max(&c, w, 1), 100.0, "largest in row {row}");
            c[at] = f64::NAN;
            assert_eq!(column_max(&c, w, 1), if row == 6 { 12.0 } else { 14.0 });
            c[at] = old;
        }
        assert_eq!(column_max(&[f64::NAN; 4], 1, 0), 0.0);
    }

    #[test]
    fn horner_sums_every_state_in_blocks_and_the_rest() {
        // Seven states (a block of four and three more), orders 3 (leading
        // terms only) and 12 (a tail too): state i has coefficients
        // c_k = 1 + (i·k mod 5) at x = 0.5, exact in binary, so every
        // summation order gives the same value.
        let (n, h) = (7, 0.5);
        for order in [3, 12] {
            let w = order + 1;
            let c = |i: usize, k: usize| 1.0 + ((i * k) % 5) as f64;
            let rows: Vec<f64> = (0..n).flat_map(|i| (0..w).map(move |k| c(i, k))).collect();
            // The state is the coefficient 0 of its row.
            let mut y: Vec<f64> = (0..n).map(|i| c(i, 0)).collect();
            let mut carried = vec![0.0; n];
            horner(&rows, w, h, &mut y, &mut carried);
            for (i, yi) in y.iter().enumerate() {
                let want: f64 = (0..w).map(|k| c(i, k) * h.powi(k as i32)).sum();
                assert_eq!(*yi, want, "order {order}, state {i}");
                assert_eq!(carried[i], 0.0, "order {order}, state {i}: exact sums carry nothing");
            }
        }
    }

    /// Coefficients stored order by order give the same states and carried
    /// errors to the bit as stored state by state, for orders with no tail,
    /// odd and even tails, whole blocks of four states and the rest, on
    /// inexact values (a pseudo-random walk) where any other order of the
    /// operations would round differently.
    #[test]
    fn coefficients_by_order_sum_to_the_same_bits_as_by_state() {
        let mut seed = 1u64;
        let mut next = || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        for (n, order) in [(7, 0), (7, 1), (7, 3), (36, 12), (36, 15), (5, 18), (3, 22)] {
            let w = order + 1;
            let rows: Vec<f64> = (0..n * w).map(|_| next()).collect();
            let by_order: Vec<f64> = (0..w)
                .flat_map(|k| (0..n).map(move |i| (k, i)))
                .map(|(k, i)| rows[i * w + k])
                .collect();
            let h = 0.3 + next();
            let y0: Vec<f64> = (0..n).map(|_| 10.0 * next()).collect();
            let carried0: Vec<f64> = (0..n).map(|_| 1e-17 * next()).collect();
            let (mut y, mut carried) = (y0.clone(), carried0.clone());
            horner(&rows, w, h, &mut y, &mut carried);
            let (mut y2, mut carried2) = (y0, carried0);
            horner_by_coefficient(&by_order, w, h, &mut y2, &mut carried2);
            for i in 0..n {
                assert_eq!(y[i].to_bits(), y2[i].to_bits(), "{n} states, order {order}, state {i}");
                assert_eq!(
                    carried[i].to_bits(),
                    carried2[i].to_bits(),
                    "{n} states, order {order}, state {i}"
                );
            }
        }
    }

    /// Increments below half an ulp of the state are lost by a plain sum
    /// and kept by the carried error: 1024 steps of 2⁻⁶⁰ from 1 (y' = 1,
    /// order 2) end at 1 + 2⁻⁵⁰ exactly.
    #[test]
    fn increments_smaller_than_an_ulp_are_carried_to_later_steps() {
        let h = 2f64.powi(-60);
        let (mut y, mut carried) = (vec![1.0; 5], vec![0.0; 5]);
        for _ in 0..1024 {
            let rows: Vec<f64> = y.iter().flat_map(|&yi| [yi, 1.0, 0.0]).collect();
            horner(&rows, 3, h, &mut y, &mut carried);
        }
        for yi in y {
            assert_eq!(yi, 1.0 + 2f64.powi(-50));
        }
    }
}
