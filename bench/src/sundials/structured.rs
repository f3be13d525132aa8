//! CVODE on a large model with the linear solver its Jacobian calls for:
//! band LU (`SUNLinSol_Band`) where the generated pattern lies within a
//! band, sparse LU by KLU (`SUNLinSol_KLU`, compressed columns) otherwise,
//! both filled from the model's generated sparse Jacobian
//! (`Model::jacobian`, in `JACOBIAN_PATTERN` order), as a user of CVODE
//! with a hand-written sparse Jacobian would.

use super::{quiet, values};
use daegen::Model;
use std::os::raw::{c_int, c_long, c_void};
use sundials_sys as sun;

/// CVODE's linear solver.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Linear {
    /// Band LU, with the pattern's lower and upper bandwidths.
    Band,
    /// KLU sparse LU.
    Klu,
}

/// The lower and upper bandwidths of a pattern.
pub fn bandwidths(pattern: &[(usize, usize)]) -> (usize, usize) {
    pattern
        .iter()
        .fold((0, 0), |(l, u), &(r, c)| (l.max(r.saturating_sub(c)), u.max(c.saturating_sub(r))))
}

/// What the callbacks see through CVODE's `user_data`.
struct Callbacks<'a, M: Model> {
    model: &'a M,
    values: Vec<f64>,
    /// For KLU: each pattern entry's position in the compressed columns.
    slot: Vec<usize>,
}

unsafe extern "C" fn rhs<M: Model>(
    t: f64,
    y: sun::N_Vector,
    dy: sun::N_Vector,
    data: *mut c_void,
) -> c_int {
    let cb = &*(data as *const Callbacks<M>);
    let n = M::STATES;
    match cb.model.rhs(t, values(y, n), values(dy, n)) {
        Ok(()) => 0,
        Err(_) => 1,
    }
}

#[allow(clippy::too_many_arguments)]
unsafe extern "C" fn band_jacobian<M: Model>(
    t: f64,
    y: sun::N_Vector,
    _fy: sun::N_Vector,
    jac: sun::SUNMatrix,
    data: *mut c_void,
    _tmp1: sun::N_Vector,
    _tmp2: sun::N_Vector,
    _tmp3: sun::N_Vector,
) -> c_int {
    let cb = &mut *(data as *mut Callbacks<M>);
    if cb.model.jacobian(t, values(y, M::STATES), &mut cb.values).is_err() {
        return 1;
    }
    sun::SUNMatZero(jac);
    for (&(r, c), &v) in M::JACOBIAN_PATTERN.iter().zip(&cb.values) {
        // Column c's pointer is at its diagonal: (r, c) is r − c from it.
        *sun::SUNBandMatrix_Column(jac, c as sun::sunindextype).offset(r as isize - c as isize) +=
            v;
    }
    0
}

#[allow(clippy::too_many_arguments)]
unsafe extern "C" fn sparse_jacobian<M: Model>(
    t: f64,
    y: sun::N_Vector,
    _fy: sun::N_Vector,
    jac: sun::SUNMatrix,
    data: *mut c_void,
    _tmp1: sun::N_Vector,
    _tmp2: sun::N_Vector,
    _tmp3: sun::N_Vector,
) -> c_int {
    let cb = &mut *(data as *mut Callbacks<M>);
    if cb.model.jacobian(t, values(y, M::STATES), &mut cb.values).is_err() {
        return 1;
    }
    let nnz = M::JACOBIAN_PATTERN.len();
    let n = M::STATES;
    let (cols, rows, out) = (
        std::slice::from_raw_parts_mut(sun::SUNSparseMatrix_IndexPointers(jac), n + 1),
        std::slice::from_raw_parts_mut(sun::SUNSparseMatrix_IndexValues(jac), nnz),
        std::slice::from_raw_parts_mut(sun::SUNSparseMatrix_Data(jac), nnz),
    );
    // The structure is the pattern's, sorted by column then row.
    let mut count = vec![0 as sun::sunindextype; n + 1];
    for &(_, c) in M::JACOBIAN_PATTERN {
        count[c + 1] += 1;
    }
    for c in 0..n {
        count[c + 1] += count[c];
    }
    cols.copy_from_slice(&count);
    for ((&(r, _), &v), &s) in M::JACOBIAN_PATTERN.iter().zip(&cb.values).zip(&cb.slot) {
        rows[s] = r as sun::sunindextype;
        out[s] = v;
    }
    0
}

