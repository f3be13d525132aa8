//! FMI 3.0's C functions for a model `M`: the types and call order of
//! `fmi3Functions.h`, each function checking its arguments and the state
//! it is called in before the instance does the work. `export_fmu!` makes
//! each of them an exported `fmi3…` symbol of the user's library; the
//! functions of what the FMU does not offer (scheduled execution, clocks,
//! configuration, adjoint derivatives, types other than Float64 and
//! String) are exported too, as importers load every symbol, and answer
//! `fmi3Error` with a log message.

use crate::boundary::{self, guarded, slice, slice_mut, target, text, Entry, Logger};
use crate::description::{instantiation_token, FmiVersion};
use crate::fmu_state;
use crate::instance::{refuse, Interface, Outcome, Phase, Status};
use daegen_runtime::Model;
use std::ffi::{c_char, c_int, c_void, CString};

/// `fmi3Status`.
pub type Fmi3Status = c_int;
/// `fmi3Instance`.
pub type Fmi3Instance = *mut c_void;
/// `fmi3ValueReference`.
pub type Fmi3ValueReference = u32;

/// `fmi3LogMessageCallback`.
pub type Fmi3LogMessage = unsafe extern "C" fn(
    env: *mut c_void,
    status: Fmi3Status,
    category: *const c_char,
    message: *const c_char,
);

fn code(status: Status) -> Fmi3Status {
    match status {
        Status::Ok => 0,
        Status::Warning => 1,
        Status::Discard => 2,
        Status::Error => 3,
        Status::Fatal => 4,
    }
}

use Phase::{Continuous, Event, Initialization, Instantiated, Step, StepFailed, Terminated};

fn run<M, F>(c: Fmi3Instance, call: &str, body: F) -> Fmi3Status
where
    M: Model + Clone + Default + Send + Sync + 'static,
    F: FnOnce(&mut Entry<M>) -> Outcome,
{
    code(boundary::with::<M, _>(c, call, body))
}

/// `fmi3GetVersion`.
pub fn get_version() -> *const c_char {
    c"3.0".as_ptr()
}

/// The logger of an instance: the importer's callback with its
/// environment.
fn logger(log_message: Option<Fmi3LogMessage>, env: *mut c_void) -> Logger {
    let env = env as usize;
    Box::new(move |status, category, message| {
        let (Some(log), Ok(category), Ok(message)) =
            (log_message, CString::new(category), CString::new(message.replace('\0', " ")))
        else {
            return;
        };
        // SAFETY: the importer's callback with its own environment.
        unsafe { log(env as *mut c_void, code(status), category.as_ptr(), message.as_ptr()) }
    })
}

/// The instance both instantiation functions make, after checking the
/// token.
///
/// # Safety
/// `name` and `token` must be null or C strings.
#[allow(clippy::too_many_arguments)]
unsafe fn instantiate<M: Model + Clone + Default + Send + Sync + 'static>(
    identifier: &str,
    call: &str,
    interface: Interface,
    name: *const c_char,
    token: *const c_char,
    logging_on: bool,
    log: Logger,
    refusal: Option<String>,
) -> Fmi3Instance {
    guarded(|| {
        if let Some(message) = refusal {
            log(Status::Error, "logStatusError", &format!("{call}: {message}"));
            return Some(std::ptr::null_mut());
        }
        // SAFETY: as FMI requires, a C string or null.
        let name = unsafe { text(name, "instanceName") }.unwrap_or("").to_string();
        let expected = instantiation_token(&M::default(), FmiVersion::V3, identifier);
        // SAFETY: as FMI requires, a C string or null.
        match unsafe { text(token, "instantiationToken") } {
            Ok(t) if t == expected => {}
            Ok(t) => {
                log(Status::Error, "logStatusError", &format!("{call}: the instantiation token \"{t}\" is not this FMU's ({expected}): the modelDescription.xml belongs to another build of the model"));
                return Some(std::ptr::null_mut());
            }
            Err(r) => {
                log(Status::Error, "logStatusError", &format!("{call}: {}", r.message));
                return Some(std::ptr::null_mut());
            }
        }
        Some(boundary::instantiate::<M>(&name, interface, logging_on, log))
    })
    .unwrap_or(std::ptr::null_mut())
}

