//! IDA on an ODE system, F(t, y, y′) = y′ − f(t, y) = 0, with the linear
//! solver its Jacobian calls for, as CVODE has them (`cvode.rs`): band LU,
//! KLU sparse LU, or GMRES with the block-diagonal preconditioner of
//! c_j·I − J; its iteration matrix is c_j·I − ∂f/∂y from the system's
//! sparse Jacobian. How users who hold their ODE in IDA's residual form
//! (as ModelingToolkit's and OpenModelica's users do) meet large problems.

use super::block_jacobi::BlockJacobi;
use super::cvode::{bandwidths, compressed_columns, matrix_and_solver, Counts, Linear, System};
use super::{quiet, values, Objects};
use std::os::raw::{c_int, c_void};
use sundials_sys as sun;

/// What the callbacks see through IDA's `user_data`.
struct Callbacks<'a, S: System> {
    system: &'a mut S,
    linear: Linear,
    values: Vec<f64>,
    /// For KLU: each pattern entry's position in the compressed columns,
    /// and the columns' starts.
    slot: Vec<usize>,
    column_start: Vec<sun::sunindextype>,
    /// For GMRES: the preconditioner.
    preconditioner: Option<BlockJacobi>,
    /// c_j of the last preconditioner set-up.
    cj: f64,
}

unsafe extern "C" fn residual<S: System>(
    t: f64,
    y: sun::N_Vector,
    yp: sun::N_Vector,
    r: sun::N_Vector,
    data: *mut c_void,
) -> c_int {
    let cb = &*(data as *const Callbacks<S>);
    let n = cb.system.states();
    let r = values(r, n);
    if !cb.system.rhs(t, values(y, n), r) {
        return 1;
    }
    for (ri, ypi) in r.iter_mut().zip(values(yp, n).iter()) {
        *ri = ypi - *ri;
    }
    0
}

/// c_j·I − J into IDA's matrix (band or compressed columns).
#[allow(clippy::too_many_arguments)]
unsafe extern "C" fn iteration_matrix<S: System>(
    t: f64,
    cj: f64,
    y: sun::N_Vector,
    _yp: sun::N_Vector,
    _r: sun::N_Vector,
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
            let entry = |r: usize, c: usize| {
                if cb.linear == Linear::Dense {
                    sun::SUNDenseMatrix_Column(jac, c as sun::sunindextype).add(r)
                } else {
                    sun::SUNBandMatrix_Column(jac, c as sun::sunindextype)
                        .offset(r as isize - c as isize)
                }
            };
            for (&(r, c), &v) in pattern.iter().zip(&cb.values) {
                *entry(r, c) -= v;
            }
            for i in 0..n {
                *entry(i, i) += cj;
            }
        }
        Linear::Gmres { .. } => {}
        Linear::Klu => {
            // The pattern has every diagonal entry (checked in `solve`).
            let nnz = pattern.len();
            std::slice::from_raw_parts_mut(sun::SUNSparseMatrix_IndexPointers(jac), n + 1)
                .copy_from_slice(&cb.column_start);
            let rows = std::slice::from_raw_parts_mut(sun::SUNSparseMatrix_IndexValues(jac), nnz);
            let out = std::slice::from_raw_parts_mut(sun::SUNSparseMatrix_Data(jac), nnz);
            for ((&(r, c), &v), &s) in pattern.iter().zip(&cb.values).zip(&cb.slot) {
                rows[s] = r as sun::sunindextype;
                out[s] = if r == c { cj - v } else { -v };
            }
        }
    }
    0
}

/// IDA's preconditioner set-up: the Jacobian's blocks, and
/// (c_j·I − J)⁻¹ = (I − J/c_j)⁻¹ / c_j block by block.
unsafe extern "C" fn preconditioner_setup<S: System>(
    t: f64,
    y: sun::N_Vector,
    _yp: sun::N_Vector,
    _r: sun::N_Vector,
    cj: f64,
    data: *mut c_void,
) -> c_int {
    let cb = &mut *(data as *mut Callbacks<S>);
    let n = cb.system.states();
    if !cb.system.jacobian(t, values(y, n), &mut cb.values) {
        return 1;
    }
    let Some(p) = cb.preconditioner.as_mut() else { return -1 };
    p.load(&cb.values);
    cb.cj = cj;
    c_int::from(!p.factor(1.0 / cj))
}

