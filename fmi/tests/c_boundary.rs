//! The exported C functions called as an importer calls them, rightly and
//! wrongly: every misuse answered with the error status and a message
//! through the importer's callback, never a crash; Model Exchange driven
//! step by step (events, a DAE's projection); directional derivatives
//! against the exact Jacobian; FMU states saved, restored and serialized;
//! instances on several threads.

mod support;

use libloading::{Library, Symbol};
use std::ffi::{c_char, c_int, c_void, CStr, CString};
use std::ptr::{null, null_mut};
use std::sync::Mutex;

const OK: c_int = 0;
const DISCARD: c_int = 2;
const ERROR: c_int = 3;

type Instance = *mut c_void;
type Log = unsafe extern "C" fn(*mut c_void, c_int, *const c_char, *const c_char);

/// What an instance logged: (status, message).
type Messages = Mutex<Vec<(c_int, String)>>;

unsafe extern "C" fn log(
    env: *mut c_void,
    status: c_int,
    _category: *const c_char,
    message: *const c_char,
) {
    // SAFETY: env is the test's `Messages`, the message a C string.
    let messages = unsafe { &*(env as *const Messages) };
    let text = unsafe { CStr::from_ptr(message) }.to_string_lossy().into_owned();
    messages.lock().unwrap().push((status, text));
}

/// One exported library, called through FMI 3.0's functions.
struct Fmu {
    lib: Library,
    token: CString,
    messages: Box<Messages>,
}

macro_rules! call {
    ($fmu:expr, $name:literal : fn($($t:ty),*) -> $r:ty, $($arg:expr),*) => {{
        // SAFETY: the symbol of FMI 3.0 of this signature.
        unsafe {
            let f: Symbol<'_, unsafe extern "C" fn($($t),*) -> $r> =
                $fmu.lib.get(concat!($name, "\0").as_bytes()).expect($name);
            f($($arg),*)
        }
    }};
}

impl Fmu {
    fn load(example: &str) -> Fmu {
        let path = support::library(example);
        // SAFETY: our own library, built by cargo.
        let lib = unsafe { Library::new(&path) }.expect("the library loads");
        let xml = {
            // SAFETY: the symbol export_fmu! defines.
            let describe: Symbol<'_, unsafe extern "C" fn(c_int) -> *const c_char> =
                unsafe { lib.get(b"daegen_fmi_model_description\0") }.unwrap();
            unsafe { CStr::from_ptr(describe(3)) }.to_string_lossy().into_owned()
        };
        let token = xml.split("instantiationToken=\"").nth(1).unwrap().split('"').next().unwrap();
        Fmu { lib, token: CString::new(token).unwrap(), messages: Box::new(Mutex::new(Vec::new())) }
    }

    fn env(&self) -> *mut c_void {
        &*self.messages as *const Messages as *mut c_void
    }

    fn me(&self) -> Instance {
        call!(self, "fmi3InstantiateModelExchange": fn(*const c_char, *const c_char, *const c_char, bool, bool, *mut c_void, Option<Log>) -> Instance,
            c"me".as_ptr(), self.token.as_ptr(), null(), false, false, self.env(), Some(log))
    }

    fn cs(&self) -> Instance {
        call!(self, "fmi3InstantiateCoSimulation": fn(*const c_char, *const c_char, *const c_char, bool, bool, bool, bool, *const u32, usize, *mut c_void, Option<Log>, *const c_void) -> Instance,
            c"cs".as_ptr(), self.token.as_ptr(), null(), false, false, false, false, null(), 0, self.env(), Some(log), null())
    }

    fn init(&self, c: Instance, tolerance: Option<f64>) {
        let s = call!(self, "fmi3EnterInitializationMode": fn(Instance, bool, f64, f64, bool, f64) -> c_int,
            c, tolerance.is_some(), tolerance.unwrap_or(0.0), 0.0, false, 0.0);
        assert_eq!(s, OK, "{:?}", self.messages.lock().unwrap());
        assert_eq!(
            call!(self, "fmi3ExitInitializationMode": fn(Instance) -> c_int, c),
            OK,
            "{:?}",
            self.messages.lock().unwrap()
        );
    }

