//! FMI 2.0's C functions for a model `M`: the types and call order of
//! `fmi2Functions.h`, each function checking its arguments and the state
//! it is called in before the instance does the work. `export_fmu!` makes
//! each of them an exported `fmi2…` symbol of the user's library.

use crate::boundary::{self, guarded, slice, slice_mut, target, text, Entry, Logger};
use crate::description::{instantiation_token, FmiVersion};
use crate::fmu_state;
use crate::instance::{refuse, Interface, Outcome, Phase, Status};
use daegen_runtime::Model;
use std::ffi::{c_char, c_int, c_uint, c_void, CString};

/// `fmi2Status`.
pub type Fmi2Status = c_int;
/// `fmi2Boolean` (an `int`).
pub type Fmi2Boolean = c_int;
/// `fmi2Component`.
pub type Fmi2Component = *mut c_void;
/// `fmi2ValueReference`.
pub type Fmi2ValueReference = c_uint;

/// `fmi2CallbackLogger`: printf-like, so the FMU passes `"%s"` and its
/// message.
pub type Fmi2Logger = unsafe extern "C" fn(
    env: *mut c_void,
    instance_name: *const c_char,
    status: Fmi2Status,
    category: *const c_char,
    message: *const c_char,
    ...
);

/// `fmi2CallbackFunctions`.
#[repr(C)]
pub struct Fmi2CallbackFunctions {
    /// The logger.
    pub logger: Option<Fmi2Logger>,
    /// Unused: the FMU allocates with Rust's allocator
    /// (`canNotUseMemoryManagementFunctions`).
    pub allocate_memory: Option<unsafe extern "C" fn(usize, usize) -> *mut c_void>,
    /// Unused, as `allocate_memory`.
    pub free_memory: Option<unsafe extern "C" fn(*mut c_void)>,
    /// Unused: steps are synchronous.
    pub step_finished: Option<unsafe extern "C" fn(*mut c_void, Fmi2Status)>,
    /// The importer's pointer passed back to the logger.
    pub component_environment: *mut c_void,
}

/// `fmi2EventInfo`.
#[repr(C)]
pub struct Fmi2EventInfo {
    /// Another event update is needed at this instant.
    pub new_discrete_states_needed: Fmi2Boolean,
    /// A terminal event acted.
    pub terminate_simulation: Fmi2Boolean,
    /// The nominals changed (never).
    pub nominals_of_continuous_states_changed: Fmi2Boolean,
    /// The continuous states changed.
    pub values_of_continuous_states_changed: Fmi2Boolean,
    /// `next_event_time` holds the next time event.
    pub next_event_time_defined: Fmi2Boolean,
    /// The next time event.
    pub next_event_time: f64,
}

fn code(status: Status) -> Fmi2Status {
    match status {
        Status::Ok => 0,
        Status::Warning => 1,
        Status::Discard => 2,
        Status::Error => 3,
        Status::Fatal => 4,
    }
}

fn flag(b: bool) -> Fmi2Boolean {
    Fmi2Boolean::from(b)
}

use Phase::{Continuous, Event, Initialization, Instantiated, Step, StepFailed, Terminated};

fn run<M, F>(c: Fmi2Component, call: &str, body: F) -> Fmi2Status
where
    M: Model + Clone + Default + Send + Sync + 'static,
    F: FnOnce(&mut Entry<M>) -> Outcome,
{
    code(boundary::with::<M, _>(c, call, body))
}

/// `fmi2GetTypesPlatform`.
pub fn get_types_platform() -> *const c_char {
    c"default".as_ptr()
}

/// `fmi2GetVersion`.
pub fn get_version() -> *const c_char {
    c"2.0".as_ptr()
}

