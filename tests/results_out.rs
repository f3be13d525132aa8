//! Getting results out: every readable name, columns at the stored times,
//! samples on a grid through each method's continuous extension, storage
//! at chosen output times only, CSV, and the step callback that streams a
//! run and can stop it.

use daegen::prelude::*;
use daegen::{Flow, Step};
use std::f64::consts::PI;
use std::sync::{Arc, Mutex};

mod support;
use support::harness::{adaptive_methods_for, kind, methods_for, Kind};

/// x'' = −x from (1, 0): x = cos t; with an algebraic variable and an
/// output.
///
/// Its description keeps every line of this comment.
#[dae_model]
fn oscillator() {
    let x = state(1.0);
    init(der(x), 0.0);
    der(der(x)) == -x;
    /// The square of x, as an algebraic variable: z = x².
    let z = algebraic(0.0);
    z == x * x;
    /// Twice the energy.
    let energy = output(x * x + der(x) * der(x));
}

/// A body dropped from 1 m, stopped at the ground.
#[dae_model]
fn falling() {
    let h = state(1.0);
    der(der(h)) == -9.81;
    let impact = event(h).falling().terminal();
}

#[test]
fn names_list_states_then_algebraics_then_outputs() {
    let sol = Oscillator::default().simulate(0.0, 1.0, &Options::new()).unwrap();
    assert_eq!(sol.names(), ["x", "der(x)", "z", "energy"]);
    for name in sol.names() {
        assert!(sol.last(name).is_ok(), "{name}");
        assert_eq!(sol.column(name).unwrap().len(), sol.times().len());
    }
}

#[test]
fn columns_hold_the_values_at_the_stored_times() {
    let opts = Options::new().method(Method::Dop853).tolerance(1e-12);
    let sol = Oscillator::default().simulate(0.0, 2.0 * PI, &opts).unwrap();
    let (x, z, energy) =
        (sol.column("x").unwrap(), sol.column("z").unwrap(), sol.column("energy").unwrap());
    for (k, &t) in sol.times().iter().enumerate() {
        assert!((x[k] - t.cos()).abs() < 1e-10, "x at {t}");
        assert!((z[k] - t.cos().powi(2)).abs() < 1e-10, "z at {t}");
        assert!((energy[k] - 1.0).abs() < 1e-10, "energy at {t}");
    }
    match sol.column("y") {
        Err(Error::UnknownName { name, known }) => {
            assert_eq!(name, "y");
            assert_eq!(known, ["x", "der(x)", "z", "energy"]);
        }
        other => panic!("expected UnknownName, got {other:?}"),
    }
}

/// The largest error of `x` on a grid of 97 times, sampled from a run.
fn sampled_error(opts: &Options) -> f64 {
    let sol = Oscillator::default().simulate(0.0, 3.0, opts).unwrap();
    let grid: Vec<f64> = (0..=96).map(|k| 3.0 * k as f64 / 96.0).collect();
    let table = sol.sample(&["x", "der(x)"], &grid).unwrap();
    assert_eq!(table.times(), &grid[..]);
    let x = table.column("x").unwrap();
    grid.iter().zip(x).map(|(t, x)| (x - t.cos()).abs()).fold(0.0, f64::max)
}

/// Between the steps each fixed-step method is interpolated at its own
/// order: the error on a grid that falls between the steps (step 3/64
/// against 3/128, grid 3/96) falls by 2^p as the step halves: p = 4 for
/// RK4 and the 3/8 rule (cubic Hermite), 6 for TaylorFixed of order 6
/// (the step's own Taylor polynomial), 1 for Euler.
#[test]
fn samples_between_steps_converge_at_the_methods_order() {
    let cases: [(Method, Method, f64); 4] = [
        (Method::Rk4, Method::Rk4, 4.0),
        (Method::Rk38, Method::Rk38, 4.0),
        (
            Method::TaylorFixed { order: 6, step: 3.0 / 64.0 },
            Method::TaylorFixed { order: 6, step: 3.0 / 128.0 },
            6.0,
        ),
        (Method::Euler, Method::Euler, 1.0),
    ];
    for (coarse, fine, order) in cases {
        let error = |method: Method, step: f64| -> f64 {
            let opts = Options::new().method(method).step(step);
            if matches!(method, Method::TaylorFixed { .. }) {
                let sol = support::Oscillator::default().simulate(0.0, 3.0, &opts).unwrap();
                let grid: Vec<f64> = (0..=96).map(|k| 3.0 * k as f64 / 96.0).collect();
                let x = sol.sample(&["x"], &grid).unwrap().column("x").unwrap().to_vec();
                grid.iter().zip(x).map(|(t, x)| (x - t.cos()).abs()).fold(0.0, f64::max)
            } else {
                sampled_error(&opts)
            }
        };
        let (e1, e2) = (error(coarse, 3.0 / 64.0), error(fine, 3.0 / 128.0));
        let observed = (e1 / e2).log2();
        assert!(
            (observed - order).abs() < 0.35,
            "{coarse:?}: errors {e1:e} and {e2:e}, order {observed:.2}, expected {order}"
        );
    }
}