/// `fmi3InstantiateModelExchange`.
///
/// # Safety
/// Pointer arguments must be null or valid, as FMI requires.
#[allow(clippy::too_many_arguments)]
pub unsafe fn instantiate_model_exchange<M: Model + Clone + Default + Send + Sync + 'static>(
    identifier: &str,
    name: *const c_char,
    token: *const c_char,
    _resource_path: *const c_char,
    _visible: bool,
    logging_on: bool,
    env: *mut c_void,
    log_message: Option<Fmi3LogMessage>,
) -> Fmi3Instance {
    let log = logger(log_message, env);
    // SAFETY: the importer's strings, as FMI requires.
    unsafe {
        instantiate::<M>(
            identifier,
            "fmi3InstantiateModelExchange",
            Interface::ModelExchange,
            name,
            token,
            logging_on,
            log,
            None,
        )
    }
}

/// `fmi3InstantiateCoSimulation`: without event mode or intermediate
/// updates (`hasEventMode`, `providesIntermediateUpdate` unset).
///
/// # Safety
/// Pointer arguments must be null or valid, as FMI requires.
#[allow(clippy::too_many_arguments)]
pub unsafe fn instantiate_co_simulation<M: Model + Clone + Default + Send + Sync + 'static>(
    identifier: &str,
    name: *const c_char,
    token: *const c_char,
    _resource_path: *const c_char,
    _visible: bool,
    logging_on: bool,
    event_mode_used: bool,
    _early_return_allowed: bool,
    _required_intermediate: *const Fmi3ValueReference,
    n_required_intermediate: usize,
    env: *mut c_void,
    log_message: Option<Fmi3LogMessage>,
    _intermediate_update: *const c_void,
) -> Fmi3Instance {
    let log = logger(log_message, env);
    let refusal = if event_mode_used {
        Some("this FMU has no co-simulation event mode (hasEventMode is unset): its events act inside fmi3DoStep; instantiate with eventModeUsed = false".to_string())
    } else if n_required_intermediate > 0 {
        Some(
            "this FMU provides no intermediate updates: require no intermediate variables"
                .to_string(),
        )
    } else {
        None
    };
    // SAFETY: the importer's strings, as FMI requires.
    unsafe {
        instantiate::<M>(
            identifier,
            "fmi3InstantiateCoSimulation",
            Interface::CoSimulation,
            name,
            token,
            logging_on,
            log,
            refusal,
        )
    }
}

/// `fmi3FreeInstance`.
pub fn free_instance(c: Fmi3Instance) {
    let _ = guarded(|| Some(boundary::release(c)));
}

/// `fmi3SetDebugLogging`.
///
/// # Safety
/// `categories` must be null or point to `n` C strings.
pub unsafe fn set_debug_logging<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi3Instance,
    logging_on: bool,
    n: usize,
    categories: *const *const c_char,
) -> Fmi3Status {
    run::<M, _>(c, "fmi3SetDebugLogging", |e| {
        // SAFETY: n category pointers, as FMI requires.
        let _ = unsafe { slice(categories, n, "categories") }?;
        e.debug = logging_on;
        Ok(())
    })
}

/// `fmi3EnterInitializationMode`.
pub fn enter_initialization_mode<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi3Instance,
    tolerance_defined: bool,
    tolerance: f64,
    start: f64,
    stop_defined: bool,
    stop: f64,
) -> Fmi3Status {
    run::<M, _>(c, "fmi3EnterInitializationMode", |e| {
        e.instance.allow_in(&[Instantiated])?;
        let tolerance = Some(tolerance).filter(|_| tolerance_defined);
        let stop = Some(stop).filter(|_| stop_defined);
        e.instance.enter_initialization(tolerance, start, stop)
    })
}

/// `fmi3ExitInitializationMode`.
pub fn exit_initialization_mode<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi3Instance,
) -> Fmi3Status {
    run::<M, _>(c, "fmi3ExitInitializationMode", |e| {
        e.instance.allow_in(&[Initialization])?;
        e.instance.exit_initialization()
    })
}

/// `fmi3EnterEventMode`.
pub fn enter_event_mode<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi3Instance,
) -> Fmi3Status {
    run::<M, _>(c, "fmi3EnterEventMode", |e| {
        e.instance.require_interface(Interface::ModelExchange)?;
        e.instance.allow_in(&[Continuous])?;
        e.instance.phase = Event;
        Ok(())
    })
}

/// `fmi3Terminate`.
pub fn terminate<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi3Instance,
) -> Fmi3Status {
    run::<M, _>(c, "fmi3Terminate", |e| {
        e.instance.allow_in(&[Event, Continuous, Step, StepFailed])?;
        e.instance.phase = Terminated;
        Ok(())
    })
}

