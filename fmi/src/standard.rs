//! What differs between FMI 2.0 and FMI 3.0 where their C functions do
//! the same work: the functions' names, the phases of the state machine
//! each is allowed in, the names of their arguments in messages, and the
//! C type of a boolean. The module `calls` holds the functions once, generic
//! over this table; `fmi2` and `fmi3` each give their row and the
//! functions only their standard has.

use crate::description::FmiVersion;
use crate::instance::Phase::{self, Continuous, Event, Initialization, Instantiated, Step};
use crate::instance::Phase::{StepFailed, Terminated};

/// A C function both standards have, by what it does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Call {
    /// `fmi2SetDebugLogging`, `fmi3SetDebugLogging`.
    SetDebugLogging,
    /// `…ExitInitializationMode`.
    ExitInitializationMode,
    /// `…Terminate`.
    Terminate,
    /// `…Reset`.
    Reset,
    /// `fmi2GetReal`, `fmi3GetFloat64`.
    GetReal,
    /// `fmi2SetReal`, `fmi3SetFloat64`.
    SetReal,
    /// `…GetString`.
    GetString,
    /// `…SetString`.
    SetString,
    /// `…EnterEventMode`.
    EnterEventMode,
    /// `…EnterContinuousTimeMode`.
    EnterContinuousTimeMode,
    /// `…CompletedIntegratorStep`.
    CompletedIntegratorStep,
    /// `…SetTime`.
    SetTime,
    /// `…SetContinuousStates`.
    SetContinuousStates,
    /// `fmi2GetDerivatives`, `fmi3GetContinuousStateDerivatives`.
    GetDerivatives,
    /// `…GetEventIndicators`.
    GetEventIndicators,
    /// `…GetContinuousStates`.
    GetContinuousStates,
    /// `…GetNominalsOfContinuousStates`.
    GetNominals,
    /// `fmi2GetFMUstate`, `fmi3GetFMUState`.
    GetFmuState,
    /// `fmi2SetFMUstate`, `fmi3SetFMUState`.
    SetFmuState,
    /// `fmi2FreeFMUstate`, `fmi3FreeFMUState`.
    FreeFmuState,
    /// `fmi2SerializedFMUstateSize`, `fmi3SerializedFMUStateSize`.
    SerializedSize,
    /// `fmi2SerializeFMUstate`, `fmi3SerializeFMUState`.
    Serialize,
    /// `fmi2DeSerializeFMUstate`, `fmi3DeserializeFMUState`.
    Deserialize,
    /// `…GetDirectionalDerivative`.
    GetDirectionalDerivative,
}

/// One standard's row of the table.
pub trait Standard {
    /// Its version.
    const VERSION: FmiVersion;
    /// What it calls a real variable in messages (`Real`, `Float64`).
    const REAL: &'static str;
    /// The names of the value-reference and value arguments.
    const VALUE_ARGUMENTS: [&'static str; 2];
    /// The names of the state-vector and nominals arguments.
    const STATE_ARGUMENTS: [&'static str; 2];
    /// The names of `GetDirectionalDerivative`'s arguments: unknowns,
    /// knowns, seed, sensitivity.
    const DIRECTIONAL_ARGUMENTS: [&'static str; 4];
    /// Its C boolean (`fmi2Boolean`, an `int`; `fmi3Boolean`, a `bool`).
    type Boolean: Copy;
    /// `b` as its C boolean.
    fn boolean(b: bool) -> Self::Boolean;
    /// The C name of `call`.
    fn name(call: Call) -> &'static str;
    /// The phases `call` is allowed in; `None` for every one.
    fn phases(call: Call) -> Option<&'static [Phase]> {
        shared_phases(call)
    }
}

/// Where both standards allow a call in the same phases.
pub fn shared_phases(call: Call) -> Option<&'static [Phase]> {
    use Call::*;
    Some(match call {
        ExitInitializationMode => &[Initialization],
        Terminate => &[Event, Continuous, Step, StepFailed],
        SetReal => &[Instantiated, Initialization, Event, Continuous, Step],
        SetString => &[Instantiated, Initialization, Event, Step],
        EnterEventMode => &[Event, Continuous],
        EnterContinuousTimeMode => &[Event],
        CompletedIntegratorStep | SetContinuousStates => &[Continuous],
        SetTime => &[Event, Continuous],
        GetDerivatives => &[Initialization, Event, Continuous, Terminated],
        GetEventIndicators | GetContinuousStates => {
            &[Initialization, Event, Continuous, Terminated]
        }
        GetNominals => &[Instantiated, Initialization, Event, Continuous, Terminated],
        GetDirectionalDerivative => {
            &[Initialization, Event, Continuous, Step, StepFailed, Terminated]
        }
        SetDebugLogging | Reset | GetReal | GetString | GetFmuState | SetFmuState
        | FreeFmuState | SerializedSize | Serialize | Deserialize => return None,
    })
}
