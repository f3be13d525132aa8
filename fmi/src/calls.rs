//! The C functions FMI 2.0 and 3.0 share, written once over the
//! standard's row of [`crate::standard`]: each checks its arguments and
//! the phase it is called in, then has the instance do the work.
//! `export_fmu!` makes each an exported symbol of both standards (with a
//! count of values equal to the references' where FMI 2.0 has none).

use crate::boundary::{self, guarded, slice, slice_mut, target, text, Entry};
use crate::fmu_state;
use crate::instance::{refuse, Interface, Outcome, Status};
use crate::standard::{Call, Standard};
use daegen_runtime::Model;
use std::ffi::{c_char, c_int, c_void, CString};

/// A model type an FMU exports.
pub trait Exported: Model + Clone + Default + Send + Sync + 'static {}

impl<M: Model + Clone + Default + Send + Sync + 'static> Exported for M {}

/// An instance handle, `fmi2Component` or `fmi3Instance`.
pub type Handle = *mut c_void;

/// A status's C code, the same in both standards.
pub fn code(status: Status) -> c_int {
    match status {
        Status::Ok => 0,
        Status::Warning => 1,
        Status::Discard => 2,
        Status::Error => 3,
        Status::Fatal => 4,
    }
}

/// `body` on the instance behind `c`, as the call named `call`.
pub fn run<M: Exported>(
    c: Handle,
    call: &str,
    body: impl FnOnce(&mut Entry<M>) -> Outcome,
) -> c_int {
    code(boundary::with::<M, _>(c, call, body))
}

/// `body` as `S`'s `call`, after checking the phase it is made in (and,
/// for Model Exchange's calls, the interface).
fn checked<S: Standard, M: Exported>(
    c: Handle,
    call: Call,
    interface: Option<Interface>,
    body: impl FnOnce(&mut Entry<M>) -> Outcome,
) -> c_int {
    run::<M>(c, S::name(call), |e| {
        if let Some(interface) = interface {
            e.instance.require_interface(interface)?;
        }
        if let Some(phases) = S::phases(call) {
            e.instance.allow_in(phases)?;
        }
        body(e)
    })
}

/// `…FreeInstance`.
pub fn free_instance(c: Handle) {
    let _ = guarded(|| Some(boundary::release(c)));
}

/// `…SetDebugLogging`.
///
/// # Safety
/// `categories` must be null or point to `n` C strings.
pub unsafe fn set_debug_logging<S: Standard, M: Exported>(
    c: Handle,
    logging_on: bool,
    n: usize,
    categories: *const *const c_char,
) -> c_int {
    checked::<S, M>(c, Call::SetDebugLogging, None, |e| {
        // SAFETY: n category pointers, as FMI requires.
        let _ = unsafe { slice(categories, n, "categories") }?;
        e.debug = logging_on;
        Ok(())
    })
}

/// `…ExitInitializationMode`.
pub fn exit_initialization_mode<S: Standard, M: Exported>(c: Handle) -> c_int {
    checked::<S, M>(c, Call::ExitInitializationMode, None, |e| e.instance.exit_initialization())
}

/// `…Terminate`.
pub fn terminate<S: Standard, M: Exported>(c: Handle) -> c_int {
    checked::<S, M>(c, Call::Terminate, None, |e| {
        e.instance.phase = crate::instance::Phase::Terminated;
        Ok(())
    })
}

/// `…Reset`.
pub fn reset<S: Standard, M: Exported>(c: Handle) -> c_int {
    checked::<S, M>(c, Call::Reset, None, |e| {
        e.instance.reset();
        Ok(())
    })
}

/// Every variable is a scalar: as many values as references.
fn scalars(nvr: usize, n_values: usize) -> Outcome {
    if nvr == n_values {
        return Ok(());
    }
    Err(refuse(format!(
        "{nvr} value references but {n_values} values: every variable of this FMU is a scalar"
    )))
}

