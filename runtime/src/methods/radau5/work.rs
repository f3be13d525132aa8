//! RADAU5's work on one run: the model counted, the Newton matrices and
//! the vectors of a step, and the pieces of a step the loop calls (the
//! factorisation, the starting values, the iteration, the error estimate
//! and the step taken).

use super::coefficients::{eigenvalues, Reuse, C1, C1M1, C1MC2, C2, C2M1, DD1, DD2, DD3, TI};
use super::counted::Counted;
use super::iteration::{simplified_newton, Contraction, Iterated, Iteration, Part};
use crate::info::EvalError;
use crate::linalg::apply_mass;
use crate::linalg::newton::{Factored, Newton, Shifts};
use crate::methods::mass::Mass;
use crate::model::{has_mass_matrix, Model};
use crate::step::driver::Counts;
use crate::step::jacobian::DenseJacobian;

/// RADAU5's work on one run: the model counted, the Newton matrices,
/// the stages and their transforms, the continuous output and Newton's
/// state between steps.
pub(super) struct Radau<'m, M> {
    pub(super) w: Counted<'m, M>,
    pub(super) newton: Newton,
    pub(super) mass: Mass,
    /// The tightened tolerances and Newton's (`radau5.f`'s FNEWT).
    pub(super) rtol: f64,
    pub(super) atol: f64,
    pub(super) fnewt: f64,
    /// The error test's states (the model's own, where sensitivities are
    /// left out of it); Newton converges on all.
    pub(super) n_error: usize,
    pub(super) reuse: Reuse,
    /// A⁻¹'s eigenvalues γ, α ± iβ.
    pub(super) eigenvalues: (f64, f64, f64),
    /// The vectors of [`Vectors`], side by side.
    pub(super) buffer: Vec<f64>,
    pub(super) mass_applied: [Vec<f64>; 3],
    /// Whether Newton iterates on the model's own states first, then on
    /// the sensitivity columns, rather than on all at once.
    pub(super) staggered: bool,
    /// Newton's contraction for the states, and for the columns when they
    /// are iterated apart, carried from step to step.
    pub(super) state_control: Contraction,
    pub(super) column_control: Contraction,
    /// Newton iterations in a row that failed.
    pub(super) newton_failures: usize,
}

