//! Examples of the Modelica Standard Library 4.0.0 rewritten with
//! daegen's library (tests/models/msl.rs), run and compared with MAP-LIB's
//! reference results by csv-compare's tube (tests/support/tube.rs): every
//! compared signal inside the tube at every reference row.

// MSL's sources write π/2 to 16 digits; the models keep their numbers.
#![allow(clippy::approx_constant)]

use daegen::prelude::*;

include!("models/msl.rs");

#[path = "support/tube.rs"]
mod tube;

/// Tight enough that the tube measures the model, not the run.
fn options() -> Options {
    Options::new().method(Method::Radau5).rtol(1e-8).atol(1e-10)
}

/// Runs example `name` over its reference's interval and compares each
/// compared signal with the reference by the tube MAP-LIB uses.
fn check(name: &str) {
    let examples = msl_examples();
    let example = examples.iter().find(|e| e.name == name).expect("an example");
    let reference = tube::reference(name);
    let t1 = *reference.times.last().expect("rows");
    let sol = (example.run)(t1, &options()).unwrap_or_else(|e| panic!("{name}: {e}"));
    for &(msl, ours) in example.signals {
        let k = reference.signals.iter().position(|s| s == msl).expect("a compared signal");
        let value = |t: f64, before: bool| {
            let read = if before { sol.at_left(t, ours) } else { sol.at(t, ours) };
            read.unwrap_or_else(|e| panic!("{name}: {ours} at {t}: {e}"))
        };
        let comparison = tube::compare(&reference, k, &value, 0.002);
        println!(
            "{name} {}: {:.4} of the tube at {}",
            comparison.signal, comparison.worst, comparison.at
        );
        assert_eq!(comparison.outside, 0, "{name}: {comparison:?}");
    }
}

#[test]
fn every_example_is_in_the_table() {
    // Each example has a test below, and a reference.
    let tests = include_str!("msl_examples.rs");
    for example in msl_examples() {
        assert!(tests.contains(&format!("check(\"{}\")", example.name)), "{}", example.name);
    }
}

#[test]
fn msl_first() {
    check("First");
}

#[test]
fn msl_two_masses() {
    check("TwoMasses");
}

#[test]
fn msl_cauer_low_pass_analog() {
    check("CauerLowPassAnalog");
}

#[test]
fn msl_oscillator() {
    check("Oscillator");
}

#[test]
fn msl_damper() {
    check("Damper");
}

#[test]
fn msl_rectifier() {
    check("Rectifier");
}

#[test]
fn msl_dcpm_start() {
    check("DCPM_Start");
}

#[test]
fn msl_dcee_start() {
    check("DCEE_Start");
}

#[test]
fn msl_pre_load() {
    check("PreLoad");
}

#[test]
fn msl_inverse_model() {
    check("InverseModel");
}

#[test]
fn msl_coupled_clutches() {
    check("CoupledClutches");
}

#[test]
fn msl_pid_controller() {
    check("PID_Controller");
}
