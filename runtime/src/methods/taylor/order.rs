//! The adaptive Taylor method's order for a tolerance, chosen for the
//! least work per unit of time from the model's own cost per order.
//!
//! Jorba & Zou (2005, Experimental Mathematics 14, the choice of order
//! and step) take the step h = ρ·e⁻² and the order
//! p = ⌈−ln(tol)/2 + 1⌉, which truncates each step at (h/ρ)^(p−1) ≈ tol·e²
//! and minimises the work per unit time when a step costs ∝ p², that is,
//! when the convolutions dominate. That holds for large models (the outer
//! solar system), not for small ones: Lorenz's step is mostly a fixed
//! cost (the step-size rule, the update) and terms linear in the order, so
//! fewer, longer steps of higher order are cheaper. We keep Jorba & Zou's
//! truncation, the first term dropped being (h₀/ρ)^(p₀+1) with p₀ and h₀
//! their order and step ([`step_factor`]), and choose p to minimise
//! cost(p)/h, the work per unit of time at a given ρ.
//!
//! Matching the first dropped term, rather than (h/ρ)^(p−1) = tol·e² as
//! their derivation does, keeps the errors at a tolerance nearer theirs:
//! ρ is estimated from the last coefficients, and the higher the order,
//! the less that estimate errs on the safe side. For the same reason the
//! step stays within [`MAX_STEP_FACTOR`]·ρ, which bounds the order.

use crate::model::Model;
use crate::taylor_tape::{Operand, TapeOp};

/// The fixed work of a step (the norms and logarithms of the step-size
/// rule, the bookkeeping), in multiply-adds of the jet. Measured on Kepler
/// and Lorenz (order 15): the rule and the update take 60–90 ns, as long
/// as 350–450 of the jet's multiply-adds.
const FIXED_STEP_COST: f64 = 400.0;

/// How many times slower the interpreted tape is than the straight-line
/// recurrences, per multiply-add (3.9–9.3× measured at 1e-12 on Kepler,
/// Arenstorf and the outer solar system): its orders compete with the
/// unrolled ones only when none of those is near the best.
const INTERPRETED_SLOWDOWN: f64 = 4.0;

/// The Jorba–Zou order for a tolerance, p₀ = max(2, ⌈−ln(tol)/2 + 1⌉),
/// heyoka's choice.
pub fn jorba_zou_order(tol: f64) -> usize {
    ((-tol.ln() / 2.0 + 1.0).ceil() as usize).max(2)
}

/// The work of the model's recurrences, in multiply-adds: order k costs
/// `linear + convolution·k`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JetCost {
    /// The work per order that does not grow with it: sums, products by
    /// constants, the states' scaling by 1/k and their Horner terms.
    pub linear: f64,
    /// The work per order that grows with k: the convolutions of products,
    /// quotients and the elementary functions' recurrences.
    pub convolution: f64,
}

impl JetCost {
    /// Counts the work of a tape whose outputs are the derivatives of
    /// `states` states.
    pub fn of_tape(tape: &[TapeOp], states: usize) -> JetCost {
        let is_const = |a: &Operand| matches!(a, Operand::Const(_));
        let mut cost = JetCost { linear: 2.0 * states as f64, convolution: 0.0 };
        for op in tape {
            // (linear, convolution) per op: a product of two series is
            // k + 1 multiply-adds at order k, a square half that; a
            // function's recurrence is one or two convolutions.
            let (linear, convolution) = match op {
                TapeOp::Add(..) => (1.0, 0.0),
                TapeOp::Mul(a, b) | TapeOp::Div(a, b) if is_const(a) || is_const(b) => (1.0, 0.0),
                TapeOp::Mul(a, b) if a == b => (1.0, 0.5),
                TapeOp::Mul(..) | TapeOp::Div(..) => (1.0, 1.0),
                TapeOp::Pow(..) => (2.0, 2.0),
                TapeOp::Exp(_) | TapeOp::Ln(_) => (1.0, 1.0),
                TapeOp::Sin(_) | TapeOp::Sinh(_) => (2.0, 2.0),
                TapeOp::CosOfPrevious | TapeOp::CoshOfPrevious => (0.0, 0.0),
                TapeOp::Inverse(..) => (2.0, 2.0),
                TapeOp::Atan2(..) => (2.0, 3.0),
                TapeOp::Copy(_) => (1.0, 0.0),
                // Order k: g^[k] − Σ_j E^[j] z^[k−j] (k·n² multiply-adds)
                // and the solve with the LU (n²).
                TapeOp::Solve { size, .. } => {
                    let n2 = (size * size) as f64;
                    (n2, n2)
                }
                TapeOp::SolvedWithPrevious => (0.0, 0.0),
            };
            cost.linear += linear;
            cost.convolution += convolution;
        }
        cost
    }

