//! Step-size control: Hairer's weighted RMS error norm, the PI controller
//! of DOPRI5/DOP853 and their initial step selection (Hairer, Nørsett,
//! Wanner, *Solving ODEs I*, §II.4, and the codes `dopri5.f`, `dop853.f`),
//! and the predictive controller of RADAU5 and RODAS5P.

/// Controller constants of one method.
#[derive(Clone, Copy, Debug)]
pub struct Controller {
    /// Exponent of the error in the new step: 1/(q+1) − 0.75 β for DOPRI5.
    pub exponent: f64,
    /// PI stabilisation β (0.04 for DOPRI5, 0 for DOP853).
    pub beta: f64,
    /// The step shrinks by at most this factor (1/5 for DOPRI5, 1/3 for DOP853).
    pub min_factor: f64,
    /// The step grows by at most this factor (10 for DOPRI5, 6 for DOP853).
    pub max_factor: f64,
    /// Safety factor.
    pub safety: f64,
}

/// State of the PI controller between steps: β·ln of the last accepted
/// error (at least 1e-4), kept so that a step takes one logarithm and one
/// exponential: err^α / err_old^β = exp(α ln err − β ln err_old).
#[derive(Clone, Copy, Debug)]
pub struct PiState {
    previous_beta_ln: f64,
}

impl Default for PiState {
    fn default() -> Self {
        // Hairer's facold = 1e-4 before the first step.
        PiState { previous_beta_ln: f64::NAN }
    }
}

/// `x^e` for the controller's exponents: DOP853's 1/8 by three square
/// roots and β = 0 as 1, within two ulps of `powf` and without the libm
/// call that took a tenth of DOP853's time on two-body problems.
fn power(x: f64, e: f64) -> f64 {
    if e == 0.0 {
        1.0
    } else if e == 0.125 {
        x.sqrt().sqrt().sqrt()
    } else {
        x.powf(e)
    }
}

/// ln 1e-4: Hairer's floor on the remembered error.
const LN_FLOOR: f64 = -9.210340371976182;

impl Controller {
    /// The factor `h_new / h` after a step with scaled error `err`, and the
    /// controller state to keep if the step is accepted: Hairer's
    /// `1 / clamp(err^α / err_old^β / safety, 1/max, 1/min)`, written as
    /// `clamp(safety · exp(β ln err_old − α ln err), min, max)` so that no
    /// division waits between the error and the next step.
    #[inline]
    pub fn factor(&self, err: f64, state: PiState) -> (f64, PiState) {
        let previous = match state.previous_beta_ln.is_nan() {
            true => self.beta * LN_FLOOR,
            false => state.previous_beta_ln,
        };
        let (growth, beta_ln) = if self.beta == 0.0 {
            // No memory (DOP853): the error's power alone, without libm.
            (self.safety / power(err, self.exponent), 0.0)
        } else if err > 0.0 && err.is_finite() {
            // Two `powf` calls were a fifth of DOPRI5's step on a
            // three-state problem; one logarithm and one exponential
            // give the same factor to a few ulps.
            let ln = err.ln();
            (self.safety * (previous - self.exponent * ln).exp(), self.beta * ln.max(LN_FLOOR))
        } else {
            let floor = err.max(1e-4);
            (self.safety * previous.exp() / power(err, self.exponent), self.beta * floor.ln())
        };
        (growth.clamp(self.min_factor, self.max_factor), PiState { previous_beta_ln: beta_ln })
    }

    /// The factor after a rejected step: no PI memory, only shrinking.
    pub fn rejected_factor(&self, err: f64) -> f64 {
        let fac11 = power(err, self.exponent);
        1.0 / (fac11 / self.safety).min(1.0 / self.min_factor)
    }
}

/// `w_i = 1 / (atol + rtol · max(|y_i|, |y_new_i|))`: the error norm's
/// weights, as reciprocals so that the error multiplies by them (the
/// reciprocal is taken while the last stage evaluates; a division after
/// it would wait in every step). Inlined, so that the loop runs over the
/// model's fixed length.
#[inline(always)]
pub fn error_weights(atol: f64, rtol: f64, y: &[f64], y_new: &[f64], w: &mut [f64]) {
    for ((w, a), b) in w.iter_mut().zip(y).zip(y_new) {
        *w = 1.0 / (atol + rtol * a.abs().max(b.abs()));
    }
}

/// Evaluates f(t, y) into the last argument; `false` if f failed.
pub type RhsProbe<'a> = dyn FnMut(f64, &[f64], &mut [f64]) -> bool + 'a;