/// `fmi2Instantiate`: a new instance, or null (with a log message) for a
/// wrong GUID or interface type.
///
/// # Safety
/// Pointer arguments must be null or valid, as FMI requires.
#[allow(clippy::too_many_arguments)] // fmi2Instantiate's own
pub unsafe fn instantiate<M: Model + Clone + Default + Send + Sync + 'static>(
    identifier: &str,
    instance_name: *const c_char,
    fmu_type: c_int,
    guid: *const c_char,
    _resource_location: *const c_char,
    functions: *const Fmi2CallbackFunctions,
    _visible: Fmi2Boolean,
    logging_on: Fmi2Boolean,
) -> Fmi2Component {
    guarded(|| {
        // SAFETY: the importer's pointer, checked for null.
        let callbacks = unsafe { functions.as_ref() };
        let logger = callbacks.and_then(|f| f.logger);
        let env = callbacks.map_or(0, |f| f.component_environment as usize);
        // SAFETY: as FMI requires, a NUL-terminated string or null.
        let name = unsafe { text(instance_name, "instanceName") }.unwrap_or("").to_string();
        let c_name = CString::new(name.clone()).unwrap_or_default();
        let log: Logger = Box::new(move |status, category, message| {
            let (Some(logger), Ok(category), Ok(message)) =
                (logger, CString::new(category), CString::new(message.replace('\0', " ")))
            else {
                return;
            };
            // SAFETY: the importer's logger with its own environment, a
            // "%s" format and one C string argument.
            unsafe {
                logger(
                    env as *mut c_void,
                    c_name.as_ptr(),
                    code(status),
                    category.as_ptr(),
                    c"%s".as_ptr(),
                    message.as_ptr(),
                )
            }
        });
        let interface = match fmu_type {
            0 => Interface::ModelExchange,
            1 => Interface::CoSimulation,
            other => {
                log(Status::Error, "logStatusError", &format!("fmi2Instantiate: fmuType {other} is neither fmi2ModelExchange (0) nor fmi2CoSimulation (1)"));
                return Some(std::ptr::null_mut());
            }
        };
        let expected = instantiation_token(&M::default(), FmiVersion::V2, identifier);
        // SAFETY: as FMI requires, a NUL-terminated string or null.
        match unsafe { text(guid, "fmuGUID") } {
            Ok(g) if g == expected => {}
            Ok(g) => {
                log(Status::Error, "logStatusError", &format!("fmi2Instantiate: the GUID \"{g}\" is not this FMU's ({expected}): the modelDescription.xml belongs to another build of the model"));
                return Some(std::ptr::null_mut());
            }
            Err(r) => {
                log(Status::Error, "logStatusError", &format!("fmi2Instantiate: {}", r.message));
                return Some(std::ptr::null_mut());
            }
        }
        Some(boundary::instantiate::<M>(&name, interface, logging_on != 0, log))
    })
    .unwrap_or(std::ptr::null_mut())
}

/// `fmi2FreeInstance`.
pub fn free_instance(c: Fmi2Component) {
    let _ = guarded(|| Some(boundary::release(c)));
}

/// `fmi2SetDebugLogging`.
///
/// # Safety
/// `categories` must be null or point to `n` C strings.
pub unsafe fn set_debug_logging<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi2Component,
    logging_on: Fmi2Boolean,
    n: usize,
    categories: *const *const c_char,
) -> Fmi2Status {
    run::<M, _>(c, "fmi2SetDebugLogging", |e| {
        // SAFETY: n category pointers, as FMI requires.
        let _ = unsafe { slice(categories, n, "categories") }?;
        e.debug = logging_on != 0;
        Ok(())
    })
}

/// `fmi2SetupExperiment`.
pub fn setup_experiment<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi2Component,
    tolerance_defined: Fmi2Boolean,
    tolerance: f64,
    start: f64,
    stop_defined: Fmi2Boolean,
    stop: f64,
) -> Fmi2Status {
    run::<M, _>(c, "fmi2SetupExperiment", |e| {
        e.instance.allow_in(&[Instantiated])?;
        let tolerance = Some(tolerance).filter(|_| tolerance_defined != 0);
        let stop = Some(stop).filter(|_| stop_defined != 0);
        if !start.is_finite() {
            return Err(refuse(format!("the start time {start} is not finite")));
        }
        if let Some(tol) = tolerance.filter(|&t| t <= 0.0 || !t.is_finite()) {
            return Err(refuse(format!("the tolerance {tol} is not positive and finite")));
        }
        if let Some(stop) = stop.filter(|&s| s < start || s.is_nan()) {
            return Err(refuse(format!("the stop time {stop} is before the start time {start}")));
        }
        e.instance.setup(tolerance, start, stop);
        Ok(())
    })
}

