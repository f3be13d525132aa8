//! CVODE (variable-order BDF, orders 1–5) as a peer on the stiff
//! problems: the generated right-hand side and Jacobian as its callbacks,
//! dense LU (`SUNLinSol_Dense`) as its linear solver, `tstop` at the end
//! so it steps onto `t_end` instead of interpolating past it.

use super::{quiet, values};
use daegen_workprecision::{median_time, mixed_error, Peer, PeerProblem, Record, Settings};
use std::os::raw::{c_int, c_long, c_void};
use sundials_sys as sun;

/// CVODE with dense LU and the analytic Jacobian.
pub struct Cvode;

/// What the callbacks see through CVODE's `user_data`.
struct Callbacks<'a> {
    problem: &'a PeerProblem<'a>,
    /// The Jacobian row-major, as `PeerProblem::jacobian` writes it.
    jacobian: Vec<f64>,
}

unsafe extern "C" fn rhs(t: f64, y: sun::N_Vector, dy: sun::N_Vector, data: *mut c_void) -> c_int {
    let cb = &*(data as *const Callbacks);
    let n = cb.problem.y0.len();
    let dy = values(dy, n);
    (cb.problem.rhs)(t, values(y, n), dy);
    // A NaN (the model's evaluation failed) is a recoverable error: CVODE
    // retries with a smaller step.
    if dy.iter().all(|v| v.is_finite()) {
        0
    } else {
        1
    }
}

unsafe extern "C" fn jacobian(
    t: f64,
    y: sun::N_Vector,
    _fy: sun::N_Vector,
    jac: sun::SUNMatrix,
    data: *mut c_void,
    _tmp1: sun::N_Vector,
    _tmp2: sun::N_Vector,
    _tmp3: sun::N_Vector,
) -> c_int {
    let cb = &mut *(data as *mut Callbacks);
    let n = cb.problem.y0.len();
    (cb.problem.jacobian)(t, values(y, n), &mut cb.jacobian);
    // SUNDIALS' dense matrices are column-major.
    let out = std::slice::from_raw_parts_mut(sun::SUNDenseMatrix_Data(jac), n * n);
    for c in 0..n {
        for r in 0..n {
            out[c * n + r] = cb.jacobian[r * n + c];
        }
    }
    0
}

/// CVODE's counters after a solve.
struct Counts {
    steps: c_long,
    rhs_evals: c_long,
    error_test_failures: c_long,
    jacobian_evals: c_long,
}

impl Cvode {
    /// One solve from 0 to `t_end`: the final state and the counters, or
    /// `None` where CVODE stopped short.
    fn solve(p: &PeerProblem, tol: f64) -> Option<(Vec<f64>, Counts)> {
        let n = p.y0.len();
        let mut callbacks = Callbacks { problem: p, jacobian: vec![0.0; n * n] };
        // Every SUNDIALS object below is created and freed here, in order,
        // and the callbacks outlive the solve.
        unsafe {
            let mut ctx: sun::SUNContext = std::ptr::null_mut();
            if sun::SUNContext_Create(std::ptr::null_mut(), &mut ctx) != 0 {
                return None;
            }
            let y = sun::N_VNew_Serial(n as sun::sunindextype, ctx);
            values(y, n).copy_from_slice(&p.y0);
            let a = sun::SUNDenseMatrix(n as sun::sunindextype, n as sun::sunindextype, ctx);
            let ls = sun::SUNLinSol_Dense(y, a, ctx);
            let mut mem = sun::CVodeCreate(sun::CV_BDF, ctx);
            let mut ok = !mem.is_null()
                && sun::CVodeInit(mem, Some(rhs), 0.0, y) == 0
                && sun::CVodeSStolerances(mem, tol, tol * p.atol_factor) == 0
                && sun::CVodeSetUserData(mem, &mut callbacks as *mut Callbacks as *mut c_void) == 0
                && sun::CVodeSetErrHandlerFn(mem, Some(quiet), std::ptr::null_mut()) == 0
                && sun::CVodeSetLinearSolver(mem, ls, a) == 0
                && sun::CVodeSetJacFn(mem, Some(jacobian)) == 0
                && sun::CVodeSetMaxNumSteps(mem, 10_000_000) == 0
                && sun::CVodeSetStopTime(mem, p.t_end) == 0;
            let mut t = 0.0;
            if ok {
                ok = sun::CVode(mem, p.t_end, y, &mut t, sun::CV_NORMAL) >= 0
                    && (t - p.t_end).abs() <= 1e-12 * p.t_end.abs();
            }
            let mut counts =
                Counts { steps: 0, rhs_evals: 0, error_test_failures: 0, jacobian_evals: 0 };
            if ok {
                sun::CVodeGetNumSteps(mem, &mut counts.steps);
                sun::CVodeGetNumRhsEvals(mem, &mut counts.rhs_evals);
                sun::CVodeGetNumErrTestFails(mem, &mut counts.error_test_failures);
                sun::CVodeGetNumJacEvals(mem, &mut counts.jacobian_evals);
            }
            let out = values(y, n).to_vec();
            sun::CVodeFree(&mut mem);
            sun::SUNLinSolFree(ls);
            sun::SUNMatDestroy(a);
            sun::N_VDestroy(y);
            sun::SUNContext_Free(&mut ctx);
            ok.then_some((out, counts))
        }
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
        let (seconds, out) = median_time(settings, || Cvode::solve(p, tol));
        let base = Record {
            problem: p.name.into(),
            method: self.name(),
            tol,
            error: f64::INFINITY,
            seconds,
            steps: 0,
            rejected: 0,
            rhs_evals: 0,
            jacobian_evals: 0,
        };
        Ok(match out {
            Some((y, c)) => Record {
                error: mixed_error(&y, p.reference),
                steps: c.steps as usize,
                rejected: c.error_test_failures as usize,
                rhs_evals: c.rhs_evals as usize,
                jacobian_evals: c.jacobian_evals as usize,
                ..base
            },
            None => base,
        })
    }
}
