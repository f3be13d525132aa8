//! CVODE (variable-order BDF, orders 1–5) on any system that gives its
//! right-hand side and the non-zeros of its Jacobian, with the linear
//! solver its Jacobian calls for: dense LU, band LU, KLU sparse LU, or
//! GMRES with a block-diagonal preconditioner (matrix-free: J·v by
//! CVODE's difference quotients);
//! `tstop` at the end, so it steps onto `t1` instead of interpolating past
//! it.

use super::block_jacobi::BlockJacobi;
use super::{quiet, values, Objects};
use std::os::raw::{c_int, c_long, c_void};
use sundials_sys as sun;

/// What CVODE needs from a system.
pub trait System {
    /// The number of states.
    fn states(&self) -> usize;
    /// Writes f(t, y) into `dy`; `false` where it cannot be evaluated.
    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) -> bool;
    /// The Jacobian's non-zeros (row, column).
    fn pattern(&self) -> &[(usize, usize)];
    /// Writes ∂f/∂y at (t, y) into `values`, in [`System::pattern`]'s
    /// order; `false` where it cannot be evaluated.
    fn jacobian(&mut self, t: f64, y: &[f64], values: &mut [f64]) -> bool;
}

/// CVODE's linear solver.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Linear {
    /// Dense LU.
    Dense,
    /// Band LU, with the pattern's lower and upper bandwidths.
    Band,
    /// KLU sparse LU.
    Klu,
    /// GMRES (SPGMR, left preconditioned) with the block-diagonal
    /// preconditioner of blocks of `block` consecutive states.
    Gmres {
        /// States per diagonal block (species per grid cell).
        block: usize,
    },
}

/// The lower and upper bandwidths of a pattern.
pub fn bandwidths(pattern: &[(usize, usize)]) -> (usize, usize) {
    pattern
        .iter()
        .fold((0, 0), |(l, u), &(r, c)| (l.max(r.saturating_sub(c)), u.max(c.saturating_sub(r))))
}

/// CVODE's counters after a solve.
#[derive(Clone, Copy, Debug, Default)]
pub struct Counts {
    /// Steps taken.
    pub steps: usize,
    /// Right-hand-side evaluations.
    pub rhs_evals: usize,
    /// Steps whose error test failed.
    pub error_test_failures: usize,
    /// Jacobian evaluations (for GMRES: preconditioner evaluations).
    pub jacobian_evals: usize,
}

/// A SUNDIALS counter's getter (`CVodeGetNumSteps`, `IDAGetNumSteps`, …).
pub(crate) type Getter = unsafe extern "C" fn(*mut c_void, *mut c_long) -> c_int;

impl Counts {
    /// The counters `getters` read from an integrator's memory `mem`:
    /// steps, right-hand sides (residuals), error-test failures, Jacobian
    /// (or preconditioner) evaluations.
    ///
    /// # Safety
    /// `mem` is the memory of the integrator the getters belong to.
    pub(crate) unsafe fn read(mem: *mut c_void, getters: [Getter; 4]) -> Counts {
        let [steps, rhs, failures, jacobians] = getters.map(|get| {
            let mut value: c_long = 0;
            get(mem, &mut value);
            value as usize
        });
        Counts { steps, rhs_evals: rhs, error_test_failures: failures, jacobian_evals: jacobians }
    }
}

/// What the callbacks see through CVODE's `user_data`.
struct Callbacks<'a, S: System> {
    system: &'a mut S,
    linear: Linear,
    values: Vec<f64>,
    /// For KLU: each pattern entry's position in the compressed columns.
    slot: Vec<usize>,
    /// For KLU: the column starts.
    column_start: Vec<sun::sunindextype>,
    /// For GMRES: the preconditioner.
    preconditioner: Option<BlockJacobi>,
}

unsafe extern "C" fn rhs<S: System>(
    t: f64,
    y: sun::N_Vector,
    dy: sun::N_Vector,
    data: *mut c_void,
) -> c_int {
    let cb = &*(data as *const Callbacks<S>);
    let n = cb.system.states();
    // A failed evaluation is recoverable: CVODE retries with a smaller step.
    c_int::from(!cb.system.rhs(t, values(y, n), values(dy, n)))
}