/// Adaptive methods sample through their dense output within a small
/// multiple of the tolerance.
#[test]
fn adaptive_samples_follow_the_exact_solution() {
    // Every adaptive method that runs the model.
    for method in adaptive_methods_for::<Oscillator>() {
        let opts = Options::new().method(method).tolerance(1e-10);
        let error = sampled_error(&opts);
        assert!(error < 1e-8, "{method:?}: {error:e}");
    }
}

#[test]
fn output_times_store_those_times_at_the_methods_order() {
    let times: Vec<f64> = (0..=30).map(|k| 0.1 * k as f64).collect();
    // Every method that runs the model within 1e-8 of cos t at tol 1e-10
    // or step 1e-3: the adaptive ones and the fixed-step ones of order 4
    // or more (order 2 leaves about h² = 1e-6).
    let accurate = |m: Method| !matches!(kind(m), Kind::FixedStep { order, .. } if order < 4);
    for method in methods_for::<Oscillator>(accurate) {
        let full = Options::new().method(method).tolerance(1e-10).step(1e-3);
        let only = full.output_times(times.clone());
        let a = Oscillator::default().simulate(0.0, 3.0, &full).unwrap();
        let b = Oscillator::default().simulate(0.0, 3.0, &only).unwrap();
        assert_eq!(b.times(), &times[..], "{method:?}");
        // The same steps, interpolated by the same extension.
        assert_eq!(a.stats().steps, b.stats().steps, "{method:?}");
        let sampled = a.sample(&["x", "energy"], &times).unwrap();
        let x = b.column("x").unwrap();
        let energy = b.column("energy").unwrap();
        for k in 0..times.len() {
            let (sx, se) = (sampled.column("x").unwrap()[k], sampled.column("energy").unwrap()[k]);
            assert!((x[k] - sx).abs() <= 1e-15, "{method:?} at {}", times[k]);
            assert!((energy[k] - se).abs() <= 1e-14, "{method:?} at {}", times[k]);
            assert!((x[k] - times[k].cos()).abs() < 1e-8, "{method:?} at {}", times[k]);
        }
        // Asked at a stored time it answers; elsewhere it says what was stored.
        assert_eq!(b.at(0.5, "x").unwrap(), x[5]);
        match b.at(0.55, "x") {
            Err(Error::NotStored { t }) => assert_eq!(t, 0.55),
            other => panic!("{method:?}: expected NotStored, got {other:?}"),
        }
        assert!(b.at(0.55, "x").unwrap_err().to_string().contains("output_times"));
        assert_eq!(b.last("x").unwrap(), a.last("x").unwrap());
    }
}

#[test]
fn output_times_run_backwards_and_stop_at_a_terminal_event() {
    let back: Vec<f64> = (0..=10).map(|k| 3.0 - 0.3 * k as f64).collect();
    let sol = Oscillator::default()
        .simulate_from(
            3.0,
            &[3f64.cos(), -3f64.sin()],
            0.0,
            &Options::new().tolerance(1e-10).output_times(back.clone()),
        )
        .unwrap();
    assert_eq!(sol.times(), &back[..]);
    for (t, x) in back.iter().zip(sol.column("x").unwrap()) {
        assert!((x - t.cos()).abs() < 1e-8, "{t}");
    }
    let grid: Vec<f64> = (0..=10).map(|k| 0.1 * k as f64).collect();
    let opts = Options::new().method(Method::Dop853).output_times(grid.clone());
    let sol = Falling::default().simulate(0.0, 1.0, &opts).unwrap();
    let impact = (2.0f64 / 9.81).sqrt();
    let kept: Vec<f64> = grid.iter().copied().filter(|&t| t <= impact).collect();
    assert_eq!(sol.times(), &kept[..]);
    assert!((sol.final_time() - impact).abs() < 1e-14);
    for (t, h) in kept.iter().zip(sol.column("h").unwrap()) {
        assert!((h - (1.0 - 0.5 * 9.81 * t * t)).abs() < 1e-12, "{t}");
    }
}

#[test]
fn bad_output_times_are_refused_with_what_to_write() {
    let model = Oscillator::default();
    let cases = [
        (Options::new().output_times(vec![0.0, 2.0]), "outside the interval"),
        (Options::new().output_times(vec![0.5, 0.2]), "strictly increasing"),
        (Options::new().output_times(vec![0.5]).keep_every(3), "use one"),
        (Options::new().output_times(vec![0.5]).dense_output(false), "drop dense_output(false)"),
    ];
    for (opts, expected) in cases {
        match model.simulate(0.0, 1.0, &opts) {
            Err(Error::InvalidOptions { message }) => {
                assert!(message.contains(expected), "{message}")
            }
            other => panic!("expected InvalidOptions, got {other:?}"),
        }
    }
    match model.simulate(1.0, 0.0, &Options::new().output_times(vec![0.2, 0.5])) {
        Err(Error::InvalidOptions { message }) => {
            assert!(message.contains("strictly decreasing"), "{message}")
        }
        other => panic!("expected InvalidOptions, got {other:?}"),
    }
}