    fn get(&self, c: Instance, vr: u32) -> (c_int, f64) {
        let mut v = f64::NAN;
        let s = call!(self, "fmi3GetFloat64": fn(Instance, *const u32, usize, *mut f64, usize) -> c_int, c, &vr, 1, &mut v, 1);
        (s, v)
    }

    fn set(&self, c: Instance, vr: u32, v: f64) -> c_int {
        call!(self, "fmi3SetFloat64": fn(Instance, *const u32, usize, *const f64, usize) -> c_int, c, &vr, 1, &v, 1)
    }

    fn do_step(&self, c: Instance, t: f64, h: f64) -> (c_int, bool, f64) {
        let (mut event, mut stop, mut early, mut last) = (false, false, false, 0.0);
        let s = call!(self, "fmi3DoStep": fn(Instance, f64, f64, bool, *mut bool, *mut bool, *mut bool, *mut f64) -> c_int,
            c, t, h, false, &mut event, &mut stop, &mut early, &mut last);
        (s, stop, last)
    }

    fn free(&self, c: Instance) {
        call!(self, "fmi3FreeInstance": fn(Instance) -> (), c);
    }

    /// The last message logged, which must exist and contain `part`.
    fn said(&self, part: &str) -> String {
        let messages = self.messages.lock().unwrap();
        let (status, text) = messages.last().cloned().expect("a message was logged");
        assert_eq!(status, ERROR, "{text}");
        assert!(text.contains(part), "the message `{text}` does not say `{part}`");
        text
    }
}

// Value references of the Van der Pol example: time, x, der(x), der(x,2),
// mu, energy, solver.method, solver.tolerance.
const X: u32 = 1;
const V: u32 = 2;
const A: u32 = 3;
const MU: u32 = 4;
const ENERGY: u32 = 5;
const METHOD: u32 = 6;

