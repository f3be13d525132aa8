//! IDA (variable-order BDF for F(t, y, y′) = 0) as a peer on DAEs: the
//! residual and its iteration matrix ∂F/∂y + c_j ∂F/∂y′ as callbacks, dense
//! LU, the differential components marked (`IDASetId`) so that the error
//! test and the initial step treat the algebraic ones as such.

use super::{quiet, values, Objects};
use std::os::raw::{c_int, c_long, c_void};
use sundials_sys as sun;

/// A DAE in IDA's form, F(t, y, y′) = 0, with consistent initial values.
pub struct Residual<'a> {
    /// y(t0).
    pub y0: &'a [f64],
    /// y′(t0), consistent with `y0`.
    pub yp0: &'a [f64],
    /// 1 for a differential component, 0 for an algebraic one.
    pub differential: &'a [f64],
    /// Writes F(t, y, y′) into its last argument.
    pub residual: &'a dyn Fn(f64, &[f64], &[f64], &mut [f64]),
    /// Writes ∂F/∂y + c_j ∂F/∂y′ at (t, y, y′), row-major, into its last
    /// argument (c_j its second).
    pub iteration_matrix: &'a dyn Fn(f64, f64, &[f64], &[f64], &mut [f64]),
}

/// What the callbacks see through IDA's `user_data`.
struct Callbacks<'a> {
    dae: &'a Residual<'a>,
    matrix: Vec<f64>,
}

unsafe extern "C" fn residual(
    t: f64,
    y: sun::N_Vector,
    yp: sun::N_Vector,
    r: sun::N_Vector,
    data: *mut c_void,
) -> c_int {
    let cb = &*(data as *const Callbacks);
    let n = cb.dae.y0.len();
    let r = values(r, n);
    (cb.dae.residual)(t, values(y, n), values(yp, n), r);
    // Non-finite: recoverable, IDA retries with a smaller step.
    if r.iter().all(|v| v.is_finite()) {
        0
    } else {
        1
    }
}

/// IDA's `IDALsJacFn`: its arguments are SUNDIALS' and mostly CVODE's
/// `CVLsJacFn`'s too (cvode.rs), whence the like-shaped signatures.
#[allow(clippy::too_many_arguments)]
unsafe extern "C" fn iteration_matrix(
    t: f64,
    cj: f64,
    y: sun::N_Vector,
    yp: sun::N_Vector,
    _r: sun::N_Vector,
    jac: sun::SUNMatrix,
    data: *mut c_void,
    _tmp1: sun::N_Vector,
    _tmp2: sun::N_Vector,
    _tmp3: sun::N_Vector,
) -> c_int {
    let cb = &mut *(data as *mut Callbacks);
    let n = cb.dae.y0.len();
    (cb.dae.iteration_matrix)(t, cj, values(y, n), values(yp, n), &mut cb.matrix);
    // SUNDIALS' dense matrices are column-major.
    let out = std::slice::from_raw_parts_mut(sun::SUNDenseMatrix_Data(jac), n * n);
    for c in 0..n {
        for r in 0..n {
            out[c * n + r] = cb.matrix[r * n + c];
        }
    }
    0
}

/// Solves `dae` from 0 to `t_end` at (rtol, atol): the final state and
/// the steps taken, or `None` where IDA stopped short.
pub fn solve(dae: &Residual, t_end: f64, rtol: f64, atol: f64) -> Option<(Vec<f64>, usize)> {
    let n = dae.y0.len();
    let mut callbacks = Callbacks { dae, matrix: vec![0.0; n * n] };
    let len = n as sun::sunindextype;
    let mut objects = Objects::new()?;
    let (y, yp, id) =
        (objects.vector(dae.y0), objects.vector(dae.yp0), objects.vector(dae.differential));
    // SAFETY: every object lives in `objects` until after `IDAFree`, and the
    // callbacks outlive the solve.
    unsafe {
        let ctx = objects.ctx;
        let a = sun::SUNDenseMatrix(len, len, ctx);
        let ls = sun::SUNLinSol_Dense(y, a, ctx);
        (objects.matrix, objects.solver) = (a, ls);
        let mut mem = sun::IDACreate(ctx);
        let mut ok = !mem.is_null()
            && sun::IDAInit(mem, Some(residual), 0.0, y, yp) == 0
            && sun::IDASStolerances(mem, rtol, atol) == 0
            && sun::IDASetUserData(mem, &mut callbacks as *mut Callbacks as *mut c_void) == 0
            && sun::IDASetErrHandlerFn(mem, Some(quiet), std::ptr::null_mut()) == 0
            && sun::IDASetId(mem, id) == 0
            && sun::IDASetLinearSolver(mem, ls, a) == 0
            && sun::IDASetJacFn(mem, Some(iteration_matrix)) == 0
            && sun::IDASetMaxNumSteps(mem, 10_000_000) == 0
            && sun::IDASetStopTime(mem, t_end) == 0;
        let mut t = 0.0;
        if ok {
            ok = sun::IDASolve(mem, t_end, &mut t, y, yp, sun::IDA_NORMAL) >= 0
                && (t - t_end).abs() <= 1e-12 * t_end.abs();
        }
        let mut steps: c_long = 0;
        if ok {
            sun::IDAGetNumSteps(mem, &mut steps);
        }
        let out = values(y, n).to_vec();
        sun::IDAFree(&mut mem);
        ok.then_some((out, steps as usize))
    }
}