/// `fmi2GetReal`, `fmi3GetFloat64`.
///
/// # Safety
/// The arrays must be null or hold the counts given.
pub unsafe fn get_real<S: Standard, M: Exported>(
    c: Handle,
    vr: *const u32,
    nvr: usize,
    values: *mut f64,
    n_values: usize,
) -> c_int {
    checked::<S, M>(c, Call::GetReal, None, |e| {
        scalars(nvr, n_values)?;
        let [vr_name, values_name] = S::VALUE_ARGUMENTS;
        // SAFETY: the counts given, as FMI requires.
        let (vr, values) =
            unsafe { (slice(vr, nvr, vr_name)?, slice_mut(values, n_values, values_name)?) };
        for (k, &r) in vr.iter().enumerate() {
            values[k] = e.instance.get_real(r)?;
        }
        Ok(())
    })
}

/// `fmi2SetReal`, `fmi3SetFloat64`.
///
/// # Safety
/// The arrays must be null or hold the counts given.
pub unsafe fn set_real<S: Standard, M: Exported>(
    c: Handle,
    vr: *const u32,
    nvr: usize,
    values: *const f64,
    n_values: usize,
) -> c_int {
    checked::<S, M>(c, Call::SetReal, None, |e| {
        scalars(nvr, n_values)?;
        let [vr_name, values_name] = S::VALUE_ARGUMENTS;
        // SAFETY: the counts given, as FMI requires.
        let (vr, values) =
            unsafe { (slice(vr, nvr, vr_name)?, slice(values, n_values, values_name)?) };
        for (k, &r) in vr.iter().enumerate() {
            e.instance.set_real(r, values[k])?;
        }
        Ok(())
    })
}

/// `…GetString`: `solver.method`. The strings stay valid until the next
/// call on the instance.
///
/// # Safety
/// The arrays must be null or hold the counts given.
pub unsafe fn get_string<S: Standard, M: Exported>(
    c: Handle,
    vr: *const u32,
    nvr: usize,
    values: *mut *const c_char,
    n_values: usize,
) -> c_int {
    checked::<S, M>(c, Call::GetString, None, |e| {
        scalars(nvr, n_values)?;
        let [vr_name, values_name] = S::VALUE_ARGUMENTS;
        // SAFETY: the counts given, as FMI requires.
        let (vr, values) =
            unsafe { (slice(vr, nvr, vr_name)?, slice_mut(values, n_values, values_name)?) };
        e.strings.clear();
        for (k, &r) in vr.iter().enumerate() {
            let s = CString::new(e.instance.get_string(r)?).unwrap_or_default();
            values[k] = s.as_ptr();
            e.strings.push(s);
        }
        Ok(())
    })
}

/// `…SetString`: `solver.method`.
///
/// # Safety
/// The arrays must be null or hold the counts given.
pub unsafe fn set_string<S: Standard, M: Exported>(
    c: Handle,
    vr: *const u32,
    nvr: usize,
    values: *const *const c_char,
    n_values: usize,
) -> c_int {
    checked::<S, M>(c, Call::SetString, None, |e| {
        scalars(nvr, n_values)?;
        let [vr_name, values_name] = S::VALUE_ARGUMENTS;
        // SAFETY: the counts given, as FMI requires.
        let (vr, values) =
            unsafe { (slice(vr, nvr, vr_name)?, slice(values, n_values, values_name)?) };
        for (k, &r) in vr.iter().enumerate() {
            // SAFETY: a C string, as FMI requires.
            let v = unsafe { text(values[k], values_name) }?;
            e.instance.set_string(r, v)?;
        }
        Ok(())
    })
}

/// The getters and setters of the types this FMU has no variables of
/// (`fmi2GetInteger`, `fmi3SetBoolean`, …; a discrete value is a real):
/// any value reference is refused.
///
/// # Safety
/// `vr` must be null or hold `nvr` references.
pub unsafe fn no_such_values<S: Standard, M: Exported>(
    c: Handle,
    call: &str,
    kind: &str,
    vr: *const u32,
    nvr: usize,
) -> c_int {
    run::<M>(c, call, |e| {
        if nvr == 0 {
            return Ok(());
        }
        // SAFETY: nvr references, as FMI requires.
        let vr = unsafe { slice(vr, nvr, S::VALUE_ARGUMENTS[0]) }?;
        let name = e.instance.variable(vr[0])?.name.clone();
        let real = S::REAL;
        Err(refuse(format!("`{name}` is not {kind}: every variable of this FMU is a {real} (a discrete value too) but `solver.method`, a String")))
    })
}