/// `fmi3Reset`.
pub fn reset<M: Model + Clone + Default + Send + Sync + 'static>(c: Fmi3Instance) -> Fmi3Status {
    run::<M, _>(c, "fmi3Reset", |e| {
        e.instance.reset();
        Ok(())
    })
}

/// `fmi3GetFloat64`.
///
/// # Safety
/// The arrays must be null or hold the counts given.
pub unsafe fn get_float64<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi3Instance,
    vr: *const Fmi3ValueReference,
    nvr: usize,
    values: *mut f64,
    n_values: usize,
) -> Fmi3Status {
    run::<M, _>(c, "fmi3GetFloat64", |e| {
        scalars(nvr, n_values)?;
        // SAFETY: the counts given, as FMI requires.
        let (vr, values) =
            unsafe { (slice(vr, nvr, "valueReferences")?, slice_mut(values, n_values, "values")?) };
        for (k, &r) in vr.iter().enumerate() {
            values[k] = e.instance.get_real(r)?;
        }
        Ok(())
    })
}

/// `fmi3SetFloat64`.
///
/// # Safety
/// The arrays must be null or hold the counts given.
pub unsafe fn set_float64<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi3Instance,
    vr: *const Fmi3ValueReference,
    nvr: usize,
    values: *const f64,
    n_values: usize,
) -> Fmi3Status {
    run::<M, _>(c, "fmi3SetFloat64", |e| {
        e.instance.allow_in(&[Instantiated, Initialization, Event, Continuous, Step])?;
        scalars(nvr, n_values)?;
        // SAFETY: the counts given, as FMI requires.
        let (vr, values) =
            unsafe { (slice(vr, nvr, "valueReferences")?, slice(values, n_values, "values")?) };
        for (k, &r) in vr.iter().enumerate() {
            e.instance.set_real(r, values[k])?;
        }
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

/// `fmi3GetString`: `solver.method`, valid until the next call.
///
/// # Safety
/// The arrays must be null or hold the counts given.
pub unsafe fn get_string<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi3Instance,
    vr: *const Fmi3ValueReference,
    nvr: usize,
    values: *mut *const c_char,
    n_values: usize,
) -> Fmi3Status {
    run::<M, _>(c, "fmi3GetString", |e| {
        scalars(nvr, n_values)?;
        // SAFETY: the counts given, as FMI requires.
        let (vr, values) =
            unsafe { (slice(vr, nvr, "valueReferences")?, slice_mut(values, n_values, "values")?) };
        e.strings.clear();
        for (k, &r) in vr.iter().enumerate() {
            let s = CString::new(e.instance.get_string(r)?).unwrap_or_default();
            values[k] = s.as_ptr();
            e.strings.push(s);
        }
        Ok(())
    })
}

/// `fmi3SetString`: `solver.method`.
///
/// # Safety
/// The arrays must be null or hold the counts given.
pub unsafe fn set_string<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi3Instance,
    vr: *const Fmi3ValueReference,
    nvr: usize,
    values: *const *const c_char,
    n_values: usize,
) -> Fmi3Status {
    run::<M, _>(c, "fmi3SetString", |e| {
        e.instance.allow_in(&[Instantiated, Initialization, Event, Step])?;
        scalars(nvr, n_values)?;
        // SAFETY: the counts given, as FMI requires.
        let (vr, values) =
            unsafe { (slice(vr, nvr, "valueReferences")?, slice(values, n_values, "values")?) };
        for (k, &r) in vr.iter().enumerate() {
            // SAFETY: a C string, as FMI requires.
            let v = unsafe { text(values[k], "values") }?;
            e.instance.set_string(r, v)?;
        }
        Ok(())
    })
}

/// The getters and setters of the types this FMU has no variables of
/// (`fmi3GetInt32`, `fmi3SetBoolean`, …): any value reference is refused.
///
/// # Safety
/// `vr` must be null or hold `nvr` references.
pub unsafe fn no_such_values<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi3Instance,
    call: &str,
    kind: &str,
    vr: *const Fmi3ValueReference,
    nvr: usize,
) -> Fmi3Status {
    run::<M, _>(c, call, |e| {
        if nvr == 0 {
            return Ok(());
        }
        // SAFETY: nvr references, as FMI requires.
        let vr = unsafe { slice(vr, nvr, "valueReferences") }?;
        let name = e.instance.variable(vr[0])?.name.clone();
        Err(refuse(format!("`{name}` is not {kind}: every variable of this FMU is a Float64 (a discrete value too) but `solver.method`, a String")))
    })
}

