//! CVODES (BDF with forward sensitivities, the staggered corrector) on
//! Robertson's kinetics with the sensitivities to its three rate constants,
//! as CVODES's own example `cvsRoberts_FSA_dns` sets it up: a dense direct
//! solver with the analytic Jacobian, the analytic sensitivity right-hand
//! sides ∂f/∂y·s_i + ∂f/∂p_i, tolerances estimated from the parameters
//! (`CVodeSensEEtolerances`, p̄ = p), sensitivities in the error test
//! (Serban & Hindmarsh, "CVODES: the sensitivity-enabled ODE solver in
//! SUNDIALS", 2005).
//!
//! `daegen-cvodes-peer T1 RTOL ATOL_FACTOR...` prints one JSON object per
//! tolerance and per run (with and without sensitivities): the median wall
//! time of repeated solves, the steps, the final state and the
//! sensitivities ∂y/∂k_j (column by column). It is its own program because
//! CVODE and CVODES export the same symbols.

use std::os::raw::{c_char, c_int, c_void};
use std::time::Instant;
use sundials_sys as sun;

/// The rate constants k1, k2, k3 of Robertson's kinetics.
const RATES: [f64; 3] = [0.04, 3.0e7, 1.0e4];
/// The initial state.
const Y0: [f64; 3] = [1.0, 0.0, 0.0];

/// f(y): y1′ = −k1·y1 + k3·y2·y3, y2′ = k1·y1 − k3·y2·y3 − k2·y2²,
/// y3′ = k2·y2² (the benchmark's `RobertsonRates`).
fn rhs(y: &[f64], dy: &mut [f64]) {
    let [k1, k2, k3] = RATES;
    dy[0] = -k1 * y[0] + k3 * y[1] * y[2];
    dy[1] = k1 * y[0] - k3 * y[1] * y[2] - k2 * y[1] * y[1];
    dy[2] = k2 * y[1] * y[1];
}

/// ∂f/∂y, row-major.
fn jacobian(y: &[f64]) -> [[f64; 3]; 3] {
    let [k1, k2, k3] = RATES;
    [
        [-k1, k3 * y[2], k3 * y[1]],
        [k1, -k3 * y[2] - 2.0 * k2 * y[1], -k3 * y[1]],
        [0.0, 2.0 * k2 * y[1], 0.0],
    ]
}

/// ∂f/∂k_i.
fn rate_derivative(y: &[f64], i: usize) -> [f64; 3] {
    match i {
        0 => [-y[0], y[0], 0.0],
        1 => [0.0, -y[1] * y[1], y[1] * y[1]],
        _ => [y[1] * y[2], -y[1] * y[2], 0.0],
    }
}

/// The `n` values of a serial vector.
///
/// # Safety
/// `v` is a serial vector of `n` values.
unsafe fn values<'v>(v: sun::N_Vector, n: usize) -> &'v mut [f64] {
    std::slice::from_raw_parts_mut(sun::N_VGetArrayPointer(v), n)
}

unsafe extern "C" fn f(t: f64, y: sun::N_Vector, dy: sun::N_Vector, _: *mut c_void) -> c_int {
    let _ = t;
    rhs(values(y, 3), values(dy, 3));
    0
}

#[allow(clippy::too_many_arguments)]
unsafe extern "C" fn jac(
    _t: f64,
    y: sun::N_Vector,
    _fy: sun::N_Vector,
    a: sun::SUNMatrix,
    _: *mut c_void,
    _t1: sun::N_Vector,
    _t2: sun::N_Vector,
    _t3: sun::N_Vector,
) -> c_int {
    let j = jacobian(values(y, 3));
    for c in 0..3 {
        let column = sun::SUNDenseMatrix_Column(a, c as sun::sunindextype);
        for (r, row) in j.iter().enumerate() {
            *column.add(r) = row[c];
        }
    }
    0
}

#[allow(clippy::too_many_arguments)]
unsafe extern "C" fn sensitivity_rhs(
    _ns: c_int,
    _t: f64,
    y: sun::N_Vector,
    _ydot: sun::N_Vector,
    i: c_int,
    ys: sun::N_Vector,
    ysdot: sun::N_Vector,
    _: *mut c_void,
    _t1: sun::N_Vector,
    _t2: sun::N_Vector,
) -> c_int {
    let y = values(y, 3);
    let (s, out) = (values(ys, 3), values(ysdot, 3));
    let (j, dp) = (jacobian(y), rate_derivative(y, i as usize));
    for r in 0..3 {
        out[r] = j[r][0] * s[0] + j[r][1] * s[1] + j[r][2] * s[2] + dp[r];
    }
    0
}

unsafe extern "C" fn quiet(
    _code: c_int,
    _module: *const c_char,
    _function: *const c_char,
    _message: *mut c_char,
    _data: *mut c_void,
) {
}

