//! How stiff a problem is where the step is: Hairer's test in the explicit
//! pairs, and the spectral radius of the Jacobian for RADAU5 (by the
//! power iteration of `linalg`), which
//! [`crate::Method::Auto`] compares with the explicit pair's stability
//! boundary to switch between the two.
//!
//! An explicit pair is held back by stiffness when h·ρ(J) sits near the
//! edge of its stability region on the negative real axis (Hairer, Nørsett,
//! Wanner I §IV.2; `dopri5.f` and `dop853.f`, NSTIFF), or, on a stiff
//! problem with a smooth forcing, well inside it where the error estimate
//! of the stiff component limits the step (measured: a low-pass filter
//! with τ = 2e-4 holds DOPRI5 at h·ρ ≈ 1.5 at rtol 1e-6, 0.5 at 1e-9).
//! Non-stiff problems reach h·ρ ≈ 0.4 of the boundary only at loose
//! tolerances (Lorenz at 1e-3, the largest of the reference problems), so
//! where RADAU5's steps are cheap, `Auto` tries it from a fraction of the
//! boundary and returns to the pair when RADAU5's steps do not grow.

/// How a run that watches for a change of stiffness ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Finish {
    /// At t1 (or at a terminal event).
    Done,
    /// An explicit pair found the problem stiff at `t`, with the step `h`
    /// and its h·ρ.
    StiffAt { t: f64, h: f64, h_rho: f64 },
    /// RADAU5 found the problem non-stiff at `t`; `h` is the step it would
    /// take next.
    NonStiffAt { t: f64, h: f64 },
}

/// When RADAU5 hands back to an explicit pair: after `confirmations`
/// settled steps in a row (not growing twofold) with h·ρ below `below`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct NonStiffWatch {
    /// h·ρ of RADAU5's step below which the pair would do as well.
    pub(crate) below: f64,
    /// Steps in a row that decide.
    pub(crate) confirmations: usize,
}

/// Counts the steps where h·ρ exceeds a bound, as Hairer's codes do: the
/// problem is stiff after `confirmations` such steps not interrupted by six
/// steps below it. With a `ratio`, a step counts only where h·ρ also
/// exceeds `ratio` times the relative change of the solution over the step:
/// ρ is then `ratio` times the rate the solution itself changes at, the
/// mark of stiffness (Hairer & Wanner II §IV.1), which tells a step held by
/// a stiff component from one that follows a fast solution.
#[derive(Clone, Copy, Debug)]
pub(crate) struct StiffnessTest {
    /// h·ρ beyond which a step counts as stiff.
    pub(crate) bound: f64,
    /// Stiff steps that decide.
    pub(crate) confirmations: usize,
    /// ρ over the solution's rate beyond which a step counts (0: any).
    pub(crate) ratio: f64,
    stiff: usize,
    non_stiff: usize,
    /// The time of the first stiff step of the current streak.
    onset: f64,
}

impl StiffnessTest {
    /// A test that decides after `confirmations` steps with h·ρ > `bound`.
    pub(crate) fn new(bound: f64, confirmations: usize) -> StiffnessTest {
        StiffnessTest { bound, confirmations, ratio: 0.0, stiff: 0, non_stiff: 0, onset: f64::NAN }
    }

    /// The same test, counting only steps where ρ exceeds `ratio` times
    /// the solution's own rate.
    pub(crate) fn with_ratio(self, ratio: f64) -> StiffnessTest {
        StiffnessTest { ratio, ..self }
    }

    /// Notes a step at `t` with `h_rho` = h·ρ that changed the solution by
    /// `change()` relative to its size (asked only where h·ρ is beyond the
    /// bound and a ratio is set, so a calm step costs a comparison); `true`
    /// when the problem is found stiff.
    #[inline]
    pub(crate) fn step_is_stiff(
        &mut self,
        t: f64,
        h_rho: f64,
        change: impl FnOnce() -> f64,
    ) -> bool {
        if h_rho > self.bound && (self.ratio == 0.0 || h_rho > self.ratio * change()) {
            if self.stiff == 0 {
                self.onset = t;
            }
            self.non_stiff = 0;
            self.stiff += 1;
            self.stiff >= self.confirmations
        } else {
            self.non_stiff += 1;
            if self.non_stiff == 6 {
                self.stiff = 0;
            }
            false
        }
    }

    /// Where the streak that decided began.
    pub(crate) fn onset(&self) -> f64 {
        self.onset
    }
}

/// Hairer's estimate of h·ρ(J) from two stages at the same time t + h:
/// h‖k_s − k_{s−1}‖/‖Y_s − Y_{s−1}‖, the Jacobian's action on the last
/// difference of stage values (`dopri5.f`, HLAMB). 0 where the stage values
/// coincide. Inlined, so that the sums run over the model's fixed length.
#[inline(always)]
pub(crate) fn stage_quotient(
    h: f64,
    k_last: &[f64],
    k_before: &[f64],
    y_last: &[f64],
    y_before: &[f64],
) -> f64 {
    let num: f64 = k_last.iter().zip(k_before).map(|(a, b)| (a - b).powi(2)).sum();
    let den: f64 = y_last.iter().zip(y_before).map(|(a, b)| (a - b).powi(2)).sum();
    if den > 0.0 && num.is_finite() {
        h.abs() * (num / den).sqrt()
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hairers_test_needs_a_streak_and_forgives_isolated_steps() {
        let mut test = StiffnessTest::new(3.25, 3);
        assert!(!test.step_is_stiff(0.0, 4.0, || 1.0));
        assert!(!test.step_is_stiff(1.0, 4.0, || 1.0));
        // Five calm steps do not reset the streak, six do.
        for k in 0..5 {
            assert!(!test.step_is_stiff(2.0 + k as f64, 1.0, || 1.0));
        }
        assert!(test.step_is_stiff(7.0, 4.0, || 1.0));
        assert_eq!(test.onset(), 0.0);
        let mut test = StiffnessTest::new(3.25, 2);
        assert!(!test.step_is_stiff(0.0, 4.0, || 1.0));
        for k in 0..6 {
            assert!(!test.step_is_stiff(1.0 + k as f64, 1.0, || 1.0));
        }
        assert!(!test.step_is_stiff(8.0, 4.0, || 1.0));
        assert!(test.step_is_stiff(9.0, 4.0, || 1.0));
        assert_eq!(test.onset(), 8.0);
        // With a ratio, a step that changes the solution as fast as ρ says
        // is not held back by stiffness.
        let mut test = StiffnessTest::new(0.5, 1).with_ratio(20.0);
        assert!(!test.step_is_stiff(0.0, 1.0, || 0.5));
        assert!(test.step_is_stiff(1.0, 1.0, || 0.01));
    }

    #[test]
    fn the_stage_quotient_of_a_linear_problem_is_h_lambda() {
        let q = stage_quotient(0.01, &[-1000.0 * 2.0], &[-1000.0 * 1.5], &[2.0], &[1.5]);
        assert!((q - 10.0).abs() < 1e-12, "{q}");
    }
}
