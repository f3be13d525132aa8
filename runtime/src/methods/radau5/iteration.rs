//! RADAU5's simplified Newton iteration on the transformed stages, on all
//! states at once or staggered for sensitivities (`radau5.f`; Hairer &
//! Wanner II, §IV.8).

use super::coefficients::{C1, C2, NIT, T, TI};
use super::counted::Counted;
use crate::info::EvalError;
use crate::linalg::apply_mass;
use crate::linalg::newton::Newton;
use crate::model::Model;

/// Newton's contraction θ and the factor θ/(1 − θ) that turns the last
/// increment into an error bound (`radau5.f`'s THETA and FACCON).
#[derive(Clone, Copy)]
pub(super) struct Contraction {
    pub(super) theta: f64,
    pub(super) faccon: f64,
}

/// Which states a simplified Newton iteration solves for.
#[derive(Clone, Copy)]
pub(super) enum Part {
    /// Every state, with the whole Newton matrix.
    All,
    /// The model's own states (the first n/(1 + columns)), through `Model::own_rhs`
    /// and the base block: the first half of the staggered corrector
    /// (Feehery, Tolsma & Barton, "Efficient sensitivity analysis of
    /// large-scale differential-algebraic systems", Appl. Numer. Math. 25,
    /// 1997; CVODES's `CV_STAGGERED`).
    Own,
    /// The sensitivity columns (the states from `own` on) with the model's
    /// own stages fixed: linear and uncoupled, each with the base block.
    Columns,
}

/// How a simplified Newton iteration ended.
pub(super) enum Iterated {
    /// Converged after this many iterations.
    Converged(usize),
    /// Retry the step with h times `factor`; `failed` when the iteration
    /// diverged (rather than converging too slowly).
    Retry { factor: f64, failed: bool },
    /// The right-hand side could not be evaluated at `at`.
    Failed { at: f64, cause: EvalError },
}

/// What an iteration reads: the step, the state, the error scale, the
/// diagonal mass and Newton's tolerance.
pub(super) struct Iteration<'a> {
    pub(super) t: f64,
    pub(super) h: f64,
    /// A⁻¹'s eigenvalues γ, α ± iβ.
    pub(super) eigenvalues: (f64, f64, f64),
    pub(super) y: &'a [f64],
    pub(super) scal: &'a [f64],
    pub(super) mass: &'a [f64],
    pub(super) fnewt: f64,
}