#[test]
fn on_step_sees_every_accepted_step_and_can_stop_the_run() {
    let seen = Arc::new(Mutex::new(Vec::new()));
    let log = seen.clone();
    let opts = Options::new().method(Method::Dopri5).on_step(move |step: &Step| {
        log.lock().unwrap().push((step.t, step.get("x").unwrap(), step.steps));
        Flow::Continue
    });
    let sol = Oscillator::default().simulate(0.0, 2.0, &opts).unwrap();
    let seen = seen.lock().unwrap();
    assert_eq!(seen.len(), sol.stats().steps);
    assert_eq!(sol.cancelled_at(), None);
    for (k, &(t, x, steps)) in seen.iter().enumerate() {
        assert_eq!(steps, k + 1);
        assert_eq!(t, sol.times()[k + 1]);
        assert_eq!(x, sol.state(k + 1).unwrap()[0]);
    }

    // Stop at the first step past t = 1: the run ends there, successfully.
    let opts = Options::new().method(Method::Rk4).step(0.01).on_step(|step: &Step| {
        if step.t >= 1.0 {
            Flow::Stop
        } else {
            Flow::Continue
        }
    });
    let sol = Oscillator::default().simulate(0.0, 5.0, &opts).unwrap();
    let end = sol.cancelled_at().expect("stopped by the callback");
    assert!((1.0..1.0 + 0.011).contains(&end), "{end}");
    assert_eq!(sol.final_time(), end);
    assert_eq!(*sol.times().last().unwrap(), end);
    assert!((sol.last("x").unwrap() - end.cos()).abs() < 1e-8);
}

#[test]
fn csv_has_a_header_and_one_row_per_stored_time() {
    let opts = Options::new().output_times(vec![0.0, 0.5, 1.0]);
    let sol = Oscillator::default().simulate(0.0, 1.0, &opts).unwrap();
    let mut out = Vec::new();
    sol.write_csv(&mut out, &["x", "energy"]).unwrap();
    let text = String::from_utf8(out).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[0], "t,x,energy");
    assert_eq!(lines.len(), 4);
    let x = sol.column("x").unwrap();
    for (k, line) in lines[1..].iter().enumerate() {
        let row: Vec<f64> = line.split(',').map(|v| v.parse().unwrap()).collect();
        assert_eq!(row[0], sol.times()[k]);
        assert_eq!(row[1], x[k]);
    }
    let mut all = Vec::new();
    sol.write_csv(&mut all, &sol.names()).unwrap();
    assert!(String::from_utf8(all).unwrap().starts_with("t,x,der(x),z,energy\n"));
    assert!(matches!(sol.write_csv(Vec::new(), &["nope"]), Err(Error::UnknownName { .. })));
}

/// A writer that always fails, as a full disk does.
struct FullDisk;

impl std::io::Write for FullDisk {
    fn write(&mut self, _: &[u8]) -> std::io::Result<usize> {
        Err(std::io::Error::other("no space left on device"))
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

#[test]
fn a_failing_writer_is_an_error_not_a_panic() {
    let sol = Oscillator::default().simulate(0.0, 1.0, &Options::new()).unwrap();
    match sol.write_csv(FullDisk, &["x"]) {
        Err(Error::Io { message }) => assert!(message.contains("no space left"), "{message}"),
        other => panic!("expected Io, got {other:?}"),
    }
}

/// Printing a sampled table shows a header and one aligned row per time.
#[test]
fn a_sampled_table_prints_aligned() {
    let sol = Oscillator::default().simulate(0.0, 1.0, &Options::new().tolerance(1e-10)).unwrap();
    let table = sol.sample(&["x", "der(x)"], &[0.0, 0.5, 1.0]).unwrap();
    let text = table.to_string();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 4, "{text}");
    assert!(lines[0].trim_start().starts_with('t'), "{text}");
    assert!(lines.iter().all(|l| l.len() == lines[0].len()), "{text}");
    assert!(lines[2].contains(&format!("{:.5}", 0.5f64.cos())), "{text}");
}

/// `describe` lists every name with its doc comment and the parameters'
/// values; `progress(true)` changes nothing in the result (a run shorter
/// than a second draws no bar).
#[test]
fn describe_lists_every_name_and_progress_changes_no_result() {
    let text = Oscillator::default().describe();
    for line in [
        "Oscillator: x'' = −x from (1, 0): x = cos t; with an algebraic variable and an\n  output.\n\n  Its description keeps every line of this comment.\nstates:",
        "states:",
        "\n  x\n",
        "  der(x)  ",
        "rate of `x`",
        "algebraic variables:",
        "The square of x, as an algebraic variable: z = x².",
        "outputs:",
        "Twice the energy.",
    ] {
        assert!(text.contains(line), "{line:?} missing from:\n{text}");
    }
    let plain = Options::new().method(Method::Dop853);
    let a = Oscillator::default().simulate(0.0, 5.0, &plain).unwrap();
    let b = Oscillator::default().simulate(0.0, 5.0, &plain.progress(true)).unwrap();
    assert_eq!(a.times(), b.times());
    assert_eq!(a.final_state(), b.final_state());
}
