//! SUNDIALS' CVODE and IDA as peers, through the `sundials-sys` bindings
//! to the system's SUNDIALS 6 (`peers/install-sundials.sh`), with Rust
//! right-hand sides, residuals and Jacobians as their callbacks (Hindmarsh
//! et al., "SUNDIALS: Suite of nonlinear and differential/algebraic
//! equation solvers", ACM TOMS 31, 2005).

pub mod block_jacobi;
pub mod cvode;
pub mod ida;
pub mod ida_structured;
pub mod peer;
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

/// The SUNDIALS objects of one solve, freed together when it ends (the
/// integrator's memory is freed by its own module first).
struct Objects {
    ctx: sun::SUNContext,
    vectors: Vec<sun::N_Vector>,
    matrix: sun::SUNMatrix,
    solver: sun::SUNLinearSolver,
}

impl Objects {
    /// A context, or `None`.
    fn new() -> Option<Objects> {
        let mut ctx: sun::SUNContext = std::ptr::null_mut();
        // SAFETY: a null communicator is SUNDIALS' serial default.
        let created = unsafe { sun::SUNContext_Create(std::ptr::null_mut(), &mut ctx) };
        (created == 0).then_some(Objects {
            ctx,
            vectors: Vec::new(),
            matrix: std::ptr::null_mut(),
            solver: std::ptr::null_mut(),
        })
    }

    /// A new serial vector holding `init`.
    fn vector(&mut self, init: &[f64]) -> sun::N_Vector {
        // SAFETY: the vector has `init.len()` values and lives until drop.
        unsafe {
            let v = sun::N_VNew_Serial(init.len() as sun::sunindextype, self.ctx);
            values(v, init.len()).copy_from_slice(init);
            self.vectors.push(v);
            v
        }
    }
}

impl Drop for Objects {
    fn drop(&mut self) {
        // SAFETY: each object was created by this context and is freed once.
        unsafe {
            if !self.solver.is_null() {
                sun::SUNLinSolFree(self.solver);
            }
            if !self.matrix.is_null() {
                sun::SUNMatDestroy(self.matrix);
            }
            for &v in &self.vectors {
                sun::N_VDestroy(v);
            }
            sun::SUNContext_Free(&mut self.ctx);
        }
    }
}
