//! FMI 2.0: the types of `fmi2Functions.h`, its row of the table of
//! [`crate::standard`], and the C functions only it has (instantiation,
//! the experiment's setup, the event info, Co-Simulation's step and
//! statuses), each checking its arguments and the state it is called in
//! before the instance does the work. `export_fmu!` makes each an exported
//! `fmi2…` symbol of the user's library, with [`crate::calls`] for the
//! functions both standards share.

use crate::boundary::{self, guarded, target, text, Logger};
use crate::calls::{code, run, Exported, Handle};
use crate::description::{instantiation_token, FmiVersion};
use crate::instance::{refuse, Interface, Phase, Status};
use crate::standard::{Call, Standard};
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

/// FMI 2.0's row of the table.
pub struct Fmi2;

impl Standard for Fmi2 {
    const VERSION: FmiVersion = FmiVersion::V2;
    const REAL: &'static str = "Real";
    const VALUE_ARGUMENTS: [&'static str; 2] = ["vr", "value"];
    const STATE_ARGUMENTS: [&'static str; 2] = ["x", "x_nominal"];
    const DIRECTIONAL_ARGUMENTS: [&'static str; 4] =
        ["vUnknown_ref", "vKnown_ref", "dvKnown", "dvUnknown"];
    type Boolean = Fmi2Boolean;

    fn boolean(b: bool) -> Fmi2Boolean {
        Fmi2Boolean::from(b)
    }

    fn name(call: Call) -> &'static str {
        match call {
            Call::SetDebugLogging => "fmi2SetDebugLogging",
            Call::ExitInitializationMode => "fmi2ExitInitializationMode",
            Call::Terminate => "fmi2Terminate",
            Call::Reset => "fmi2Reset",
            Call::GetReal => "fmi2GetReal",
            Call::SetReal => "fmi2SetReal",
            Call::GetString => "fmi2GetString",
            Call::SetString => "fmi2SetString",
            Call::EnterEventMode => "fmi2EnterEventMode",
            Call::EnterContinuousTimeMode => "fmi2EnterContinuousTimeMode",
            Call::CompletedIntegratorStep => "fmi2CompletedIntegratorStep",
            Call::SetTime => "fmi2SetTime",
            Call::SetContinuousStates => "fmi2SetContinuousStates",
            Call::GetDerivatives => "fmi2GetDerivatives",
            Call::GetEventIndicators => "fmi2GetEventIndicators",
            Call::GetContinuousStates => "fmi2GetContinuousStates",
            Call::GetNominals => "fmi2GetNominalsOfContinuousStates",
            Call::GetFmuState => "fmi2GetFMUstate",
            Call::SetFmuState => "fmi2SetFMUstate",
            Call::FreeFmuState => "fmi2FreeFMUstate",
            Call::SerializedSize => "fmi2SerializedFMUstateSize",
            Call::Serialize => "fmi2SerializeFMUstate",
            Call::Deserialize => "fmi2DeSerializeFMUstate",
            Call::GetDirectionalDerivative => "fmi2GetDirectionalDerivative",
        }
    }

    fn phases(call: Call) -> Option<&'static [Phase]> {
        Some(match call {
            Call::GetReal => &[Initialization, Event, Continuous, Step, StepFailed, Terminated],
            Call::GetDerivatives => &[Event, Continuous, Terminated],
            Call::GetNominals => &[Instantiated, Event, Continuous, Terminated],
            other => return crate::standard::shared_phases(other),
        })
    }
}

fn flag(b: bool) -> Fmi2Boolean {
    Fmi2::boolean(b)
}

use Phase::{Continuous, Event, Initialization, Instantiated, Step, StepFailed, Terminated};

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
pub unsafe fn instantiate<M: Exported>(
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

/// `fmi2SetupExperiment`.
pub fn setup_experiment<M: Exported>(
    c: Handle,
    tolerance_defined: Fmi2Boolean,
    tolerance: f64,
    start: f64,
    stop_defined: Fmi2Boolean,
    stop: f64,
) -> Fmi2Status {
    run::<M>(c, "fmi2SetupExperiment", |e| {
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
pub fn enter_initialization_mode<M: Exported>(c: Handle) -> Fmi2Status {
    run::<M>(c, "fmi2EnterInitializationMode", |e| {
        e.instance.allow_in(&[Instantiated])?;
        e.instance.phase = Initialization;
        Ok(())
    })
}

// ----- Model Exchange -----

/// `fmi2NewDiscreteStates`.
///
/// # Safety
/// `info` must be null or point to an `fmi2EventInfo`.
pub unsafe fn new_discrete_states<M: Exported>(c: Handle, info: *mut Fmi2EventInfo) -> Fmi2Status {
    run::<M>(c, "fmi2NewDiscreteStates", |e| {
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

// ----- Co-Simulation -----

/// `fmi2DoStep`: a terminal event inside the step ends it early with
/// `fmi2Discard`; `fmi2GetBooleanStatus(fmi2Terminated)` then says so and
/// `fmi2GetRealStatus(fmi2LastSuccessfulTime)` gives the time reached.
pub fn do_step<M: Exported>(c: Handle, t: f64, h: f64, _no_set_prior: Fmi2Boolean) -> Fmi2Status {
    run::<M>(c, "fmi2DoStep", |e| {
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
pub fn cancel_step<M: Exported>(c: Handle) -> Fmi2Status {
    run::<M>(c, "fmi2CancelStep", |_| {
        Err(refuse("no step is pending: fmi2DoStep returns when its step is done"))
    })
}

/// `fmi2SetRealInputDerivatives` and `fmi2GetRealOutputDerivatives`: the
/// FMU holds its inputs constant over a step and gives no output
/// derivatives (`canInterpolateInputs`, `maxOutputDerivativeOrder` unset).
pub fn no_derivatives<M: Exported>(c: Handle, call: &str) -> Fmi2Status {
    run::<M>(c, call, |_| {
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
pub unsafe fn get_status<M: Exported>(
    c: Handle,
    call: &str,
    kind: c_int,
    value: StatusValue<'_>,
) -> Fmi2Status {
    run::<M>(c, call, |e| {
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
