//! The peers, run through the generated right-hand side and Jacobian of
//! each registered model (so both sides evaluate the same `f`): the
//! `ode_solvers` crate's Dopri5 and Dop853 on non-stiff problems, the
//! `diffsol` crate's BDF and TR-BDF2 on stiff ones, and SciPy and heyoka
//! through `shared/peers/peer.py` on the problems it defines.

use daegen_workprecision::{median_time, mixed_error, Peer, PeerProblem, Record, Settings};
use std::cell::RefCell;
use std::process::Command;

/// `ode_solvers` 0.6 Dopri5 or Dop853 with their default controllers
/// (Hairer's: β = 0.04, factors 0.2–10 for Dopri5; β = 0, 0.333–6 for
/// Dop853), recording every accepted step (`OutputType::Sparse`): its dense
/// output samples accumulate `xd += dx` and miss the end point, so the
/// last sample is one dx before t_end (final errors of 0.5 on Kepler at any
/// tolerance in earlier runs).
pub struct OdeSolvers {
    pub dop853: bool,
}

struct Wrapped<'a>(&'a (dyn Fn(f64, &[f64], &mut [f64]) + Sync));

impl<const N: usize> ode_solvers::System<f64, ode_solvers::SVector<f64, N>> for Wrapped<'_> {
    fn system(
        &self,
        t: f64,
        y: &ode_solvers::SVector<f64, N>,
        dy: &mut ode_solvers::SVector<f64, N>,
    ) {
        (self.0)(t, y.as_slice(), dy.as_mut_slice());
    }
}

impl OdeSolvers {
    /// One solve with stack vectors of the problem's size (as a user of
    /// the crate with a fixed-size system writes it).
    fn solve<const N: usize>(
        &self,
        p: &PeerProblem,
        tol: f64,
    ) -> Option<(Vec<f64>, ode_solvers::dop_shared::Stats)> {
        let y0 = ode_solvers::SVector::<f64, N>::from_column_slice(&p.y0);
        let atol = tol * p.atol_factor;
        let (t1, dx) = (p.t_end, p.t_end / 1000.0);
        let system = Wrapped(p.rhs);
        let sparse = ode_solvers::OutputType::Sparse;
        let (stats, x_end, y_end) = if self.dop853 {
            let mut s = ode_solvers::Dop853::from_param(
                system, 0.0, t1, dx, y0, tol, atol, 0.9, 0.0, 0.333, 6.0, t1, 0.0, 10_000_000,
                1000, sparse,
            );
            let stats = s.integrate().ok()?;
            (stats, *s.x_out().last()?, s.y_out().last()?.as_slice().to_vec())
        } else {
            let mut s = ode_solvers::Dopri5::from_param(
                system, 0.0, t1, dx, y0, tol, atol, 0.9, 0.04, 0.2, 10.0, t1, 0.0, 10_000_000,
                1000, sparse,
            );
            let stats = s.integrate().ok()?;
            (stats, *s.x_out().last()?, s.y_out().last()?.as_slice().to_vec())
        };
        ((x_end - t1).abs() <= 1e-12 * t1.abs()).then_some((y_end, stats))
    }
}

impl Peer for OdeSolvers {
    fn name(&self) -> String {
        format!("ode_solvers {}", if self.dop853 { "Dop853" } else { "Dopri5" })
    }
    fn applies(&self, p: &PeerProblem) -> bool {
        p.nonstiff && matches!(p.y0.len(), 1..=8 | 12 | 36)
    }
    fn run(&self, p: &PeerProblem, tol: f64, settings: &Settings) -> Result<Record, String> {
        let (seconds, out) = median_time(settings, || match p.y0.len() {
            1 => self.solve::<1>(p, tol),
            2 => self.solve::<2>(p, tol),
            3 => self.solve::<3>(p, tol),
            4 => self.solve::<4>(p, tol),
            5 => self.solve::<5>(p, tol),
            6 => self.solve::<6>(p, tol),
            7 => self.solve::<7>(p, tol),
            8 => self.solve::<8>(p, tol),
            12 => self.solve::<12>(p, tol),
            _ => self.solve::<36>(p, tol),
        });
        Ok(match out {
            Some((y, stats)) => Record {
                error: mixed_error(&y, p.reference),
                steps: stats.accepted_steps as usize,
                rejected: stats.rejected_steps as usize,
                rhs_evals: stats.num_eval as usize,
                ..failed(p, self.name(), tol, seconds)
            },
            None => failed(p, self.name(), tol, seconds),
        })
    }
}