// ----- Model Exchange -----

/// `…EnterEventMode`.
pub fn enter_event_mode<S: Standard, M: Exported>(c: Handle) -> c_int {
    checked::<S, M>(c, Call::EnterEventMode, Some(Interface::ModelExchange), |e| {
        e.instance.phase = crate::instance::Phase::Event;
        Ok(())
    })
}

/// `…EnterContinuousTimeMode`.
pub fn enter_continuous_time_mode<S: Standard, M: Exported>(c: Handle) -> c_int {
    checked::<S, M>(c, Call::EnterContinuousTimeMode, Some(Interface::ModelExchange), |e| {
        e.instance.phase = crate::instance::Phase::Continuous;
        Ok(())
    })
}

/// `…CompletedIntegratorStep`.
///
/// # Safety
/// The flags must be null or point to a boolean each.
pub unsafe fn completed_integrator_step<S: Standard, M: Exported>(
    c: Handle,
    enter_event_mode: *mut S::Boolean,
    terminate_simulation: *mut S::Boolean,
) -> c_int {
    checked::<S, M>(c, Call::CompletedIntegratorStep, Some(Interface::ModelExchange), |e| {
        // SAFETY: the importer's flags, checked for null.
        let (event, stop) = unsafe {
            (
                target(enter_event_mode, "enterEventMode")?,
                target(terminate_simulation, "terminateSimulation")?,
            )
        };
        let (enter, terminate) = e.instance.completed_integrator_step();
        (*event, *stop) = (S::boolean(enter), S::boolean(terminate));
        Ok(())
    })
}

/// `…SetTime`.
pub fn set_time<S: Standard, M: Exported>(c: Handle, time: f64) -> c_int {
    checked::<S, M>(c, Call::SetTime, Some(Interface::ModelExchange), |e| e.instance.set_time(time))
}

/// `…SetContinuousStates`.
///
/// # Safety
/// `x` must be null or point to `nx` values.
pub unsafe fn set_continuous_states<S: Standard, M: Exported>(
    c: Handle,
    x: *const f64,
    nx: usize,
) -> c_int {
    checked::<S, M>(c, Call::SetContinuousStates, Some(Interface::ModelExchange), |e| {
        // SAFETY: nx values, as FMI requires.
        let x = unsafe { slice(x, nx, S::STATE_ARGUMENTS[0]) }?;
        e.instance.set_continuous_states(x)
    })
}

/// `fmi2GetDerivatives`, `fmi3GetContinuousStateDerivatives`.
///
/// # Safety
/// `dx` must be null or point to `nx` values.
pub unsafe fn get_derivatives<S: Standard, M: Exported>(
    c: Handle,
    dx: *mut f64,
    nx: usize,
) -> c_int {
    checked::<S, M>(c, Call::GetDerivatives, Some(Interface::ModelExchange), |e| {
        // SAFETY: nx values, as FMI requires.
        let dx = unsafe { slice_mut(dx, nx, "derivatives") }?;
        e.instance.derivatives(dx)
    })
}

/// `…GetEventIndicators`.
///
/// # Safety
/// `g` must be null or point to `ni` values.
pub unsafe fn get_event_indicators<S: Standard, M: Exported>(
    c: Handle,
    g: *mut f64,
    ni: usize,
) -> c_int {
    checked::<S, M>(c, Call::GetEventIndicators, Some(Interface::ModelExchange), |e| {
        // SAFETY: ni values, as FMI requires.
        let g = unsafe { slice_mut(g, ni, "eventIndicators") }?;
        e.instance.indicators(g)
    })
}

/// `…GetContinuousStates`.
///
/// # Safety
/// `x` must be null or point to `nx` values.
pub unsafe fn get_continuous_states<S: Standard, M: Exported>(
    c: Handle,
    x: *mut f64,
    nx: usize,
) -> c_int {
    checked::<S, M>(c, Call::GetContinuousStates, Some(Interface::ModelExchange), |e| {
        // SAFETY: nx values, as FMI requires.
        let x = unsafe { slice_mut(x, nx, S::STATE_ARGUMENTS[0]) }?;
        e.instance.get_continuous_states(x)
    })
}

