//! The adaptive Taylor method (Jorba & Zou 2005, as in heyoka's
//! `taylor_determine_h`): coefficients from the model's AD tape
//! (`taylor_tape.rs`), order p = max(2, ⌈−ln(tol)/2 + 1⌉) from the
//! tolerance, step h = min(ρ_{p−1}, ρ_p)·e⁻²·e^(−0.7/(p−1)) with
//! ρ_k = (N/‖x^\[k\]‖∞)^(1/k), N = max(1, ‖x‖∞) (absolute below 1, relative
//! above). No step is rejected. Time is summed with compensation, and each
//! step's polynomial is the dense output.

use crate::error::Error;
use crate::events::{stop_at_terminal_event, EventWatch};
use crate::model::Model;
use crate::options::Options;
use crate::projection::{project_onto_constraints, Projector};
use crate::solution::Solution;
use crate::taylor_tape::{mul_add, TaylorWork};

/// Sub-intervals of each step on which event functions are checked for a
/// sign change.
const EVENT_SAMPLES: usize = 8;

/// The position of the first NaN or infinity in `c`, if any. The common
/// case, all finite, is one pass of four independent sums of `x − x`
/// (zero for finite x, NaN otherwise).
fn first_non_finite(c: &[f64]) -> Option<usize> {
    let mut lanes = [0.0f64; 4];
    let chunks = c.chunks_exact(4);
    let tail = chunks.remainder();
    for x in chunks {
        for l in 0..4 {
            lanes[l] += x[l] - x[l];
        }
    }
    let total = tail
        .iter()
        .fold(lanes.iter().sum::<f64>(), |s, x| s + (x - x));
    if total == 0.0 {
        return None;
    }
    c.iter().position(|x| !x.is_finite())
}

/// Sums each state's series (rows of `w` coefficients) at `h`: the even
/// and the odd coefficients each by Horner's rule in h², y = E(h²) +
/// h·O(h²) (Estrin's split), four states at a time. The eight chains are
/// independent, so they overlap instead of waiting on one another: the sum
/// costs the latency of w/2 fused multiply-adds, not 2w operations.
fn horner(rows: &[f64], w: usize, h: f64, y: &mut [f64]) {
    let h2 = h * h;
    for (ys, block) in y.chunks_mut(4).zip(rows.chunks(4 * w)) {
        if let ([y0, y1, y2, y3], true) = (&mut *ys, block.len() == 4 * w) {
            let (r0, rest) = block.split_at(w);
            let (r1, rest) = rest.split_at(w);
            let (r2, r3) = rest.split_at(w);
            let (mut even, mut odd) = ([0.0f64; 4], [0.0f64; 4]);
            let pairs = r0
                .chunks(2)
                .zip(r1.chunks(2))
                .zip(r2.chunks(2).zip(r3.chunks(2)))
                .rev();
            for ((c0, c1), (c2, c3)) in pairs {
                for (l, c) in [c0, c1, c2, c3].into_iter().enumerate() {
                    even[l] = mul_add(even[l], h2, c[0]);
                    odd[l] = mul_add(odd[l], h2, c.get(1).copied().unwrap_or(0.0));
                }
            }
            [*y0, *y1, *y2, *y3] = [
                mul_add(h, odd[0], even[0]),
                mul_add(h, odd[1], even[1]),
                mul_add(h, odd[2], even[2]),
                mul_add(h, odd[3], even[3]),
            ];
        } else {
            for (yi, row) in ys.iter_mut().zip(block.chunks_exact(w)) {
                *yi = row.iter().rev().fold(0.0, |acc, &c| mul_add(acc, h, c));
            }
        }
    }
}

/// The order the method uses for a tolerance.
pub fn order_for(tol: f64) -> usize {
    ((-tol.ln() / 2.0 + 1.0).ceil() as usize).max(2)
}

/// Component `i` of the step polynomial at `s = (t − t_old)/h`; the
/// coefficients are stored state by state, already multiplied by hᵏ.
pub(crate) fn interpolate(c: &[f64], n: usize, i: usize, s: f64) -> f64 {
    let w = c.len() / n;
    c[i * w..(i + 1) * w]
        .iter()
        .rev()
        .fold(0.0, |acc, ck| acc * s + ck)
}