impl<'m, M: Model> Radau<'m, M> {
    pub(super) fn new(
        model: &'m M,
        options: &crate::options::Options,
        t0: f64,
        y0: &[f64],
    ) -> Radau<'m, M> {
        let n = M::STATES;
        // radau5.f tightens the user's tolerances: rtol' = 0.1 rtol^(2/3).
        let rtol = 0.1 * options.rtol.max(1e-15).powf(2.0 / 3.0);
        let atol = rtol * options.atol / options.rtol.max(1e-15);
        let fnewt = (10.0 * f64::EPSILON / rtol).max(0.03f64.min(rtol.sqrt()));
        // A singular mass matrix (Hairer's IMAS = 1): diagonal, or general
        // and dense; dense Newton either way.
        let pattern = if has_mass_matrix::<M>() { &[] } else { M::JACOBIAN.pattern() };
        let (mut newton, factor_operations) = if M::SENSITIVITY_COLUMNS > 0 && !pattern.is_empty() {
            let columns = M::SENSITIVITY_COLUMNS;
            Newton::for_sensitivities(n / (1 + columns), columns, pattern, Shifts::RealAndComplex)
        } else {
            Newton::for_pattern(n, pattern, Shifts::RealAndComplex)
        };
        let jacobian = DenseJacobian::with_matrix::<M>(newton.dense_jacobian());
        let counts = Counts { linear_solver: newton.label(), ..Counts::default() };
        let reuse = Reuse::for_factorisation(factor_operations);
        let own = n / (1 + M::SENSITIVITY_COLUMNS);
        let mut probe = vec![0.0; own];
        let staggered =
            newton.sensitivity().is_some() && model.own_rhs(t0, y0, &mut probe).is_some();
        let zeros = || [vec![0.0; n], vec![0.0; n], vec![0.0; n]];
        let control = Contraction { theta: reuse.thet, faccon: 1.0 };
        Radau {
            w: Counted { model, jacobian, counts },
            newton,
            mass: Mass::of(model),
            rtol,
            atol,
            fnewt,
            n_error: crate::methods::error_states::<M>(options),
            reuse,
            eigenvalues: eigenvalues(),
            buffer: vec![0.0; Vectors::LEN * n],
            mass_applied: zeros(),
            staggered,
            state_control: control,
            column_control: control,
            newton_failures: 0,
        }
    }

    /// The error scale at `y`; the index-2 variables of a mass-matrix
    /// model are measured relative to the step `h` (radau5.f's HHFAC).
    pub(super) fn set_scale(&mut self, y: &[f64], h: f64) {
        let scal = Vectors::of::<M>(&mut self.buffer).scal;
        for (s, v) in scal.iter_mut().zip(y) {
            *s = self.atol + self.rtol * v.abs();
        }
        for &i in M::INDEX2_COMPONENTS {
            if let Some(s) = scal.get_mut(i) {
                *s /= h.abs();
            }
        }
    }

    /// f at `(t, y)`, the step's start.
    pub(super) fn evaluate_start(&mut self, t: f64, y: &[f64]) -> Result<(), EvalError> {
        self.w.rhs(t, y, Vectors::of::<M>(&mut self.buffer).f_start)
    }

    /// The Jacobian at `(t, y)`, the step's start.
    pub(super) fn evaluate_jacobian(&mut self, t: f64, y: &mut [f64]) -> Result<(), EvalError> {
        self.w.evaluate_jacobian(t, y, Vectors::of::<M>(&mut self.buffer).f_start)
    }

    /// The collocation polynomial's coefficients.
    pub(super) fn cont(&mut self) -> &[f64] {
        Vectors::of::<M>(&mut self.buffer).cont
    }

    /// Factors the two Newton matrices for the step `h`, evaluating the
    /// dense Jacobian where the structure asks for it: `false` where one
    /// is singular.
    pub(super) fn factor(&mut self, t: f64, y: &mut [f64], h: f64) -> Result<bool, EvalError> {
        let (gamma, alpha, beta) = self.eigenvalues;
        let (real, complex) = (gamma / h, (alpha / h, beta / h));
        let (mass, pattern) = (self.mass.for_factorisation::<M>(), M::JACOBIAN.pattern());
        let jacobian = &self.w.jacobian;
        let (matrix, values) = (&jacobian.matrix, jacobian.values());
        let mut factored = self.newton.factor(real, complex, mass, matrix, values, pattern);
        if factored == Factored::NeedsDenseJacobian {
            self.w.jacobian = DenseJacobian::new::<M>();
            self.w.evaluate_jacobian(t, y, Vectors::of::<M>(&mut self.buffer).f_start)?;
            let jacobian = &self.w.jacobian;
            let (matrix, values) = (&jacobian.matrix, jacobian.values());
            factored = self.newton.factor(real, complex, mass, matrix, values, pattern);
            self.w.counts.linear_solver = self.newton.label();
        }
        Ok(factored == Factored::Yes)
    }

    /// Newton's starting values: zero on the first step, else the last
    /// collocation polynomial extrapolated to the new step, `h/h_old =
    /// ratio`.
    pub(super) fn starting_values(&mut self, first: bool, ratio: f64) {
        let n = M::STATES;
        let Vectors { z: [z1, z2, z3], f: [f1, f2, f3], cont, .. } =
            Vectors::of::<M>(&mut self.buffer);
        if first {
            for v in [z1, z2, z3, f1, f2, f3] {
                v.fill(0.0);
            }
            return;
        }
        let (c1q, c2q, c3q) = (C1 * ratio, C2 * ratio, ratio);
        for i in 0..n {
            let (ak1, ak2, ak3) = (cont[n + i], cont[2 * n + i], cont[3 * n + i]);
            let z1i = c1q * (ak1 + (c1q - C2M1) * (ak2 + (c1q - C1M1) * ak3));
            let z2i = c2q * (ak1 + (c2q - C2M1) * (ak2 + (c2q - C1M1) * ak3));
            let z3i = c3q * (ak1 + (c3q - C2M1) * (ak2 + (c3q - C1M1) * ak3));
            z1[i] = z1i;
            z2[i] = z2i;
            z3[i] = z3i;
            f1[i] = TI[0][0] * z1i + TI[0][1] * z2i + TI[0][2] * z3i;
            f2[i] = TI[1][0] * z1i + TI[1][1] * z2i + TI[1][2] * z3i;
            f3[i] = TI[2][0] * z1i + TI[2][1] * z2i + TI[2][2] * z3i;
        }
    }

    /// The simplified Newton iteration of a step of `h` from `(t, y)`: on
    /// every state at once, or staggered (the model's own states first,
    /// then the sensitivity columns with those fixed). Converged after the
    /// most iterations any part took.
    pub(super) fn iterate(&mut self, t: f64, h: f64, y: &[f64]) -> Iterated {
        // Unstaggered, the part is a constant: the iteration's loops then
        // know their bounds (read from a list of parts, they ran 20 %
        // longer on Arenstorf).
        if !self.staggered {
            return self.iterate_part(Part::All, t, h, y);
        }
        match self.iterate_part(Part::Own, t, h, y) {
            Iterated::Converged(own) => match self.iterate_part(Part::Columns, t, h, y) {
                Iterated::Converged(columns) => Iterated::Converged(own.max(columns)),
                other => other,
            },
            other => other,
        }
    }

    /// [`simplified_newton`] on `part`'s states.
    #[inline(always)]
    pub(super) fn iterate_part(&mut self, part: Part, t: f64, h: f64, y: &[f64]) -> Iterated {
        // Slices of the model's constant length: with the vectors' lengths
        // unknown, the iteration's loops ran a third longer.
        let n = M::STATES;
        let Vectors { z, f, stage, scratch, scal, .. } = Vectors::of::<M>(&mut self.buffer);
        let iteration = Iteration {
            t,
            h,
            eigenvalues: self.eigenvalues,
            y: &y[..n],
            scal,
            mass: &self.mass.diagonal[..n],
            fnewt: self.fnewt,
        };
        let control = match part {
            Part::Columns => &mut self.column_control,
            _ => &mut self.state_control,
        };
        simplified_newton(
            &mut self.w,
            &mut self.newton,
            (&iteration, part, &self.mass.dense),
            (z, f),
            (stage, scratch, &mut self.mass_applied),
            control,
        )
    }

    /// The scaled error of the step (ESTRAD): (γ/h − J)⁻¹ (f(y) +
    /// (DD·Z)/h), `refine`d once through f where it fails the test (on the
    /// first step and after a rejection).
    pub(super) fn error(
        &mut self,
        t: f64,
        h: f64,
        y: &[f64],
        refine: bool,
    ) -> Result<f64, EvalError> {
        let n = M::STATES;
        let Vectors { z: [z1, z2, z3], f: [f1, f2, _], f_start: y0, stage, scratch, scal, .. } =
            Vectors::of::<M>(&mut self.buffer);
        let (hee1, hee2, hee3) = (DD1 / h, DD2 / h, DD3 / h);
        if self.mass.dense.is_empty() {
            let mass = &self.mass.diagonal[..n];
            for i in 0..n {
                f2[i] = mass[i] * (hee1 * z1[i] + hee2 * z2[i] + hee3 * z3[i]);
            }
        } else {
            let combined = &mut self.mass_applied[0];
            for i in 0..n {
                combined[i] = hee1 * z1[i] + hee2 * z2[i] + hee3 * z3[i];
            }
            apply_mass(&self.mass.dense, combined, f2);
        }
        for i in 0..n {
            scratch[i] = f2[i] + y0[i];
        }
        self.newton.solve_real(scratch);
        let n_error = self.n_error;
        let scal = &*scal;
        let estimate = |scratch: &[f64]| {
            (scratch[..n_error].iter().zip(scal).map(|(e, s)| (e / s).powi(2)).sum::<f64>()
                / n_error as f64)
                .sqrt()
                .max(1e-10)
        };
        let err = estimate(scratch);
        if err < 1.0 || !refine {
            return Ok(err);
        }
        for i in 0..n {
            stage[i] = y[i] + scratch[i];
        }
        self.w.rhs(t, stage, f1)?;
        for i in 0..n {
            scratch[i] = f1[i] + f2[i];
        }
        self.newton.solve_real(scratch);
        Ok(estimate(scratch))
    }

    /// Takes the step: `y` moves by Z₃ and the continuous output becomes
    /// the new collocation polynomial's.
    pub(super) fn advance(&mut self, y: &mut [f64]) {
        let n = M::STATES;
        let Vectors { z: [z1, z2, z3], cont, .. } = Vectors::of::<M>(&mut self.buffer);
        let y = &mut y[..n];
        for i in 0..n {
            y[i] += z3[i];
            let (z1i, z2i) = (z1[i], z2[i]);
            cont[n + i] = (z2i - z3[i]) / C2M1;
            let ak = (z1i - z2i) / C1MC2;
            let acont3 = (ak - z1i / C1) / C2;
            cont[2 * n + i] = (ak - cont[n + i]) / C1M1;
            cont[3 * n + i] = cont[2 * n + i] - acont3;
            cont[i] = y[i];
        }
    }
}