/// `fmi2EnterInitializationMode`.
pub fn enter_initialization_mode<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi2Component,
) -> Fmi2Status {
    run::<M, _>(c, "fmi2EnterInitializationMode", |e| {
        e.instance.allow_in(&[Instantiated])?;
        e.instance.phase = Initialization;
        Ok(())
    })
}

/// `fmi2ExitInitializationMode`.
pub fn exit_initialization_mode<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi2Component,
) -> Fmi2Status {
    run::<M, _>(c, "fmi2ExitInitializationMode", |e| {
        e.instance.allow_in(&[Initialization])?;
        e.instance.exit_initialization()
    })
}

/// `fmi2Terminate`.
pub fn terminate<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi2Component,
) -> Fmi2Status {
    run::<M, _>(c, "fmi2Terminate", |e| {
        e.instance.allow_in(&[Event, Continuous, Step, StepFailed])?;
        e.instance.phase = Terminated;
        Ok(())
    })
}

/// `fmi2Reset`.
pub fn reset<M: Model + Clone + Default + Send + Sync + 'static>(c: Fmi2Component) -> Fmi2Status {
    run::<M, _>(c, "fmi2Reset", |e| {
        e.instance.reset();
        Ok(())
    })
}

/// `fmi2GetReal`.
///
/// # Safety
/// `vr` and `value` must be null or point to `nvr` values.
pub unsafe fn get_real<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi2Component,
    vr: *const Fmi2ValueReference,
    nvr: usize,
    value: *mut f64,
) -> Fmi2Status {
    run::<M, _>(c, "fmi2GetReal", |e| {
        e.instance.allow_in(&[Initialization, Event, Continuous, Step, StepFailed, Terminated])?;
        // SAFETY: nvr values each, as FMI requires.
        let (vr, value) = unsafe { (slice(vr, nvr, "vr")?, slice_mut(value, nvr, "value")?) };
        for (k, &r) in vr.iter().enumerate() {
            value[k] = e.instance.get_real(r)?;
        }
        Ok(())
    })
}

/// `fmi2SetReal`.
///
/// # Safety
/// `vr` and `value` must be null or point to `nvr` values.
pub unsafe fn set_real<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi2Component,
    vr: *const Fmi2ValueReference,
    nvr: usize,
    value: *const f64,
) -> Fmi2Status {
    run::<M, _>(c, "fmi2SetReal", |e| {
        e.instance.allow_in(&[Instantiated, Initialization, Event, Continuous, Step])?;
        // SAFETY: nvr values each, as FMI requires.
        let (vr, value) = unsafe { (slice(vr, nvr, "vr")?, slice(value, nvr, "value")?) };
        for (k, &r) in vr.iter().enumerate() {
            e.instance.set_real(r, value[k])?;
        }
        Ok(())
    })
}

/// `fmi2GetString`: `solver.method`. The strings stay valid until the
/// next call on the instance.
///
/// # Safety
/// `vr` and `value` must be null or point to `nvr` values.
pub unsafe fn get_string<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi2Component,
    vr: *const Fmi2ValueReference,
    nvr: usize,
    value: *mut *const c_char,
) -> Fmi2Status {
    run::<M, _>(c, "fmi2GetString", |e| {
        e.instance.allow_in(&[
            Instantiated,
            Initialization,
            Event,
            Continuous,
            Step,
            StepFailed,
            Terminated,
        ])?;
        // SAFETY: nvr values each, as FMI requires.
        let (vr, value) = unsafe { (slice(vr, nvr, "vr")?, slice_mut(value, nvr, "value")?) };
        e.strings.clear();
        for (k, &r) in vr.iter().enumerate() {
            let s = CString::new(e.instance.get_string(r)?).unwrap_or_default();
            value[k] = s.as_ptr();
            e.strings.push(s);
        }
        Ok(())
    })
}