#[allow(clippy::too_many_arguments)]
unsafe extern "C" fn jacobian<S: System>(
    t: f64,
    y: sun::N_Vector,
    _fy: sun::N_Vector,
    jac: sun::SUNMatrix,
    data: *mut c_void,
    _tmp1: sun::N_Vector,
    _tmp2: sun::N_Vector,
    _tmp3: sun::N_Vector,
) -> c_int {
    let cb = &mut *(data as *mut Callbacks<S>);
    let n = cb.system.states();
    if !cb.system.jacobian(t, values(y, n), &mut cb.values) {
        return 1;
    }
    let pattern = cb.system.pattern();
    match cb.linear {
        Linear::Dense | Linear::Band => {
            sun::SUNMatZero(jac);
            for (&(r, c), &v) in pattern.iter().zip(&cb.values) {
                let column = if cb.linear == Linear::Dense {
                    sun::SUNDenseMatrix_Column(jac, c as sun::sunindextype).add(r)
                } else {
                    // A band column's pointer is at its diagonal.
                    sun::SUNBandMatrix_Column(jac, c as sun::sunindextype)
                        .offset(r as isize - c as isize)
                };
                *column += v;
            }
        }
        // GMRES takes no matrix: its preconditioner evaluates the Jacobian.
        Linear::Gmres { .. } => {}
        Linear::Klu => {
            let nnz = pattern.len();
            std::slice::from_raw_parts_mut(sun::SUNSparseMatrix_IndexPointers(jac), n + 1)
                .copy_from_slice(&cb.column_start);
            let rows = std::slice::from_raw_parts_mut(sun::SUNSparseMatrix_IndexValues(jac), nnz);
            let out = std::slice::from_raw_parts_mut(sun::SUNSparseMatrix_Data(jac), nnz);
            for ((&(r, _), &v), &s) in pattern.iter().zip(&cb.values).zip(&cb.slot) {
                rows[s] = r as sun::sunindextype;
                out[s] = v;
            }
        }
    }
    0
}

/// CVODE's preconditioner set-up: the Jacobian's blocks, evaluated anew
/// unless CVODE says the last ones will do (`jok`), and I − γ·J inverted.
unsafe extern "C" fn preconditioner_setup<S: System>(
    t: f64,
    y: sun::N_Vector,
    _fy: sun::N_Vector,
    jok: c_int,
    jcur: *mut c_int,
    gamma: f64,
    data: *mut c_void,
) -> c_int {
    let cb = &mut *(data as *mut Callbacks<S>);
    let n = cb.system.states();
    let Some(p) = cb.preconditioner.as_mut() else { return -1 };
    if jok == 0 {
        if !cb.system.jacobian(t, values(y, n), &mut cb.values) {
            return 1;
        }
        p.load(&cb.values);
        *jcur = 1;
    } else {
        *jcur = 0;
    }
    c_int::from(!p.factor(gamma))
}

/// CVODE's preconditioner solve: z = P⁻¹ r.
#[allow(clippy::too_many_arguments)]
unsafe extern "C" fn preconditioner_solve<S: System>(
    _t: f64,
    _y: sun::N_Vector,
    _fy: sun::N_Vector,
    r: sun::N_Vector,
    z: sun::N_Vector,
    _gamma: f64,
    _delta: f64,
    _lr: c_int,
    data: *mut c_void,
) -> c_int {
    let cb = &*(data as *const Callbacks<S>);
    let n = cb.system.states();
    let Some(p) = cb.preconditioner.as_ref() else { return -1 };
    p.solve(values(r, n), values(z, n));
    0
}

/// Each pattern entry's position in compressed columns sorted by row, and
/// the columns' starts.
pub(crate) fn compressed_columns(
    n: usize,
    pattern: &[(usize, usize)],
) -> (Vec<usize>, Vec<sun::sunindextype>) {
    let mut order: Vec<usize> = (0..pattern.len()).collect();
    order.sort_by_key(|&k| (pattern[k].1, pattern[k].0));
    let mut slot = vec![0; pattern.len()];
    for (position, &k) in order.iter().enumerate() {
        slot[k] = position;
    }
    let mut start = vec![0 as sun::sunindextype; n + 1];
    for &(_, c) in pattern {
        start[c + 1] += 1;
    }
    for c in 0..n {
        start[c + 1] += start[c];
    }
    (slot, start)
}