/// RADAU5's vectors of n states, side by side in one buffer: slices of
/// one buffer at constant offsets are known not to overlap, which lets
/// the compiler vectorise the loops over several of them. As vectors of
/// their own, reached through [`Radau`], they might have been one, and the
/// Newton iteration took twice the instructions a state.
pub(super) struct Vectors<'a> {
    /// The stage increments Z and their transforms W = T⁻¹Z (F in
    /// `radau5.f`).
    pub(super) z: [&'a mut [f64]; 3],
    pub(super) f: [&'a mut [f64]; 3],
    /// f at the step's start (Y0 in `radau5.f`).
    pub(super) f_start: &'a mut [f64],
    pub(super) stage: &'a mut [f64],
    pub(super) scratch: &'a mut [f64],
    /// The error scale, atol + rtol·|y|.
    pub(super) scal: &'a mut [f64],
    /// The collocation polynomial's four coefficients.
    pub(super) cont: &'a mut [f64],
}

impl<'a> Vectors<'a> {
    /// The buffer's length in vectors of n.
    const LEN: usize = 14;

    /// The vectors of `M` in `buffer`, which [`Radau::new`] makes `LEN`
    /// times its states long: one length check, after which every
    /// vector's length is a constant.
    #[inline(always)]
    pub(super) fn of<M: Model>(buffer: &'a mut [f64]) -> Vectors<'a> {
        let n = M::STATES;
        let mut rest = &mut buffer[..Self::LEN * n];
        let mut next = |len: usize| {
            let (head, tail) = std::mem::take(&mut rest).split_at_mut(len);
            rest = tail;
            head
        };
        Vectors {
            z: [next(n), next(n), next(n)],
            f: [next(n), next(n), next(n)],
            f_start: next(n),
            stage: next(n),
            scratch: next(n),
            scal: next(n),
            cont: next(4 * n),
        }
    }
}