/// IDA's preconditioner solve: z = P⁻¹ r.
#[allow(clippy::too_many_arguments)]
unsafe extern "C" fn preconditioner_solve<S: System>(
    _t: f64,
    _y: sun::N_Vector,
    _yp: sun::N_Vector,
    _r: sun::N_Vector,
    rvec: sun::N_Vector,
    zvec: sun::N_Vector,
    _cj: f64,
    _delta: f64,
    data: *mut c_void,
) -> c_int {
    let cb = &*(data as *const Callbacks<S>);
    let n = cb.system.states();
    let Some(p) = cb.preconditioner.as_ref() else { return -1 };
    let z = values(zvec, n);
    p.solve(values(rvec, n), z);
    z.iter_mut().for_each(|v| *v /= cb.cj);
    0
}

/// Integrates `system` from `(t0, y0)` to `t1` by IDA's BDF at (rtol,
/// atol) with `linear`: the final state and the counters, or `None` where
/// it stopped short (or where KLU is asked of a pattern without its whole
/// diagonal).
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
    if linear == Linear::Klu {
        let mut diagonal = vec![false; n];
        system.pattern().iter().filter(|(r, c)| r == c).for_each(|&(r, _)| diagonal[r] = true);
        if diagonal.contains(&false) {
            return None;
        }
    }
    let preconditioner = match linear {
        Linear::Gmres { block } => Some(BlockJacobi::new(n, block, system.pattern())),
        _ => None,
    };
    // y′(t0) = f(t0, y0): consistent for an ODE.
    let mut yp0 = vec![0.0; n];
    if !system.rhs(t0, y0, &mut yp0) {
        return None;
    }
    let mut callbacks = Callbacks {
        system,
        linear,
        values: vec![0.0; nnz],
        slot,
        column_start,
        preconditioner,
        cj: 1.0,
    };
    let mut objects = Objects::new()?;
    let (y, yp) = (objects.vector(y0), objects.vector(&yp0));
    // SAFETY: every object lives in `objects` until after `IDAFree`, and
    // the callbacks outlive the solve.
    unsafe {
        let ctx = objects.ctx;
        let (a, ls) = matrix_and_solver(linear, y, (len, ml, mu, nnz), ctx);
        let krylov = matches!(linear, Linear::Gmres { .. });
        (objects.matrix, objects.solver) = (a, ls);
        let mut mem = sun::IDACreate(ctx);
        let mut ok = !mem.is_null()
            && (krylov || !a.is_null())
            && !ls.is_null()
            && sun::IDAInit(mem, Some(residual::<S>), t0, y, yp) == 0
            && sun::IDASStolerances(mem, rtol, atol) == 0
            && sun::IDASetUserData(mem, &mut callbacks as *mut Callbacks<S> as *mut c_void) == 0
            && sun::IDASetErrHandlerFn(mem, Some(quiet), std::ptr::null_mut()) == 0
            && sun::IDASetLinearSolver(mem, ls, a) == 0
            && if krylov {
                sun::IDASetPreconditioner(
                    mem,
                    Some(preconditioner_setup::<S>),
                    Some(preconditioner_solve::<S>),
                ) == 0
            } else {
                sun::IDASetJacFn(mem, Some(iteration_matrix::<S>)) == 0
            }
            && sun::IDASetMaxNumSteps(mem, 10_000_000) == 0
            && sun::IDASetStopTime(mem, t1) == 0;
        let mut t = t0;
        if ok {
            ok = sun::IDASolve(mem, t1, &mut t, y, yp, sun::IDA_NORMAL) >= 0
                && (t - t1).abs() <= 1e-12 * t1.abs().max(1.0);
        }
        let mut counts = Counts::default();
        if ok {
            let jacobian_count =
                if krylov { sun::IDAGetNumPrecEvals } else { sun::IDAGetNumJacEvals };
            counts = Counts::read(
                mem,
                [
                    sun::IDAGetNumSteps,
                    sun::IDAGetNumResEvals,
                    sun::IDAGetNumErrTestFails,
                    jacobian_count,
                ],
            );
        }
        let out = values(y, n).to_vec();
        sun::IDAFree(&mut mem);
        ok.then_some((out, counts))
    }
}
