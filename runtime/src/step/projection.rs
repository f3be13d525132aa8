//! Projection onto the constraints: after each accepted step, and to make
//! the initial values consistent.
//!
//! The integrated system is the index-1 form, which keeps the constraints
//! and their derivatives below the acceleration level only up to the
//! integration error; left alone they drift. After each step the state is
//! projected level by level (positions onto `Φ = 0`, then velocities onto
//! `Φ_q v + Φ_t = 0`) by Gauss–Newton with the minimal-norm correction
//! `Δ = −Gᵀ (G Gᵀ)⁻¹ Φ` on the states the level corrects (Hairer, Lubich,
//! Wanner, *Geometric Numerical Integration* §IV.4; Hairer & Wanner II
//! §VII.2; Simbody projects every step the same way). Velocity constraints
//! are linear in the velocities, so one iteration solves them exactly; the
//! position level converges quadratically from the O(tol) error of a step.

use crate::error::Error;
use crate::info::ProjectionLevel;
use crate::model::Model;
use crate::solution::{Residuals, Solution};

/// Gauss–Newton iterations per level after a step (design notes: ≤ 3).
pub(crate) const STEP_ITERATIONS: usize = 3;
/// Iterations for the initial values, which may be rough guesses.
pub(crate) const INITIAL_ITERATIONS: usize = 50;

/// Why a projection failed.
#[derive(Debug)]
pub(crate) struct Failure {
    /// Index into [`Model::CONSTRAINTS`].
    pub row: usize,
    /// What went wrong.
    pub message: String,
}

/// Workspace for projecting one model's states, allocated once per run.
pub(crate) struct Projector<'m, M: Model> {
    model: &'m M,
    residuals: Vec<f64>,
    jacobian: Vec<f64>,
    normal: Vec<f64>,
    multipliers: Vec<f64>,
}