/// Integrates `model` from `t0` to `t1` with the adaptive Taylor method.
pub(crate) fn integrate<M: Model>(
    model: &M,
    t0: f64,
    t1: f64,
    y0: &[f64],
    options: &Options,
    mut solution: Solution,
) -> Result<Solution, Error> {
    let Some((tape, outputs)) = model.taylor_tape() else {
        return Err(Error::InvalidOptions {
            message:
                "Method::Taylor needs the model expanded with #[dae_model(taylor = p)] (any p)"
                    .into(),
        });
    };
    let n = M::STATES;
    let tol = if options.rtol > 0.0 {
        options.rtol
    } else {
        options.atol
    };
    let p = order_for(tol);
    // The straight-line recurrences when the macro emitted this order,
    // else the interpreted tape.
    let unrolled = M::TAYLOR_UNROLLED.contains(&p) && !options.taylor_compact;
    let mut work = (!unrolled).then(|| TaylorWork::new(&tape, &outputs, n, p));
    let mut jet = vec![0.0; if unrolled { n * (p + 1) } else { 0 }];
    let mut y = y0.to_vec();
    let mut dense = vec![0.0; (p + 1) * n];
    let mut powers = vec![0.0; p + 1];
    // Taylor steps are long (a good part of an orbit): the event functions
    // are sampled inside them, so two crossings in one step are both found.
    let mut events = EventWatch::new(model, t0, y0, EVENT_SAMPLES);
    let mut projector = Projector::new(model);
    let keep_dense = options.dense_output || events.is_some();
    if keep_dense {
        solution.set_interpolant(p + 1, interpolate);
    }
    let direction = if t1 >= t0 { 1.0 } else { -1.0 };
    let hmax = options.max_step.unwrap_or(f64::INFINITY);
    let safety = (-2.0f64).exp() * (-0.7 / (p as f64 - 1.0)).exp();
    let (mut t, mut compensation, mut steps) = (t0, 0.0f64, 0usize);
    while (t1 - t) * direction > 0.0 {
        if steps >= options.max_steps {
            return Err(Error::MaxSteps {
                t,
                max_steps: options.max_steps,
                partial: Box::new(solution),
            });
        }
        let coefficients: &[f64] = match work.as_mut() {
            Some(work) => {
                work.compute(t, &y);
                work.rows()
            }
            None => {
                model.taylor_jet_unrolled(t, &y, p, &mut jet);
                &jet
            }
        };
        let w = p + 1;
        let state = |i: usize| &coefficients[i * w..(i + 1) * w];
        solution.stats_mut().rhs_evals += 1;
        let norm = |k: usize| (0..n).map(|i| state(i)[k].abs()).fold(0.0, f64::max);
        let big_n = norm(0).max(1.0);
        // ρ_k = (N/‖x^[k]‖)^(1/k); of ρ_{p−1} and ρ_p the smaller, compared
        // through logarithms so that only one power is taken.
        let (norm_pm1, norm_p) = (norm(p - 1), norm(p));
        let log_rho = |nk: f64, k: usize| {
            if nk == 0.0 {
                f64::INFINITY
            } else {
                (big_n / nk).ln() / k as f64
            }
        };
        let rho = log_rho(norm_pm1, p - 1).min(log_rho(norm_p, p)).exp();
        let remaining = (t1 - t).abs();
        // A polynomial solution has an infinite radius: the step is then
        // limited by the interval and max_step only.
        let mut h = (rho * safety).min(hmax);
        let last = !(h < remaining);
        if last {
            h = remaining;
        }
        if !(h > t.abs().max(1e-300) * f64::EPSILON) {
            // Non-finite coefficients make the step collapse: say which.
            if let Some(at) = first_non_finite(&coefficients[..n * w]) {
                return Err(Error::NonFinite {
                    t,
                    variable: M::INFO.states[at / w],
                    partial: Box::new(solution),
                });
            }
            return Err(Error::StepSizeUnderflow {
                t,
                h,
                partial: Box::new(solution),
            });
        }
        let h = direction * h;
        if keep_dense {
            // The coefficients scaled by hᵏ are the step's dense output
            // (the powers as four interleaved chains of h⁴ products).
            let (h2, h3) = (h * h, h * h * h);
            let h4 = h2 * h2;
            for (k, power) in powers.iter_mut().enumerate().take(4) {
                *power = [1.0, h, h2, h3][k];
            }
            for k in 4..=p {
                powers[k] = powers[k - 4] * h4;
            }
            for (d, c) in dense.chunks_exact_mut(w).zip(coefficients.chunks_exact(w)) {
                for ((d, c), power) in d.iter_mut().zip(c).zip(&powers) {
                    *d = c * power;
                }
            }
        }
        // A non-finite coefficient makes its state non-finite (h is finite
        // and non-zero), which the check after the step reports.
        horner(&coefficients[..n * w], w, h, &mut y);
        let step = h - compensation;
        let t_next = t + step;
        compensation = (t_next - t) - step;
        t = if last { t1 } else { t_next };
        if let Some(i) = y.iter().position(|v| !v.is_finite()) {
            return Err(Error::NonFinite {
                t,
                variable: M::INFO.states[i],
                partial: Box::new(solution),
            });
        }
        project_onto_constraints!(projector, t, &mut y, solution);
        if keep_dense {
            solution.push_dense(t, &y, &dense);
        } else {
            solution.push(t, &y);
        }
        solution.stats_mut().steps += 1;
        steps += 1;
        stop_at_terminal_event!(events, solution);
    }
    Ok(solution)
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
    fn horner_sums_every_state_in_blocks_and_the_rest() {
        // Seven states (a block of four and three more), order 3:
        // state i is 1 + i·x + x² + (i+1)·x³ at x = 0.5.
        let (w, n, h) = (4, 7, 0.5);
        let rows: Vec<f64> = (0..n)
            .flat_map(|i| [1.0, i as f64, 1.0, (i + 1) as f64])
            .collect();
        let mut y = vec![0.0; n];
        horner(&rows, w, h, &mut y);
        for (i, yi) in y.iter().enumerate() {
            let want = 1.0 + i as f64 * h + h * h + (i + 1) as f64 * h * h * h;
            assert_eq!(*yi, want, "state {i}");
        }
    }

    #[test]
    fn order_follows_heyoka() {
        // heyoka: tol 1e-16 → p = 20, 1e-9 → p = 12 (design notes).
        assert_eq!(order_for(1e-16), 20);
        assert_eq!(order_for(1e-9), 12);
        assert_eq!(order_for(0.5), 2);
    }
}