#[test]
fn misuse_is_refused_with_a_message_and_never_crashes() {
    let fmu = Fmu::load("van_der_pol_fmu");
    // A null, an unknown and a freed instance: refused without a callback
    // to log through.
    assert_eq!(fmu.get(null_mut(), X).0, ERROR);
    assert_eq!(fmu.get(0xdead_beef as Instance, X).0, ERROR);
    let gone = fmu.me();
    fmu.free(gone);
    assert_eq!(fmu.get(gone, X).0, ERROR);
    assert_eq!(
        call!(fmu, "fmi3DoStep": fn(Instance, f64, f64, bool, *mut bool, *mut bool, *mut bool, *mut f64) -> c_int,
        gone, 0.0, 0.1, false, null_mut(), null_mut(), null_mut(), null_mut()),
        ERROR
    );
    fmu.free(gone); // twice: nothing happens

    // A wrong instantiation token: no instance, and the reason.
    let bad = call!(fmu, "fmi3InstantiateModelExchange": fn(*const c_char, *const c_char, *const c_char, bool, bool, *mut c_void, Option<Log>) -> Instance,
        c"bad".as_ptr(), c"{00000000-0000-0000-0000-000000000000}".as_ptr(), null(), false, false, fmu.env(), Some(log));
    assert!(bad.is_null());
    fmu.said("is not this FMU's");
    // A null token and a null name.
    let bad = call!(fmu, "fmi3InstantiateModelExchange": fn(*const c_char, *const c_char, *const c_char, bool, bool, *mut c_void, Option<Log>) -> Instance,
        null(), null(), null(), false, false, fmu.env(), Some(log));
    assert!(bad.is_null());
    fmu.said("null pointer");
    // No logger at all: still no crash.
    let quiet = call!(fmu, "fmi3InstantiateModelExchange": fn(*const c_char, *const c_char, *const c_char, bool, bool, *mut c_void, Option<Log>) -> Instance,
        null(), fmu.token.as_ptr(), null(), false, false, null_mut(), None);
    assert!(!quiet.is_null());
    assert_eq!(fmu.get(quiet, 999).0, ERROR);
    fmu.free(quiet);

    let c = fmu.me();
    // Calls in the wrong state.
    let mut dx = [0.0; 2];
    let s = call!(fmu, "fmi3GetContinuousStateDerivatives": fn(Instance, *mut f64, usize) -> c_int, c, dx.as_mut_ptr(), 2);
    assert_eq!(s, ERROR);
    fmu.said("not allowed in Instantiated");
    assert_eq!(call!(fmu, "fmi3ExitInitializationMode": fn(Instance) -> c_int, c), ERROR);
    fmu.said("not allowed in Instantiated");
    let (s, _, _) = fmu.do_step(c, 0.0, 0.1);
    assert_eq!(s, ERROR);
    fmu.said("belongs to Co-Simulation");
    // Unknown value references, calculated variables, non-finite values.
    assert_eq!(fmu.set(c, 999, 1.0), ERROR);
    fmu.said("no variable with value reference 999");
    assert_eq!(fmu.set(c, ENERGY, 1.0), ERROR);
    fmu.said("`energy` is calculated");
    assert_eq!(fmu.set(c, MU, f64::NAN), ERROR);
    fmu.said("not finite");
    // Null arrays with values to read, and counts that disagree.
    let s = call!(fmu, "fmi3GetFloat64": fn(Instance, *const u32, usize, *mut f64, usize) -> c_int, c, null(), 2, dx.as_mut_ptr(), 2);
    assert_eq!(s, ERROR);
    fmu.said("null pointer");
    let vrs = [X, V];
    let s = call!(fmu, "fmi3GetFloat64": fn(Instance, *const u32, usize, *mut f64, usize) -> c_int, c, vrs.as_ptr(), 2, dx.as_mut_ptr(), 1);
    assert_eq!(s, ERROR);
    fmu.said("every variable of this FMU is a scalar");
    // Types the FMU has none of, and strings that are not methods.
    let mut i = 0i32;
    let s = call!(fmu, "fmi3GetInt32": fn(Instance, *const u32, usize, *mut i32, usize) -> c_int, c, &X, 1, &mut i, 1);
    assert_eq!(s, ERROR);
    fmu.said("is not an Int32");
    let name = c"Euler7";
    let s = call!(fmu, "fmi3SetString": fn(Instance, *const u32, usize, *const *const c_char, usize) -> c_int, c, &METHOD, 1, &name.as_ptr(), 1);
    assert_eq!(s, ERROR);
    fmu.said("use one of Auto, Taylor, Dopri5, Dop853, Radau5, Rodas5P");
    // What the FMU does not offer is refused, not missing.
    assert_eq!(call!(fmu, "fmi3EnterConfigurationMode": fn(Instance) -> c_int, c), ERROR);
    fmu.said("does not offer structural parameters");

    fmu.init(c, None);
    // Event mode now: integrator calls belong to continuous-time mode.
    let x = [1.0, 0.0];
    let s = call!(fmu, "fmi3SetContinuousStates": fn(Instance, *const f64, usize) -> c_int, c, x.as_ptr(), 2);
    assert_eq!(s, ERROR);
    fmu.said("not allowed in Event Mode");
    assert_eq!(call!(fmu, "fmi3EnterContinuousTimeMode": fn(Instance) -> c_int, c), OK);
    let s = call!(fmu, "fmi3SetContinuousStates": fn(Instance, *const f64, usize) -> c_int, c, x.as_ptr(), 3);
    assert_eq!(s, ERROR);
    fmu.said("3 continuous states given; VanDerPol has 2");
    let bad = [f64::INFINITY, 0.0];
    let s = call!(fmu, "fmi3SetContinuousStates": fn(Instance, *const f64, usize) -> c_int, c, bad.as_ptr(), 2);
    assert_eq!(s, ERROR);
    fmu.said("not finite");
    assert_eq!(call!(fmu, "fmi3SetTime": fn(Instance, f64) -> c_int, c, f64::NAN), ERROR);
    fmu.said("not finite");
    // A state set after initialization by SetFloat64: refused.
    assert_eq!(fmu.set(c, X, 1.0), ERROR);
    fmu.said("SetContinuousStates");
    let (mut event, mut stop) = (false, false);
    let s = call!(fmu, "fmi3CompletedIntegratorStep": fn(Instance, bool, *mut bool, *mut bool) -> c_int, c, false, null_mut(), &mut stop);
    assert_eq!(s, ERROR);
    fmu.said("`enterEventMode` is a null pointer");
    let s = call!(fmu, "fmi3CompletedIntegratorStep": fn(Instance, bool, *mut bool, *mut bool) -> c_int, c, false, &mut event, &mut stop);
    assert_eq!(s, OK);
    assert!(!event && !stop);
    assert_eq!(call!(fmu, "fmi3Terminate": fn(Instance) -> c_int, c), OK);
    assert_eq!(call!(fmu, "fmi3Terminate": fn(Instance) -> c_int, c), ERROR);
    fmu.said("not allowed in Terminated");
    // Reset: back to the start, usable again.
    assert_eq!(call!(fmu, "fmi3Reset": fn(Instance) -> c_int, c), OK);
    fmu.init(c, None);
    fmu.free(c);
}