    /// The work of one step of order p, fixed part included.
    pub fn step(&self, p: usize) -> f64 {
        let p = p as f64;
        FIXED_STEP_COST + self.linear * p + self.convolution * p * (p + 1.0) / 2.0
    }
}

/// The step's factor of ρ at order p for the tolerance, h/ρ =
/// exp(−(2 + 0.7/(p₀−1))·(p₀+1)/(p+1)): the first term dropped,
/// (h/ρ)^(p+1), is the one Jorba & Zou drop at p₀ with h/ρ =
/// e⁻²·e^(−0.7/(p₀−1)), their step exactly at p = p₀.
pub fn step_factor(tol: f64, p: usize) -> f64 {
    let p0 = jorba_zou_order(tol) as f64;
    (-(2.0 + 0.7 / (p0 - 1.0)) * (p0 + 1.0) / (p as f64 + 1.0)).exp()
}

/// When the method picks the order itself, the first term it drops is
/// this fraction of Jorba & Zou's, so that its final error at a tolerance
/// is not above theirs (heyoka's). Their error does not fall evenly with
/// the tolerance: from an odd p₀ to the even one after it, it falls by up
/// to 100× (Lorenz, p₀ = 11 → 12: 8.0e-7 → 7.4e-9), from an even p₀ to
/// the next by as little as 1.5×, while the e² its truncation falls is the
/// mean. Our orders are even, and with the dropped term equal to theirs
/// our errors follow that mean: 0.14–1.6× theirs in geometric mean over
/// tolerances 1e-6 … 1e-15 four a decade, but up to 2.8–3.7× at their
/// even p₀ (Kepler e = 0.9, Lorenz, the outer solar system). A fifth of
/// their dropped term brings the largest ratio where the truncation
/// dominates to 0.74 (at tolerances where rounding does, both errors are
/// draws: `cd bench && cargo run --release -- --taylor-error`), for
/// 5^(1/(p+1)) = 1.07–1.12 times the steps at orders 14–24. An order
/// given in the options keeps Jorba & Zou's step, heyoka's at p₀.
pub const CHOSEN_ORDER_MARGIN: f64 = 0.2;

/// The step's factor of ρ at an order the method picked:
/// [`step_factor`] with the first term dropped [`CHOSEN_ORDER_MARGIN`]
/// times theirs, (h/ρ)^(p+1) = margin·(h₀/ρ)^(p₀+1).
pub fn chosen_order_step_factor(tol: f64, p: usize) -> f64 {
    step_factor(tol, p) * CHOSEN_ORDER_MARGIN.powf(1.0 / (p as f64 + 1.0))
}

/// The longest step, as a fraction of ρ, that an order may take. Beyond
/// about 0.2 the first dropped term no longer predicts the error: with the
/// orders uncapped (h/ρ up to 0.33), the final errors on Kepler and Lorenz
/// at a tolerance were up to 20–90× those of Jorba & Zou's order (Lorenz
/// at 1e-9, Kepler at 1e-13), for 0.76–1.06× their time at equal error;
/// capped here, within the scatter of Jorba & Zou's own errors, for
/// 0.76–0.98× their time (Kepler, Arenstorf, Lorenz at 1e-9 … 1e-15, the
/// fastest solve that reaches each error on a grid four tolerances a
/// decade). The estimate of ρ from two coefficients errs more at higher
/// orders, and the dropped tail (h/ρ)^(p+1)/(1 − h/ρ) grows with h/ρ.
pub const MAX_STEP_FACTOR: f64 = 0.2019; // e^−1.6

