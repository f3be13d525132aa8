//! `export_fmu!`: the exported C symbols of an FMU, every `fmi2…` and
//! `fmi3…` function of both standards, each a one-line call into the
//! functions both share (`calls`, with the standard's row of the table) or
//! into its standard's own (`fmi2`, `fmi3`) for the model type given. One library carries both
//! versions; each archive holds the library and its version's
//! `modelDescription.xml`.

/// Exports `$model` (a `#[dae_model]` type) as an FMU from a `cdylib`
/// crate: every function of FMI 2.0 and 3.0, Model Exchange and
/// Co-Simulation, and the model description the packaging command writes
/// into the archive. The model identifier is the crate's name.
///
/// ```ignore
/// use daegen::prelude::*;
///
/// #[dae_model]
/// fn van_der_pol() { /* … */ }
///
/// daegen_fmi::export_fmu!(VanDerPol);
/// ```
///
/// The functions are `unsafe extern "C"`: the importer's pointers are
/// checked for null and its handles looked up before use (see
/// [`crate::boundary`]), which is all a library can check of a C caller.
#[macro_export]
macro_rules! export_fmu {
    ($model:ty) => {
        const _: () = {
            use ::std::ffi::{c_char, c_int, c_uint, c_void};
            use $crate::calls as both;
            use $crate::fmi2 as f2;
            use $crate::fmi3 as f3;
            type M = $model;
            type V2 = $crate::fmi2::Fmi2;
            type V3 = $crate::fmi3::Fmi3;
            const IDENTIFIER: &str = env!("CARGO_CRATE_NAME");

            /// The model description of FMI version `version` (2 or 3), for
            /// the packaging command; null for another version.
            #[no_mangle]
            pub extern "C" fn daegen_fmi_model_description(version: c_int) -> *const c_char {
                static V2: ::std::sync::OnceLock<::std::ffi::CString> = ::std::sync::OnceLock::new();
                static V3: ::std::sync::OnceLock<::std::ffi::CString> = ::std::sync::OnceLock::new();
                let (cell, v) = match version {
                    2 => (&V2, $crate::FmiVersion::V2),
                    3 => (&V3, $crate::FmiVersion::V3),
                    _ => return ::std::ptr::null(),
                };
                cell.get_or_init(|| $crate::packaged_description::<M>(v, IDENTIFIER)).as_ptr()
            }

            // ----- FMI 2.0 -----

            #[no_mangle]
            pub extern "C" fn fmi2GetTypesPlatform() -> *const c_char { f2::get_types_platform() }
            #[no_mangle]
            pub extern "C" fn fmi2GetVersion() -> *const c_char { f2::get_version() }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2SetDebugLogging(c: *mut c_void, on: c_int, n: usize, categories: *const *const c_char) -> c_int {
                unsafe { both::set_debug_logging::<V2, M>(c, on != 0, n, categories) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2Instantiate(name: *const c_char, kind: c_int, guid: *const c_char, resources: *const c_char, functions: *const f2::Fmi2CallbackFunctions, visible: c_int, logging_on: c_int) -> *mut c_void {
                unsafe { f2::instantiate::<M>(IDENTIFIER, name, kind, guid, resources, functions, visible, logging_on) }
            }
            #[no_mangle]
            pub extern "C" fn fmi2FreeInstance(c: *mut c_void) { both::free_instance(c) }
            #[no_mangle]
            pub extern "C" fn fmi2SetupExperiment(c: *mut c_void, tol_defined: c_int, tol: f64, start: f64, stop_defined: c_int, stop: f64) -> c_int {
                f2::setup_experiment::<M>(c, tol_defined, tol, start, stop_defined, stop)
            }
            #[no_mangle]
            pub extern "C" fn fmi2EnterInitializationMode(c: *mut c_void) -> c_int { f2::enter_initialization_mode::<M>(c) }
            #[no_mangle]
            pub extern "C" fn fmi2ExitInitializationMode(c: *mut c_void) -> c_int { both::exit_initialization_mode::<V2, M>(c) }
            #[no_mangle]
            pub extern "C" fn fmi2Terminate(c: *mut c_void) -> c_int { both::terminate::<V2, M>(c) }
            #[no_mangle]
            pub extern "C" fn fmi2Reset(c: *mut c_void) -> c_int { both::reset::<V2, M>(c) }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2GetReal(c: *mut c_void, vr: *const c_uint, n: usize, v: *mut f64) -> c_int {
                unsafe { both::get_real::<V2, M>(c, vr, n, v, n) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2SetReal(c: *mut c_void, vr: *const c_uint, n: usize, v: *const f64) -> c_int {
                unsafe { both::set_real::<V2, M>(c, vr, n, v, n) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2GetString(c: *mut c_void, vr: *const c_uint, n: usize, v: *mut *const c_char) -> c_int {
                unsafe { both::get_string::<V2, M>(c, vr, n, v, n) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2SetString(c: *mut c_void, vr: *const c_uint, n: usize, v: *const *const c_char) -> c_int {
                unsafe { both::set_string::<V2, M>(c, vr, n, v, n) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2GetInteger(c: *mut c_void, vr: *const c_uint, n: usize, _v: *mut c_int) -> c_int {
                unsafe { both::no_such_values::<V2, M>(c, "fmi2GetInteger", "an Integer", vr, n) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2GetBoolean(c: *mut c_void, vr: *const c_uint, n: usize, _v: *mut c_int) -> c_int {
                unsafe { both::no_such_values::<V2, M>(c, "fmi2GetBoolean", "a Boolean", vr, n) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2SetInteger(c: *mut c_void, vr: *const c_uint, n: usize, _v: *const c_int) -> c_int {
                unsafe { both::no_such_values::<V2, M>(c, "fmi2SetInteger", "an Integer", vr, n) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2SetBoolean(c: *mut c_void, vr: *const c_uint, n: usize, _v: *const c_int) -> c_int {
                unsafe { both::no_such_values::<V2, M>(c, "fmi2SetBoolean", "a Boolean", vr, n) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2GetFMUstate(c: *mut c_void, s: *mut *mut c_void) -> c_int {
                unsafe { both::get_fmu_state::<V2, M>(c, s) }
            }
            #[no_mangle]
            pub extern "C" fn fmi2SetFMUstate(c: *mut c_void, s: *mut c_void) -> c_int { both::set_fmu_state::<V2, M>(c, s) }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2FreeFMUstate(c: *mut c_void, s: *mut *mut c_void) -> c_int {
                unsafe { both::free_fmu_state::<V2, M>(c, s) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2SerializedFMUstateSize(c: *mut c_void, s: *mut c_void, size: *mut usize) -> c_int {
                unsafe { both::serialized_size::<V2, M>(c, s, size) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2SerializeFMUstate(c: *mut c_void, s: *mut c_void, bytes: *mut u8, size: usize) -> c_int {
                unsafe { both::serialize::<V2, M>(c, s, bytes, size) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2DeSerializeFMUstate(c: *mut c_void, bytes: *const u8, size: usize, s: *mut *mut c_void) -> c_int {
                unsafe { both::deserialize::<V2, M>(c, bytes, size, s) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2GetDirectionalDerivative(c: *mut c_void, u: *const c_uint, nu: usize, k: *const c_uint, nk: usize, dk: *const f64, du: *mut f64) -> c_int {
                unsafe { both::get_directional_derivative::<V2, M>(c, u, nu, k, nk, dk, nk, du, nu) }
            }
            #[no_mangle]
            pub extern "C" fn fmi2EnterEventMode(c: *mut c_void) -> c_int { both::enter_event_mode::<V2, M>(c) }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2NewDiscreteStates(c: *mut c_void, info: *mut f2::Fmi2EventInfo) -> c_int {
                unsafe { f2::new_discrete_states::<M>(c, info) }
            }
            #[no_mangle]
            pub extern "C" fn fmi2EnterContinuousTimeMode(c: *mut c_void) -> c_int { both::enter_continuous_time_mode::<V2, M>(c) }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2CompletedIntegratorStep(c: *mut c_void, _no_prior: c_int, event: *mut c_int, stop: *mut c_int) -> c_int {
                unsafe { both::completed_integrator_step::<V2, M>(c, event, stop) }
            }
            #[no_mangle]
            pub extern "C" fn fmi2SetTime(c: *mut c_void, t: f64) -> c_int { both::set_time::<V2, M>(c, t) }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2SetContinuousStates(c: *mut c_void, x: *const f64, n: usize) -> c_int {
                unsafe { both::set_continuous_states::<V2, M>(c, x, n) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2GetDerivatives(c: *mut c_void, dx: *mut f64, n: usize) -> c_int {
                unsafe { both::get_derivatives::<V2, M>(c, dx, n) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2GetEventIndicators(c: *mut c_void, g: *mut f64, n: usize) -> c_int {
                unsafe { both::get_event_indicators::<V2, M>(c, g, n) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2GetContinuousStates(c: *mut c_void, x: *mut f64, n: usize) -> c_int {
                unsafe { both::get_continuous_states::<V2, M>(c, x, n) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2GetNominalsOfContinuousStates(c: *mut c_void, x: *mut f64, n: usize) -> c_int {
                unsafe { both::get_nominals::<V2, M>(c, x, n) }
            }
            #[no_mangle]
            pub extern "C" fn fmi2SetRealInputDerivatives(c: *mut c_void, _vr: *const c_uint, _n: usize, _order: *const c_int, _v: *const f64) -> c_int {
                f2::no_derivatives::<M>(c, "fmi2SetRealInputDerivatives")
            }
            #[no_mangle]
            pub extern "C" fn fmi2GetRealOutputDerivatives(c: *mut c_void, _vr: *const c_uint, _n: usize, _order: *const c_int, _v: *mut f64) -> c_int {
                f2::no_derivatives::<M>(c, "fmi2GetRealOutputDerivatives")
            }
            #[no_mangle]
            pub extern "C" fn fmi2DoStep(c: *mut c_void, t: f64, h: f64, no_prior: c_int) -> c_int {
                f2::do_step::<M>(c, t, h, no_prior)
            }
            #[no_mangle]
            pub extern "C" fn fmi2CancelStep(c: *mut c_void) -> c_int { f2::cancel_step::<M>(c) }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2GetStatus(c: *mut c_void, kind: c_int, v: *mut c_int) -> c_int {
                unsafe { f2::get_status::<M>(c, "fmi2GetStatus", kind, f2::StatusValue::Status(v)) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2GetRealStatus(c: *mut c_void, kind: c_int, v: *mut f64) -> c_int {
                unsafe { f2::get_status::<M>(c, "fmi2GetRealStatus", kind, f2::StatusValue::Real(v)) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2GetIntegerStatus(c: *mut c_void, kind: c_int, v: *mut c_int) -> c_int {
                unsafe { f2::get_status::<M>(c, "fmi2GetIntegerStatus", kind, f2::StatusValue::Integer(v)) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2GetBooleanStatus(c: *mut c_void, kind: c_int, v: *mut c_int) -> c_int {
                unsafe { f2::get_status::<M>(c, "fmi2GetBooleanStatus", kind, f2::StatusValue::Boolean(v)) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2GetStringStatus(c: *mut c_void, kind: c_int, v: *mut *const c_char) -> c_int {
                unsafe { f2::get_status::<M>(c, "fmi2GetStringStatus", kind, f2::StatusValue::Text(v, ::std::marker::PhantomData)) }
            }

            // ----- FMI 3.0 -----

            #[no_mangle]
            pub extern "C" fn fmi3GetVersion() -> *const c_char { f3::get_version() }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3SetDebugLogging(c: *mut c_void, on: bool, n: usize, categories: *const *const c_char) -> c_int {
                unsafe { both::set_debug_logging::<V3, M>(c, on, n, categories) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3InstantiateModelExchange(name: *const c_char, token: *const c_char, resources: *const c_char, visible: bool, logging_on: bool, env: *mut c_void, log: Option<f3::Fmi3LogMessage>) -> *mut c_void {
                unsafe { f3::instantiate_model_exchange::<M>(IDENTIFIER, name, token, resources, visible, logging_on, env, log) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3InstantiateCoSimulation(name: *const c_char, token: *const c_char, resources: *const c_char, visible: bool, logging_on: bool, event_mode_used: bool, early_return_allowed: bool, required: *const u32, n_required: usize, env: *mut c_void, log: Option<f3::Fmi3LogMessage>, intermediate: *const c_void) -> *mut c_void {
                unsafe { f3::instantiate_co_simulation::<M>(IDENTIFIER, name, token, resources, visible, logging_on, event_mode_used, early_return_allowed, required, n_required, env, log, intermediate) }
            }
            #[no_mangle]
            pub extern "C" fn fmi3InstantiateScheduledExecution(_name: *const c_char, _token: *const c_char, _resources: *const c_char, _visible: bool, _logging_on: bool, _env: *mut c_void, _log: Option<f3::Fmi3LogMessage>, _clock_update: *const c_void, _lock: *const c_void, _unlock: *const c_void) -> *mut c_void {
                f3::instantiate_scheduled_execution()
            }
            #[no_mangle]
            pub extern "C" fn fmi3FreeInstance(c: *mut c_void) { both::free_instance(c) }
            #[no_mangle]
            pub extern "C" fn fmi3EnterInitializationMode(c: *mut c_void, tol_defined: bool, tol: f64, start: f64, stop_defined: bool, stop: f64) -> c_int {
                f3::enter_initialization_mode::<M>(c, tol_defined, tol, start, stop_defined, stop)
            }
            #[no_mangle]
            pub extern "C" fn fmi3ExitInitializationMode(c: *mut c_void) -> c_int { both::exit_initialization_mode::<V3, M>(c) }
            #[no_mangle]
            pub extern "C" fn fmi3EnterEventMode(c: *mut c_void) -> c_int { both::enter_event_mode::<V3, M>(c) }
            #[no_mangle]
            pub extern "C" fn fmi3Terminate(c: *mut c_void) -> c_int { both::terminate::<V3, M>(c) }
            #[no_mangle]
            pub extern "C" fn fmi3Reset(c: *mut c_void) -> c_int { both::reset::<V3, M>(c) }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3GetFloat64(c: *mut c_void, vr: *const u32, n: usize, v: *mut f64, nv: usize) -> c_int {
                unsafe { both::get_real::<V3, M>(c, vr, n, v, nv) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3SetFloat64(c: *mut c_void, vr: *const u32, n: usize, v: *const f64, nv: usize) -> c_int {
                unsafe { both::set_real::<V3, M>(c, vr, n, v, nv) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3GetString(c: *mut c_void, vr: *const u32, n: usize, v: *mut *const c_char, nv: usize) -> c_int {
                unsafe { both::get_string::<V3, M>(c, vr, n, v, nv) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3SetString(c: *mut c_void, vr: *const u32, n: usize, v: *const *const c_char, nv: usize) -> c_int {
                unsafe { both::set_string::<V3, M>(c, vr, n, v, nv) }
            }
            $crate::export_fmu!(@none_of fmi3GetFloat32, fmi3SetFloat32, f32, "a Float32");
            $crate::export_fmu!(@none_of fmi3GetInt8, fmi3SetInt8, i8, "an Int8");
            $crate::export_fmu!(@none_of fmi3GetUInt8, fmi3SetUInt8, u8, "a UInt8");
            $crate::export_fmu!(@none_of fmi3GetInt16, fmi3SetInt16, i16, "an Int16");
            $crate::export_fmu!(@none_of fmi3GetUInt16, fmi3SetUInt16, u16, "a UInt16");
            $crate::export_fmu!(@none_of fmi3GetInt32, fmi3SetInt32, i32, "an Int32");
            $crate::export_fmu!(@none_of fmi3GetUInt32, fmi3SetUInt32, u32, "a UInt32");
            $crate::export_fmu!(@none_of fmi3GetInt64, fmi3SetInt64, i64, "an Int64");
            $crate::export_fmu!(@none_of fmi3GetUInt64, fmi3SetUInt64, u64, "a UInt64");
            $crate::export_fmu!(@none_of fmi3GetBoolean, fmi3SetBoolean, bool, "a Boolean");
            #[no_mangle]
            pub unsafe extern "C" fn fmi3GetBinary(c: *mut c_void, vr: *const u32, n: usize, _sizes: *mut usize, _v: *mut *const u8, _nv: usize) -> c_int {
                unsafe { both::no_such_values::<V3, M>(c, "fmi3GetBinary", "a Binary", vr, n) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3SetBinary(c: *mut c_void, vr: *const u32, n: usize, _sizes: *const usize, _v: *const *const u8, _nv: usize) -> c_int {
                unsafe { both::no_such_values::<V3, M>(c, "fmi3SetBinary", "a Binary", vr, n) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3GetClock(c: *mut c_void, vr: *const u32, n: usize, _v: *mut bool) -> c_int {
                unsafe { both::no_such_values::<V3, M>(c, "fmi3GetClock", "a Clock", vr, n) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3SetClock(c: *mut c_void, vr: *const u32, n: usize, _v: *const bool) -> c_int {
                unsafe { both::no_such_values::<V3, M>(c, "fmi3SetClock", "a Clock", vr, n) }
            }
            #[no_mangle]
            pub extern "C" fn fmi3GetNumberOfVariableDependencies(c: *mut c_void, _vr: u32, _n: *mut usize) -> c_int {
                f3::not_offered::<M>(c, "fmi3GetNumberOfVariableDependencies", "dependencies per element (providesPerElementDependencies): read them from the ModelStructure")
            }
            #[no_mangle]
            pub extern "C" fn fmi3GetVariableDependencies(c: *mut c_void, _vr: u32, _ed: *mut usize, _ind: *mut u32, _ei: *mut usize, _kinds: *mut c_int, _n: usize) -> c_int {
                f3::not_offered::<M>(c, "fmi3GetVariableDependencies", "dependencies per element (providesPerElementDependencies): read them from the ModelStructure")
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3GetFMUState(c: *mut c_void, s: *mut *mut c_void) -> c_int {
                unsafe { both::get_fmu_state::<V3, M>(c, s) }
            }
            #[no_mangle]
            pub extern "C" fn fmi3SetFMUState(c: *mut c_void, s: *mut c_void) -> c_int { both::set_fmu_state::<V3, M>(c, s) }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3FreeFMUState(c: *mut c_void, s: *mut *mut c_void) -> c_int {
                unsafe { both::free_fmu_state::<V3, M>(c, s) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3SerializedFMUStateSize(c: *mut c_void, s: *mut c_void, size: *mut usize) -> c_int {
                unsafe { both::serialized_size::<V3, M>(c, s, size) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3SerializeFMUState(c: *mut c_void, s: *mut c_void, bytes: *mut u8, size: usize) -> c_int {
                unsafe { both::serialize::<V3, M>(c, s, bytes, size) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3DeserializeFMUState(c: *mut c_void, bytes: *const u8, size: usize, s: *mut *mut c_void) -> c_int {
                unsafe { both::deserialize::<V3, M>(c, bytes, size, s) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3GetDirectionalDerivative(c: *mut c_void, u: *const u32, nu: usize, k: *const u32, nk: usize, seed: *const f64, ns: usize, out: *mut f64, no: usize) -> c_int {
                unsafe { both::get_directional_derivative::<V3, M>(c, u, nu, k, nk, seed, ns, out, no) }
            }
            #[no_mangle]
            pub extern "C" fn fmi3GetAdjointDerivative(c: *mut c_void, _u: *const u32, _nu: usize, _k: *const u32, _nk: usize, _seed: *const f64, _ns: usize, _out: *mut f64, _no: usize) -> c_int {
                f3::not_offered::<M>(c, "fmi3GetAdjointDerivative", "adjoint derivatives (providesAdjointDerivatives); use fmi3GetDirectionalDerivative")
            }
            #[no_mangle]
            pub extern "C" fn fmi3EnterConfigurationMode(c: *mut c_void) -> c_int {
                f3::not_offered::<M>(c, "fmi3EnterConfigurationMode", "structural parameters (configuration mode)")
            }
            #[no_mangle]
            pub extern "C" fn fmi3ExitConfigurationMode(c: *mut c_void) -> c_int {
                f3::not_offered::<M>(c, "fmi3ExitConfigurationMode", "structural parameters (configuration mode)")
            }
            #[no_mangle]
            pub extern "C" fn fmi3GetIntervalDecimal(c: *mut c_void, _vr: *const u32, _n: usize, _i: *mut f64, _q: *mut c_int) -> c_int {
                f3::not_offered::<M>(c, "fmi3GetIntervalDecimal", "clock variables (its clocks are time events)")
            }
            #[no_mangle]
            pub extern "C" fn fmi3GetIntervalFraction(c: *mut c_void, _vr: *const u32, _n: usize, _counters: *mut u64, _r: *mut u64, _q: *mut c_int) -> c_int {
                f3::not_offered::<M>(c, "fmi3GetIntervalFraction", "clock variables (its clocks are time events)")
            }
            #[no_mangle]
            pub extern "C" fn fmi3GetShiftDecimal(c: *mut c_void, _vr: *const u32, _n: usize, _s: *mut f64) -> c_int {
                f3::not_offered::<M>(c, "fmi3GetShiftDecimal", "clock variables (its clocks are time events)")
            }
            #[no_mangle]
            pub extern "C" fn fmi3GetShiftFraction(c: *mut c_void, _vr: *const u32, _n: usize, _counters: *mut u64, _r: *mut u64) -> c_int {
                f3::not_offered::<M>(c, "fmi3GetShiftFraction", "clock variables (its clocks are time events)")
            }
            #[no_mangle]
            pub extern "C" fn fmi3SetIntervalDecimal(c: *mut c_void, _vr: *const u32, _n: usize, _i: *const f64) -> c_int {
                f3::not_offered::<M>(c, "fmi3SetIntervalDecimal", "clock variables (its clocks are time events)")
            }
            #[no_mangle]
            pub extern "C" fn fmi3SetIntervalFraction(c: *mut c_void, _vr: *const u32, _n: usize, _counters: *const u64, _r: *const u64) -> c_int {
                f3::not_offered::<M>(c, "fmi3SetIntervalFraction", "clock variables (its clocks are time events)")
            }
            #[no_mangle]
            pub extern "C" fn fmi3SetShiftDecimal(c: *mut c_void, _vr: *const u32, _n: usize, _s: *const f64) -> c_int {
                f3::not_offered::<M>(c, "fmi3SetShiftDecimal", "clock variables (its clocks are time events)")
            }
            #[no_mangle]
            pub extern "C" fn fmi3SetShiftFraction(c: *mut c_void, _vr: *const u32, _n: usize, _counters: *const u64, _r: *const u64) -> c_int {
                f3::not_offered::<M>(c, "fmi3SetShiftFraction", "clock variables (its clocks are time events)")
            }
            #[no_mangle]
            pub extern "C" fn fmi3EvaluateDiscreteStates(c: *mut c_void) -> c_int {
                f3::not_offered::<M>(c, "fmi3EvaluateDiscreteStates", "fmi3EvaluateDiscreteStates (providesEvaluateDiscreteStates); its discrete values change in fmi3UpdateDiscreteStates")
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3UpdateDiscreteStates(c: *mut c_void, need: *mut bool, stop: *mut bool, nominals: *mut bool, values: *mut bool, defined: *mut bool, next: *mut f64) -> c_int {
                unsafe { f3::update_discrete_states::<M>(c, need, stop, nominals, values, defined, next) }
            }
            #[no_mangle]
            pub extern "C" fn fmi3EnterContinuousTimeMode(c: *mut c_void) -> c_int { both::enter_continuous_time_mode::<V3, M>(c) }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3CompletedIntegratorStep(c: *mut c_void, _no_prior: bool, event: *mut bool, stop: *mut bool) -> c_int {
                unsafe { both::completed_integrator_step::<V3, M>(c, event, stop) }
            }
            #[no_mangle]
            pub extern "C" fn fmi3SetTime(c: *mut c_void, t: f64) -> c_int { both::set_time::<V3, M>(c, t) }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3SetContinuousStates(c: *mut c_void, x: *const f64, n: usize) -> c_int {
                unsafe { both::set_continuous_states::<V3, M>(c, x, n) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3GetContinuousStateDerivatives(c: *mut c_void, dx: *mut f64, n: usize) -> c_int {
                unsafe { both::get_derivatives::<V3, M>(c, dx, n) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3GetEventIndicators(c: *mut c_void, g: *mut f64, n: usize) -> c_int {
                unsafe { both::get_event_indicators::<V3, M>(c, g, n) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3GetContinuousStates(c: *mut c_void, x: *mut f64, n: usize) -> c_int {
                unsafe { both::get_continuous_states::<V3, M>(c, x, n) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3GetNominalsOfContinuousStates(c: *mut c_void, x: *mut f64, n: usize) -> c_int {
                unsafe { both::get_nominals::<V3, M>(c, x, n) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3GetNumberOfEventIndicators(c: *mut c_void, n: *mut usize) -> c_int {
                unsafe { f3::get_number_of::<M>(c, "fmi3GetNumberOfEventIndicators", true, n) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3GetNumberOfContinuousStates(c: *mut c_void, n: *mut usize) -> c_int {
                unsafe { f3::get_number_of::<M>(c, "fmi3GetNumberOfContinuousStates", false, n) }
            }
            #[no_mangle]
            pub extern "C" fn fmi3EnterStepMode(c: *mut c_void) -> c_int { f3::enter_step_mode::<M>(c) }
            #[no_mangle]
            pub extern "C" fn fmi3GetOutputDerivatives(c: *mut c_void, _vr: *const u32, _n: usize, _orders: *const i32, _v: *mut f64, _nv: usize) -> c_int {
                f3::not_offered::<M>(c, "fmi3GetOutputDerivatives", "output derivatives (maxOutputDerivativeOrder is 0)")
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi3DoStep(c: *mut c_void, t: f64, h: f64, no_prior: bool, event: *mut bool, stop: *mut bool, early: *mut bool, last: *mut f64) -> c_int {
                unsafe { f3::do_step::<M>(c, t, h, no_prior, event, stop, early, last) }
            }
            #[no_mangle]
            pub extern "C" fn fmi3ActivateModelPartition(c: *mut c_void, _clock: u32, _t: f64) -> c_int {
                f3::not_offered::<M>(c, "fmi3ActivateModelPartition", "scheduled execution")
            }
        };
    };
    (@none_of $get:ident, $set:ident, $t:ty, $kind:literal) => {
        #[no_mangle]
        pub unsafe extern "C" fn $get(c: *mut c_void, vr: *const u32, n: usize, _v: *mut $t, _nv: usize) -> c_int {
            unsafe { both::no_such_values::<V3, M>(c, stringify!($get), $kind, vr, n) }
        }
        #[no_mangle]
        pub unsafe extern "C" fn $set(c: *mut c_void, vr: *const u32, n: usize, _v: *const $t, _nv: usize) -> c_int {
            unsafe { both::no_such_values::<V3, M>(c, stringify!($set), $kind, vr, n) }
        }
    };
}
