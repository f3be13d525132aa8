//! CVODE as a peer of the work-precision sweep on the stiff problems: the
//! generated right-hand side and (dense) Jacobian of each registered model
//! through [`PeerProblem`], dense LU.

use super::cvode::{solve, Linear, System};
use crate::peers::failed;
use daegen_workprecision::{median_time, mixed_error, Peer, PeerProblem, Record, Settings};

/// CVODE with dense LU and the analytic Jacobian.
pub struct Cvode;

/// A registered problem as a CVODE system: its Jacobian dense, every
/// entry a non-zero, row by row.
struct Dense<'a> {
    problem: &'a PeerProblem<'a>,
    pattern: Vec<(usize, usize)>,
}

impl System for Dense<'_> {
    fn states(&self) -> usize {
        self.problem.y0.len()
    }
    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) -> bool {
        (self.problem.rhs)(t, y, dy);
        // NaN where the model's evaluation failed.
        dy.iter().all(|v| v.is_finite())
    }
    fn pattern(&self) -> &[(usize, usize)] {
        &self.pattern
    }
    fn jacobian(&mut self, t: f64, y: &[f64], values: &mut [f64]) -> bool {
        (self.problem.jacobian)(t, y, values);
        true
    }
}

impl Peer for Cvode {
    fn name(&self) -> String {
        "CVODE BDF (dense)".into()
    }
    fn applies(&self, p: &PeerProblem) -> bool {
        p.stiff
    }
    fn run(&self, p: &PeerProblem, tol: f64, settings: &Settings) -> Result<Record, String> {
        let n = p.y0.len();
        let pattern = (0..n).flat_map(|r| (0..n).map(move |c| (r, c))).collect();
        let mut system = Dense { problem: p, pattern };
        let tolerances = (tol, tol * p.atol_factor);
        let (seconds, out) = median_time(settings, || {
            solve(&mut system, 0.0, &p.y0, p.t_end, tolerances, Linear::Dense)
        });
        Ok(match out {
            Some((y, c)) => Record {
                error: mixed_error(&y, p.reference),
                steps: c.steps,
                rejected: c.error_test_failures,
                rhs_evals: c.rhs_evals,
                jacobian_evals: c.jacobian_evals,
                ..failed(p, self.name(), tol, seconds)
            },
            None => failed(p, self.name(), tol, seconds),
        })
    }
}