/// `fmi2SetString`: `solver.method`.
///
/// # Safety
/// `vr` and `value` must be null or point to `nvr` values.
pub unsafe fn set_string<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi2Component,
    vr: *const Fmi2ValueReference,
    nvr: usize,
    value: *const *const c_char,
) -> Fmi2Status {
    run::<M, _>(c, "fmi2SetString", |e| {
        e.instance.allow_in(&[Instantiated, Initialization, Event, Step])?;
        // SAFETY: nvr values each, as FMI requires.
        let (vr, value) = unsafe { (slice(vr, nvr, "vr")?, slice(value, nvr, "value")?) };
        for (k, &r) in vr.iter().enumerate() {
            // SAFETY: a C string, as FMI requires.
            let v = unsafe { text(value[k], "value") }?;
            e.instance.set_string(r, v)?;
        }
        Ok(())
    })
}

/// `fmi2GetInteger`, `fmi2GetBoolean`, `fmi2SetInteger`,
/// `fmi2SetBoolean`: a daegen model has no integer or boolean variables
/// (a discrete value is a real), so any value reference is refused.
///
/// # Safety
/// `vr` must be null or hold `nvr` references.
pub unsafe fn no_such_values<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi2Component,
    call: &str,
    kind: &str,
    vr: *const Fmi2ValueReference,
    nvr: usize,
) -> Fmi2Status {
    run::<M, _>(c, call, |e| {
        if nvr == 0 {
            return Ok(());
        }
        // SAFETY: nvr values, as FMI requires.
        let vr = unsafe { slice(vr, nvr, "vr") }?;
        let name = e.instance.variable(vr[0])?.name.clone();
        Err(refuse(format!("`{name}` is not {kind}: every variable of this FMU is a Real (a discrete value too) but `solver.method`, a String")))
    })
}

// ----- Model Exchange -----

/// `fmi2EnterEventMode`.
pub fn enter_event_mode<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi2Component,
) -> Fmi2Status {
    run::<M, _>(c, "fmi2EnterEventMode", |e| {
        e.instance.require_interface(Interface::ModelExchange)?;
        e.instance.allow_in(&[Event, Continuous])?;
        e.instance.phase = Event;
        Ok(())
    })
}

/// `fmi2NewDiscreteStates`.
///
/// # Safety
/// `info` must be null or point to an `fmi2EventInfo`.
pub unsafe fn new_discrete_states<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi2Component,
    info: *mut Fmi2EventInfo,
) -> Fmi2Status {
    run::<M, _>(c, "fmi2NewDiscreteStates", |e| {
        e.instance.require_interface(Interface::ModelExchange)?;
        e.instance.allow_in(&[Event])?;
        // SAFETY: the importer's struct, checked for null.
        let info = unsafe { target(info, "eventInfo") }?;
        let update = e.instance.update_discrete_states()?;
        info.new_discrete_states_needed = 0;
        info.terminate_simulation = flag(update.terminate);
        info.nominals_of_continuous_states_changed = 0;
        info.values_of_continuous_states_changed = flag(update.values_changed);
        info.next_event_time_defined = flag(update.next_event_time.is_some());
        info.next_event_time = update.next_event_time.unwrap_or(0.0);
        Ok(())
    })
}

/// `fmi2EnterContinuousTimeMode`.
pub fn enter_continuous_time_mode<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi2Component,
) -> Fmi2Status {
    run::<M, _>(c, "fmi2EnterContinuousTimeMode", |e| {
        e.instance.require_interface(Interface::ModelExchange)?;
        e.instance.allow_in(&[Event])?;
        e.instance.phase = Continuous;
        Ok(())
    })
}