/// A run that gave no answer (its error infinite, no counts); with the
/// counts and the error of one that did, its record.
pub(crate) fn failed(p: &PeerProblem, method: String, tol: f64, seconds: f64) -> Record {
    Record {
        problem: p.name.into(),
        method,
        tol,
        error: f64::INFINITY,
        seconds,
        steps: 0,
        rejected: 0,
        rhs_evals: 0,
        jacobian_evals: 0,
    }
}

/// `diffsol` 0.18 BDF or TR-BDF2 (its SDIRK) with nalgebra's dense LU; the
/// Jacobian–vector products it asks for come from the generated Jacobian.
pub struct Diffsol {
    pub sdirk: bool,
}

impl Peer for Diffsol {
    fn name(&self) -> String {
        format!("diffsol {}", if self.sdirk { "TR-BDF2" } else { "BDF" })
    }
    fn applies(&self, p: &PeerProblem) -> bool {
        p.stiff
    }
    fn run(&self, p: &PeerProblem, tol: f64, settings: &Settings) -> Result<Record, String> {
        use diffsol::{NalgebraLU, NalgebraMat, OdeBuilder, OdeSolverMethod, Vector};
        let n = p.y0.len();
        // Scratch for copying diffsol's vectors to slices and back.
        let x_buf = RefCell::new(vec![0.0; n]);
        let y_buf = RefCell::new(vec![0.0; n]);
        let j_buf = RefCell::new(vec![0.0; n * n]);
        let j_at = RefCell::new((f64::NAN, vec![f64::NAN; n]));
        let (seconds, out) = median_time(settings, || {
            // A fresh solve starts with no cached Jacobian.
            j_at.borrow_mut().0 = f64::NAN;
            let problem = OdeBuilder::<NalgebraMat<f64>>::new()
                .rtol(tol)
                .atol([tol * p.atol_factor])
                .rhs_implicit(
                    |x, _p, t, y| {
                        let (mut xb, mut yb) = (x_buf.borrow_mut(), y_buf.borrow_mut());
                        for i in 0..n {
                            xb[i] = x[i];
                        }
                        (p.rhs)(t, &xb, &mut yb);
                        for i in 0..n {
                            y[i] = yb[i];
                        }
                    },
                    |x, _p, t, v, y| {
                        // diffsol builds its Jacobian from n products at one
                        // x: evaluate J once per (t, x), as a hand-written
                        // product would cost about one evaluation.
                        let (mut at, mut j) = (j_at.borrow_mut(), j_buf.borrow_mut());
                        let same = at.0 == t && (0..n).all(|i| at.1[i] == x[i]);
                        if !same {
                            at.0 = t;
                            for i in 0..n {
                                at.1[i] = x[i];
                            }
                            (p.jacobian)(t, &at.1, &mut j);
                        }
                        for r in 0..n {
                            y[r] = (0..n).map(|c| j[r * n + c] * v[c]).sum();
                        }
                    },
                )
                .init(
                    |_p, _t, y| {
                        for i in 0..n {
                            y[i] = p.y0[i];
                        }
                    },
                    n,
                )
                .build()
                .ok()?;
            if self.sdirk {
                let mut s = problem.tr_bdf2::<NalgebraLU<f64>>().ok()?;
                s.solve(p.t_end).ok()?;
                let st = s.get_statistics().clone();
                Some((s.state().y.clone_as_vec(), st))
            } else {
                let mut s = problem.bdf::<NalgebraLU<f64>>().ok()?;
                s.solve(p.t_end).ok()?;
                let st = s.get_statistics().clone();
                Some((s.state().y.clone_as_vec(), st))
            }
        });
        Ok(match out {
            Some((y, stats)) => Record {
                error: mixed_error(&y, p.reference),
                steps: stats.number_of_steps,
                rejected: stats.number_of_error_test_failures,
                jacobian_evals: stats.number_of_linear_solver_setups,
                ..failed(p, self.name(), tol, seconds)
            },
            None => failed(p, self.name(), tol, seconds),
        })
    }
}