#[test]
fn a_failing_step_is_an_error_with_the_reason_and_the_state_before_it() {
    let fmu = Fmu::load("van_der_pol_fmu");
    let c = fmu.cs();
    // DOPRI5 on a stiff Van der Pol stops where it detects stiffness.
    let name = c"Dopri5";
    let s = call!(fmu, "fmi3SetString": fn(Instance, *const u32, usize, *const *const c_char, usize) -> c_int, c, &METHOD, 1, &name.as_ptr(), 1);
    assert_eq!(s, OK);
    assert_eq!(fmu.set(c, MU, 1e5), OK);
    fmu.init(c, None);
    // A communication point that is not the FMU's time, a negative step.
    assert_eq!(fmu.do_step(c, 0.5, 0.1).0, ERROR);
    fmu.said("is not the instance's time 0");
    assert_eq!(fmu.do_step(c, 0.0, -0.1).0, ERROR);
    fmu.said("not positive");
    let (s, _, last) = fmu.do_step(c, 0.0, 100.0);
    assert_eq!(s, ERROR);
    let text = fmu.said("failed");
    assert!(text.contains("Dopri5") && text.contains("stiff"), "{text}");
    assert_eq!(last, 0.0);
    // The state before the step is still readable; no further step.
    assert_eq!(fmu.get(c, X), (OK, 2.0));
    assert_eq!(fmu.do_step(c, 0.0, 0.1).0, ERROR);
    fmu.said("not allowed in Step Failed");
    assert_eq!(call!(fmu, "fmi3Terminate": fn(Instance) -> c_int, c), OK);
    fmu.free(c);
}

#[test]
fn directional_derivatives_are_the_exact_jacobian() {
    let fmu = Fmu::load("van_der_pol_fmu");
    let c = fmu.me();
    assert_eq!(fmu.set(c, MU, 1.5), OK);
    fmu.init(c, None);
    assert_eq!(call!(fmu, "fmi3EnterContinuousTimeMode": fn(Instance) -> c_int, c), OK);
    let (x, v) = (0.7, -1.3);
    let state = [x, v];
    assert_eq!(
        call!(fmu, "fmi3SetContinuousStates": fn(Instance, *const f64, usize) -> c_int, c, state.as_ptr(), 2),
        OK
    );
    // a = μ(1 − x²)v − x: ∂a/∂x = −2μxv − 1, ∂a/∂v = μ(1 − x²).
    let derivative = |unknown: u32, known: u32| {
        let mut out = f64::NAN;
        let s = call!(fmu, "fmi3GetDirectionalDerivative": fn(Instance, *const u32, usize, *const u32, usize, *const f64, usize, *mut f64, usize) -> c_int,
            c, &unknown, 1, &known, 1, &1.0, 1, &mut out, 1);
        assert_eq!(s, OK);
        out
    };
    let close = |a: f64, b: f64| (a - b).abs() <= 4.0 * f64::EPSILON * b.abs();
    assert!(close(derivative(A, X), -2.0 * 1.5 * x * v - 1.0));
    assert!(close(derivative(A, V), 1.5 * (1.0 - x * x)));
    assert_eq!(derivative(V, V), 1.0);
    assert_eq!(derivative(V, X), 0.0);
    // The energy x² + v² by differences: 2x, within their error.
    assert!((derivative(ENERGY, X) - 2.0 * x).abs() < 1e-9);
    // With respect to the parameter: ∂a/∂μ = (1 − x²)v.
    assert!((derivative(A, MU) - (1.0 - x * x) * v).abs() < 1e-9);
    // A time derivative of nothing: refused.
    let mut out = 0.0;
    let s = call!(fmu, "fmi3GetDirectionalDerivative": fn(Instance, *const u32, usize, *const u32, usize, *const f64, usize, *mut f64, usize) -> c_int,
        c, &A, 1, &ENERGY, 1, &1.0, 1, &mut out, 1);
    assert_eq!(s, ERROR);
    fmu.said("is not a known");
    fmu.free(c);
}

