//! FMI 3.0: the types of `fmi3Functions.h`, its row of the table of
//! [`crate::standard`], and the C functions only it has (the two
//! instantiations, initialization with the experiment, the discrete-state
//! update, the counts, Co-Simulation's step), each checking its arguments
//! and the state it is called in before the instance does the work.
//! `export_fmu!` makes each an exported `fmi3…` symbol of the user's
//! library, with [`crate::calls`] for the functions both standards share;
//! the functions of what the FMU does not offer (scheduled execution,
//! clocks, configuration, adjoint derivatives, types other than Float64
//! and String) are exported too, as importers load every symbol, and
//! answer `fmi3Error` with a log message.

use crate::boundary::{self, guarded, target, text, Logger};
use crate::calls::{code, run, Exported, Handle};
use crate::description::{instantiation_token, FmiVersion};
use crate::instance::{refuse, Interface, Phase, Status};
use crate::standard::{Call, Standard};
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

/// FMI 3.0's row of the table.
pub struct Fmi3;

impl Standard for Fmi3 {
    const VERSION: FmiVersion = FmiVersion::V3;
    const REAL: &'static str = "Float64";
    const VALUE_ARGUMENTS: [&'static str; 2] = ["valueReferences", "values"];
    const STATE_ARGUMENTS: [&'static str; 2] = ["continuousStates", "nominals"];
    const DIRECTIONAL_ARGUMENTS: [&'static str; 4] = ["unknowns", "knowns", "seed", "sensitivity"];
    type Boolean = bool;

    fn boolean(b: bool) -> bool {
        b
    }

    fn name(call: Call) -> &'static str {
        match call {
            Call::SetDebugLogging => "fmi3SetDebugLogging",
            Call::ExitInitializationMode => "fmi3ExitInitializationMode",
            Call::Terminate => "fmi3Terminate",
            Call::Reset => "fmi3Reset",
            Call::GetReal => "fmi3GetFloat64",
            Call::SetReal => "fmi3SetFloat64",
            Call::GetString => "fmi3GetString",
            Call::SetString => "fmi3SetString",
            Call::EnterEventMode => "fmi3EnterEventMode",
            Call::EnterContinuousTimeMode => "fmi3EnterContinuousTimeMode",
            Call::CompletedIntegratorStep => "fmi3CompletedIntegratorStep",
            Call::SetTime => "fmi3SetTime",
            Call::SetContinuousStates => "fmi3SetContinuousStates",
            Call::GetDerivatives => "fmi3GetContinuousStateDerivatives",
            Call::GetEventIndicators => "fmi3GetEventIndicators",
            Call::GetContinuousStates => "fmi3GetContinuousStates",
            Call::GetNominals => "fmi3GetNominalsOfContinuousStates",
            Call::GetFmuState => "fmi3GetFMUState",
            Call::SetFmuState => "fmi3SetFMUState",
            Call::FreeFmuState => "fmi3FreeFMUState",
            Call::SerializedSize => "fmi3SerializedFMUStateSize",
            Call::Serialize => "fmi3SerializeFMUState",
            Call::Deserialize => "fmi3DeserializeFMUState",
            Call::GetDirectionalDerivative => "fmi3GetDirectionalDerivative",
        }
    }

    fn phases(call: Call) -> Option<&'static [Phase]> {
        match call {
            // Event mode is entered from continuous time only.
            Call::EnterEventMode => Some(&[Continuous]),
            other => crate::standard::shared_phases(other),
        }
    }
}

use Phase::{Continuous, Event, Instantiated, Step};

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
unsafe fn instantiate<M: Exported>(
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
pub unsafe fn instantiate_model_exchange<M: Exported>(
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
pub unsafe fn instantiate_co_simulation<M: Exported>(
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

/// `fmi3EnterInitializationMode`.
pub fn enter_initialization_mode<M: Exported>(
    c: Handle,
    tolerance_defined: bool,
    tolerance: f64,
    start: f64,
    stop_defined: bool,
    stop: f64,
) -> Fmi3Status {
    run::<M>(c, "fmi3EnterInitializationMode", |e| {
        e.instance.allow_in(&[Instantiated])?;
        let tolerance = Some(tolerance).filter(|_| tolerance_defined);
        let stop = Some(stop).filter(|_| stop_defined);
        e.instance.enter_initialization(tolerance, start, stop)
    })
}

/// A function of a part of FMI 3.0 this FMU does not offer: refused with
/// what it is.
pub fn not_offered<M: Exported>(c: Handle, call: &str, what: &str) -> Fmi3Status {
    run::<M>(c, call, |_| Err(refuse(format!("this FMU does not offer {what}"))))
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
pub unsafe fn update_discrete_states<M: Exported>(
    c: Handle,
    discrete_states_need_update: *mut bool,
    terminate_simulation: *mut bool,
    nominals_changed: *mut bool,
    values_changed: *mut bool,
    next_event_time_defined: *mut bool,
    next_event_time: *mut f64,
) -> Fmi3Status {
    run::<M>(c, "fmi3UpdateDiscreteStates", |e| {
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

/// `fmi3GetNumberOfEventIndicators` and `fmi3GetNumberOfContinuousStates`.
///
/// # Safety
/// `n` must be null or point to a `size_t`.
pub unsafe fn get_number_of<M: Exported>(
    c: Handle,
    call: &str,
    indicators: bool,
    n: *mut usize,
) -> Fmi3Status {
    run::<M>(c, call, |e| {
        // SAFETY: the importer's pointer, checked for null.
        let n = unsafe { target(n, "n") }?;
        *n =
            if indicators { e.instance.event_indicators() } else { e.instance.continuous_states() };
        Ok(())
    })
}

// ----- Co-Simulation -----

/// `fmi3EnterStepMode`: without co-simulation event mode, never needed.
pub fn enter_step_mode<M: Exported>(c: Handle) -> Fmi3Status {
    run::<M>(c, "fmi3EnterStepMode", |e| {
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
pub unsafe fn do_step<M: Exported>(
    c: Handle,
    t: f64,
    h: f64,
    _no_set_prior: bool,
    event_handling_needed: *mut bool,
    terminate_simulation: *mut bool,
    early_return: *mut bool,
    last_successful_time: *mut f64,
) -> Fmi3Status {
    run::<M>(c, "fmi3DoStep", |e| {
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
