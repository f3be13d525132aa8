//! The adaptive Taylor method on a batch model (`#[dae_model(batch = L)]`):
//! the members' tapes run as one tape whose coefficients are lanes, so each
//! operation of the recurrences serves every member at once, and the batch
//! takes the step of its most demanding member (heyoka's batch mode,
//! Biscani & Izzo 2021). Each lane's order, norms and ρ are the scalar
//! method's (`mod.rs`); the step is the least of the lanes' steps.

use super::order::{choose_order, chosen_order_step_factor, step_factor, JetCost};
use super::{horner_by_coefficient, interpolate};
use crate::error::Error;
use crate::lanes::Lanes;
use crate::model::Model;
use crate::options::Options;
use crate::solution::Solution;
use crate::step::Problem;
use crate::taylor_tape::{Tape, TapeOp, TaylorWork};

/// Integrates the batch `model` from `t0` to `t1`, its members' tapes
/// stepped together on lanes.
pub(crate) fn integrate<M: Model>(
    problem: Problem<'_, M>,
    solution: Solution,
) -> Result<Solution, Error> {
    let Problem { model, t0, t1, y0, options } = problem;
    let Some(tapes) = model.taylor_member_tapes() else {
        // Members with their reason are refused before the run.
        let message = crate::methods::taylor_refusal::<M>("its members have no Taylor tape");
        return Err(Error::InvalidOptions { message });
    };
    let run = Batch { tapes: &tapes, states: M::STATES / M::LANES, t0, t1, y0, options };
    run.integrate(M::INFO.states, solution)
}

/// A batch's run: its members' tapes, the number of states of one member,
/// and the interval, initial states (component `i` of lane `l` at
/// `i·lanes + l`) and options.
struct Batch<'a> {
    tapes: &'a [Tape],
    states: usize,
    t0: f64,
    t1: f64,
    y0: &'a [f64],
    options: &'a Options,
}