/// `fmi2CompletedIntegratorStep`.
///
/// # Safety
/// The flags must be null or point to an `fmi2Boolean` each.
pub unsafe fn completed_integrator_step<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi2Component,
    _no_set_prior: Fmi2Boolean,
    enter_event_mode: *mut Fmi2Boolean,
    terminate_simulation: *mut Fmi2Boolean,
) -> Fmi2Status {
    run::<M, _>(c, "fmi2CompletedIntegratorStep", |e| {
        e.instance.require_interface(Interface::ModelExchange)?;
        e.instance.allow_in(&[Continuous])?;
        // SAFETY: the importer's flags, checked for null.
        let (event, stop) = unsafe {
            (
                target(enter_event_mode, "enterEventMode")?,
                target(terminate_simulation, "terminateSimulation")?,
            )
        };
        let (enter, terminate) = e.instance.completed_integrator_step();
        *event = flag(enter);
        *stop = flag(terminate);
        Ok(())
    })
}

/// `fmi2SetTime`.
pub fn set_time<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi2Component,
    time: f64,
) -> Fmi2Status {
    run::<M, _>(c, "fmi2SetTime", |e| {
        e.instance.require_interface(Interface::ModelExchange)?;
        e.instance.allow_in(&[Event, Continuous])?;
        e.instance.set_time(time)
    })
}

/// `fmi2SetContinuousStates`.
///
/// # Safety
/// `x` must be null or point to `nx` values.
pub unsafe fn set_continuous_states<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi2Component,
    x: *const f64,
    nx: usize,
) -> Fmi2Status {
    run::<M, _>(c, "fmi2SetContinuousStates", |e| {
        e.instance.require_interface(Interface::ModelExchange)?;
        e.instance.allow_in(&[Continuous])?;
        // SAFETY: nx values, as FMI requires.
        let x = unsafe { slice(x, nx, "x") }?;
        e.instance.set_continuous_states(x)
    })
}

/// `fmi2GetDerivatives`.
///
/// # Safety
/// `dx` must be null or point to `nx` values.
pub unsafe fn get_derivatives<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi2Component,
    dx: *mut f64,
    nx: usize,
) -> Fmi2Status {
    run::<M, _>(c, "fmi2GetDerivatives", |e| {
        e.instance.require_interface(Interface::ModelExchange)?;
        e.instance.allow_in(&[Event, Continuous, Terminated])?;
        // SAFETY: nx values, as FMI requires.
        let dx = unsafe { slice_mut(dx, nx, "derivatives") }?;
        e.instance.derivatives(dx)
    })
}

/// `fmi2GetEventIndicators`.
///
/// # Safety
/// `g` must be null or point to `ni` values.
pub unsafe fn get_event_indicators<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi2Component,
    g: *mut f64,
    ni: usize,
) -> Fmi2Status {
    run::<M, _>(c, "fmi2GetEventIndicators", |e| {
        e.instance.require_interface(Interface::ModelExchange)?;
        e.instance.allow_in(&[Initialization, Event, Continuous, Terminated])?;
        // SAFETY: ni values, as FMI requires.
        let g = unsafe { slice_mut(g, ni, "eventIndicators") }?;
        e.instance.indicators(g)
    })
}

/// `fmi2GetContinuousStates`.
///
/// # Safety
/// `x` must be null or point to `nx` values.
pub unsafe fn get_continuous_states<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi2Component,
    x: *mut f64,
    nx: usize,
) -> Fmi2Status {
    run::<M, _>(c, "fmi2GetContinuousStates", |e| {
        e.instance.require_interface(Interface::ModelExchange)?;
        e.instance.allow_in(&[Initialization, Event, Continuous, Terminated])?;
        // SAFETY: nx values, as FMI requires.
        let x = unsafe { slice_mut(x, nx, "x") }?;
        e.instance.get_continuous_states(x)
    })
}