/// Each pattern entry's position in compressed columns sorted by row.
fn compressed_slots(pattern: &[(usize, usize)]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..pattern.len()).collect();
    order.sort_by_key(|&k| (pattern[k].1, pattern[k].0));
    let mut slot = vec![0; pattern.len()];
    for (position, &k) in order.iter().enumerate() {
        slot[k] = position;
    }
    slot
}

/// Integrates `model` from `(t0, y0)` to `t1` by CVODE's BDF at (rtol,
/// atol) with `linear`: the final state and the steps, or `None` where it
/// stopped short.
pub fn solve<M: Model>(
    model: &M,
    t0: f64,
    y0: &[f64],
    t1: f64,
    rtol: f64,
    atol: f64,
    linear: Linear,
) -> Option<(Vec<f64>, usize)> {
    let n = M::STATES;
    let len = n as sun::sunindextype;
    let pattern = M::JACOBIAN_PATTERN;
    let mut callbacks =
        Callbacks { model, values: vec![0.0; pattern.len()], slot: compressed_slots(pattern) };
    // Every SUNDIALS object below is created and freed here, in order, and
    // the callbacks outlive the solve.
    unsafe {
        let mut ctx: sun::SUNContext = std::ptr::null_mut();
        if sun::SUNContext_Create(std::ptr::null_mut(), &mut ctx) != 0 {
            return None;
        }
        let y = sun::N_VNew_Serial(len, ctx);
        values(y, n).copy_from_slice(y0);
        let (a, ls, jac): (_, _, sun::CVLsJacFn) = match linear {
            Linear::Band => {
                let (ml, mu) = bandwidths(pattern);
                let a =
                    sun::SUNBandMatrix(len, mu as sun::sunindextype, ml as sun::sunindextype, ctx);
                (a, sun::SUNLinSol_Band(y, a, ctx), Some(band_jacobian::<M>))
            }
            Linear::Klu => {
                let a = sun::SUNSparseMatrix(
                    len,
                    len,
                    pattern.len() as sun::sunindextype,
                    sun::CSC_MAT as c_int,
                    ctx,
                );
                (a, sun::SUNLinSol_KLU(y, a, ctx), Some(sparse_jacobian::<M>))
            }
        };
        let mut mem = sun::CVodeCreate(sun::CV_BDF, ctx);
        let mut ok = !mem.is_null()
            && !a.is_null()
            && !ls.is_null()
            && sun::CVodeInit(mem, Some(rhs::<M>), t0, y) == 0
            && sun::CVodeSStolerances(mem, rtol, atol) == 0
            && sun::CVodeSetUserData(mem, &mut callbacks as *mut Callbacks<M> as *mut c_void) == 0
            && sun::CVodeSetErrHandlerFn(mem, Some(quiet), std::ptr::null_mut()) == 0
            && sun::CVodeSetLinearSolver(mem, ls, a) == 0
            && sun::CVodeSetJacFn(mem, jac) == 0
            && sun::CVodeSetMaxNumSteps(mem, 10_000_000) == 0
            && sun::CVodeSetStopTime(mem, t1) == 0;
        let mut t = t0;
        if ok {
            ok = sun::CVode(mem, t1, y, &mut t, sun::CV_NORMAL) >= 0
                && (t - t1).abs() <= 1e-12 * t1.abs().max(1.0);
        }
        let mut steps: c_long = 0;
        if ok {
            sun::CVodeGetNumSteps(mem, &mut steps);
        }
        let out = values(y, n).to_vec();
        sun::CVodeFree(&mut mem);
        sun::SUNLinSolFree(ls);
        sun::SUNMatDestroy(a);
        sun::N_VDestroy(y);
        sun::SUNContext_Free(&mut ctx);
        ok.then_some((out, steps as usize))
    }
}