impl Batch<'_> {
    /// Runs the batch on the least width of 2, 4, 8 or 16 lanes that holds
    /// it (the lanes beyond repeat its last member), so that the
    /// recurrences are compiled for four widths only, in this crate.
    fn integrate(
        &self,
        names: &'static [&'static str],
        solution: Solution,
    ) -> Result<Solution, Error> {
        match self.tapes.len() {
            0..=2 => self.step_loop::<2>(names, solution),
            3..=4 => self.step_loop::<4>(names, solution),
            5..=8 => self.step_loop::<8>(names, solution),
            _ => self.step_loop::<16>(names, solution),
        }
    }

    /// The step loop of `mod.rs` on `W` lanes; `names` are the batch's
    /// state names, component `i` of lane `l` at `i·lanes + l`.
    fn step_loop<const W: usize>(
        &self,
        names: &'static [&'static str],
        mut solution: Solution,
    ) -> Result<Solution, Error> {
        let (n, lanes, options) = (self.states, self.tapes.len(), self.options);
        if lanes == 0 || lanes > W || self.y0.len() != n * lanes {
            return Err(Error::InvalidOptions {
                message: format!(
                    "a batch of {lanes} lanes of {n} states has {} initial values",
                    self.y0.len()
                ),
            });
        }
        let (tape, outputs) =
            lane_tape::<W>(self.tapes).map_err(|message| Error::InvalidOptions { message })?;
        let tol = if options.rtol > 0.0 { options.rtol } else { options.atol };
        let p = match options.taylor_order {
            Some(p) => p,
            None => choose_order(tol, &JetCost::of_tape(&self.tapes[0].0, n), &[]).0,
        };
        solution.stats_mut().taylor_order = p;
        solution.stats_mut().taylor_unrolled = false;
        let w = p + 1;
        let mut work = TaylorWork::<Lanes<W>>::new(&tape, &outputs, n, p);
        // The batch state on W lanes, component i of lane l at i·W + l.
        let lane = |l: usize| l.min(lanes - 1);
        let mut y: Vec<f64> = (0..n * W).map(|j| self.y0[(j / W) * lanes + lane(j % W)]).collect();
        let mut carried = vec![0.0; n * W];
        let mut state = vec![Lanes::<W>::splat(0.0); n];
        let mut block = vec![0.0; w * W];
        let mut out = vec![0.0; n * lanes];
        let keep_dense = options.dense_output;
        let mut dense = vec![0.0; if keep_dense { w * n * lanes } else { 0 }];
        let mut powers = vec![0.0; w];
        if keep_dense {
            solution.set_interpolant(w, interpolate);
        }
        let direction = if self.t1 >= self.t0 { 1.0 } else { -1.0 };
        let hmax = options.max_step.unwrap_or(f64::INFINITY);
        // An order given keeps Jorba & Zou's step; one picked here drops less.
        let safety = match options.taylor_order {
            Some(_) => step_factor(tol, p),
            None => chosen_order_step_factor(tol, p),
        };
        let (inv_pm1, inv_p) = (1.0 / (p - 1) as f64, 1.0 / p as f64);
        let (mut t, mut compensation) = (self.t0, 0.0f64);
        let variable = |j: usize| names.get((j / W) * lanes + lane(j % W)).copied().unwrap_or("");
        while (self.t1 - t) * direction > 0.0 {
            if solution.stats().steps >= options.max_steps {
                return Err(Error::MaxSteps {
                    t,
                    max_steps: options.max_steps,
                    partial: Box::new(solution),
                });
            }
            for (s, chunk) in state.iter_mut().zip(y.chunks_exact(W)) {
                s.0.copy_from_slice(chunk);
            }
            work.compute(t, &state);
            let rows = &work.rows()[..n * w];
            solution.stats_mut().rhs_evals += 1;
            let rho = lanes_rho(rows, w, [p - 1, p], [inv_pm1, inv_p]);
            let remaining = (self.t1 - t).abs();
            let mut h = (rho * safety).min(hmax);
            // Within 1 % of the end the step reaches it (as Hairer's codes do),
            // rather than leave a remainder that may be below the time's ulp.
            let last = 1.01 * h >= remaining || h.is_nan();
            if last {
                h = remaining;
            }
            if h <= t.abs().max(1e-300) * f64::EPSILON || h.is_nan() {
                let bad = rows.iter().enumerate().find_map(|(at, c)| {
                    c.0.iter().position(|x| !x.is_finite()).map(|l| (at / w) * W + l)
                });
                return Err(match bad {
                    Some(j) => {
                        Error::NonFinite { t, variable: variable(j), partial: Box::new(solution) }
                    }
                    None => Error::StepSizeUnderflow { t, h, partial: Box::new(solution) },
                });
            }
            let h = direction * h;
            if keep_dense {
                powers[0] = 1.0;
                for k in 1..w {
                    powers[k] = powers[k - 1] * h;
                }
                for (i, row) in rows.chunks_exact(w).enumerate() {
                    for l in 0..lanes {
                        let d = &mut dense[(i * lanes + l) * w..(i * lanes + l + 1) * w];
                        for ((d, c), power) in d.iter_mut().zip(row).zip(&powers) {
                            *d = c.0[l] * power;
                        }
                    }
                }
            }
            // State i's block holds its coefficients order by order, its
            // lanes side by side: the layout `horner_by_coefficient` sums.
            for ((row, yi), ci) in
                rows.chunks_exact(w).zip(y.chunks_exact_mut(W)).zip(carried.chunks_exact_mut(W))
            {
                for (b, c) in block.chunks_exact_mut(W).zip(row) {
                    b.copy_from_slice(&c.0);
                }
                horner_by_coefficient(&block, w, h, yi, ci);
            }
            let step = h - compensation;
            let t_next = t + step;
            compensation = (t_next - t) - step;
            t = if last { self.t1 } else { t_next };
            if let Some(j) = y.iter().position(|v| !v.is_finite()) {
                return Err(Error::NonFinite {
                    t,
                    variable: variable(j),
                    partial: Box::new(solution),
                });
            }
            for (j, o) in out.iter_mut().enumerate() {
                *o = y[(j / lanes) * W + j % lanes];
            }
            if keep_dense {
                solution.push_dense(t, &out, &dense);
            } else {
                solution.push(t, &out);
            }
            solution.stats_mut().steps += 1;
            if solution.after_accepted_step() {
                break;
            }
        }
        Ok(solution)
    }
}

/// The least over the lanes of ρ = min(ρ_{k₁}, ρ_{k₂}), ρ_k =
/// (N/‖x^\[k\]‖∞)^(1/k) with N = max(1, ‖x‖∞), each lane's norms over its
/// own coefficients (rows of `w`), as the scalar method takes them; NaN if
/// a lane's is.
fn lanes_rho<const W: usize>(rows: &[Lanes<W>], w: usize, k: [usize; 2], inv_k: [f64; 2]) -> f64 {
    // The largest magnitude of coefficient `k` in each lane, NaNs ignored.
    let norm = |k: usize| {
        let mut m = [0.0f64; W];
        for c in rows.iter().skip(k).step_by(w) {
            for (m, x) in m.iter_mut().zip(c.0) {
                if x.abs() > *m {
                    *m = x.abs();
                }
            }
        }
        m
    };
    let (n0, n1, n2) = (norm(0), norm(k[0]), norm(k[1]));
    let mut rho = f64::INFINITY;
    for l in 0..W {
        let log_n = n0[l].max(1.0).ln();
        let log_rho =
            |nk: f64, inv_k: f64| if nk == 0.0 { f64::INFINITY } else { (log_n - nk.ln()) * inv_k };
        let mut r = log_rho(n1[l], inv_k[0]).min(log_rho(n2[l], inv_k[1])).exp();
        if n1[l] == 0.0 && n2[l] == 0.0 {
            r = super::radius_from_lower_orders(&|k| norm(k)[l], log_n, k[1]);
        }
        if r.is_nan() || r < rho {
            rho = r;
        }
    }
    rho
}