impl<'m, M: Model> Projector<'m, M> {
    /// A projector for `model`, or `None` if it has no constraints.
    pub(crate) fn new(model: &'m M) -> Option<Projector<'m, M>> {
        if M::CONSTRAINTS.is_empty() {
            return None;
        }
        let widest = M::PROJECTION.iter().map(|l| l.rows.len() * l.slots.len()).max().unwrap_or(0);
        let rows = M::PROJECTION.iter().map(|l| l.rows.len()).max().unwrap_or(0);
        Some(Projector {
            model,
            residuals: vec![0.0; M::CONSTRAINTS.len()],
            jacobian: vec![0.0; widest],
            normal: vec![0.0; rows * rows],
            multipliers: vec![0.0; rows],
        })
    }

    /// Projects `y` onto every level in turn, holding the states marked in
    /// `hold` (if given), with at most `iterations` Gauss–Newton steps per
    /// level; returns the largest |Φ| of the position-level constraints
    /// after it and of their velocity level (the constraints differentiated
    /// once). A model that keeps its constraints itself (the mass-matrix
    /// form, no [`Model::PROJECTION`]) is only measured.
    pub(crate) fn project(
        &mut self,
        t: f64,
        y: &mut [f64],
        iterations: usize,
        hold: Option<&[bool]>,
    ) -> Result<Residuals, Failure> {
        for (k, level) in M::PROJECTION.iter().enumerate() {
            self.project_level(k, level, t, y, iterations, hold)?;
        }
        self.model.constraints(t, y, &mut self.residuals);
        let mut worst = Residuals::default();
        // The model's own constraints; a sensitivity column's linearised
        // ones (after them) are not the solution's residuals.
        let own = M::CONSTRAINTS.len() / (1 + M::SENSITIVITY_COLUMNS);
        for (r, info) in M::CONSTRAINTS.iter().enumerate().take(own) {
            let v = self.residuals[r].abs();
            if !v.is_finite() {
                return Err(Failure { row: r, message: "its residual is not finite".into() });
            }
            match info.level {
                0 => worst.position = worst.position.max(v),
                1 => worst.velocity = worst.velocity.max(v),
                _ => {}
            }
        }
        Ok(worst)
    }

    fn project_level(
        &mut self,
        k: usize,
        level: &ProjectionLevel,
        t: f64,
        y: &mut [f64],
        iterations: usize,
        hold: Option<&[bool]>,
    ) -> Result<(), Failure> {
        let (m, cols) = (level.rows.len(), level.slots.len());
        let free = |c: usize| hold.is_none_or(|h| !h[level.slots[c]]);
        let mut last_step = f64::INFINITY;
        for _ in 0..iterations {
            self.model.constraints(t, y, &mut self.residuals);
            if level.rows.iter().all(|&r| self.residuals[r] == 0.0) {
                return Ok(());
            }
            let jacobian = &mut self.jacobian[..m * cols];
            self.model.constraint_jacobian(k, t, y, jacobian);
            for c in (0..cols).filter(|&c| !free(c)) {
                for r in 0..m {
                    jacobian[r * cols + c] = 0.0;
                }
            }
            // G Gᵀ μ = Φ, then Δ = −Gᵀ μ.
            let normal = &mut self.normal[..m * m];
            for a in 0..m {
                for b in 0..=a {
                    let ga = &jacobian[a * cols..(a + 1) * cols];
                    let gb = &jacobian[b * cols..(b + 1) * cols];
                    let v: f64 = ga.iter().zip(gb).map(|(x, y)| x * y).sum();
                    normal[a * m + b] = v;
                    normal[b * m + a] = v;
                }
            }
            let mu = &mut self.multipliers[..m];
            for (a, &r) in level.rows.iter().enumerate() {
                mu[a] = self.residuals[r];
            }
            if let Err(a) = solve_symmetric(normal, m, mu) {
                let held = (0..cols).any(|c| !free(c));
                return Err(Failure {
                    row: level.rows[a],
                    message: if held {
                        "the initial values cannot be made consistent with the fixed states: the constraint does not depend on the free ones here; fix fewer states or change the guesses".into()
                    } else {
                        REDUNDANT.into()
                    },
                });
            }
            let mut step = 0.0f64;
            let mut size = 1.0f64;
            for c in 0..cols {
                let d: f64 = (0..m).map(|a| jacobian[a * cols + c] * mu[a]).sum();
                let slot = level.slots[c];
                y[slot] -= d;
                step = step.max(d.abs());
                size = size.max(y[slot].abs());
            }
            if !step.is_finite() {
                return Err(Failure {
                    row: level.rows[0],
                    message: "the correction is not finite".into(),
                });
            }
            if step <= 4.0 * f64::EPSILON * size || step >= last_step {
                return Ok(());
            }
            last_step = step;
        }
        Ok(())
    }
}

const REDUNDANT: &str = "the constraint Jacobian is rank-deficient here: this constraint repeats the others (a redundant constraint) or the configuration is singular; remove it or move away from the singular configuration";

impl<M: Model> Projector<'_, M> {
    /// The first constraint whose gradient depends on those before it at
    /// `(t, y)`, level by level.
    pub(crate) fn redundant_row(&mut self, t: f64, y: &[f64]) -> Option<usize> {
        for (k, level) in M::PROJECTION.iter().enumerate() {
            let (m, cols) = (level.rows.len(), level.slots.len());
            let jacobian = &mut self.jacobian[..m * cols];
            self.model.constraint_jacobian(k, t, y, jacobian);
            let scale = jacobian.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            // Each row reduced against the rows kept before it.
            let mut basis: Vec<(usize, Vec<f64>)> = Vec::new();
            for r in 0..m {
                let mut row = jacobian[r * cols..(r + 1) * cols].to_vec();
                for (pivot, b) in &basis {
                    let f = row[*pivot] / b[*pivot];
                    for (x, bv) in row.iter_mut().zip(b) {
                        *x -= f * bv;
                    }
                }
                let pivot = (0..cols).max_by(|&p, &q| row[p].abs().total_cmp(&row[q].abs()));
                match pivot {
                    Some(p) if row[p].abs() > 1e-10 * scale => basis.push((p, row)),
                    _ => return Some(level.rows[r]),
                }
            }
        }
        None
    }