/// The highest order considered at a tolerance: the last whose step
/// ([`chosen_order_step_factor`]) stays within [`MAX_STEP_FACTOR`]·ρ, at
/// most 2·p₀.
pub fn highest_order(tol: f64) -> usize {
    let p0 = jorba_zou_order(tol);
    (p0..=2 * p0)
        .take_while(|&p| chosen_order_step_factor(tol, p) <= MAX_STEP_FACTOR)
        .last()
        .unwrap_or(p0)
}

/// The order of least work per unit time for the tolerance, and whether
/// it is one of `unrolled` (else the interpreted tape runs it), among the
/// even orders 2 ..= [`highest_order`].
///
/// Even orders only: on an eccentric orbit the error gathers at the
/// pericentre passages, about which the motion is symmetric in time, and
/// the first term an odd order drops, of even degree, lies in the
/// components even in time there (Kepler's q₁ and p₂), the ones that carry
/// the energy; its error then drifts the phase orbit after orbit. On
/// Kepler e = 0.9 at 1e-12 (ten orbits, same step rule) orders 12, 14, …,
/// 20 end 1.5e-10 to 1.3e-9 off, orders 13, 15, …, 19 8e-9 to 2.4e-8.
/// Arenstorf and Lorenz show no such effect, and the work optimum is flat:
/// the fastest solve reaching each error on a grid of tolerances is the
/// same, within ±5 %, with the odd orders allowed.
pub fn choose_order(tol: f64, cost: &JetCost, unrolled: &[usize]) -> (usize, bool) {
    let highest = highest_order(tol);
    let work_per_time =
        |p: usize, slowdown: f64| cost.step(p) * slowdown / chosen_order_step_factor(tol, p);
    let mut best = (2, false);
    let mut least = work_per_time(2, INTERPRETED_SLOWDOWN);
    for p in (2..=highest).filter(|p| p % 2 == 0) {
        for (is_unrolled, slowdown) in [(false, INTERPRETED_SLOWDOWN), (true, 1.0)] {
            if is_unrolled && !unrolled.contains(&p) {
                continue;
            }
            let work = work_per_time(p, slowdown);
            if work < least {
                (best, least) = ((p, is_unrolled), work);
            }
        }
    }
    best
}

/// The order `Method::Taylor` would choose for `model` at `tol` if every
/// order were unrolled: the one to list in `#[dae_model(unroll = [..])]`
/// for that tolerance. `None` when the model has no Taylor tape.
pub fn order_to_unroll<M: Model>(model: &M, tol: f64) -> Option<usize> {
    let (tape, _) = model.taylor_tape()?;
    let cost = JetCost::of_tape(&tape, M::STATES);
    let every: Vec<usize> = (2..=highest_order(tol)).collect();
    Some(choose_order(tol, &cost, &every).0)
}

#[cfg(test)]
mod tests {
    use super::*;

    const TOLERANCES: [f64; 4] = [1e-6, 1e-9, 1e-12, 1e-15];

    #[test]
    fn the_step_is_jorba_and_zous_at_their_order_and_longer_above_it() {
        for tol in TOLERANCES {
            let p0 = jorba_zou_order(tol);
            let theirs = (-2.0f64).exp() * (-0.7 / (p0 as f64 - 1.0)).exp();
            assert!((step_factor(tol, p0) / theirs - 1.0).abs() <= 4.0 * f64::EPSILON);
            for p in p0..2 * p0 {
                assert!(step_factor(tol, p + 1) > step_factor(tol, p));
                // The first term dropped is theirs: (h/ρ)^(p+1) fixed.
                let dropped = step_factor(tol, p).powi(p as i32 + 1);
                assert!((dropped / theirs.powi(p0 as i32 + 1) - 1.0).abs() <= 1e-13);
            }
        }
    }

    #[test]
    fn jorba_zou_order_follows_heyoka() {
        assert_eq!(jorba_zou_order(1e-16), 20);
        assert_eq!(jorba_zou_order(1e-12), 15);
        assert_eq!(jorba_zou_order(1e-9), 12);
        assert_eq!(jorba_zou_order(0.5), 2);
    }