/// The matrix (null for GMRES) and the linear solver `linear` calls for,
/// for systems of `len` states with bandwidths `(ml, mu)` and `nnz`
/// non-zeros.
///
/// # Safety
/// `y` is a serial vector of `len` values of context `ctx`.
pub(crate) unsafe fn matrix_and_solver(
    linear: Linear,
    y: sun::N_Vector,
    (len, ml, mu, nnz): (sun::sunindextype, usize, usize, usize),
    ctx: sun::SUNContext,
) -> (sun::SUNMatrix, sun::SUNLinearSolver) {
    match linear {
        Linear::Dense => {
            let a = sun::SUNDenseMatrix(len, len, ctx);
            (a, sun::SUNLinSol_Dense(y, a, ctx))
        }
        Linear::Band => {
            let a = sun::SUNBandMatrix(len, mu as sun::sunindextype, ml as sun::sunindextype, ctx);
            (a, sun::SUNLinSol_Band(y, a, ctx))
        }
        Linear::Klu => {
            let a = sun::SUNSparseMatrix(
                len,
                len,
                nnz as sun::sunindextype,
                sun::CSC_MAT as c_int,
                ctx,
            );
            (a, sun::SUNLinSol_KLU(y, a, ctx))
        }
        Linear::Gmres { .. } => {
            // SPGMR's default Krylov dimension (5), as cvDiurnal_kry.
            let ls = sun::SUNLinSol_SPGMR(y, sun::SUN_PREC_LEFT as c_int, 0, ctx);
            (std::ptr::null_mut(), ls)
        }
    }
}

/// Integrates `system` from `(t0, y0)` to `t1` by CVODE's BDF at (rtol,
/// atol) with `linear`: the final state and the counters, or `None` where
/// it stopped short.
pub fn solve<S: System>(
    system: &mut S,
    t0: f64,
    y0: &[f64],
    t1: f64,
    (rtol, atol): (f64, f64),
    linear: Linear,
) -> Option<(Vec<f64>, Counts)> {
    let n = system.states();
    let len = n as sun::sunindextype;
    let nnz = system.pattern().len();
    let (ml, mu) = bandwidths(system.pattern());
    let (slot, column_start) = compressed_columns(n, system.pattern());
    let preconditioner = match linear {
        Linear::Gmres { block } => Some(BlockJacobi::new(n, block, system.pattern())),
        _ => None,
    };
    let mut callbacks =
        Callbacks { system, linear, values: vec![0.0; nnz], slot, column_start, preconditioner };
    let mut objects = Objects::new()?;
    let y = objects.vector(y0);
    // SAFETY: every object lives in `objects` until after `CVodeFree`, and
    // the callbacks outlive the solve.
    unsafe {
        let ctx = objects.ctx;
        let (a, ls) = matrix_and_solver(linear, y, (len, ml, mu, nnz), ctx);
        let krylov = matches!(linear, Linear::Gmres { .. });
        (objects.matrix, objects.solver) = (a, ls);
        let mut mem = sun::CVodeCreate(sun::CV_BDF, ctx);
        let mut ok = !mem.is_null()
            && (krylov || !a.is_null())
            && !ls.is_null()
            && sun::CVodeInit(mem, Some(rhs::<S>), t0, y) == 0
            && sun::CVodeSStolerances(mem, rtol, atol) == 0
            && sun::CVodeSetUserData(mem, &mut callbacks as *mut Callbacks<S> as *mut c_void) == 0
            && sun::CVodeSetErrHandlerFn(mem, Some(quiet), std::ptr::null_mut()) == 0
            && sun::CVodeSetLinearSolver(mem, ls, a) == 0
            && if krylov {
                sun::CVodeSetPreconditioner(
                    mem,
                    Some(preconditioner_setup::<S>),
                    Some(preconditioner_solve::<S>),
                ) == 0
            } else {
                sun::CVodeSetJacFn(mem, Some(jacobian::<S>)) == 0
            }
            && sun::CVodeSetMaxNumSteps(mem, 10_000_000) == 0
            && sun::CVodeSetStopTime(mem, t1) == 0;
        let mut t = t0;
        if ok {
            ok = sun::CVode(mem, t1, y, &mut t, sun::CV_NORMAL) >= 0
                && (t - t1).abs() <= 1e-12 * t1.abs().max(1.0);
        }
        let mut counts = Counts::default();
        if ok {
            let jacobian_count =
                if krylov { sun::CVodeGetNumPrecEvals } else { sun::CVodeGetNumJacEvals };
            counts = Counts::read(
                mem,
                [
                    sun::CVodeGetNumSteps,
                    sun::CVodeGetNumRhsEvals,
                    sun::CVodeGetNumErrTestFails,
                    jacobian_count,
                ],
            );
        }
        let out = values(y, n).to_vec();
        sun::CVodeFree(&mut mem);
        ok.then_some((out, counts))
    }
}