/// A function of a part of FMI 3.0 this FMU does not offer: refused with
/// what it is.
pub fn not_offered<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi3Instance,
    call: &str,
    what: &str,
) -> Fmi3Status {
    run::<M, _>(c, call, |_| Err(refuse(format!("this FMU does not offer {what}"))))
}

/// `fmi3InstantiateScheduledExecution`: not offered, null.
pub fn instantiate_scheduled_execution() -> Fmi3Instance {
    std::ptr::null_mut()
}

// ----- Model Exchange -----

/// `fmi3UpdateDiscreteStates`.
///
/// # Safety
/// The flags must be null or point to their values.
#[allow(clippy::too_many_arguments)]
pub unsafe fn update_discrete_states<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi3Instance,
    discrete_states_need_update: *mut bool,
    terminate_simulation: *mut bool,
    nominals_changed: *mut bool,
    values_changed: *mut bool,
    next_event_time_defined: *mut bool,
    next_event_time: *mut f64,
) -> Fmi3Status {
    run::<M, _>(c, "fmi3UpdateDiscreteStates", |e| {
        e.instance.require_interface(Interface::ModelExchange)?;
        e.instance.allow_in(&[Event])?;
        // SAFETY: the importer's flags, checked for null.
        let (need, stop, nominals, values, defined, next) = unsafe {
            (
                target(discrete_states_need_update, "discreteStatesNeedUpdate")?,
                target(terminate_simulation, "terminateSimulation")?,
                target(nominals_changed, "nominalsOfContinuousStatesChanged")?,
                target(values_changed, "valuesOfContinuousStatesChanged")?,
                target(next_event_time_defined, "nextEventTimeDefined")?,
                target(next_event_time, "nextEventTime")?,
            )
        };
        let update = e.instance.update_discrete_states()?;
        *need = false;
        *stop = update.terminate;
        *nominals = false;
        *values = update.values_changed;
        *defined = update.next_event_time.is_some();
        *next = update.next_event_time.unwrap_or(0.0);
        Ok(())
    })
}

/// `fmi3EnterContinuousTimeMode`.
pub fn enter_continuous_time_mode<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi3Instance,
) -> Fmi3Status {
    run::<M, _>(c, "fmi3EnterContinuousTimeMode", |e| {
        e.instance.require_interface(Interface::ModelExchange)?;
        e.instance.allow_in(&[Event])?;
        e.instance.phase = Continuous;
        Ok(())
    })
}

/// `fmi3CompletedIntegratorStep`.
///
/// # Safety
/// The flags must be null or point to their values.
pub unsafe fn completed_integrator_step<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi3Instance,
    _no_set_prior: bool,
    enter_event_mode: *mut bool,
    terminate_simulation: *mut bool,
) -> Fmi3Status {
    run::<M, _>(c, "fmi3CompletedIntegratorStep", |e| {
        e.instance.require_interface(Interface::ModelExchange)?;
        e.instance.allow_in(&[Continuous])?;
        // SAFETY: the importer's flags, checked for null.
        let (event, stop) = unsafe {
            (
                target(enter_event_mode, "enterEventMode")?,
                target(terminate_simulation, "terminateSimulation")?,
            )
        };
        (*event, *stop) = e.instance.completed_integrator_step();
        Ok(())
    })
}

/// `fmi3SetTime`.
pub fn set_time<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi3Instance,
    time: f64,
) -> Fmi3Status {
    run::<M, _>(c, "fmi3SetTime", |e| {
        e.instance.require_interface(Interface::ModelExchange)?;
        e.instance.allow_in(&[Event, Continuous])?;
        e.instance.set_time(time)
    })
}

/// `fmi3SetContinuousStates`.
///
/// # Safety
/// `x` must be null or point to `nx` values.
pub unsafe fn set_continuous_states<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi3Instance,
    x: *const f64,
    nx: usize,
) -> Fmi3Status {
    run::<M, _>(c, "fmi3SetContinuousStates", |e| {
        e.instance.require_interface(Interface::ModelExchange)?;
        e.instance.allow_in(&[Continuous])?;
        // SAFETY: nx values, as FMI requires.
        let x = unsafe { slice(x, nx, "continuousStates") }?;
        e.instance.set_continuous_states(x)
    })
}