/// SciPy's `solve_ivp` or heyoka through peer.py, on problems it defines
/// (under the name `Bench::peer` gives).
pub struct Python {
    pub solver: &'static str,
}

/// heyoka's solves take milliseconds: a median over this many is as steady
/// as our own timing (up to 200 repeats in 0.5 s).
pub const HEYOKA_REPEATS: usize = 51;

const PEER_SCRIPT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/peers/peer.py");

impl Python {
    /// Runs peer.py once and returns the JSON it printed.
    pub fn call(
        &self,
        problem: &str,
        tol: f64,
        atol: Option<f64>,
        repeat: usize,
    ) -> Result<String, String> {
        let mut cmd = Command::new("python3");
        cmd.arg(PEER_SCRIPT)
            .arg(problem)
            .arg("--solver")
            .arg(self.solver)
            .arg("--tol")
            .arg(format!("{tol:e}"))
            .arg("--repeat")
            .arg(repeat.to_string());
        if let Some(a) = atol {
            cmd.arg("--atol").arg(format!("{a:e}"));
        }
        let out = cmd.output().map_err(|e| format!("python3 not found: {e}"))?;
        let stderr = String::from_utf8_lossy(&out.stderr);
        if stderr.contains("ModuleNotFoundError") || stderr.contains("No module named") {
            return Err(format!(
                "not installed ({}); `python3 -m pip install heyoka scipy`",
                stderr.lines().last().unwrap_or("").trim()
            ));
        }
        if !out.status.success() {
            return Err(format!("peer.py failed: {}", stderr.lines().last().unwrap_or("").trim()));
        }
        Ok(String::from_utf8_lossy(&out.stdout).into_owned())
    }
}

/// A number field of peer.py's JSON.
pub fn field(text: &str, name: &str) -> Option<f64> {
    let i = text.find(&format!("\"{name}\""))?;
    let rest = &text[i + name.len() + 3..];
    let end = rest.find([',', '}'])?;
    rest[..end].trim().parse().ok()
}

/// The numbers of array `name` in peer.py's JSON line.
pub fn array(text: &str, name: &str) -> Option<Vec<f64>> {
    let i = text.find(&format!("\"{name}\""))?;
    let rest = &text[i..];
    let (a, b) = (rest.find('[')?, rest.find(']')?);
    rest[a + 1..b].split(',').map(|v| v.trim().parse().ok()).collect()
}

impl Peer for Python {
    fn name(&self) -> String {
        match self.solver {
            "heyoka" => "heyoka".into(),
            s => format!("SciPy {s}"),
        }
    }
    fn applies(&self, p: &PeerProblem) -> bool {
        p.peer.is_some()
            && match self.solver {
                "Radau" | "BDF" => p.stiff,
                _ => p.nonstiff,
            }
    }
    /// peer.py starts Python and builds heyoka's integrator for every
    /// run; it times its own repeats.
    fn in_process(&self) -> bool {
        false
    }
    fn run(&self, p: &PeerProblem, tol: f64, settings: &Settings) -> Result<Record, String> {
        let problem = p.peer.unwrap_or_default();
        let atol = (p.atol_factor != 1.0).then_some(tol * p.atol_factor);
        // SciPy's solves take up to a second each.
        let repeat = match self.solver {
            "heyoka" => settings.min_repeats.max(HEYOKA_REPEATS),
            _ => settings.min_repeats.max(3),
        };
        let text = self.call(problem, tol, atol, repeat)?;
        let seconds =
            field(&text, "solve_s").ok_or_else(|| format!("peer.py printed {text:.200}"))?;
        // peer.py's own mixed error where it has the reference; else ours.
        let error = field(&text, "max_mixed_err")
            .or_else(|| array(&text, "y_end").map(|y| mixed_error(&y, p.reference)))
            .unwrap_or(f64::INFINITY);
        Ok(Record {
            problem: p.name.into(),
            method: self.name(),
            tol,
            error,
            seconds,
            steps: field(&text, "steps").map_or(0, |s| s as usize),
            rejected: 0,
            rhs_evals: 0,
            jacobian_evals: 0,
        })
    }
    fn setup_seconds(&self, p: &PeerProblem) -> Option<f64> {
        if self.solver != "heyoka" {
            return None;
        }
        let text = self.call(p.peer?, 1e-12, None, 1).ok()?;
        field(&text, "setup_s")
    }
}