/// Hairer's initial step (`hinit` of `dopri5.f`): a guess from ‖y‖/‖f‖,
/// refined by one explicit Euler step that estimates the second derivative.
/// `f1` is scratch for f at the Euler point; returns |h| (the caller adds
/// the sign). For a batch of `lanes` members (component `i` of lane `l` at
/// `i·lanes + l`; 1 for any other model): each lane's guess as it would
/// be alone, the Euler probe with the smallest, and the smallest lane's
/// step.
#[allow(clippy::too_many_arguments)]
pub fn initial_step(
    f: &mut RhsProbe<'_>,
    t: f64,
    y: &[f64],
    f0: &[f64],
    direction: f64,
    order: usize,
    hmax: f64,
    (atol, rtol): (f64, f64),
    scratch_y: &mut [f64],
    f1: &mut [f64],
    lanes: usize,
) -> f64 {
    let lanes = lanes.max(1);
    let sk: Vec<f64> = y.iter().map(|v| atol + rtol * v.abs()).collect();
    // Σ over lane `l`'s components of term(i)², in component order.
    let lane_sum = |l: usize, term: &dyn Fn(usize) -> f64| -> f64 {
        (l..y.len()).step_by(lanes).map(|i| term(i).powi(2)).sum()
    };
    let mut h = f64::INFINITY;
    let mut dnf = vec![0.0; lanes];
    for l in 0..lanes {
        dnf[l] = lane_sum(l, &|i| f0[i] / sk[i]);
        let dny = lane_sum(l, &|i| y[i] / sk[i]);
        let guess =
            if dnf[l] <= 1e-10 || dny <= 1e-10 { 1e-6 } else { (dny / dnf[l]).sqrt() * 0.01 };
        h = h.min(guess);
    }
    h = h.min(hmax);
    for ((z, y), f) in scratch_y.iter_mut().zip(y).zip(f0) {
        *z = y + direction * h * f;
    }
    if !f(t + direction * h, scratch_y, f1) {
        return h * 1e-3;
    }
    let mut step = f64::INFINITY;
    for l in 0..lanes {
        let der2 = lane_sum(l, &|i| (f1[i] - f0[i]) / sk[i]).sqrt() / h;
        let der12 = der2.abs().max(dnf[l].sqrt());
        let h1 = if der12 <= 1e-15 {
            (h * 1e-3).max(1e-6)
        } else {
            (0.01 / der12).powf(1.0 / order as f64)
        };
        step = step.min((100.0 * h).min(h1).min(hmax));
    }
    step
}

/// Gustafsson's predictive step control, as RADAU5 and RODAS have it
/// (Hairer & Wanner II, §IV.8, (8.21); `radau5.f`, `rodas.f`): from the
/// second accepted step on, h/h_new is at least the quotient predicted
/// from the last two accepted steps and their errors, which holds the step
/// back where the error grows.
#[derive(Clone, Copy)]
pub(crate) struct Predictive {
    /// The error's exponent 1/(q+1).
    exponent: f64,
    /// The safety factor.
    safety: f64,
    /// h/h_new's bounds.
    bounds: (f64, f64),
    /// The last accepted step, and its error (at least 1e-2).
    h_accepted: f64,
    err_accepted: f64,
}

impl Predictive {
    /// The controller of a method with these constants, from the first
    /// step `h`.
    pub(crate) fn new(exponent: f64, safety: f64, bounds: (f64, f64), h: f64) -> Predictive {
        Predictive { exponent, safety, bounds, h_accepted: h, err_accepted: 1e-2 }
    }

    /// h/h_new after the accepted step `h` with error `err`, from the
    /// classical quotient `quot`; `predict` from the second accepted step.
    #[inline]
    pub(crate) fn accepted(&mut self, h: f64, err: f64, quot: f64, predict: bool) -> f64 {
        let mut quot = quot;
        if predict {
            let growth = (err * err / self.err_accepted).powf(self.exponent);
            let predicted =
                ((self.h_accepted / h) * growth / self.safety).clamp(self.bounds.0, self.bounds.1);
            quot = quot.max(predicted);
        }
        self.h_accepted = h;
        self.err_accepted = err.max(1e-2);
        quot
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The shortcuts agree with `powf` to two ulps from 1e-300 to 1e300.
    #[test]
    fn controller_powers_agree_with_powf() {
        for i in 0..=6000 {
            let x = 10f64.powf(-300.0 + 0.1 * i as f64) * 1.2345;
            for e in [0.0, 0.125] {
                let (fast, libm) = (power(x, e), x.powf(e));
                assert!(
                    (fast - libm).abs() <= 2.0 * f64::EPSILON * libm,
                    "{x}^{e}: {fast} vs {libm}"
                );
            }
        }
        assert_eq!(power(0.0, 0.125), 0.0);
    }

    #[test]
    fn controller_bounds_the_change_of_step() {
        let c = Controller {
            exponent: 0.2 - 0.04 * 0.75,
            beta: 0.04,
            min_factor: 0.2,
            max_factor: 10.0,
            safety: 0.9,
        };
        let s = PiState::default();
        assert_eq!(c.factor(0.0, s).0, 10.0, "a zero error grows the step by the maximum factor");
        assert_eq!(c.factor(1e12, s).0, 0.2, "a huge error shrinks it by the minimum factor");
        let (grow, _) = c.factor(1e-3, s);
        assert!(grow > 1.0 && grow <= 10.0);
        assert!(c.rejected_factor(2.0) < 1.0);
    }

    #[test]
    fn initial_step_for_exponential_decay_is_sensible() {
        // y' = -y: the step of a 5th-order method at tol 1e-6 is O(0.1).
        let mut f = |_t: f64, y: &[f64], dy: &mut [f64]| {
            dy[0] = -y[0];
            true
        };
        let (mut z, mut f1) = ([0.0], [0.0]);
        let h = initial_step(
            &mut f,
            0.0,
            &[1.0],
            &[-1.0],
            1.0,
            5,
            10.0,
            (1e-6, 1e-6),
            &mut z,
            &mut f1,
            1,
        );
        assert!(h > 1e-3 && h < 1.0, "h = {h}");
    }
}