/// `fmi2GetNominalsOfContinuousStates`.
///
/// # Safety
/// `x` must be null or point to `nx` values.
pub unsafe fn get_nominals<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi2Component,
    x: *mut f64,
    nx: usize,
) -> Fmi2Status {
    run::<M, _>(c, "fmi2GetNominalsOfContinuousStates", |e| {
        e.instance.require_interface(Interface::ModelExchange)?;
        e.instance.allow_in(&[Instantiated, Event, Continuous, Terminated])?;
        // SAFETY: nx values, as FMI requires.
        let x = unsafe { slice_mut(x, nx, "x_nominal") }?;
        e.instance.nominals(x)
    })
}

// ----- Co-Simulation -----

/// `fmi2DoStep`: a terminal event inside the step ends it early with
/// `fmi2Discard`; `fmi2GetBooleanStatus(fmi2Terminated)` then says so and
/// `fmi2GetRealStatus(fmi2LastSuccessfulTime)` gives the time reached.
pub fn do_step<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi2Component,
    t: f64,
    h: f64,
    _no_set_prior: Fmi2Boolean,
) -> Fmi2Status {
    run::<M, _>(c, "fmi2DoStep", |e| {
        e.instance.require_interface(Interface::CoSimulation)?;
        e.instance.allow_in(&[Step])?;
        let done = e.instance.do_step(t, h)?;
        if done.terminate {
            return Err(crate::instance::Refusal {
                status: Status::Discard,
                message: format!("a terminal event ended the simulation at t = {}", done.reached),
            });
        }
        Ok(())
    })
}

/// `fmi2CancelStep`: steps are synchronous, never pending.
pub fn cancel_step<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi2Component,
) -> Fmi2Status {
    run::<M, _>(c, "fmi2CancelStep", |_| {
        Err(refuse("no step is pending: fmi2DoStep returns when its step is done"))
    })
}

/// `fmi2SetRealInputDerivatives` and `fmi2GetRealOutputDerivatives`: the
/// FMU holds its inputs constant over a step and gives no output
/// derivatives (`canInterpolateInputs`, `maxOutputDerivativeOrder` unset).
pub fn no_derivatives<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi2Component,
    call: &str,
) -> Fmi2Status {
    run::<M, _>(c, call, |_| {
        Err(refuse(
            "this FMU holds its inputs constant over a step and gives no output derivatives",
        ))
    })
}

/// The statuses of `fmi2GetStatus` and its typed siblings: `kind` 0
/// DoStepStatus, 1 PendingStatus, 2 LastSuccessfulTime, 3 Terminated.
pub enum StatusValue<'a> {
    /// `fmi2GetStatus` (DoStepStatus: the last step's, always done).
    Status(*mut Fmi2Status),
    /// `fmi2GetRealStatus` (LastSuccessfulTime).
    Real(*mut f64),
    /// `fmi2GetIntegerStatus` (none).
    Integer(*mut c_int),
    /// `fmi2GetBooleanStatus` (Terminated).
    Boolean(*mut Fmi2Boolean),
    /// `fmi2GetStringStatus` (PendingStatus: none pending).
    Text(*mut *const c_char, std::marker::PhantomData<&'a ()>),
}

/// `fmi2GetStatus`, `fmi2GetRealStatus`, `fmi2GetIntegerStatus`,
/// `fmi2GetBooleanStatus`, `fmi2GetStringStatus`.
///
/// # Safety
/// The value pointer must be null or point to a value of its type.
pub unsafe fn get_status<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi2Component,
    call: &str,
    kind: c_int,
    value: StatusValue<'_>,
) -> Fmi2Status {
    run::<M, _>(c, call, |e| {
        e.instance.require_interface(Interface::CoSimulation)?;
        e.instance.allow_in(&[Step, StepFailed, Terminated])?;
        let unknown = || refuse(format!("{call} has no status of kind {kind}"));
        // SAFETY: the importer's pointers, checked for null.
        unsafe {
            match (value, kind) {
                (StatusValue::Status(v), 0) => *target(v, "value")? = 0,
                (StatusValue::Real(v), 2) => *target(v, "value")? = e.instance.time(),
                (StatusValue::Boolean(v), 3) => *target(v, "value")? = flag(e.instance.ended()),
                (StatusValue::Text(v, _), 1) => *target(v, "value")? = c"".as_ptr(),
                _ => return Err(unknown()),
            }
        }
        Ok(())
    })
}