/// One solve to `t1`: steps, y(t1) and, with `sensitivities`, ∂y/∂k_j at
/// `t1` (three values per rate); `None` where CVODES stopped short.
fn solve(t1: f64, rtol: f64, atol: f64, sensitivities: bool) -> Option<(usize, Vec<f64>)> {
    // SAFETY: every object is created from `ctx`, used while it lives, and
    // freed once below; the callbacks only read the vectors CVODES passes.
    unsafe {
        let mut ctx: sun::SUNContext = std::ptr::null_mut();
        if sun::SUNContext_Create(std::ptr::null_mut(), &mut ctx) != 0 {
            return None;
        }
        let y = sun::N_VNew_Serial(3, ctx);
        values(y, 3).copy_from_slice(&Y0);
        let a = sun::SUNDenseMatrix(3, 3, ctx);
        let ls = sun::SUNLinSol_Dense(y, a, ctx);
        let ys = sun::N_VCloneVectorArray(3, y);
        for j in 0..3 {
            values(*ys.add(j), 3).fill(0.0);
        }
        let mut mem = sun::CVodeCreate(sun::CV_BDF as c_int, ctx);
        let mut rates = RATES;
        let mut ok = !mem.is_null()
            && sun::CVodeInit(mem, Some(f), 0.0, y) == 0
            && sun::CVodeSStolerances(mem, rtol, atol) == 0
            && sun::CVodeSetErrHandlerFn(mem, Some(quiet), std::ptr::null_mut()) == 0
            && sun::CVodeSetLinearSolver(mem, ls, a) == 0
            && sun::CVodeSetJacFn(mem, Some(jac)) == 0
            && sun::CVodeSetMaxNumSteps(mem, 1_000_000) == 0
            && sun::CVodeSetStopTime(mem, t1) == 0;
        if ok && sensitivities {
            ok = sun::CVodeSensInit1(mem, 3, sun::CV_STAGGERED as c_int, Some(sensitivity_rhs), ys)
                == 0
                && sun::CVodeSetSensParams(
                    mem,
                    rates.as_mut_ptr(),
                    rates.as_mut_ptr(),
                    std::ptr::null_mut(),
                ) == 0
                && sun::CVodeSensEEtolerances(mem) == 0
                && sun::CVodeSetSensErrCon(mem, 1) == 0;
        }
        let mut t = 0.0;
        if ok {
            ok = sun::CVode(mem, t1, y, &mut t, sun::CV_NORMAL as c_int) >= 0
                && (t - t1).abs() <= 1e-12 * t1;
        }
        let mut out = values(y, 3).to_vec();
        if ok && sensitivities {
            ok = sun::CVodeGetSens(mem, &mut t, ys) == 0;
            for j in 0..3 {
                out.extend_from_slice(values(*ys.add(j), 3));
            }
        }
        let mut steps: std::os::raw::c_long = 0;
        sun::CVodeGetNumSteps(mem, &mut steps);
        sun::CVodeFree(&mut mem);
        sun::N_VDestroyVectorArray(ys, 3);
        sun::SUNLinSolFree(ls);
        sun::SUNMatDestroy(a);
        sun::N_VDestroy(y);
        sun::SUNContext_Free(&mut ctx);
        ok.then_some((steps as usize, out))
    }
}

/// The median wall time of repeated solves (at least five, more while
/// under half a second in all) and the last solve's result.
fn timed(run: &dyn Fn() -> Option<(usize, Vec<f64>)>) -> (f64, Option<(usize, Vec<f64>)>) {
    let mut times = Vec::new();
    let started = Instant::now();
    let mut last = None;
    while times.len() < 5 || (times.len() < 201 && started.elapsed().as_secs_f64() < 0.5) {
        let start = Instant::now();
        last = run();
        times.push(start.elapsed().as_secs_f64());
    }
    times.sort_by(f64::total_cmp);
    (times[times.len() / 2], last)
}

fn main() {
    let args: Vec<f64> = std::env::args().skip(1).filter_map(|a| a.parse().ok()).collect();
    let [t1, atol_factor, rtols @ ..] = args.as_slice() else {
        eprintln!("usage: daegen-cvodes-peer T1 ATOL_FACTOR RTOL...");
        std::process::exit(2);
    };
    for &rtol in rtols {
        for sensitivities in [false, true] {
            let (seconds, result) = timed(&|| solve(*t1, rtol, rtol * atol_factor, sensitivities));
            let (steps, values) = result.unwrap_or((0, Vec::new()));
            let list: Vec<String> = values.iter().map(|v| format!("{v:e}")).collect();
            println!(
                "{{\"rtol\": {rtol:e}, \"sensitivities\": {sensitivities}, \"seconds\": {seconds:e}, \"steps\": {steps}, \"values\": [{}]}}",
                list.join(", ")
            );
        }
    }
}