    /// Degrees of freedom at `(t, y)`: the states of the first level minus
    /// the rank of its Jacobian (n − rank Φ_q for a mechanism), plus the
    /// coordinates no constraint involves.
    pub(crate) fn degrees_of_freedom(&mut self, t: f64, y: &[f64]) -> usize {
        let Some(level) = M::PROJECTION.first() else {
            return M::STATES;
        };
        let (m, cols) = (level.rows.len(), level.slots.len());
        let jacobian = &mut self.jacobian[..m * cols];
        self.model.constraint_jacobian(0, t, y, jacobian);
        cols - rank(jacobian, m, cols) + M::UNCONSTRAINED_COORDINATES
    }
}

/// Rank by Gaussian elimination with partial pivoting, pivots below
/// 1e-10 of the largest entry counted as zero.
fn rank(a: &mut [f64], rows: usize, cols: usize) -> usize {
    let scale = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let mut rank = 0;
    for col in 0..cols {
        if rank == rows {
            break;
        }
        let pivot = (rank..rows)
            .max_by(|&p, &q| a[p * cols + col].abs().total_cmp(&a[q * cols + col].abs()))
            .unwrap_or(rank);
        let p = a[pivot * cols + col];
        if p.abs() <= 1e-10 * scale || p.is_nan() {
            continue;
        }
        for c in 0..cols {
            a.swap(rank * cols + c, pivot * cols + c);
        }
        for row in rank + 1..rows {
            let f = a[row * cols + col] / p;
            for c in col..cols {
                a[row * cols + c] -= f * a[rank * cols + c];
            }
        }
        rank += 1;
    }
    rank
}

/// Solves `a x = b` (`n × n`, destroyed; the normal matrices of the
/// projection are symmetric, but nothing here needs it) by Gaussian
/// elimination with partial pivoting; `Err(row)`
/// names the first row whose pivot vanished relative to the matrix.
fn solve_symmetric(a: &mut [f64], n: usize, b: &mut [f64]) -> Result<(), usize> {
    let scale = (0..n).map(|i| a[i * n + i].abs()).fold(0.0, f64::max);
    let mut order: Vec<usize> = (0..n).collect();
    for col in 0..n {
        let pivot = (col..n)
            .max_by(|&p, &q| a[p * n + col].abs().total_cmp(&a[q * n + col].abs()))
            .unwrap_or(col);
        let p = a[pivot * n + col];
        if p.abs() <= 1e-13 * scale || !p.is_finite() {
            return Err(order[col]);
        }
        if pivot != col {
            for c in 0..n {
                a.swap(col * n + c, pivot * n + c);
            }
            b.swap(col, pivot);
            order.swap(col, pivot);
        }
        for row in col + 1..n {
            let f = a[row * n + col] / p;
            if f != 0.0 {
                for c in col..n {
                    a[row * n + c] -= f * a[col * n + c];
                }
                b[row] -= f * b[col];
            }
        }
    }
    for col in (0..n).rev() {
        let mut v = b[col];
        for c in col + 1..n {
            v -= a[col * n + c] * b[c];
        }
        b[col] = v / a[col * n + col];
    }
    Ok(())
}

/// Makes the initial values consistent: projects them onto every
/// constraint level, then checks that the constraints hold.
pub(crate) fn consistent_initial_values<M: Model>(
    model: &M,
    t0: f64,
    y: &mut [f64],
    solution: Solution,
) -> Result<Solution, Error> {
    let Some(mut projector) = Projector::new(model) else {
        return Ok(solution);
    };
    let failed = |row: usize, message: String, solution: Solution| Error::Constraint {
        t: t0,
        constraint: M::CONSTRAINTS[row].equation,
        level: M::CONSTRAINTS[row].level,
        message,
        partial: Box::new(solution),
    };
    let mut hold = vec![false; M::STATES];
    for &i in M::FIXED_STATES {
        hold[i] = true;
    }
    for level in M::PROJECTION {
        if level.slots.iter().all(|&s| hold[s]) {
            return Err(failed(
                level.rows[0],
                format!(
                    "every state it corrects is fixed ({}): remove `.fixed()` from one of them",
                    level.slots.iter().map(|&s| M::INFO.states[s]).collect::<Vec<_>>().join(", ")
                ),
                solution,
            ));
        }
    }
    if let Some(row) = projector.redundant_row(t0, y) {
        return Err(failed(row, REDUNDANT.into(), solution));
    }
    if let Err(f) = projector.project(t0, y, INITIAL_ITERATIONS, Some(&hold)) {
        return Err(failed(f.row, f.message, solution));
    }
    // Every level, not just positions, must hold to rounding.
    model.constraints(t0, y, &mut projector.residuals);
    let size = y.iter().fold(1.0f64, |m, v| m.max(v.abs()));
    for (r, &v) in projector.residuals.iter().enumerate() {
        if v.abs() > 1e-10 * size || v.is_nan() {
            return Err(failed(
                r,
                format!("the initial values cannot be made consistent: its residual is {v:e} after {INITIAL_ITERATIONS} Gauss–Newton iterations; start nearer a configuration that satisfies it, or fix fewer states"),
                solution,
            ));
        }
    }
    let mut solution = solution;
    solution.set_degrees_of_freedom(projector.degrees_of_freedom(t0, y));
    Ok(solution)
}

