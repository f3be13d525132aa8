//! What the FMU costs against the model it wraps (`--fmi`), measured in
//! one run through the same Rust functions the exported symbols call:
//!
//! - Model Exchange: one evaluation as an importer's integrator makes it
//!   (`fmi3SetTime`, `fmi3SetContinuousStates`,
//!   `fmi3GetContinuousStateDerivatives`) against `Model::rhs`, for Van der
//!   Pol (2 states) and the PI speed drive (4 states, an algebraic loop
//!   solved inside);
//! - Co-Simulation: Van der Pol over 10 s in communication steps of 0.1
//!   and 0.01 s (`fmi3DoStep`, then `fmi3GetFloat64` of x) against one
//!   native run with the same output times, at tolerances 1e-6 and 1e-10,
//!   with the error of each against a native run at 1e-13.
//!
//! Writes `results/fmi.md`.

use super::*;
use daegen_fmi::calls;
use daegen_fmi::description::{instantiation_token, FmiVersion};
use daegen_fmi::fmi3::{self, Fmi3};
use daegen_workprecision::median_time;
use std::ffi::{c_void, CString};
use std::ptr::{null, null_mut};

/// Van der Pol's oscillator, as the FMU examples export it.
#[dae_model]
fn van_der_pol_fmu() {
    let mu = param(1.0);
    let x = state(2.0);
    init(der(x), 0.0);
    der(der(x)) == mu * (1.0 - x * x) * der(x) - x;
}

/// A DC motor and PI speed controller in flat form, its supply voltage
/// an algebraic variable of a loop.
#[dae_model]
fn drive_fmu() {
    let r = param(1.0);
    let l = param(0.5e-3);
    let k = param(0.05);
    let j = param(1e-4);
    let kp = param(0.02);
    let ki = param(0.5);
    let i = state(0.0);
    let w = state(0.0);
    let phi = state(0.0);
    let x = state(0.0);
    let v = algebraic(0.0);
    l * der(i) == v - r * i - k * w;
    j * der(w) == k * i - 1e-5 * w;
    der(phi) == w;
    der(x) == 100.0 - w;
    v == kp * (100.0 - w) + ki * x;
}

/// A Model Exchange instance of `M`, initialized and in continuous-time
/// mode.
fn model_exchange<M: Model + Clone + Default + Send + Sync + 'static>() -> *mut c_void {
    let token = CString::new(instantiation_token(&M::default(), FmiVersion::V3, "bench"))
        .unwrap_or_default();
    // SAFETY: valid strings, no logger.
    let c = unsafe {
        fmi3::instantiate_model_exchange::<M>(
            "bench",
            c"me".as_ptr(),
            token.as_ptr(),
            null(),
            false,
            false,
            null_mut(),
            None,
        )
    };
    assert_eq!(fmi3::enter_initialization_mode::<M>(c, false, 0.0, 0.0, false, 0.0), 0);
    assert_eq!(calls::exit_initialization_mode::<Fmi3, M>(c), 0);
    let (mut a, mut b, mut d, mut e, mut f, mut g) = (false, false, false, false, false, 0.0);
    // SAFETY: valid flags.
    let s = unsafe {
        fmi3::update_discrete_states::<M>(c, &mut a, &mut b, &mut d, &mut e, &mut f, &mut g)
    };
    assert_eq!(s, 0);
    assert_eq!(calls::enter_continuous_time_mode::<Fmi3, M>(c), 0);
    c
}

/// Seconds per evaluation: through the FMU, and of `rhs` itself.
fn evaluation<M: Model + Clone + Default + Send + Sync + 'static>(
    settings: &Settings,
) -> (f64, f64) {
    const CALLS: usize = 100_000;
    let c = model_exchange::<M>();
    let n = M::STATES;
    let mut x = vec![0.0; n];
    // SAFETY: n values.
    unsafe { calls::get_continuous_states::<Fmi3, M>(c, x.as_mut_ptr(), n) };
    let mut dx = vec![0.0; n];
    let (through, _) = median_time(settings, || {
        for k in 0..CALLS {
            x[0] += 1e-12;
            calls::set_time::<Fmi3, M>(c, k as f64 * 1e-6);
            // SAFETY: n values each.
            unsafe {
                calls::set_continuous_states::<Fmi3, M>(c, x.as_ptr(), n);
                calls::get_derivatives::<Fmi3, M>(c, dx.as_mut_ptr(), n);
            }
        }
        dx[0]
    });
    calls::free_instance(c);
    let model = M::default();
    let (direct, _) = median_time(settings, || {
        for k in 0..CALLS {
            x[0] += 1e-12;
            let _ = model.rhs(k as f64 * 1e-6, std::hint::black_box(&x), &mut dx);
        }
        dx[0]
    });
    (through / CALLS as f64, direct / CALLS as f64)
}