/// `radau5.f`'s simplified Newton iteration on the transformed stages
/// (Hairer & Wanner II, §IV.8, (8.13)–(8.16)) for the states of `part`:
/// `z` the stage increments Z, `f` their transforms W = T⁻¹Z, updated in
/// place. Inlined always, so that for each part its loops know their
/// bounds.
#[inline(always)]
pub(super) fn simplified_newton<M: Model>(
    w: &mut Counted<'_, M>,
    newton: &mut Newton,
    (it, part, mass_matrix): (&Iteration<'_>, Part, &[f64]),
    (z, f): ([&mut [f64]; 3], [&mut [f64]; 3]),
    (stage, scratch, mass_applied): (&mut [f64], &mut [f64], &mut [Vec<f64>; 3]),
    control: &mut Contraction,
) -> Iterated {
    // Constants of the model: the loops below know their lengths.
    let (n, own) = (M::STATES, M::STATES / (1 + M::SENSITIVITY_COLUMNS));
    let range = match part {
        Part::All => 0..n,
        Part::Own => 0..own,
        Part::Columns => own..n,
    };
    let (gamma, alpha, beta) = it.eigenvalues;
    let [z1, z2, z3] = z;
    let [f1, f2, f3] = f;
    let mut newt = 0usize;
    control.faccon = control.faccon.max(f64::EPSILON).powf(0.8);
    control.theta = control.theta.abs();
    let (mut dyno_old, mut thq_old) = (0.0f64, 0.0f64);
    loop {
        if newt >= NIT {
            return Iterated::Retry { factor: 0.5, failed: true };
        }
        for (zk, c) in [(&mut *z1, C1), (&mut *z2, C2), (&mut *z3, 1.0)] {
            let at = it.t + c * it.h;
            // The columns' right-hand side reads the states' stages too.
            let read = if let Part::Own = part { 0..own } else { 0..n };
            for i in read {
                stage[i] = it.y[i] + zk[i];
            }
            let evaluated = match part {
                Part::All => w.rhs(at, stage, zk),
                Part::Own => w.own_rhs(at, stage, &mut zk[..own]),
                Part::Columns => w.rhs(at, stage, scratch).map(|()| {
                    zk[own..].copy_from_slice(&scratch[own..]);
                }),
            };
            if let Err(cause) = evaluated {
                return Iterated::Failed { at, cause };
            }
        }
        for i in range.clone() {
            let (a1, a2, a3) = (z1[i], z2[i], z3[i]);
            z1[i] = TI[0][0] * a1 + TI[0][1] * a2 + TI[0][2] * a3;
            z2[i] = TI[1][0] * a1 + TI[1][1] * a2 + TI[1][2] * a3;
            z3[i] = TI[2][0] * a1 + TI[2][1] * a2 + TI[2][2] * a3;
        }
        let (fac1, alphn, betan) = (gamma / it.h, alpha / it.h, beta / it.h);
        if mass_matrix.is_empty() {
            for i in range.clone() {
                let m = it.mass[i];
                let (s2, s3) = (-m * f2[i], -m * f3[i]);
                z1[i] -= m * f1[i] * fac1;
                z2[i] += s2 * alphn - s3 * betan;
                z3[i] += s3 * alphn + s2 * betan;
            }
        } else {
            for (out, f) in mass_applied.iter_mut().zip([&*f1, &*f2, &*f3]) {
                apply_mass(mass_matrix, f, out);
            }
            let [m1, m2, m3] = &*mass_applied;
            for i in range.clone() {
                let (s2, s3) = (-m2[i], -m3[i]);
                z1[i] -= m1[i] * fac1;
                z2[i] += s2 * alphn - s3 * betan;
                z3[i] += s3 * alphn + s2 * betan;
            }
        }
        match (part, newton.sensitivity()) {
            (Part::Own, Some(s)) => {
                s.solve_own_real(&mut z1[..own]);
                s.solve_own_complex(&mut z2[..own], &mut z3[..own]);
            }
            (Part::Columns, Some(s)) => {
                s.solve_columns_real(z1);
                s.solve_columns_complex(z2, z3);
            }
            _ => {
                newton.solve_real(z1);
                newton.solve_complex(z2, z3);
            }
        }
        newt += 1;
        let r = range.clone();
        let dyno = rms([&z1[r.clone()], &z2[r.clone()], &z3[r.clone()]], &it.scal[r]);
        if !dyno.is_finite() {
            return Iterated::Retry { factor: 0.5, failed: true };
        }
        if newt > 1 && newt < NIT {
            let thq = dyno / dyno_old;
            control.theta = if newt == 2 { thq } else { (thq * thq_old).sqrt() };
            thq_old = thq;
            let theta = control.theta;
            if theta < 0.99 {
                control.faccon = theta / (1.0 - theta);
                let dyth = control.faccon * dyno * theta.powi((NIT - 1 - newt) as i32) / it.fnewt;
                if dyth >= 1.0 {
                    // Convergence too slow for the remaining iterations: shrink h.
                    let qnewt = dyth.clamp(1e-4, 20.0);
                    let factor = 0.8 * qnewt.powf(-1.0 / (4.0 + (NIT - 1 - newt) as f64));
                    return Iterated::Retry { factor, failed: false };
                }
            } else {
                return Iterated::Retry { factor: 0.5, failed: true };
            }
        }
        dyno_old = dyno.max(f64::EPSILON);
        for i in range.clone() {
            let (a, b, c) = (f1[i] + z1[i], f2[i] + z2[i], f3[i] + z3[i]);
            f1[i] = a;
            f2[i] = b;
            f3[i] = c;
            z1[i] = T[0][0] * a + T[0][1] * b + T[0][2] * c;
            z2[i] = T[1][0] * a + T[1][1] * b + T[1][2] * c;
            z3[i] = T[2][0] * a + b;
        }
        if control.faccon * dyno <= it.fnewt {
            return Iterated::Converged(newt);
        }
    }
}

pub(super) fn rms(values: [&[f64]; 3], scale: &[f64]) -> f64 {
    let n = scale.len();
    let sum: f64 =
        values.iter().map(|v| v.iter().zip(scale).map(|(x, s)| (x / s).powi(2)).sum::<f64>()).sum();
    // A model without states has nothing to converge: its norm is zero.
    (sum / (3 * n).max(1) as f64).sqrt()
}