/// `fmi3GetContinuousStateDerivatives`.
///
/// # Safety
/// `dx` must be null or point to `nx` values.
pub unsafe fn get_derivatives<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi3Instance,
    dx: *mut f64,
    nx: usize,
) -> Fmi3Status {
    run::<M, _>(c, "fmi3GetContinuousStateDerivatives", |e| {
        e.instance.require_interface(Interface::ModelExchange)?;
        e.instance.allow_in(&[Initialization, Event, Continuous, Terminated])?;
        // SAFETY: nx values, as FMI requires.
        let dx = unsafe { slice_mut(dx, nx, "derivatives") }?;
        e.instance.derivatives(dx)
    })
}

/// `fmi3GetEventIndicators`.
///
/// # Safety
/// `g` must be null or point to `ni` values.
pub unsafe fn get_event_indicators<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi3Instance,
    g: *mut f64,
    ni: usize,
) -> Fmi3Status {
    run::<M, _>(c, "fmi3GetEventIndicators", |e| {
        e.instance.require_interface(Interface::ModelExchange)?;
        e.instance.allow_in(&[Initialization, Event, Continuous, Terminated])?;
        // SAFETY: ni values, as FMI requires.
        let g = unsafe { slice_mut(g, ni, "eventIndicators") }?;
        e.instance.indicators(g)
    })
}

/// `fmi3GetContinuousStates`.
///
/// # Safety
/// `x` must be null or point to `nx` values.
pub unsafe fn get_continuous_states<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi3Instance,
    x: *mut f64,
    nx: usize,
) -> Fmi3Status {
    run::<M, _>(c, "fmi3GetContinuousStates", |e| {
        e.instance.require_interface(Interface::ModelExchange)?;
        e.instance.allow_in(&[Initialization, Event, Continuous, Terminated])?;
        // SAFETY: nx values, as FMI requires.
        let x = unsafe { slice_mut(x, nx, "continuousStates") }?;
        e.instance.get_continuous_states(x)
    })
}

/// `fmi3GetNominalsOfContinuousStates`.
///
/// # Safety
/// `x` must be null or point to `nx` values.
pub unsafe fn get_nominals<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi3Instance,
    x: *mut f64,
    nx: usize,
) -> Fmi3Status {
    run::<M, _>(c, "fmi3GetNominalsOfContinuousStates", |e| {
        e.instance.require_interface(Interface::ModelExchange)?;
        e.instance.allow_in(&[Instantiated, Initialization, Event, Continuous, Terminated])?;
        // SAFETY: nx values, as FMI requires.
        let x = unsafe { slice_mut(x, nx, "nominals") }?;
        e.instance.nominals(x)
    })
}

/// `fmi3GetNumberOfEventIndicators` and `fmi3GetNumberOfContinuousStates`.
///
/// # Safety
/// `n` must be null or point to a `size_t`.
pub unsafe fn get_number_of<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi3Instance,
    call: &str,
    indicators: bool,
    n: *mut usize,
) -> Fmi3Status {
    run::<M, _>(c, call, |e| {
        // SAFETY: the importer's pointer, checked for null.
        let n = unsafe { target(n, "n") }?;
        *n =
            if indicators { e.instance.event_indicators() } else { e.instance.continuous_states() };
        Ok(())
    })
}

// ----- Co-Simulation -----

/// `fmi3EnterStepMode`: without co-simulation event mode, never needed.
pub fn enter_step_mode<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi3Instance,
) -> Fmi3Status {
    run::<M, _>(c, "fmi3EnterStepMode", |e| {
        e.instance.require_interface(Interface::CoSimulation)?;
        Err(refuse(format!(
            "this FMU has no co-simulation event mode; it is in {} already",
            e.instance.phase.name()
        )))
    })
}

/// `fmi3DoStep`: a terminal event inside the step ends it early with
/// `terminateSimulation` and the time reached in `lastSuccessfulTime`.
///
/// # Safety
/// The flags must be null or point to their values.
#[allow(clippy::too_many_arguments)]
pub unsafe fn do_step<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi3Instance,
    t: f64,
    h: f64,
    _no_set_prior: bool,
    event_handling_needed: *mut bool,
    terminate_simulation: *mut bool,
    early_return: *mut bool,
    last_successful_time: *mut f64,
) -> Fmi3Status {
    run::<M, _>(c, "fmi3DoStep", |e| {
        e.instance.require_interface(Interface::CoSimulation)?;
        e.instance.allow_in(&[Step])?;
        // SAFETY: the importer's flags, checked for null.
        let (event, stop, early, last) = unsafe {
            (
                target(event_handling_needed, "eventHandlingNeeded")?,
                target(terminate_simulation, "terminateSimulation")?,
                target(early_return, "earlyReturn")?,
                target(last_successful_time, "lastSuccessfulTime")?,
            )
        };
        let done = e.instance.do_step(t, h);
        *event = false;
        *early = false;
        *last = e.instance.time();
        let done = done?;
        *stop = done.terminate;
        Ok(())
    })
}

