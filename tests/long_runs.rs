//! Long runs with bounded memory: `Options::keep_every(k)` stores every
//! k-th accepted step and the last one, while `stats()` counts them all.

use daegen::prelude::*;

mod support;
use support::{Falling, Oscillator};

#[test]
fn a_million_steps_keep_a_thousand_states() {
    let n = 1_000_000usize;
    let h = 2.0 * std::f64::consts::PI / 1000.0;
    let t1 = n as f64 * h;
    let opts = Options::new().method(Method::Rk4).step(h).keep_every(1000);
    let sol = Oscillator::default().simulate(0.0, t1, &opts).unwrap();
    assert_eq!(sol.stats().steps, n);
    // Steps 0, 1000, 2000, …: the initial state, then every 1000th.
    assert_eq!(sol.times().len(), n / 1000 + 1);
    assert_eq!(*sol.times().last().unwrap(), t1);
    // RK4's energy error per step is h⁶/72 (|R(ih)|² = 1 − h⁶/72 + O(h⁸)),
    // so after n steps x² + v² = 1 − n h⁶/72 ≈ 1 − 8.4e-10.
    let end = sol.final_state();
    let energy = end[0] * end[0] + end[1] * end[1];
    let predicted = 1.0 - n as f64 * h.powi(6) / 72.0;
    assert!((energy - predicted).abs() <= 1e-3 * (1.0 - predicted), "{energy} vs {predicted}");
    // Every stored state is on the circle to that accuracy, at its time.
    for (k, &t) in sol.times().iter().enumerate() {
        let s = sol.state(k).unwrap();
        assert!(((s[0] * s[0] + s[1] * s[1]) - 1.0).abs() <= 1e-9, "t = {t}");
    }
}

#[test]
fn keep_every_thins_the_stored_steps_and_at_refuses_between_them() {
    let opts = Options::new().method(Method::Dop853).tolerance(1e-12).keep_every(7);
    let thin = Oscillator::default().simulate(0.0, 100.0, &opts).unwrap();
    let full = Oscillator::default().simulate(0.0, 100.0, &opts.keep_every(1)).unwrap();
    let steps = full.times().len() - 1;
    assert_eq!(thin.stats().steps, steps);
    assert_eq!(thin.times().len(), steps / 7 + 1 + usize::from(steps % 7 != 0));
    assert_eq!(thin.final_state(), full.final_state());
    assert!((thin.last("x").unwrap() - 100f64.cos()).abs() <= 1e-9);
    // At a kept step `at` answers; between kept steps it says it cannot,
    // rather than interpolating linearly across the steps it dropped.
    let kept = thin.times()[3];
    assert_eq!(thin.at(kept, "x").unwrap(), thin.state(3).unwrap()[0]);
    let between = 0.5 * (thin.times()[3] + thin.times()[4]);
    match thin.at(between, "x") {
        Err(daegen::Error::Thinned { t, keep_every: 7 }) => assert_eq!(t, between),
        other => panic!("expected Thinned, got {other:?}"),
    }
    let message = thin.at(between, "x").unwrap_err().to_string();
    assert!(message.contains("keep_every(7)"), "{message}");
    let zero = Oscillator::default().simulate(0.0, 1.0, &opts.keep_every(0));
    assert!(matches!(zero, Err(daegen::Error::InvalidOptions { .. })));
}

/// Thinning stores fewer steps but watches every one: the impact of a body
/// dropped from 1 m is found at sqrt(2/9.81) s, to machine precision, and
/// the run ends there.
#[test]
fn a_thinned_run_still_finds_every_event() {
    let opts = Options::new().method(Method::Dop853).keep_every(10);
    let sol = Falling::default().simulate(0.0, 1.0, &opts).unwrap();
    let impact = (2.0f64 / 9.81).sqrt();
    let hit = sol.stopped_by().expect("the impact ends the run");
    assert!((hit.t - impact).abs() < 1e-14, "{}", hit.t);
    assert_eq!(sol.final_time(), hit.t);
    assert_eq!(*sol.times().last().unwrap(), hit.t);
    assert!(sol.last("h").unwrap().abs() < 1e-13);
}