    /// Work ∝ p² (convolutions only) is Jorba & Zou's premise: their order
    /// comes back, give or take the rounding of p₀, one for the exact
    /// minimum of p²·exp(a(p₀+1)/(p+1)) at p + 1 ≈ a(p₀+1)/2, a ≈ 2.05, and
    /// one to make it even.
    #[test]
    fn convolution_bound_models_keep_jorba_and_zous_order() {
        let cost = JetCost { linear: 0.0, convolution: 1e6 };
        for tol in TOLERANCES {
            let p0 = jorba_zou_order(tol);
            let (p, unrolled) = choose_order(tol, &cost, &[]);
            assert!(!unrolled);
            assert!(p % 2 == 0 && p + 1 >= p0 && p <= p0 + 2, "tol {tol:e}: {p} against {p0}");
        }
    }

    #[test]
    fn a_chosen_order_drops_a_fifth_of_their_term() {
        for tol in TOLERANCES {
            let p0 = jorba_zou_order(tol);
            let theirs = step_factor(tol, p0).powi(p0 as i32 + 1);
            for p in p0..2 * p0 {
                let dropped = chosen_order_step_factor(tol, p).powi(p as i32 + 1);
                assert!((dropped / (CHOSEN_ORDER_MARGIN * theirs) - 1.0).abs() <= 1e-13);
            }
        }
    }

    /// A step of fixed cost only: the longest steps win, up to the cap on
    /// h/ρ (e^−1.6: p + 1 ≤ 1.6⁻¹((2 + 0.7/(p₀−1))(p₀+1) + ln 5), 20 at
    /// 1e-12) and the last even order below it.
    #[test]
    fn fixed_cost_models_take_the_highest_order() {
        let cost = JetCost { linear: 0.0, convolution: 0.0 };
        for tol in TOLERANCES {
            let p0 = jorba_zou_order(tol) as f64;
            let exponent = (2.0 + 0.7 / (p0 - 1.0)) * (p0 + 1.0) + 5f64.ln();
            let bound = (exponent / 1.6 - 1.0).floor() as usize;
            assert_eq!(highest_order(tol), bound, "tol {tol:e}");
            assert!(chosen_order_step_factor(tol, bound) <= MAX_STEP_FACTOR);
            assert!(chosen_order_step_factor(tol, bound + 1) > MAX_STEP_FACTOR);
            // The highest even order.
            assert_eq!(choose_order(tol, &cost, &[]).0, bound / 2 * 2, "tol {tol:e}");
        }
        assert_eq!(highest_order(1e-12), 20);
    }

    /// Lorenz's costs (17 linear, 2 convolution): a higher order than
    /// Jorba & Zou's, and an unrolled order is preferred to the tape's
    /// unless it is far from the best.
    #[test]
    fn small_models_take_higher_orders_and_prefer_unrolled_ones() {
        let cost = JetCost { linear: 17.0, convolution: 2.0 };
        let best = choose_order(1e-12, &cost, &[]).0;
        assert!(best > jorba_zou_order(1e-12) + 2, "{best}");
        assert_eq!(choose_order(1e-12, &cost, &[best]), (best, true));
        assert_eq!(choose_order(1e-12, &cost, &[15, 18]), (18, true));
        // Order 4 unrolled is worse than the tape at its best; odd orders
        // are not used even when unrolled.
        assert!(!choose_order(1e-12, &cost, &[4]).1);
        assert_eq!(choose_order(1e-12, &cost, &[17]).0 % 2, 0);
        // Unrolled orders are all cheaper than the tape's.
        let all: Vec<usize> = (2..=30).collect();
        assert_eq!(choose_order(1e-12, &cost, &all), (best, true));
    }

    #[test]
    fn the_cost_of_a_tape_counts_each_operation_once() {
        use Operand::{Const, State, Var};
        // A sum, a scaled term, a product, a square, a power and a pair.
        let tape = [
            TapeOp::Add(State(1), Var(9)),
            TapeOp::Mul(Const(10.0), Var(0)),
            TapeOp::Mul(State(0), State(2)),
            TapeOp::Mul(State(0), State(0)),
            TapeOp::Pow(Var(3), -1.5),
            TapeOp::Sin(State(1)),
            TapeOp::CosOfPrevious,
        ];
        let cost = JetCost::of_tape(&tape, 3);
        // 6 for the three states, then 1 + 1 + 1 + 1 + 2 + 2 + 0.
        assert_eq!(cost.linear, 14.0);
        assert_eq!(cost.convolution, 1.0 + 0.5 + 2.0 + 2.0);
        assert_eq!(cost.step(2), FIXED_STEP_COST + 28.0 + 5.5 * 3.0);
    }
}