// ----- FMU state -----

/// `fmi3GetFMUState`: a new state, or the one `*state` names replaced.
///
/// # Safety
/// `state` must be null or point to an `fmi3FMUState`.
pub unsafe fn get_fmu_state<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi3Instance,
    state: *mut *mut c_void,
) -> Fmi3Status {
    // SAFETY: as this function's contract.
    run::<M, _>(c, "fmi3GetFMUState", |e| unsafe { fmu_state::get(e, state) })
}

/// `fmi3SetFMUState`.
pub fn set_fmu_state<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi3Instance,
    state: *mut c_void,
) -> Fmi3Status {
    run::<M, _>(c, "fmi3SetFMUState", |e| fmu_state::set(e, state))
}

/// `fmi3FreeFMUState`.
///
/// # Safety
/// `state` must be null or point to an `fmi3FMUState`.
pub unsafe fn free_fmu_state<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi3Instance,
    state: *mut *mut c_void,
) -> Fmi3Status {
    // SAFETY: as this function's contract.
    run::<M, _>(c, "fmi3FreeFMUState", |_| unsafe { fmu_state::free(state) })
}

/// `fmi3SerializedFMUStateSize`.
///
/// # Safety
/// `size` must be null or point to a `size_t`.
pub unsafe fn serialized_size<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi3Instance,
    state: *mut c_void,
    size: *mut usize,
) -> Fmi3Status {
    // SAFETY: as this function's contract.
    run::<M, _>(c, "fmi3SerializedFMUStateSize", |_| unsafe { fmu_state::size(state, size) })
}

/// `fmi3SerializeFMUState`: the state's numbers, little-endian.
///
/// # Safety
/// `bytes` must be null or point to `size` bytes.
pub unsafe fn serialize<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi3Instance,
    state: *mut c_void,
    bytes: *mut u8,
    size: usize,
) -> Fmi3Status {
    // SAFETY: as this function's contract.
    run::<M, _>(c, "fmi3SerializeFMUState", |_| unsafe { fmu_state::serialize(state, bytes, size) })
}

/// `fmi3DeserializeFMUState`.
///
/// # Safety
/// `bytes` must be null or point to `size` bytes; `state` null or to an
/// `fmi3FMUState`.
pub unsafe fn deserialize<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi3Instance,
    bytes: *const u8,
    size: usize,
    state: *mut *mut c_void,
) -> Fmi3Status {
    // SAFETY: as this function's contract.
    run::<M, _>(c, "fmi3DeserializeFMUState", |e| unsafe {
        fmu_state::deserialize(e, bytes, size, state)
    })
}

/// `fmi3GetDirectionalDerivative`.
///
/// # Safety
/// The arrays must be null or hold the counts given.
#[allow(clippy::too_many_arguments)]
pub unsafe fn get_directional_derivative<M: Model + Clone + Default + Send + Sync + 'static>(
    c: Fmi3Instance,
    unknowns: *const Fmi3ValueReference,
    n_unknowns: usize,
    knowns: *const Fmi3ValueReference,
    n_knowns: usize,
    seed: *const f64,
    n_seed: usize,
    sensitivity: *mut f64,
    n_sensitivity: usize,
) -> Fmi3Status {
    run::<M, _>(c, "fmi3GetDirectionalDerivative", |e| {
        e.instance.allow_in(&[Initialization, Event, Continuous, Step, StepFailed, Terminated])?;
        // SAFETY: the counts given, as FMI requires.
        let (u, k, s, out) = unsafe {
            (
                slice(unknowns, n_unknowns, "unknowns")?,
                slice(knowns, n_knowns, "knowns")?,
                slice(seed, n_seed, "seed")?,
                slice_mut(sensitivity, n_sensitivity, "sensitivity")?,
            )
        };
        e.instance.directional_derivative(u, k, s, out)
    })
}