/// x(10) and the seconds of a co-simulation of Van der Pol in steps of
/// `h` at `tol`.
fn co_simulation(h: f64, tol: f64, settings: &Settings) -> (f64, f64) {
    type M = VanDerPolFmu;
    let token = CString::new(instantiation_token(&M::default(), FmiVersion::V3, "bench"))
        .unwrap_or_default();
    let steps = (10.0 / h).round() as usize;
    let (seconds, x) = median_time(settings, || {
        // SAFETY: valid strings, no logger or intermediate variables.
        let c = unsafe {
            fmi3::instantiate_co_simulation::<M>(
                "bench",
                c"cs".as_ptr(),
                token.as_ptr(),
                null(),
                false,
                false,
                false,
                false,
                null(),
                0,
                null_mut(),
                None,
                null(),
            )
        };
        fmi3::enter_initialization_mode::<M>(c, true, tol, 0.0, false, 0.0);
        calls::exit_initialization_mode::<Fmi3, M>(c);
        let (mut a, mut b, mut d, mut last) = (false, false, false, 0.0);
        let mut x = 0.0;
        for k in 0..steps {
            // SAFETY: valid flags and one value reference.
            unsafe {
                fmi3::do_step::<M>(c, k as f64 * h, h, true, &mut a, &mut b, &mut d, &mut last);
                calls::get_real::<Fmi3, M>(c, &1, 1, &mut x, 1);
            }
        }
        calls::free_instance(c);
        x
    });
    (seconds, x)
}

/// Writes results/fmi.md.
pub fn fmi_section() -> String {
    let settings = Settings::default();
    let mut text = format!(
        "# FMUs against the model they wrap\n\nMachine: {}. Written by `cd bench && cargo run --release -- --fmi` (bench/src/fmi.rs), through the functions the exported FMI 3.0 symbols call. Time: the median of the runs in the budget.\n\n## Model Exchange: one evaluation\n\nAn importer's integrator sets the time and the states and reads the derivatives; against `Model::rhs` alone. The difference is the FMU's checks: the instance looked up by its handle, its lock, the state machine, `catch_unwind`, the copy of the states.\n\n| model | states | through the FMU | rhs | ratio |\n|---|---|---|---|---|\n",
        machine()
    );
    for (name, (through, direct)) in [
        ("Van der Pol", evaluation::<VanDerPolFmu>(&settings)),
        ("PI speed drive (flat)", evaluation::<DriveFmu>(&settings)),
    ] {
        let states = if name.starts_with("Van") { 2 } else { 4 };
        text.push_str(&format!(
            "| {name} | {states} | {:.0} ns | {:.0} ns | {:.1} |\n",
            through * 1e9,
            direct * 1e9,
            through / direct
        ));
    }
    text.push_str("\n## Co-Simulation: Van der Pol over 10 s\n\n`fmi3DoStep` over each communication step, each a run of `Auto` from the instance's state (a fresh start: the first step size chosen again), and x read after each; against one native run with the communication points as output times. Error: |x(10) − reference| with the reference from DOP853 at 1e-13.\n\n| step | tol | FMU time | FMU error | native time | native error | ratio |\n|---|---|---|---|---|---|---|\n");
    let reference = VanDerPolFmu::default()
        .simulate(0.0, 10.0, &Options::new().method(Method::Dop853).tolerance(1e-13))
        .and_then(|s| s.last("x"))
        .unwrap_or(f64::NAN);
    for h in [0.1, 0.01] {
        for tol in [1e-6, 1e-10] {
            eprintln!("fmi: co-simulation h {h}, tol {tol:e}");
            let (fmu_seconds, fmu_x) = co_simulation(h, tol, &settings);
            let times: Vec<f64> = (1..=(10.0 / h).round() as usize).map(|k| k as f64 * h).collect();
            let opts = Options::new().rtol(tol).atol(tol * 1e-3).output_times(times);
            let (native_seconds, native_x) = median_time(&settings, || {
                VanDerPolFmu::default().simulate(0.0, 10.0, &opts).and_then(|s| s.last("x"))
            });
            let native_x = native_x.unwrap_or(f64::NAN);
            text.push_str(&format!(
                "| {h} | {tol:.0e} | {:.3} ms | {:.1e} | {:.3} ms | {:.1e} | {:.1} |\n",
                fmu_seconds * 1e3,
                (fmu_x - reference).abs(),
                native_seconds * 1e3,
                (native_x - reference).abs(),
                fmu_seconds / native_seconds
            ));
        }
    }
    text
}