#[test]
fn fmu_states_restore_a_co_simulation_bit_for_bit() {
    let fmu = Fmu::load("van_der_pol_fmu");
    let c = fmu.cs();
    fmu.init(c, Some(1e-10));
    assert_eq!(fmu.do_step(c, 0.0, 1.0).0, OK);
    let mut saved: *mut c_void = null_mut();
    assert_eq!(
        call!(fmu, "fmi3GetFMUState": fn(Instance, *mut *mut c_void) -> c_int, c, &mut saved),
        OK
    );
    assert_eq!(fmu.do_step(c, 1.0, 1.0).0, OK);
    let first = fmu.get(c, X).1;
    // Back to t = 1 and again: the same step.
    assert_eq!(call!(fmu, "fmi3SetFMUState": fn(Instance, *mut c_void) -> c_int, c, saved), OK);
    assert_eq!(fmu.get(c, 0).1, 1.0);
    assert_eq!(fmu.do_step(c, 1.0, 1.0).0, OK);
    assert_eq!(fmu.get(c, X).1.to_bits(), first.to_bits());
    // Serialized and read back, into another instance.
    let mut size = 0usize;
    assert_eq!(
        call!(fmu, "fmi3SerializedFMUStateSize": fn(Instance, *mut c_void, *mut usize) -> c_int, c, saved, &mut size),
        OK
    );
    let mut bytes = vec![0u8; size];
    assert_eq!(
        call!(fmu, "fmi3SerializeFMUState": fn(Instance, *mut c_void, *mut u8, usize) -> c_int, c, saved, bytes.as_mut_ptr(), size),
        OK
    );
    let other = fmu.cs();
    let mut copy: *mut c_void = null_mut();
    assert_eq!(
        call!(fmu, "fmi3DeserializeFMUState": fn(Instance, *const u8, usize, *mut *mut c_void) -> c_int, other, bytes.as_ptr(), size, &mut copy),
        OK
    );
    assert_eq!(call!(fmu, "fmi3SetFMUState": fn(Instance, *mut c_void) -> c_int, other, copy), OK);
    assert_eq!(fmu.do_step(other, 1.0, 1.0).0, OK);
    assert_eq!(fmu.get(other, X).1.to_bits(), first.to_bits());
    // Garbage, a short buffer, and a freed state: refused.
    let garbage = [7u8; 24];
    let mut junk: *mut c_void = null_mut();
    assert_eq!(
        call!(fmu, "fmi3DeserializeFMUState": fn(Instance, *const u8, usize, *mut *mut c_void) -> c_int, other, garbage.as_ptr(), 24, &mut junk),
        ERROR
    );
    fmu.said("is not one of VanDerPol");
    assert_eq!(
        call!(fmu, "fmi3SerializeFMUState": fn(Instance, *mut c_void, *mut u8, usize) -> c_int, c, saved, bytes.as_mut_ptr(), size - 8),
        ERROR
    );
    fmu.said("the buffer has");
    assert_eq!(
        call!(fmu, "fmi3FreeFMUState": fn(Instance, *mut *mut c_void) -> c_int, c, &mut saved),
        OK
    );
    assert!(saved.is_null());
    assert_eq!(call!(fmu, "fmi3SetFMUState": fn(Instance, *mut c_void) -> c_int, c, copy), OK);
    assert_eq!(
        call!(fmu, "fmi3FreeFMUState": fn(Instance, *mut *mut c_void) -> c_int, c, &mut copy),
        OK
    );
    assert_eq!(
        call!(fmu, "fmi3SetFMUState": fn(Instance, *mut c_void) -> c_int, c, 12345 as *mut c_void),
        ERROR
    );
    fmu.said("is not a live FMU state");
    fmu.free(c);
    fmu.free(other);
}