/// Makes the algebraic components of a mass-matrix model consistent at
/// `t0`: Newton on its algebraic rows `0 = F_a(t0, w)` in the algebraic
/// components, from the model's guesses (the generated Jacobian, or
/// forward differences).
pub(crate) fn consistent_algebraic_components<M: Model>(
    model: &M,
    t0: f64,
    w: &mut [f64],
    solution: Solution,
) -> Result<Solution, Error> {
    let algebraic: Vec<usize> = (0..M::STATES).filter(|&i| M::MASS.is_algebraic(i)).collect();
    let m = algebraic.len();
    if m == 0 {
        return Ok(solution);
    }
    let n = M::STATES;
    let (mut f, mut scratch) = (vec![0.0; n], vec![0.0; n]);
    let mut values = vec![0.0; M::JACOBIAN.pattern().len()];
    let mut jaa = vec![0.0; m * m];
    let fail = |i: usize, message: String, solution: Solution| Error::Constraint {
        t: t0,
        constraint: M::INFO.states[i],
        level: 0,
        message,
        partial: Box::new(solution),
    };
    for _ in 0..INITIAL_ITERATIONS {
        if let Err(cause) = model.rhs(t0, w, &mut f) {
            return Err(Error::Evaluation { t: t0, cause, partial: Box::new(solution) });
        }
        let size = algebraic.iter().fold(1.0f64, |a, &i| a.max(w[i].abs()));
        let residual = algebraic.iter().fold(0.0f64, |a, &i| a.max(f[i].abs()));
        if residual <= 4.0 * f64::EPSILON * size {
            return Ok(solution);
        }
        jaa.iter_mut().for_each(|v| *v = 0.0);
        if model.jacobian(t0, w, &mut values).is_ok() {
            for (&(r, c), &v) in M::JACOBIAN.pattern().iter().zip(&values) {
                let a = algebraic.iter().position(|&i| i == r);
                let b = algebraic.iter().position(|&i| i == c);
                if let (Some(a), Some(b)) = (a, b) {
                    jaa[a * m + b] = v;
                }
            }
        } else {
            for (b, &c) in algebraic.iter().enumerate() {
                let saved = w[c];
                let delta = (f64::EPSILON * saved.abs().max(1e-5)).sqrt();
                w[c] = saved + delta;
                let r = model.rhs(t0, w, &mut scratch);
                w[c] = saved;
                if let Err(cause) = r {
                    return Err(Error::Evaluation { t: t0, cause, partial: Box::new(solution) });
                }
                for (a, &r) in algebraic.iter().enumerate() {
                    jaa[a * m + b] = (scratch[r] - f[r]) / delta;
                }
            }
        }
        let mut step: Vec<f64> = algebraic.iter().map(|&i| f[i]).collect();
        if let Err(a) = solve_symmetric(&mut jaa, m, &mut step) {
            return Err(fail(
                algebraic[a],
                "the algebraic equations are singular in the algebraic variables at the start: the DAE is not of index 1 there".into(),
                solution,
            ));
        }
        for (k, &i) in algebraic.iter().enumerate() {
            w[i] -= step[k];
        }
    }
    Err(fail(
        algebraic[0],
        format!("the algebraic equations could not be solved for the algebraic variables at the start after {INITIAL_ITERATIONS} Newton iterations: give guesses nearer a solution"),
        solution,
    ))
}