// ----- FMU state -----

/// `fmi2GetFMUstate`: a new state, or the one `*state` names replaced.
///
/// # Safety
/// `state` must be null or point to an `fmi2FMUstate`.
pub unsafe fn get_fmu_state<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi2Component,
    state: *mut *mut c_void,
) -> Fmi2Status {
    // SAFETY: as this function's contract.
    run::<M, _>(c, "fmi2GetFMUstate", |e| unsafe { fmu_state::get(e, state) })
}

/// `fmi2SetFMUstate`.
pub fn set_fmu_state<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi2Component,
    state: *mut c_void,
) -> Fmi2Status {
    run::<M, _>(c, "fmi2SetFMUstate", |e| fmu_state::set(e, state))
}

/// `fmi2FreeFMUstate`.
///
/// # Safety
/// `state` must be null or point to an `fmi2FMUstate`.
pub unsafe fn free_fmu_state<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi2Component,
    state: *mut *mut c_void,
) -> Fmi2Status {
    // SAFETY: as this function's contract.
    run::<M, _>(c, "fmi2FreeFMUstate", |_| unsafe { fmu_state::free(state) })
}

/// `fmi2SerializedFMUstateSize`.
///
/// # Safety
/// `size` must be null or point to a `size_t`.
pub unsafe fn serialized_size<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi2Component,
    state: *mut c_void,
    size: *mut usize,
) -> Fmi2Status {
    // SAFETY: as this function's contract.
    run::<M, _>(c, "fmi2SerializedFMUstateSize", |_| unsafe { fmu_state::size(state, size) })
}

/// `fmi2SerializeFMUstate`: the state's numbers, little-endian.
///
/// # Safety
/// `bytes` must be null or point to `size` bytes.
pub unsafe fn serialize<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi2Component,
    state: *mut c_void,
    bytes: *mut u8,
    size: usize,
) -> Fmi2Status {
    // SAFETY: as this function's contract.
    run::<M, _>(c, "fmi2SerializeFMUstate", |_| unsafe { fmu_state::serialize(state, bytes, size) })
}

/// `fmi2DeSerializeFMUstate`.
///
/// # Safety
/// `bytes` must be null or point to `size` bytes; `state` null or to an
/// `fmi2FMUstate`.
pub unsafe fn deserialize<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi2Component,
    bytes: *const u8,
    size: usize,
    state: *mut *mut c_void,
) -> Fmi2Status {
    // SAFETY: as this function's contract.
    run::<M, _>(c, "fmi2DeSerializeFMUstate", |e| unsafe {
        fmu_state::deserialize(e, bytes, size, state)
    })
}

/// `fmi2GetDirectionalDerivative`.
///
/// # Safety
/// The arrays must be null or hold the counts given.
pub unsafe fn get_directional_derivative<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi2Component,
    unknowns: *const Fmi2ValueReference,
    n_unknowns: usize,
    knowns: *const Fmi2ValueReference,
    n_knowns: usize,
    seed: *const f64,
    sensitivity: *mut f64,
) -> Fmi2Status {
    run::<M, _>(c, "fmi2GetDirectionalDerivative", |e| {
        e.instance.allow_in(&[Initialization, Event, Continuous, Step, StepFailed, Terminated])?;
        // SAFETY: the counts given, as FMI requires.
        let (u, k, s, out) = unsafe {
            (
                slice(unknowns, n_unknowns, "vUnknown_ref")?,
                slice(knowns, n_knowns, "vKnown_ref")?,
                slice(seed, n_knowns, "dvKnown")?,
                slice_mut(sensitivity, n_unknowns, "dvUnknown")?,
            )
        };
        e.instance.directional_derivative(u, k, s, out)
    })
}
