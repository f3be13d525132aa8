//! SUNDIALS' CVODE and IDA as peers, through the `sundials-sys` bindings
//! to the system's SUNDIALS 6 (`peers/install-sundials.sh`), with Rust
//! right-hand sides, residuals and Jacobians as their callbacks (Hindmarsh
//! et al., "SUNDIALS: Suite of nonlinear and differential/algebraic
//! equation solvers", ACM TOMS 31, 2005).

pub mod cvode;
pub mod ida;
pub mod structured;

use std::os::raw::{c_char, c_int, c_void};
use sundials_sys as sun;

/// The `n` values of a serial vector.
///
/// # Safety
/// `v` is a serial `N_Vector` of length `n`.
unsafe fn values<'v>(v: sun::N_Vector, n: usize) -> &'v mut [f64] {
    std::slice::from_raw_parts_mut(sun::N_VGetArrayPointer(v), n)
}

/// Silences SUNDIALS' messages: a failed run is a record with an infinite
/// error, not a line on the terminal.
unsafe extern "C" fn quiet(
    _code: c_int,
    _module: *const c_char,
    _function: *const c_char,
    _message: *mut c_char,
    _data: *mut c_void,
) {
}