#[test]
fn instances_run_on_several_threads_at_once() {
    let fmu = Fmu::load("van_der_pol_fmu");
    let run = |mu: f64| {
        let c = fmu.cs();
        assert_eq!(fmu.set(c, MU, mu), OK);
        fmu.init(c, Some(1e-9));
        for k in 0..20 {
            assert_eq!(fmu.do_step(c, k as f64 * 0.25, 0.25).0, OK);
        }
        let x = fmu.get(c, X).1;
        fmu.free(c);
        x
    };
    let alone: Vec<f64> = [0.5, 1.0, 2.0, 3.0].iter().map(|&mu| run(mu)).collect();
    let together: Vec<f64> = std::thread::scope(|s| {
        let handles: Vec<_> =
            [0.5, 1.0, 2.0, 3.0].iter().map(|&mu| s.spawn(move || run(mu))).collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    assert_eq!(alone, together);
    // One instance called from two threads at once: each call is done or
    // refused whole, none crashes, and the instance stays usable.
    let c = fmu.cs();
    fmu.init(c, None);
    let handle = c as usize;
    std::thread::scope(|s| {
        for _ in 0..2 {
            s.spawn(|| {
                for _ in 0..2000 {
                    let (status, v) = fmu.get(handle as Instance, X);
                    assert!(status == OK && v == 2.0 || status == ERROR, "{status} {v}");
                }
            });
        }
    });
    assert_eq!(fmu.get(c, X), (OK, 2.0));
    fmu.free(c);
}

/// Model Exchange driven as an importer drives it: RK4 steps, the event
/// indicators checked after each, event mode where one changes sign.
fn drive(
    fmu: &Fmu,
    c: Instance,
    n: usize,
    t1: f64,
    steps: usize,
    mut on_event: impl FnMut(f64, &[f64]),
) -> Vec<f64> {
    let mut x = vec![0.0; n];
    let mut g = vec![0.0; 1];
    let ni = {
        let mut k = 0usize;
        call!(fmu, "fmi3GetNumberOfEventIndicators": fn(Instance, *mut usize) -> c_int, c, &mut k);
        k
    };
    g.resize(ni, 0.0);
    let update = |fmu: &Fmu| {
        let (mut need, mut stop, mut nominals, mut changed, mut defined, mut next) =
            (false, false, false, false, false, 0.0);
        let s = call!(fmu, "fmi3UpdateDiscreteStates": fn(Instance, *mut bool, *mut bool, *mut bool, *mut bool, *mut bool, *mut f64) -> c_int,
            c, &mut need, &mut stop, &mut nominals, &mut changed, &mut defined, &mut next);
        assert_eq!(s, OK, "{:?}", fmu.messages.lock().unwrap());
        changed
    };
    update(fmu);
    assert_eq!(call!(fmu, "fmi3EnterContinuousTimeMode": fn(Instance) -> c_int, c), OK);
    call!(fmu, "fmi3GetContinuousStates": fn(Instance, *mut f64, usize) -> c_int, c, x.as_mut_ptr(), n);
    call!(fmu, "fmi3GetEventIndicators": fn(Instance, *mut f64, usize) -> c_int, c, g.as_mut_ptr(), ni);
    let h = t1 / steps as f64;
    let rates = |t: f64, x: &[f64]| {
        let mut dx = vec![0.0; n];
        call!(fmu, "fmi3SetTime": fn(Instance, f64) -> c_int, c, t);
        call!(fmu, "fmi3SetContinuousStates": fn(Instance, *const f64, usize) -> c_int, c, x.as_ptr(), n);
        let s = call!(fmu, "fmi3GetContinuousStateDerivatives": fn(Instance, *mut f64, usize) -> c_int, c, dx.as_mut_ptr(), n);
        assert_eq!(s, OK);
        dx
    };
    for k in 0..steps {
        let t = k as f64 * h;
        let k1 = rates(t, &x);
        let k2 = rates(
            t + h / 2.0,
            &x.iter().zip(&k1).map(|(x, d)| x + h / 2.0 * d).collect::<Vec<_>>(),
        );
        let k3 = rates(
            t + h / 2.0,
            &x.iter().zip(&k2).map(|(x, d)| x + h / 2.0 * d).collect::<Vec<_>>(),
        );
        let k4 = rates(t + h, &x.iter().zip(&k3).map(|(x, d)| x + h * d).collect::<Vec<_>>());
        for i in 0..n {
            x[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
        call!(fmu, "fmi3SetTime": fn(Instance, f64) -> c_int, c, t + h);
        call!(fmu, "fmi3SetContinuousStates": fn(Instance, *const f64, usize) -> c_int, c, x.as_ptr(), n);
        let mut g_new = vec![0.0; ni];
        call!(fmu, "fmi3GetEventIndicators": fn(Instance, *mut f64, usize) -> c_int, c, g_new.as_mut_ptr(), ni);
        let crossed = g.iter().zip(&g_new).any(|(a, b)| (a > &0.0) != (b > &0.0));
        let (mut step_event, mut stop) = (false, false);
        call!(fmu, "fmi3CompletedIntegratorStep": fn(Instance, bool, *mut bool, *mut bool) -> c_int, c, true, &mut step_event, &mut stop);
        if crossed || step_event {
            assert_eq!(call!(fmu, "fmi3EnterEventMode": fn(Instance) -> c_int, c), OK);
            if update(fmu) {
                call!(fmu, "fmi3GetContinuousStates": fn(Instance, *mut f64, usize) -> c_int, c, x.as_mut_ptr(), n);
            }
            on_event(t + h, &x);
            assert_eq!(call!(fmu, "fmi3EnterContinuousTimeMode": fn(Instance) -> c_int, c), OK);
        }
        call!(fmu, "fmi3GetEventIndicators": fn(Instance, *mut f64, usize) -> c_int, c, g_new.as_mut_ptr(), ni);
        g = g_new;
    }
    x
}

#[test]
fn model_exchange_projects_a_drifting_dae_back_onto_its_constraints() {
    let fmu = Fmu::load("pendulum_fmu");
    let c = fmu.me();
    fmu.init(c, Some(1e-8));
    let mut projections = 0;
    // RK4 with a coarse step (0.02) drifts off x² + y² = 1 past the
    // tolerance, 1e-8, at nearly every step: the FMU asks for an event
    // and projects the state onto the constraint and its hidden level.
    let x = drive(&fmu, c, 4, 2.0, 100, |_, x| {
        projections += 1;
        let position = x[0] * x[0] + x[1] * x[1] - 1.0;
        let velocity = x[0] * x[2] + x[1] * x[3];
        assert!(position.abs() < 1e-12 && velocity.abs() < 1e-12, "{position:e} {velocity:e}");
    });
    println!("{projections} projections");
    assert!(projections > 10, "{projections} projections");
    assert!((x[0] * x[0] + x[1] * x[1] - 1.0).abs() < 1e-7);
    fmu.free(c);
}

#[test]
fn model_exchange_acts_on_events_in_their_direction() {
    let fmu = Fmu::load("bouncing_ball_fmu");
    let c = fmu.me();
    fmu.init(c, None);
    let mut bounces = Vec::new();
    // Each bounce: the speed reversed and scaled by e = 0.8 where the
    // height crossed zero falling; no action where it rises through zero
    // after the bounce.
    drive(&fmu, c, 2, 2.5, 25_000, |t, x| {
        if x[1] > 0.0 && x[0] <= 0.0 {
            bounces.push((t, x[1]));
        }
    });
    // Impact k at t₁(1 + 2e(1 − e^(k−1))/(1 − e)), t₁ = √(2/g), with
    // speed e^k √(2g): each impact located to within a step (1e-4), so
    // the k-th within k steps.
    let (g, e) = (9.81f64, 0.8f64);
    let t1 = (2.0 / g).sqrt();
    assert!(bounces.len() >= 3, "{bounces:?}");
    for (k, &(t, v)) in bounces.iter().take(3).enumerate() {
        let k = k as i32 + 1;
        let exact = t1 * (1.0 + 2.0 * e * (1.0 - e.powi(k - 1)) / (1.0 - e));
        assert!((t - exact).abs() <= k as f64 * 1e-4, "impact {k}: {t} vs {exact}");
        assert!((v - e.powi(k) * (2.0 * g).sqrt()).abs() < 2e-3, "impact {k}: {v}");
    }
    fmu.free(c);
}

#[test]
fn fmi2_answers_misuse_with_the_error_status() {
    // FMI 2.0's logger is printf-like, which Rust cannot define: these
    // checks read the statuses, with no logger given.
    let path = support::library("bouncing_ball_fmu");
    // SAFETY: our own library.
    let lib = unsafe { Library::new(&path) }.unwrap();
    let fmu = Fmu { lib, token: CString::default(), messages: Box::new(Mutex::new(Vec::new())) };
    let xml = {
        let describe: Symbol<'_, unsafe extern "C" fn(c_int) -> *const c_char> =
            unsafe { fmu.lib.get(b"daegen_fmi_model_description\0") }.unwrap();
        unsafe { CStr::from_ptr(describe(2)) }.to_string_lossy().into_owned()
    };
    let guid =
        CString::new(xml.split("guid=\"").nth(1).unwrap().split('"').next().unwrap()).unwrap();
    #[repr(C)]
    struct Callbacks {
        logger: *const c_void,
        allocate: *const c_void,
        free: *const c_void,
        step_finished: *const c_void,
        env: *mut c_void,
    }
    let callbacks = Callbacks {
        logger: null(),
        allocate: null(),
        free: null(),
        step_finished: null(),
        env: null_mut(),
    };
    let instantiate = |kind: c_int, guid: *const c_char, functions: *const Callbacks| {
        call!(fmu, "fmi2Instantiate": fn(*const c_char, c_int, *const c_char, *const c_char, *const Callbacks, c_int, c_int) -> Instance,
            c"ball".as_ptr(), kind, guid, null(), functions, 0, 0)
    };
    assert!(instantiate(0, c"{wrong}".as_ptr(), &callbacks).is_null());
    assert!(instantiate(7, guid.as_ptr(), &callbacks).is_null());
    // No callbacks at all: allowed, silent.
    let c = instantiate(1, guid.as_ptr(), null());
    assert!(!c.is_null());
    assert_eq!(
        call!(fmu, "fmi2DoStep": fn(Instance, f64, f64, c_int) -> c_int, c, 0.0, 0.1, 0),
        ERROR
    );
    assert_eq!(
        call!(fmu, "fmi2SetupExperiment": fn(Instance, c_int, f64, f64, c_int, f64) -> c_int, c, 1, 1e-10, 0.0, 1, -1.0),
        ERROR
    );
    assert_eq!(
        call!(fmu, "fmi2SetupExperiment": fn(Instance, c_int, f64, f64, c_int, f64) -> c_int, c, 1, 1e-10, 0.0, 0, 0.0),
        OK
    );
    assert_eq!(call!(fmu, "fmi2EnterInitializationMode": fn(Instance) -> c_int, c), OK);
    assert_eq!(call!(fmu, "fmi2ExitInitializationMode": fn(Instance) -> c_int, c), OK);
    let mut x = [0.0; 2];
    assert_eq!(
        call!(fmu, "fmi2GetDerivatives": fn(Instance, *mut f64, usize) -> c_int, c, x.as_mut_ptr(), 2),
        ERROR
    );
    let mut v = 0;
    assert_eq!(
        call!(fmu, "fmi2GetInteger": fn(Instance, *const u32, usize, *mut c_int) -> c_int, c, &1, 1, &mut v),
        ERROR
    );
    // The ball stops bouncing at the Zeno point t ≈ 4.06 s: the step that
    // reaches it fails, with the time before it kept.
    let mut t = 0.0;
    let mut status = OK;
    while status == OK && t < 10.0 {
        status = call!(fmu, "fmi2DoStep": fn(Instance, f64, f64, c_int) -> c_int, c, t, 0.5, 1);
        if status == OK {
            t += 0.5;
        }
    }
    assert!(status == ERROR || status == DISCARD, "{status}");
    let mut reached = f64::NAN;
    assert_eq!(
        call!(fmu, "fmi2GetRealStatus": fn(Instance, c_int, *mut f64) -> c_int, c, 2, &mut reached),
        OK
    );
    assert_eq!(reached, t);
    assert_eq!(call!(fmu, "fmi2Terminate": fn(Instance) -> c_int, c), OK);
    call!(fmu, "fmi2FreeInstance": fn(Instance) -> (), c);
    assert_eq!(call!(fmu, "fmi2Terminate": fn(Instance) -> c_int, c), ERROR);
}