/// The members' tapes as one on lanes, padded to `W` with the last: the
/// same operations on the same operands in every member (the generated
/// tape's shape does not depend on parameter values), each constant the
/// members' values side by side. `Err` when the shapes differ.
fn lane_tape<const W: usize>(tapes: &[Tape]) -> Result<Tape<Lanes<W>>, String> {
    let member = |l: usize| &tapes[l.min(tapes.len() - 1)];
    let (first_ops, first_outputs) = member(0);
    let differ = "the members' Taylor tapes differ in shape, so they cannot share lanes; run the members one by one with `Ensemble::final_states`";
    for l in 1..tapes.len() {
        let (ops, outputs) = member(l);
        let shape = |op: &TapeOp| op.map_constants(|_| ());
        let same_ops = ops.len() == first_ops.len()
            && ops.iter().zip(first_ops).all(|(a, b)| shape(a) == shape(b));
        let same_outputs = outputs.len() == first_outputs.len()
            && outputs
                .iter()
                .zip(first_outputs)
                .all(|(a, b)| a.map_constant(|_| ()) == b.map_constant(|_| ()));
        if !same_ops || !same_outputs {
            return Err(differ.to_string());
        }
    }
    // Each member's constants of one operation (or output), in order.
    let constants = |of: &dyn Fn(usize, &mut Vec<f64>)| -> Vec<Vec<f64>> {
        (0..tapes.len())
            .map(|l| {
                let mut values = Vec::new();
                of(l, &mut values);
                values
            })
            .collect()
    };
    let ops = (0..first_ops.len())
        .map(|v| {
            let values = constants(&|l, values| {
                member(l).0[v].map_constants(|c| values.push(*c));
            });
            first_ops[v].map_constants(gather::<W>(&values))
        })
        .collect();
    let outputs = (0..first_outputs.len())
        .map(|i| {
            let values = constants(&|l, values| {
                member(l).1[i].map_constant(|c| values.push(*c));
            });
            first_outputs[i].map_constant(gather::<W>(&values))
        })
        .collect();
    Ok((ops, outputs))
}

/// The constants of one operation (or output) in each member, in order,
/// as lanes: the `j`-th call gives every member's `j`-th constant.
fn gather<const W: usize>(constants: &[Vec<f64>]) -> impl FnMut(&f64) -> Lanes<W> + '_ {
    let mut j = 0;
    move |_: &f64| {
        let lanes = Lanes(std::array::from_fn(|l| constants[l.min(constants.len() - 1)][j]));
        j += 1;
        lanes
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::taylor_tape::Operand;

    /// Lanes of one tape with different constants give each lane the
    /// coefficients its own tape gives alone, to the bit: y' = −k·y + c
    /// with sin(t) forcing, members (k, c) unlike.
    #[test]
    fn each_lane_has_its_members_coefficients_to_the_bit() {
        let tape_of = |k: f64, c: f64| -> Tape {
            (
                vec![
                    TapeOp::Mul(Operand::Const(-k), Operand::State(0)),
                    TapeOp::Sin(Operand::Time),
                    TapeOp::CosOfPrevious,
                    TapeOp::Mul(Operand::Var(1), Operand::Const(c)),
                    TapeOp::Add(Operand::Var(0), Operand::Var(3)),
                    TapeOp::Pow(Operand::State(0), k),
                ],
                vec![Operand::Var(4), Operand::Var(5)],
            )
        };
        let members = [(0.5, 2.0), (1.5, -1.0), (3.0, 0.25)];
        let tapes: Vec<Tape> = members.iter().map(|&(k, c)| tape_of(k, c)).collect();
        let (ops, outputs) = lane_tape::<4>(&tapes).unwrap();
        let order = 12;
        let mut batch = TaylorWork::<Lanes<4>>::new(&ops, &outputs, 2, order);
        let y = [[0.7, 1.1, 2.3, 2.3], [1.0, 0.5, 0.9, 0.9]];
        batch.compute(0.3, &[Lanes(y[0]), Lanes(y[1])]);
        for (l, (tape, outputs)) in tapes.iter().enumerate() {
            let mut alone = TaylorWork::new(tape, outputs, 2, order);
            alone.compute(0.3, &[y[0][l], y[1][l]]);
            for i in 0..2 {
                for k in 0..=order {
                    assert_eq!(
                        batch.state(i)[k].0[l].to_bits(),
                        alone.state(i)[k].to_bits(),
                        "lane {l}, state {i}, order {k}"
                    );
                }
            }
        }
    }

    #[test]
    fn members_of_different_shapes_are_refused_with_what_to_do() {
        let a: Tape =
            (vec![TapeOp::Mul(Operand::State(0), Operand::Const(2.0))], vec![Operand::Var(0)]);
        let b: Tape =
            (vec![TapeOp::Add(Operand::State(0), Operand::Const(2.0))], vec![Operand::Var(0)]);
        let err = lane_tape::<2>(&[a, b]).unwrap_err();
        assert!(err.contains("differ in shape") && err.contains("Ensemble::final_states"), "{err}");
    }
}