/// `…GetNominalsOfContinuousStates`.
///
/// # Safety
/// `x` must be null or point to `nx` values.
pub unsafe fn get_nominals<S: Standard, M: Exported>(c: Handle, x: *mut f64, nx: usize) -> c_int {
    checked::<S, M>(c, Call::GetNominals, Some(Interface::ModelExchange), |e| {
        // SAFETY: nx values, as FMI requires.
        let x = unsafe { slice_mut(x, nx, S::STATE_ARGUMENTS[1]) }?;
        e.instance.nominals(x)
    })
}

// ----- FMU state -----

/// `…GetFMUState`: a new state, or the one `*state` names replaced.
///
/// # Safety
/// `state` must be null or point to an FMU state.
pub unsafe fn get_fmu_state<S: Standard, M: Exported>(c: Handle, state: *mut *mut c_void) -> c_int {
    // SAFETY: as this function's contract.
    checked::<S, M>(c, Call::GetFmuState, None, |e| unsafe { fmu_state::get(e, state) })
}

/// `…SetFMUState`.
pub fn set_fmu_state<S: Standard, M: Exported>(c: Handle, state: *mut c_void) -> c_int {
    checked::<S, M>(c, Call::SetFmuState, None, |e| fmu_state::set(e, state))
}

/// `…FreeFMUState`.
///
/// # Safety
/// `state` must be null or point to an FMU state.
pub unsafe fn free_fmu_state<S: Standard, M: Exported>(
    c: Handle,
    state: *mut *mut c_void,
) -> c_int {
    // SAFETY: as this function's contract.
    checked::<S, M>(c, Call::FreeFmuState, None, |_| unsafe { fmu_state::free(state) })
}

/// `…SerializedFMUStateSize`.
///
/// # Safety
/// `size` must be null or point to a `size_t`.
pub unsafe fn serialized_size<S: Standard, M: Exported>(
    c: Handle,
    state: *mut c_void,
    size: *mut usize,
) -> c_int {
    // SAFETY: as this function's contract.
    checked::<S, M>(c, Call::SerializedSize, None, |_| unsafe { fmu_state::size(state, size) })
}

/// `…SerializeFMUState`: the state's numbers, little-endian.
///
/// # Safety
/// `bytes` must be null or point to `size` bytes.
pub unsafe fn serialize<S: Standard, M: Exported>(
    c: Handle,
    state: *mut c_void,
    bytes: *mut u8,
    size: usize,
) -> c_int {
    // SAFETY: as this function's contract.
    checked::<S, M>(c, Call::Serialize, None, |_| unsafe {
        fmu_state::serialize(state, bytes, size)
    })
}

/// `…DeserializeFMUState`.
///
/// # Safety
/// `bytes` must be null or point to `size` bytes; `state` null or to an
/// FMU state.
pub unsafe fn deserialize<S: Standard, M: Exported>(
    c: Handle,
    bytes: *const u8,
    size: usize,
    state: *mut *mut c_void,
) -> c_int {
    // SAFETY: as this function's contract.
    checked::<S, M>(c, Call::Deserialize, None, |e| unsafe {
        fmu_state::deserialize(e, bytes, size, state)
    })
}

/// `…GetDirectionalDerivative`.
///
/// # Safety
/// The arrays must be null or hold the counts given.
#[allow(clippy::too_many_arguments)] // fmi3GetDirectionalDerivative's own
pub unsafe fn get_directional_derivative<S: Standard, M: Exported>(
    c: Handle,
    unknowns: *const u32,
    n_unknowns: usize,
    knowns: *const u32,
    n_knowns: usize,
    seed: *const f64,
    n_seed: usize,
    sensitivity: *mut f64,
    n_sensitivity: usize,
) -> c_int {
    checked::<S, M>(c, Call::GetDirectionalDerivative, None, |e| {
        let [u_name, k_name, seed_name, out_name] = S::DIRECTIONAL_ARGUMENTS;
        // SAFETY: the counts given, as FMI requires.
        let (u, k, s, out) = unsafe {
            (
                slice(unknowns, n_unknowns, u_name)?,
                slice(knowns, n_knowns, k_name)?,
                slice(seed, n_seed, seed_name)?,
                slice_mut(sensitivity, n_sensitivity, out_name)?,
            )
        };
        e.instance.directional_derivative(u, k, s, out)
    })
}
